// GJK and EPA on shapes with a margin: a shape that is conv(core) ⊕ ball(r) (a sphere: a point and
// its radius; a capsule: a segment; RoundedShape: any inner shape) is queried through its core, and
// the radii are added in closed form (van den Bergen, "Collision Detection in Interactive 3D
// Environments", §4.3.7 "margins"; core/geometry/shapes.h: support = supportCore + margin d / |d|):
//   distance(A, B) = distance(core A, core B) − rA − rB                     (when positive)
//   depth(A, B)    = rA + rB − distance(core A, core B)                     (cores apart)
//                  = depth(core A, core B) + rA + rB                        (cores overlapping)
// with the core query's axis or normal n (unit, from A toward B) in every case, and the witnesses
// pushed out along it: pointA = coreA + rA n, pointB = coreB − rB n.
//
// Why: on a sphere's full support GJK converges only linearly (each step halves the angle: ~16
// iterations to 1e-13, 3 µs for two capsules) and EPA needs ever more faces on the round surface
// (tens of µs, 1e-4..1e-8 error); on the cores — points, segments, polytopes — both terminate
// exactly in a few steps, and the closed form adds no error beyond one addition. `cdlab query`
// answers every bounded pair this way. Shapes without a margin (margin() 0 or absent) go to
// gjkDistance / penetration unchanged.
#pragma once

#include <cmath>
#include <type_traits>

#include "core/gjk_epa/epa.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

/// A shape's core as a support mapping of its own (support = supportCore, no margin).
template <SupportMapping S>
struct CoreOf {
    const S* shape = nullptr;
    Vec3 support(const Vec3& d) const { return coreSupport(*shape, d); }
    double boundingRadius() const { return boundingRadiusOf(*shape); }  // the shape's: a bound for the core
};

/// The core in world coordinates, placed once where it is a point or a segment (a posed sphere or
/// capsule: the same points the per-call supportCore computes, without two rotations per support
/// call), else CoreOf.
template <SupportMapping S>
auto worldCore(const S& shape) {
    if constexpr (std::is_same_v<S, SphereShape>) {
        return PointShape{Vec3::Zero()};
    } else if constexpr (std::is_same_v<S, CapsuleShape>) {
        return SegmentShape{shape.a, shape.b};
    } else if constexpr (std::is_same_v<S, Transformed<SphereShape>>) {
        return PointShape{shape.transform.position};
    } else if constexpr (std::is_same_v<S, Transformed<CapsuleShape>>) {
        return SegmentShape{shape.transform.apply(shape.shape.a), shape.transform.apply(shape.shape.b)};
    } else {
        return CoreOf<S>{&shape};
    }
}

namespace detail {

template <class A, class B>
double marginCoordinateScale(const A& a, const B& b) {
    return std::max(boundingRadiusOf(a), boundingRadiusOf(b));
}

// GJK's result on the cores as the result on the shapes: the radii subtracted, the witnesses pushed
// out along the axis; within rA + rB the shapes intersect (distance 0, axis zero). radii > 0.
inline GjkResult withMargins(GjkResult g, double ra, double rb) {
    const double radii = ra + rb;
    if (g.status == GjkStatus::InvalidInput) return g;
    const Vec3 axis = g.separatingAxis;  // zero when the cores intersect
    g.pointA += ra * axis;  // cores apart: on the segment between them, inside both shapes when overlapping
    g.pointB -= rb * axis;
    if (g.intersect || !(g.distance > radii)) {
        g.status = GjkStatus::Intersecting;
        g.intersect = true;
        g.distance = 0.0;
        g.separatingAxis = Vec3::Zero();
        g.lowerBound = g.upperBound = 0.0;
        return g;
    }
    g.distance -= radii;
    g.lowerBound = std::max(g.lowerBound - radii, 0.0);
    g.upperBound -= radii;
    return g;
}

inline bool validRadii(double ra, double rb) { return ra >= 0.0 && rb >= 0.0 && std::isfinite(ra + rb); }

}  // namespace detail

/// GJK distance of two shapes with margins (see the file comment): GJK on the cores, the radii
/// subtracted. The result is GJK's on the cores with distance, pointA / pointB, bounds and status
/// adjusted to the shapes (intersecting when the cores are within rA + rB: distance 0, axis zero);
/// simplex and iterations are the cores' (a warm start in options.warmStart must be one of these).
/// A negative or NaN radius: InvalidInput.
template <SupportMapping A, SupportMapping B>
GjkResult gjkDistanceWithMargins(const A& shapeA, const B& shapeB, const GjkOptions& options = {}) {
    const double ra = marginOf(shapeA), rb = marginOf(shapeB);
    if (!detail::validRadii(ra, rb)) return GjkResult{};
    if (ra + rb == 0.0) return gjkDistance(shapeA, shapeB, options);
    return detail::withMargins(gjkDistance(worldCore(shapeA), worldCore(shapeB), options), ra, rb);
}

/// Penetration of two shapes with margins (see the file comment): status, depth, normal and deepest
/// points as penetration() reports them for the shapes themselves; iterations, bounds and polytope
/// size are the core queries'. Separated shapes: status Separated, normal = the axis, pointA /
/// pointB the closest points. `gjkOut` optionally receives gjkDistanceWithMargins' result.
template <SupportMapping A, SupportMapping B>
EpaResult penetrationWithMargins(const A& shapeA, const B& shapeB, const EpaOptions& options = {},
                                 GjkResult* gjkOut = nullptr) {
    const double ra = marginOf(shapeA), rb = marginOf(shapeB), radii = ra + rb;
    if (!detail::validRadii(ra, rb)) {
        if (gjkOut) *gjkOut = GjkResult{};
        return EpaResult{};
    }
    if (radii == 0.0) return penetration(shapeA, shapeB, options, nullptr, gjkOut);
    const auto ca = worldCore(shapeA);
    const auto cb = worldCore(shapeB);
    const GjkResult g = gjkDistance(ca, cb, options.gjk);
    const GjkResult onShapes = detail::withMargins(g, ra, rb);
    if (gjkOut) *gjkOut = onShapes;
    EpaResult r;
    if (g.status == GjkStatus::InvalidInput) return r;
    const double scale = detail::marginCoordinateScale(shapeA, shapeB);
    const auto finish = [&](double depth, const Vec3& normal, const Vec3& coreA, const Vec3& coreB) {
        r.depth = depth;
        r.normal = normal;
        r.pointA = coreA + ra * normal;  // pointA − pointB = (coreA − coreB) + radii n = depth n
        r.pointB = coreB - rb * normal;
        r.status = depth <= detail::kEpaTouch * scale ? EpaStatus::Touching : EpaStatus::Penetrating;
    };
    if (!onShapes.intersect) {  // apart: the closest points of the shapes
        r.status = EpaStatus::Separated;
        r.termination = EpaTermination::NotIntersecting;
        r.normal = onShapes.separatingAxis;
        r.pointA = onShapes.pointA;
        r.pointB = onShapes.pointB;
        r.iterations = g.iterations;
    } else if (g.edgePairCrossed) {  // cores crossing by a sliver, decided exactly inside GJK
        finish(g.crossedDepth + radii, g.crossedNormal, g.pointA, g.pointB);
        r.termination = EpaTermination::Converged;
        r.iterations = g.iterations;
        r.edgePairRefined = true;
        r.lowerBound = r.upperBound = r.depth;
    } else if (!g.intersect && g.distance > 0.0) {
        // Cores apart, shapes overlapping: the cores' axis, however close they are (GJK's closest
        // points near the origin come from error-free products, its axis holds to a few ulps; EPA
        // needs a simplex holding the origin, which a separated GJK does not leave).
        finish(std::max(radii - g.distance, 0.0), g.separatingAxis, g.pointA, g.pointB);
        r.termination = EpaTermination::Converged;
        r.iterations = g.iterations;
        r.lowerBound = r.upperBound = r.depth;
    } else {  // cores overlapping or touching: EPA on the cores (a flat or point start falls back
              // to a unit normal of least overlap inside epaPenetration)
        const EpaResult e = epaPenetration(ca, cb, g.simplex, options);
        if (e.status == EpaStatus::InvalidInput) return e;
        r = e;
        // Cores that only touch or cross (two segments: a flat difference) have no deepest points
        // for EPA to find — its blown-up start can put them far along a core —, but GJK's common
        // point of the two is where they meet.
        const bool coresMeet = e.depth <= detail::kEpaTouch * scale;
        finish(e.depth + radii, e.normal, coresMeet ? g.pointA : e.pointA, coresMeet ? g.pointB : e.pointB);
        r.lowerBound = e.lowerBound + radii;
        r.upperBound = e.upperBound + radii;
    }
    return r;
}

}  // namespace cdlab
