// The whole set of closest point pairs of two separated convex polytopes, when it is not one pair.
// GJK returns one pair (p_A, p_B) and the separating axis; but two parallel faces, a face and a
// parallel edge, or two parallel edges are closest along a polygon or a segment of pairs. With the
// unit axis n from A toward B and the distance d, the closest pairs are exactly (p, p + d n) for p
// in F_A ∩ (F_B − d n): F_A the face of A extreme along n, F_B the face of B extreme along −n (every
// closest pair's points lie on the supporting planes of the slab between A and B, and a point p of
// F_A has a partner iff p + d n is in F_B). Used by the GJK figure (frame closest_set); test:
// tests/core/closest/closest_set_test.cpp.
#pragma once

#include <span>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

struct ClosestSet {
    /// On A: one point (the pair is unique), two (a segment of pairs) or a convex polygon in the
    /// plane ⟂ n, counter-clockwise seen from B. Empty when the input is not separated (d <= 0).
    std::vector<Vec3> onA;
    Vec3 offset = Vec3::Zero();  ///< d n: the partner on B of a point p of onA is p + offset
};

/// The closest set of conv(a) and conv(b) (world vertices, duplicates allowed), separated by
/// `distance` > 0 along the unit `axis` (A toward B), as GJK reports them. `tolerance` (world
/// units) decides which vertices are on the extreme faces and merges points closer than it;
/// `fallback` (GJK's p_A) answers when the two extreme features are skew edges (one pair).
ClosestSet closestSetOfPolytopes(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& axis, double distance,
                                 double tolerance, const Vec3& fallback);

}  // namespace cdlab
