// The long-double kit the Minkowski oracles share (minkowski_facet_oracle.h, minkowski_hull_oracle.cpp):
// distances from the origin to a segment, a convex polygon and a triangle, by projection and
// clamping (brute force, no Voronoi-region logic, nothing from core's algorithms).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/types.h"

namespace cdlab::long_double {

using LVec = Eigen::Matrix<long double, 3, 1>;

inline LVec toL(const Vec3& v) { return LVec(v.x(), v.y(), v.z()); }

/// |origin - segment pq|, clamped projection.
inline long double segmentDistanceL(const LVec& p, const LVec& q) {
    const LVec t = q - p;
    const long double tt = t.squaredNorm();
    long double s = tt > 0 ? -p.dot(t) / tt : 0;
    s = std::clamp(s, 0.0L, 1.0L);
    return (p + s * t).norm();
}

/// |origin - convex polygon| (vertices in order, unit normal n consistent with the winding): the
/// projection when it lies inside every edge, else the nearest edge.
inline long double polygonDistanceL(const std::vector<LVec>& v, const LVec& n) {
    const long double offset = n.dot(v[0]);
    const LVec x = offset * n;  // projection of the origin on the plane
    bool inside = true;
    for (size_t i = 0; i < v.size() && inside; ++i) {
        const LVec& p = v[i];
        const LVec& q = v[(i + 1) % v.size()];
        if (n.dot((q - p).cross(x - p)) < 0) inside = false;
    }
    if (inside) return std::abs(offset);
    long double best = INFINITY;
    for (size_t i = 0; i < v.size(); ++i) best = std::min(best, segmentDistanceL(v[i], v[(i + 1) % v.size()]));
    return best;
}

/// |origin - triangle abc| (a degenerate triangle: its nearest edge).
inline long double triangleDistanceL(const LVec& a, const LVec& b, const LVec& c) {
    const LVec n = (b - a).cross(c - a);
    const long double len = n.norm();
    if (len > 0) return polygonDistanceL({a, b, c}, n / len);
    return std::min({segmentDistanceL(a, b), segmentDistanceL(b, c), segmentDistanceL(c, a)});
}

}  // namespace cdlab::long_double
