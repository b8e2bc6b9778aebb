// Test-only oracle for two convex polygons in the plane (conservative advancement, the
// mtd_backtracking demo): their distance (the least vertex-edge distance both ways, when some edge
// normal separates them) and their penetration depth (the least overlap over all edge normals, 2D
// SAT), in long double. Shares no code with core/ (no GJK, no EPA).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/types.h"

namespace oracle {

struct P2 {
    long double x, y;
};

/// Counter-clockwise polygon corners from doubles.
inline std::vector<P2> polygon2(const std::vector<cdlab::Vec3>& points) {
    std::vector<P2> out;
    for (const cdlab::Vec3& p : points) out.push_back({p.x(), p.y()});
    return out;
}

inline long double pointSegment2(P2 p, P2 a, P2 b) {
    const long double dx = b.x - a.x, dy = b.y - a.y;
    long double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy);
    t = std::clamp<long double>(t, 0, 1);
    return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

/// The overlap of a and b along edge i's outward normal of `a` (counter-clockwise): negative when
/// that normal separates them (minus the gap).
inline long double overlapAlongEdge(const std::vector<P2>& a, std::size_t i, const std::vector<P2>& b) {
    const P2 p = a[i], q = a[(i + 1) % a.size()];
    const long double nx = q.y - p.y, ny = p.x - q.x, len = std::hypot(nx, ny);
    long double aMax = -INFINITY, bMin = INFINITY;
    for (P2 v : a) aMax = std::max(aMax, (v.x * nx + v.y * ny) / len);
    for (P2 v : b) bMin = std::min(bMin, (v.x * nx + v.y * ny) / len);
    return aMax - bMin;
}

/// Penetration depth of two convex polygons (0 or less: apart): the least overlap over the edge
/// normals of both (2D SAT).
inline long double polygonDepth(const std::vector<P2>& a, const std::vector<P2>& b) {
    long double depth = INFINITY;
    for (std::size_t i = 0; i < a.size(); ++i) depth = std::min(depth, overlapAlongEdge(a, i, b));
    for (std::size_t i = 0; i < b.size(); ++i) depth = std::min(depth, overlapAlongEdge(b, i, a));
    return depth;
}

/// Distance of two convex polygons (0 when they touch or overlap).
inline long double polygonDistance(const std::vector<P2>& a, const std::vector<P2>& b) {
    if (polygonDepth(a, b) >= 0) return 0;
    long double d = INFINITY;
    for (int k = 0; k < 2; ++k) {
        const auto& u = k ? a : b;
        const auto& w = k ? b : a;
        for (P2 p : u)
            for (std::size_t i = 0; i < w.size(); ++i) d = std::min(d, pointSegment2(p, w[i], w[(i + 1) % w.size()]));
    }
    return d;
}

}  // namespace oracle
