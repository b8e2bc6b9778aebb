// Convex polygon tests in 2D, and for planar polygons in 3D (Ericson, Real-Time Collision
// Detection §5.4.1 point in polygon, §5.2.1 separating-axis test, §3.4 (Newell normal)).
//
// Polygons are closed convex sets given by their vertices in order (either winding); edges run
// v[i] -> v[i+1 mod n]. Zero-area polygons (all vertices collinear, or only 1-2 vertices) are
// treated as the segment (or point) they span. An empty vertex list is the empty set.
// The 2D booleans are exact for the double inputs (orient2d of core/base/orient.h); results for
// non-convex input are unspecified.
#pragma once

#include <span>

#include "core/base/types.h"

namespace cdlab {

/// Default planeTolerance of the 3D polygon tests (world units): how far off a polygon's plane a
/// point may sit and still count as in it; far above the ~1e-16 rounding of a plane through unit-
/// sized vertices, far below any modelled feature.
inline constexpr double kPolygonPlaneTolerance = 1e-9;

/// Closed 2D segments p0p1 and q0q1 share a point (exact; degenerate segments are points).
bool segmentsIntersect2d(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);

/// Point p lies in the closed convex polygon (exact; boundary counts).
bool pointInConvexPolygon2d(std::span<const Vec2> polygon, const Vec2& p);

/// Result of the 2D polygon-polygon separating-axis test.
struct PolygonOverlapResult {
    bool hit = false;
    /// When !hit and a polygon edge separates: polygon (0 = first, 1 = second) and the index i
    /// of its edge v[i] -> v[i+1] whose outward normal is the separating axis. Both are -1 when
    /// the separation was found by the degenerate-polygon fallback, or when hit.
    int separatingPolygon = -1;
    int separatingEdge = -1;
};

/// Closed convex polygons a and b overlap (2D SAT over the edge normals of both, Ericson
/// §5.2.1; exact, each axis decided by orient2d signs). Zero-area polygons fall back to an
/// exact vertex-containment / edge-crossing test.
PolygonOverlapResult intersectConvexPolygons2d(std::span<const Vec2> a, std::span<const Vec2> b);

/// Parameter interval of the line p + t d (t in [tMin, tMax]) inside a closed convex polygon
/// with nonzero area (Cyrus-Beck clipping, floating point). hit is false when empty.
struct LineClip2d {
    bool hit = false;
    double tEnter = 0.0;
    double tExit = 0.0;
};
/// Clip p + t d, t in [tMin, tMax], to the polygon; inexact at the boundary (floating point).
LineClip2d clipLineToConvexPolygon2d(std::span<const Vec2> polygon, const Vec2& p, const Vec2& d, double tMin,
                                     double tMax);

/// Unit normal of a planar polygon by Newell's method (zero vector for zero area); sign follows
/// the right-hand rule on the vertex order.
Vec3 polygonNormal(std::span<const Vec3> polygon);

/// Point p lies in the closed convex 3D polygon: |distance to its plane| <= planeTolerance
/// (world units), and its projection lies in the polygon (exact 2D test after dropping the
/// dominant normal axis). Zero-area polygons: p must lie on the segment (or point) they span
/// exactly (planeTolerance unused).
bool pointInConvexPolygon3d(std::span<const Vec3> polygon, const Vec3& p,
                            double planeTolerance = kPolygonPlaneTolerance);

/// Coplanar convex 3D polygons overlap: false when some vertex of b is farther than
/// planeTolerance (world units) from the plane of a; otherwise the 2D test on both polygons
/// projected along a's dominant normal axis.
PolygonOverlapResult intersectCoplanarConvexPolygons3d(std::span<const Vec3> a, std::span<const Vec3> b,
                                                       double planeTolerance = kPolygonPlaneTolerance);

}  // namespace cdlab
