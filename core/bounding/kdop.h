// k-DOPs (discrete-orientation polytopes): the intersection of K/2 slabs whose normals come from a
// fixed set of directions shared by every k-DOP, so that two of them are compared by K/2
// interval tests with no rotation.
//
// Source: C. Ericson, "Real-Time Collision Detection" (2005) §4.6 (k-DOPs; §4.6.1 overlap test,
// §4.6.2 computing a k-DOP); J. Klosowski et al., "Efficient Collision Detection Using Bounding
// Volume Hierarchies of k-DOPs", IEEE TVCG 1998.
//
// Directions (unnormalized, integer components, so that a projection is a sum of coordinates):
//   slabs 0-2   (1,0,0) (0,1,0) (0,0,1)                                   6-DOP = the AABB
//   slabs 3-6   (1,1,1) (1,1,-1) (1,-1,1) (-1,1,1)                         14-DOP = 6 + corners
//   slabs 7-12  (1,1,0) (1,-1,0) (1,0,1) (1,0,-1) (0,1,1) (0,1,-1)         18-DOP = 6 + edges
//                                                                          26-DOP = all 13
// Slab i holds the points x with min[i] <= d_i . x <= max[i] (d_i as listed, not unit).
// Frame: world frame only (a k-DOP cannot be rotated; refit or bound the rotated one instead).
// Units: min / max are in length units times |d_i| (1, sqrt 2 or sqrt 3).
#pragma once

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

/// k-DOP corners: a corner candidate may violate another slab by this times the box size and still
/// count (rounding is ~1e-16 relative; any real feature of the polytope is far larger).
inline constexpr double kKdopCornerRelative = 1e-9;

/// k-DOP with K in {6, 14, 18, 26}: K/2 slabs over kdopDirections<K>(). Default: empty (every
/// min = +inf, max = -inf; no hit in testKdopKdop).
template <int K>
struct Kdop {
    static_assert(K == 6 || K == 14 || K == 18 || K == 26, "k-DOPs exist for K = 6, 14, 18, 26");
    static constexpr int kSlabs = K / 2;
    std::array<double, K / 2> min;
    std::array<double, K / 2> max;
    Kdop() {
        min.fill(std::numeric_limits<double>::infinity());
        max.fill(-std::numeric_limits<double>::infinity());
    }
};

/// The K/2 slab normals of a K-DOP in slab order (see the table above).
template <int K>
std::span<const Vec3> kdopDirections();

/// Smallest K-DOP holding every finite point (non-finite points skipped; none: the empty k-DOP).
/// Slab i: [min_p d_i . p, max_p d_i . p], widened on the diagonal slabs by the rounding of the
/// three-term sum (see kdop.cpp) so that it also holds the points in exact arithmetic.
template <int K>
Kdop<K> fitKdop(std::span<const Vec3> points);

/// K-DOP of every vertex of the triangles (a k-DOP of a convex set is that of its vertices).
template <int K>
Kdop<K> fitKdop(std::span<const Triangle> triangles);

/// Result of a k-DOP overlap test.
struct KdopOverlapResult {
    bool hit = false;
    int separatingSlab = -1;  ///< !hit: the first slab whose intervals are disjoint (-1 for NaN / empty)
};

/// k-DOP overlap (Ericson §4.6.1): disjoint iff some slab's intervals are disjoint, touching
/// intervals do not separate. CONSERVATIVE: K/2 slab normals are not all the separating axes of
/// two k-DOPs (the cross products of their edges are missing), so two k-DOPs may be reported as
/// overlapping when they are in fact disjoint, never the reverse. For a BVH that only costs an
/// extra descent; it never loses a pair.
template <int K>
KdopOverlapResult testKdopKdop(const Kdop<K>& a, const Kdop<K>& b);

/// True iff p is in every slab of the k-DOP (d_i . p in [min_i, max_i], double arithmetic).
template <int K>
bool contains(const Kdop<K>& dop, const Vec3& p);

/// The k-DOP as a convex polyhedron (world frame): vertices from every triple of slab planes
/// that meets inside all slabs, then their convex hull. Empty for an empty, non-finite or flat
/// (zero-volume) k-DOP.
template <int K>
ConvexPolyhedron kdopPolytope(const Kdop<K>& dop);

/// Volume of the k-DOP (units^3): that of kdopPolytope; 0 when flat or empty.
template <int K>
double volume(const Kdop<K>& dop);

}  // namespace cdlab
