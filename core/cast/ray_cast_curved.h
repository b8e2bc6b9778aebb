// Ray cast against a solid cylinder or cone in its own frame (axis y; core/geometry/shapes.h's
// CylinderShape and ConeShape): the first t >= 0 at which origin + t·direction touches the solid,
// the point there and an outward unit normal.
//
// Method. Each solid is the set where a concave function of the point is >= 0, the minimum of its
// faces' signed distances (Ericson, Real-Time Collision Detection §5.3.7 intersects the same faces
// one by one):
//   cylinder  F = min(h − |y|, r − |x⊥|)
//   cone      F = min(y + h, (k (h − y) − |x⊥|) / sqrt(1 + k²)),  k = r / 2h  (apex at y = h)
// Along the ray, f(t) = F(origin + t·direction) is concave, so {t : f(t) >= 0} is one interval and
// f' decreases. The peak of f is where f' changes sign: bisection on that sign (exact for the
// kinks where the active face changes, and for the smooth peak of a side, where |x⊥| is least) —
// not on the values, which are flat at a smooth peak and would leave it ~1e-8 off. If the peak is
// below −touchTolerance the ray misses; otherwise the entry is the first t at which f reaches
// min(0, peak), by bisection on f's sign. A grazing ray (tangent to the side, along a cap, over
// the rim) thus hits at its tangent point, and a ray through a gap wider than the tolerance
// misses. The face active at the entry gives the normal (at a rim or the apex, one of the normal
// cone's: the face the ray enters through last, or +y at the apex).
//
// The bracket is the part of the ray inside the bounding sphere of radius sqrt(h² + r²) (then
// [0, maxT]); t is returned in units of |direction|, as castRayRoundedHull.
#pragma once

#include "core/base/primitives.h"
#include "core/cast/ray_cast.h"

namespace cdlab {

/// First contact of the ray with the cylinder |y| <= halfHeight, x² + z² <= radius² (ray in its frame).
ConvexCastHit castRayCylinder(const Ray& ray, double halfHeight, double radius, const ConvexCastOptions& options = {});

/// First contact of the ray with the cone of apex (0, halfHeight, 0) and base disc of `radius` at
/// y = −halfHeight (ray in its frame). halfHeight 0 is the disc, radius 0 the segment.
ConvexCastHit castRayCone(const Ray& ray, double halfHeight, double radius, const ConvexCastOptions& options = {});

}  // namespace cdlab
