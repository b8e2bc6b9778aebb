// Rays and segments against planes, spheres, boxes and triangles (Ericson, Real-Time Collision
// Detection §5.3; Möller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", 1997).
//
// Conventions, for every function here:
//  - World frame, any consistent length unit.
//  - A ray's points are origin + t * direction, t >= 0 (t in units of |direction|); a
//    segment's points are a + t * (b - a), t in [0, 1].
//  - Shapes are closed: grazing / touching counts as a hit.
//  - t is the FIRST parameter of contact; a ray or segment starting inside the shape reports
//    t = 0. point is the world point at t. When hit is false the other fields are unspecified.
//  - Degenerate input never crashes: NaN / inf anywhere, a zero ray direction, a negative
//    radius, an empty box (min > max), a zero plane normal or a zero-area triangle give no hit.
//    A segment with a == b is a point and hits iff the point lies in the shape.
#pragma once

#include <vector>

#include "core/base/primitives.h"

namespace cdlab {

/// Hit of a ray or segment with a shape: see the conventions above.
struct RayHit {
    bool hit = false;
    double t = 0.0;
    Vec3 point = Vec3::Zero();
};

/// Ray against plane normal . x = offset (Ericson §5.3.1). A ray lying in the plane hits at t = 0.
RayHit intersectRayPlane(const Ray& ray, const Plane& plane);

/// Segment against plane (Ericson §5.3.1). A segment lying in the plane hits at t = 0.
RayHit intersectSegmentPlane(const Segment& segment, const Plane& plane);

/// The quadratic of the ray-sphere test, recorded for demos: |m + t d|^2 = r^2 with m = o - c is
/// a t^2 + 2 b t + c = 0, a = d.d, b = m.d, c = m.m - r^2, discriminant b^2 - a c (computed as
/// a r^2 - |m x d|^2, equal in exact arithmetic, without the loss of r^2 far from the centre).
struct SphereQuadraticTrace {
    enum class Outcome {
        Invalid,       ///< NaN / inf, a negative radius or a zero direction: no test made
        StartsInside,  ///< c <= 0: the origin is in the closed sphere, t = 0
        PointOutside,  ///< a = 0 (a zero-length segment) and c > 0: a point outside
        PointsAway,    ///< b > 0 (origin outside): the ray moves away from the centre
        NoRealRoot,    ///< discriminant < 0: the line misses the sphere
        BeyondEnd,     ///< the entry root is past the segment's end (t > 1)
        Hit,           ///< the smaller root t0 is the first contact
    };
    Outcome outcome = Outcome::Invalid;
    double a = 0.0, b = 0.0, c = 0.0, discriminant = 0.0;
    /// The line's entry and exit parameters (t0 <= t1), when the discriminant is >= 0.
    bool rootsValid = false;
    double t0 = 0.0, t1 = 0.0;
};
const char* nameOf(SphereQuadraticTrace::Outcome outcome);

/// Ray against solid sphere (Ericson §5.3.2, direction need not be unit).
RayHit intersectRaySphere(const Ray& ray, const Sphere& sphere, SphereQuadraticTrace* trace = nullptr);

/// Segment against solid sphere (Ericson §5.3.2 restricted to t in [0, 1]).
RayHit intersectSegmentSphere(const Segment& segment, const Sphere& sphere, SphereQuadraticTrace* trace = nullptr);

/// One slab of the ray-box test, recorded for demos.
struct SlabStep {
    int axis = 0;
    bool parallel = false;  ///< direction[axis] is +0 or -0: the slab only tests the origin.
    double tNear = 0.0;     ///< entry / exit parameters of this slab (when !parallel)
    double tFar = 0.0;
    double tEnter = 0.0;  ///< running interval after this slab
    double tExit = 0.0;
    bool rejected = false;  ///< the running interval became empty here
};
struct SlabTrace {
    std::vector<SlabStep> steps;
};

/// Hit of a ray or segment with a box: [tEnter, tExit] is the parameter interval inside the box
/// (clipped to the ray / segment), point = the point at tEnter. enterAxis is the axis whose slab
/// gave tEnter, or -1 when the ray starts inside the box (tEnter == 0 then).
struct RayBoxHit {
    bool hit = false;
    double tEnter = 0.0;
    double tExit = 0.0;
    Vec3 point = Vec3::Zero();
    int enterAxis = -1;
};

/// Ray against AABB by slabs (Ericson §5.3.3). A direction component of +0 or -0 makes that
/// slab a pure containment test of the origin (no 0 * inf); a ray starting inside or on the
/// boundary hits at t = 0.
RayBoxHit intersectRayAabb(const Ray& ray, const Aabb& box, SlabTrace* trace = nullptr);

/// Segment against AABB by slabs (Ericson §5.3.3), t in [0, 1].
RayBoxHit intersectSegmentAabb(const Segment& segment, const Aabb& box, SlabTrace* trace = nullptr);

/// Options of the ray-triangle test.
struct RayTriangleOptions {
    /// false: only the front face counts, i.e. direction . n < 0 with n = (b - a) x (c - a)
    /// (counterclockwise a, b, c seen from the ray's origin side). true: both faces.
    bool doubleSided = true;
};

/// Hit of a ray or segment with a triangle.
struct RayTriangleHit {
    bool hit = false;
    double t = 0.0;
    Vec3 point = Vec3::Zero();
    /// Weights (wa, wb, wc) of a, b, c at point: all >= 0, summing to 1.
    Vec3 barycentric = Vec3::Zero();
    /// direction . n > 0 (n = (b - a) x (c - a)): the ray meets the back face.
    bool backFace = false;
    /// The ray / segment lies in the triangle's plane; t is its first contact in that plane.
    bool coplanar = false;
};

/// Ray against triangle (Möller-Trumbore 1997; Ericson §5.3.6). The hit/miss decision is exact
/// for the double inputs: it is made from signs of scalar triple products (Ericson §5.3.4)
/// evaluated with core/base/orient.h, so rays through an edge or vertex never slip between two
/// triangles sharing it. t and barycentric are then the quotients of the same triple products
/// (Cramer's rule, as Möller-Trumbore), evaluated in doubles with a rigorous error bound and, where
/// d . n or a numerator cancels (a ray within rounding of the plane), exactly and rounded once: the
/// point o + t d is on the triangle up to its own rounding, never before it (issue 41 class 3).
/// A ray in the triangle's plane hits iff it meets the triangle in that plane (decided in doubles
/// by 2D clipping; single-sided: no hit); t is then its first point of the triangle.
RayTriangleHit intersectRayTriangle(const Ray& ray, const Triangle& triangle, const RayTriangleOptions& options = {});

/// Segment against triangle (Ericson §5.3.6, both faces). Exact decision from orient3d of the
/// segment end points and the vertices (also in the coplanar case, by exact 2D tests); t,
/// point and barycentric computed in doubles.
RayTriangleHit intersectSegmentTriangle(const Segment& segment, const Triangle& triangle);

}  // namespace cdlab
