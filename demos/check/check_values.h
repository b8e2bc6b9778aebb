// What `cdlab check` measures answers with (demos/check/check.cpp, demos/check/trace_check.cpp):
// number formatting for verdicts, JSON vectors, the size of a problem (for tolerances), and support
// values and distances of the query's shapes computed by cdlab's own query code.
#pragma once

#include <optional>
#include <string>

#include "core/base/types.h"
#include "demos/scene/json_reader.h"

namespace cdlab::demos {

/// A difference or a tolerance: three digits say enough.
std::string num(double x);
/// A value: enough digits to show where two answers part.
std::string value(double x);

bool isVec(const Json& j);
Vec3 vec(const Json& j);

/// The size of the problem: the extent of every point of the query's shapes (radii count twice),
/// and their largest coordinate (whose rounding no answer can beat).
struct Size {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    double radius = 0, largest = 0;
    void add(const Json& j, const std::string& key = "");
    /// relative x the extent, plus 16 ulps of the largest coordinate.
    double tolerance(double relative) const;
};

/// Support value h_S(n) = max over S of x·n for a query shape (a compound: its pieces; a mesh: its
/// vertices); nothing for unbounded shapes or what cannot be read.
std::optional<double> support(const Json& shape, const Vec3& n);

/// Distance from a point to a query shape, by cdlab's own distance op (0 inside).
std::optional<double> distanceTo(const Vec3& p, const Json& shape);

}  // namespace cdlab::demos
