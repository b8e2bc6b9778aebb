// Triangle-triangle intersection (closed triangles, world frame).
//
// Plane-side rejection as in Möller, "A Fast Triangle-Triangle Intersection Test" (1997) and
// Guigue & Devillers, "Fast and Robust Triangle-Triangle Overlap Test Using Orientation
// Predicates" (2003): if all vertices of one triangle lie strictly on one side of the other's
// plane, there is no intersection; if all lie on the plane, the triangles are coplanar and the
// exact 2D test decides (Möller §4, projection on the dominant axis). Otherwise the decision
// uses the fact that two non-coplanar closed triangles meet iff an edge of one meets the other
// (each end point of their common segment lies on an edge of one of them), with the exact
// segment-triangle test of core/overlap/intersect_ray.h. Every predicate is an exact orientation
// sign (core/base/orient.h), so the boolean is exact for the double inputs, touching included.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// Result of the triangle-triangle test.
struct TriangleTriangleResult {
    bool hit = false;
    /// Both triangles lie in one plane (exactly); then there is no segment.
    bool coplanar = false;
    /// For a non-coplanar hit: the intersection, the segment [segmentStart, segmentEnd] on the
    /// line where the planes meet (start == end when they touch at one point). Its end points
    /// are computed in doubles (edge-plane intersections).
    bool hasSegment = false;
    Vec3 segmentStart = Vec3::Zero();
    Vec3 segmentEnd = Vec3::Zero();
};

/// Closed triangle-triangle test, exact boolean (see above). Zero-area triangles and NaN / inf
/// input give hit == false.
TriangleTriangleResult intersectTriangleTriangle(const Triangle& a, const Triangle& b);

}  // namespace cdlab
