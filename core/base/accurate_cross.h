// The cross product of two edges of a triangle, rounded once from the exact value.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// (b - a) x (c - a), twice the area vector of triangle abc, computed with error-free
/// transformations (exact differences by two-sum, Dekker two-products, compensated sum; Ogita,
/// Rump, Oishi, "Accurate sum and dot product", SIAM J. Sci. Comput. 2005). The result is the exact
/// cross product rounded to ~2 ulps, so even a sliver triangle (height 1e-12 of its length) gets a
/// normal accurate to ~DBL_EPSILON in direction; the plain formula's error is DBL_EPSILON * L / h.
/// Needs -ffp-contract=off (set project-wide). Body frame of the inputs; units length^2.
Vec3 accurateCross(const Vec3& a, const Vec3& b, const Vec3& c);

/// (b - a) x v, with b - a taken exactly (two-sum) and the products and sums error-free as above:
/// the exact value rounded to ~2 ulps. For a ray or a segment against a sphere or a cylinder, where
/// |e x d| / |d| is the distance e⊥ of the centre (axis) from the line: its error is then relative
/// to |e⊥|, not to the far offset |e| (tests/core/overlap/intersect_ray_far_test.cpp).
Vec3 accurateOffsetCross(const Vec3& a, const Vec3& b, const Vec3& v);

}  // namespace cdlab
