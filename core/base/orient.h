// Robust orientation predicates: floating-point filter + exact fallback.
//
// Follows Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates" (1997): the determinant is first evaluated in doubles and its sign accepted when
// |det| exceeds Shewchuk's a-priori error bound (errboundA); otherwise it is recomputed exactly
// with the expansion arithmetic of exact_predicates.h (BigDyadic where an expansion could
// underflow or overflow): the exact sign of the determinant of the double inputs, for every
// finite input. Non-finite inputs give 0; callers reject NaN / inf before asking.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// Exact sign (-1, 0, +1) of (b - a) x (c - a) . (d - a): +1 when d lies on the side that the
/// normal of the counterclockwise triangle a, b, c points to, 0 when the four are coplanar.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Exact sign of (b - a) x (c - a) in 2D: +1 when a, b, c turn counterclockwise, 0 collinear.
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c);

/// Exact sign of det[u1 - v1; u2 - v2; u3 - v3] (rows), the differences taken exactly.
/// orient3d(a, b, c, d) == signDet3(b, a, c, a, d, a); a zero v gives a plain row.
int signDet3(const Vec3& u1, const Vec3& v1, const Vec3& u2, const Vec3& v2, const Vec3& u3, const Vec3& v3);

/// Index of the component of n with the largest magnitude (0 for the zero vector).
int dominantAxis(const Vec3& n);

/// p with component `axis` removed, keeping the cyclic order (axis+1, axis+2). Projecting
/// points of a plane whose normal has n[axis] > 0 keeps 2D orientation equal to 3D orientation
/// seen from the normal side; n[axis] < 0 flips it, n[axis] == 0 collapses the plane.
Vec2 dropAxis(const Vec3& p, int axis);

/// A coordinate axis along which projecting the triangle keeps it non-degenerate (the
/// dominant axis of its normal when that works), or -1 when a, b, c are exactly collinear
/// (zero area), decided exactly.
int projectionAxis(const Triangle& t);

}  // namespace cdlab
