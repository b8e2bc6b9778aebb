// Ray cast against a rounded convex hull S = conv(P) ⊕ ball(r): the first t >= 0 at which
// origin + t·direction touches S, the point there and an outward unit normal of S at it.
// Every bounded shape of cdlab is such a set (a box: its 8 corners, r = 0; a sphere: its centre;
// a capsule: its segment), and so is the Minkowski difference of two of them, which makes this
// also the linear cast of core/cast/time_of_impact.h.
//
// Method (closed form; Ericson, Real-Time Collision Detection §5.3, and van den Bergen, "Ray
// Casting against General Convex Objects with Application to Continuous Collision Detection",
// 2004, for the verdict on the Minkowski form):
//   1. The verdict. The origin is inside when GJK puts it within r + touchTolerance of conv(P); the
//      ray hits when GJK puts the segment [origin, origin + tEnd·direction] within r +
//      touchTolerance of conv(P), tEnd = min(maxT, the last t at which any point of S is still
//      ahead). GJK terminates exactly on polytopes, so a grazing ray (tangent to a sphere, along a
//      face or through an edge) is a hit and a ray through a gap wider than the tolerance is not.
//   2. The first contact. ∂S lies on the boundary pieces of the core's hull: its faces pushed out
//      by r along their normals, cylinders of radius r around its edges and spheres of radius r at
//      its vertices (for r = 0, the faces alone). Every piece lies in S, and the entry point lies on
//      one, so the smallest t at which the ray meets any piece is the first contact, and the piece
//      gives the normal: the face's normal (computed from the input points, accurateCross), the
//      cylinder's or the sphere's radial direction. Triangles are tested with the exact-decision
//      ray/triangle test (core/overlap/intersect_ray.h), so no ray slips between two faces.
//      A piece's t is its exact crossing rounded (intersectRayTriangle takes t from the decision's
//      own determinants, exactly where d · n cancels), so a ray within rounding of a face plane gets
//      a point on S up to rounding, never one before it (issue 41 class 3).
//      Grazing: a ray lying in a face plane (exactly, or within the touching tolerance) is a HIT at
//      the first point of the face it touches (the first t within the tolerance of S); its origin
//      within the tolerance of S is `inside`, t = 0. It is never answered as a miss.
//   3. A hit by the verdict that no piece sees is a graze below rounding (or a core of dimension
//      < 2 with r = 0: a segment or point, which a ray meets only on a set of measure zero): t and
//      the normal then come from GJK's closest points of step 1.
// A flat core (all points within the hull tolerance of a plane) is the 2D hull polygon, its faces
// two-sided; a collinear core is a segment; a single point a point.
//
// Degenerate input never crashes: no points, NaN / inf, a zero direction or a negative radius give
// no hit.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "core/base/primitives.h"

namespace cdlab {

struct ConvexCastOptions {
    /// Only hits with t <= maxT count (t in units of |direction|).
    double maxT = std::numeric_limits<double>::infinity();
    /// Distances at or below this count as touching: the ray grazes S, or the origin is on S.
    /// 0 is exact up to GJK's rounding; callers pass their touching rule (a few hundred ulps of the
    /// extent, as `cdlab query` does) so that the cast agrees with their intersection test.
    double touchTolerance = 0.0;
};

/// Which piece of ∂S the ray enters through (the core feature under the hit point).
enum class CastFeature { None, Face, Edge, Vertex };
const char* nameOf(CastFeature feature);

struct ConvexCastHit {
    bool hit = false;
    bool inside = false;  ///< origin inside S or on it (within the tolerance): t = 0, point = origin, no normal
    double t = 0.0;
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();  ///< unit outward normal of S at point (a vector of its normal cone)
    /// The core point under the hit, point − radius·normal = Σ weight[i]·points[index[i]] for
    /// i < count; count = 0 when the hit came from the grazing fallback (step 3).
    CastFeature feature = CastFeature::None;
    int count = 0;
    int index[3] = {-1, -1, -1};
    double weight[3] = {0.0, 0.0, 0.0};
};

/// One boundary piece the ray meets, for the trace.
struct ConvexCastCandidate {
    CastFeature feature = CastFeature::None;
    int count = 0;
    int index[3] = {-1, -1, -1};
    double t = 0.0;
};

struct ConvexCastTrace {
    int coreDimension = -1;  ///< 0 point, 1 segment, 2 polygon, 3 polyhedron (-1: not reached)
    int coreVertices = 0;    ///< vertices of the core's hull
    double tEnd = 0.0;       ///< the ray segment the verdict tested: [0, tEnd]
    double gap = 0.0;        ///< GJK distance of that segment (or of the origin, when inside) to S
    std::vector<ConvexCastCandidate> candidates;  ///< pieces met, in increasing t
};

/// First contact of the ray with conv(points) ⊕ ball(radius); see the method above.
ConvexCastHit castRayRoundedHull(const Ray& ray, std::span<const Vec3> points, double radius = 0.0,
                                 const ConvexCastOptions& options = {}, ConvexCastTrace* trace = nullptr);

}  // namespace cdlab
