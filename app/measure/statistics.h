// Small measurements shared by the accuracy demo, `cdlab bench` and `cdlab stress`.
#pragma once

#include <vector>

#include "core/base/types.h"

namespace cdlab::demos {

/// The median (the mean of the two middle values for an even count); NaN for no values.
double median(std::vector<double> values);

/// CPU time of the calling thread, in seconds: on a shared machine wall time per query triples
/// while the thread's CPU time stays what the query costs.
double threadSeconds();

/// The same in milliseconds.
inline double threadMilliseconds() { return 1e3 * threadSeconds(); }
/// Thread CPU time since t0 (a threadMilliseconds() reading), in milliseconds.
inline double millisecondsSince(double t0) { return threadMilliseconds() - t0; }

/// The size L of a point set that relative errors are measured against: the largest distance of a
/// point from the points' centroid.
double centroidRadius(const std::vector<Vec3>& points);

}  // namespace cdlab::demos
