// Independent oracles for `cdlab bench` (and its unit test): answers that share no code with
// GJK, EPA or the simplex solvers of core/.
//  - Convex sets given by vertex lists: the convex hull of the Minkowski difference {a_i - b_j}
//    (core/geometry/convex_hull.h, an incremental hull that knows nothing of support mappings), then in
//    long double: distance from the origin = min over hull faces of the distance to that convex
//    polygon (projection if it falls inside the polygon, else the nearest edge: brute force);
//    when the origin is inside every face plane, depth = min face offset, normal = that face's.
//  - Point vs triangle / tetrahedron: projection and edge clamping in long double (brute force,
//    no Voronoi-region logic).
#pragma once

#include <vector>

#include "core/base/types.h"

namespace cdlab::demos {

struct MinkowskiOracle {
    bool ok = false;             ///< false: the hull failed (degenerate input); nothing else meaningful
    bool inside = false;         ///< origin strictly inside conv{a_i - b_j}: the sets overlap
    double distance = 0.0;       ///< origin to the hull (0 when inside), world units
    double depth = 0.0;          ///< inside: origin to the hull boundary (min face offset)
    Vec3 normal = Vec3::Zero();  ///< inside: outward unit normal of the nearest face
    int faces = 0;               ///< hull faces examined
};

/// Oracle for two convex polytopes given by their world-frame vertices.
MinkowskiOracle minkowskiOracle(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

/// Distance between the convex hulls of two small vertex sets that do not overlap, by brute force
/// in long double with no hull at all: the minimum over every vertex triple of A and of B of the
/// triangle-triangle distance (6 vertex-triangle and 9 segment-segment distances). Meaningless
/// (too large) when the hulls overlap. O(n^3 m^3): for sets of up to ~6 vertices.
double oracleDistanceBruteForce(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

/// Distance between segments pq and rs, long double (ternary search, robust when parallel).
double oracleSegmentDistance(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s);

/// Distance from p to the solid triangle t, long double brute force.
double oracleDistanceToTriangle(const Vec3& p, const Triangle& t);

/// Distance from p to the solid tetrahedron t (0 inside), long double brute force.
double oracleDistanceToTetrahedron(const Vec3& p, const Tetrahedron& t);

}  // namespace cdlab::demos
