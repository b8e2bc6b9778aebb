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
// exactly in a few steps, and the closed form adds no error beyond one addition.
//
// marginPairOnCores is the one implementation: penetrationWithMargins (typed shapes) and core/query's
// pairQuery (the shapes of `cdlab query`, which also polishes curved cores) both call it, with the
// one touching rule of core/base/touch_rule.h. Typed shapes without a margin (both radii 0) go to
// gjkDistance / penetration, whose own rules are GJK's and EPA's (core/gjk_epa/gjk.h, epa.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "core/base/touch_rule.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"
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

/// Options of marginPairOnCores.
struct MarginPairOptions {
    /// false: an overlapping pair answers only `intersect` (EPA does not run).
    bool depth = true;
    /// W, the extent of the cores' Minkowski difference in the result's units (core/base/touch_rule.h);
    /// unset: computed from the cores' supports along the axes.
    std::optional<double> minkowskiExtent = std::nullopt;
    GjkOptions gjk{};  ///< GJK on the cores (a warm start: gjk.warmStart)
    EpaOptions epa{};  ///< EPA on the cores, when they overlap
    GjkTrace* gjkTrace = nullptr;
    EpaTrace* epaTrace = nullptr;
};

/// How marginPairOnCores decided (the branches of the file comment).
enum class MarginPairCase {
    InvalidInput,  ///< a non-finite support point (GJK's or EPA's status says which)
    Separated,     ///< the cores are farther apart than rA + rB + the touching tolerance
    Overlapping,   ///< touching or overlapping; the depth was not asked for
    CrossedEdges,  ///< cores crossing by a sliver of nearly parallel edges, decided exactly inside GJK
    CoresApart,    ///< cores apart (or touching) but within rA + rB: depth = rA + rB − distance
    Epa,           ///< cores overlapping: EPA's depth + rA + rB
};

/// A pair of shapes conv(core) ⊕ ball(r), in the result's units (see unscale below).
struct MarginPair {
    MarginPairCase how = MarginPairCase::InvalidInput;
    bool intersect = false;
    double distance = 0.0;        ///< separated: > 0
    double depth = 0.0;           ///< intersecting (with the depth asked): >= 0
    Vec3 normal = Vec3::UnitX();  ///< unit, from A toward B
    Vec3 pointA = Vec3::Zero();   ///< separated: closest points; intersecting: deepest points,
    Vec3 pointB = Vec3::Zero();   ///<   pointA − pointB = depth · normal
    double touchTolerance = 0.0;  ///< kTouchRelative · (W + rA + rB)
    GjkResult gjk;                ///< GJK on the cores (the cores' units; with a Polish, Intersecting
                                  ///< also for cores that the polish found touching)
    EpaResult epa;                ///< EPA on the cores, when how == Epa (or EPA failed)
};

/// The identity "polish" of marginPairOnCores (polytope and point / segment cores terminate exactly).
struct NoPolish {
    static constexpr bool active = false;
    void operator()(Vec3&, double&, Vec3&, Vec3&, double, double) const {}
};

/// GJK and, when the cores overlap, EPA on the cores ca and cb, with the radii ra and rb added in
/// closed form (the file comment). The cores may be given in their own units (a power-of-two
/// scaling): unscale(x) maps their lengths to the result's, in which ra, rb and the extent are given.
/// A Polish with active == true refines a smooth core pair's axis / normal m and its value
/// (−distance or depth) with its witnesses: polish(m, value, pointA, pointB, lowerBound, upperBound)
/// on GJK's separated answer and on EPA's, which then runs to epa.relativeTolerance only
/// (core/query's curved solids; tests/core/query/pair_query_test.cpp).
template <class CoreA, class CoreB, class Unscale, class Polish = NoPolish>
MarginPair marginPairOnCores(const CoreA& ca, const CoreB& cb, double ra, double rb, const MarginPairOptions& options,
                             Unscale unscale, const Polish& polish = {}) {
    const auto unscaleVec = [&](const Vec3& v) { return Vec3(v.unaryExpr(unscale)); };
    const double radii = ra + rb;
    const double extent = options.minkowskiExtent ? *options.minkowskiExtent : unscale(minkowskiExtentOfSupports(ca, cb));
    MarginPair ans;
    ans.touchTolerance = kTouchRelative * (extent + ra + rb);
    GjkResult& g = ans.gjk;
    g = gjkDistance(ca, cb, options.gjk, options.gjkTrace);
    if (g.status == GjkStatus::InvalidInput) return ans;
    if (Polish::active && !g.intersect()) {
        // GJK stops ~1e-8 short on a smooth patch (its simplex shrinks to nearly equal points).
        double value = -g.distance;
        polish(g.separatingAxis, value, g.pointA, g.pointB, g.lowerBound, g.upperBound);
        g.distance = std::max(-value, 0.0);
        // The cores touch: no EPA needed, depth 0 along the axis (kept: the CoresApart branch's normal).
        if (value >= 0) g.status = GjkStatus::Intersecting;
    }
    const double coreDistance = unscale(g.distance);
    const Vec3 coreA = unscaleVec(g.pointA), coreB = unscaleVec(g.pointB);
    const auto witnesses = [&](const Vec3& onA, const Vec3& onB) {
        ans.pointA = onA + ra * ans.normal;  // pointA − pointB = (onA − onB) + radii n
        ans.pointB = onB - rb * ans.normal;
    };
    if (!g.intersect() && coreDistance > radii + ans.touchTolerance) {
        ans.how = MarginPairCase::Separated;
        ans.distance = coreDistance - radii;
        ans.normal = g.separatingAxis;  // unit, from A toward B
        witnesses(coreA, coreB);
        return ans;
    }
    ans.intersect = true;
    ans.how = MarginPairCase::Overlapping;
    if (!options.depth) return ans;
    // GJK's crossed edge pair (its simplex does not hold the origin): the face of A − B the crossing
    // edges span is the nearest one.
    if (const std::optional<EdgePairCrossing> c = crossedEdgePenetration(ca, cb, g)) {
        ans.how = MarginPairCase::CrossedEdges;
        ans.depth = unscale(c->depth) + radii;
        ans.normal = c->normal;
        witnesses(unscaleVec(c->pointA), unscaleVec(c->pointB));
        return ans;
    }
    if ((!g.intersect() && coreDistance > 0) || (Polish::active && g.separatingAxis.squaredNorm() > 0)) {
        // Cores apart, shapes overlapping (or touching): the core axis is the normal, however close
        // the cores (GJK's closest points near the origin come from error-free products: its axis
        // holds to a few ulps). EPA needs a simplex holding the origin: cores 3e-14 apart sent there
        // gave two capsules 0.33 deep where they are 0.1.
        ans.how = MarginPairCase::CoresApart;
        ans.depth = std::max(radii - coreDistance, 0.0);
        ans.normal = g.separatingAxis;
        witnesses(coreA, coreB);
        return ans;
    }
    EpaResult& e = ans.epa;
    e = epaPenetration(ca, cb, g.simplex, options.epa, options.epaTrace);
    if (e.status == EpaStatus::InvalidInput) {
        ans.how = MarginPairCase::InvalidInput;
        return ans;
    }
    ans.how = MarginPairCase::Epa;
    if (Polish::active) {  // EPA's polytope needs ever more faces on a smooth patch
        double value = e.depth;
        polish(e.normal, value, e.pointA, e.pointB, e.lowerBound, e.upperBound);
        e.depth = std::max(value, 0.0);
    }
    // EPA always gives a unit normal (a degenerate start falls back to the axis of least overlap
    // inside epaPenetration).
    ans.depth = unscale(e.depth) + radii;
    ans.normal = e.normal;
    // Cores that only touch or cross (their own depth within the touching band: two segments, a flat
    // difference) have no deepest points for EPA to find — its blown-up start put them 0.4 off a
    // capsule —, but GJK's common point is where they meet. Only when it is one: GJK's intersecting
    // witnesses from a tetrahedron need not meet (a point core in a 1e6 polytope: 6200 apart), and
    // pointA − pointB = depth · normal needs coreA − coreB = core depth · normal, i.e. ~0 here
    // (tests/core/gjk_epa/epa_witness_test.cpp).
    const bool coresMeet =
        unscale(e.depth) <= kTouchRelative * extent && unscale((g.pointA - g.pointB).norm()) <= kTouchRelative * extent;
    witnesses(coresMeet ? coreA : unscaleVec(e.pointA), coresMeet ? coreB : unscaleVec(e.pointB));
    return ans;
}

namespace detail {

inline bool validRadii(double ra, double rb) { return ra >= 0.0 && rb >= 0.0 && std::isfinite(ra + rb); }

// GJK's result on the cores as the result on the shapes: the radii subtracted, the witnesses pushed
// out along the axis; intersecting (distance 0, axis zero) when p decided so.
inline GjkResult gjkOnShapes(const MarginPair& p, double ra, double rb) {
    GjkResult g = p.gjk;
    if (p.how == MarginPairCase::InvalidInput && g.status == GjkStatus::InvalidInput) return g;
    if (p.intersect) {
        g.pointA += ra * g.separatingAxis;
        g.pointB -= rb * g.separatingAxis;
        g.status = GjkStatus::Intersecting;
        g.distance = 0.0;
        g.separatingAxis = Vec3::Zero();
        g.lowerBound = g.upperBound = 0.0;
        return g;
    }
    g.pointA = p.pointA;
    g.pointB = p.pointB;
    g.distance = p.distance;
    g.lowerBound = std::max(g.lowerBound - (ra + rb), 0.0);
    g.upperBound -= ra + rb;
    return g;
}

}  // namespace detail

/// GJK distance of two shapes with margins (see the file comment): GJK on the cores, the radii
/// subtracted, the touching rule of core/base/touch_rule.h. The result is GJK's on the cores with
/// distance, pointA / pointB, bounds and status adjusted to the shapes (intersecting when the cores
/// are within rA + rB + the touching tolerance: distance 0, axis zero); simplex and iterations are
/// the cores' (a warm start in options.warmStart must be one of these). A negative or NaN radius:
/// InvalidInput. Shapes without a margin (both radii 0) are answered by gjkDistance itself.
template <SupportMapping A, SupportMapping B>
GjkResult gjkDistanceWithMargins(const A& shapeA, const B& shapeB, const GjkOptions& options = {}) {
    const double ra = marginOf(shapeA), rb = marginOf(shapeB);
    if (!detail::validRadii(ra, rb)) return GjkResult{};
    if (ra + rb == 0.0) return gjkDistance(shapeA, shapeB, options);
    MarginPairOptions o;
    o.depth = false;
    o.gjk = options;
    const auto identity = [](double x) { return x; };
    return detail::gjkOnShapes(marginPairOnCores(worldCore(shapeA), worldCore(shapeB), ra, rb, o, identity), ra, rb);
}

/// Penetration of two shapes with margins (see the file comment): status, depth, normal and deepest
/// points as penetration() reports them for the shapes themselves, decided by the touching rule of
/// core/base/touch_rule.h (Touching: depth within kTouchRelative · (W + rA + rB)); iterations, bounds
/// and polytope size are the core queries' (termination DecidedByGjk with GJK's iterations where EPA
/// did not run: crossed core edges, or cores apart within the radii). Separated shapes: status
/// Separated, normal = the axis, pointA / pointB the closest points. `gjkOut` optionally receives
/// gjkDistanceWithMargins' result.
/// Shapes without a margin (both radii 0) are answered by penetration() itself.
template <SupportMapping A, SupportMapping B>
EpaResult penetrationWithMargins(const A& shapeA, const B& shapeB, const EpaOptions& options = {},
                                 GjkResult* gjkOut = nullptr) {
    const double ra = marginOf(shapeA), rb = marginOf(shapeB), radii = ra + rb;
    if (!detail::validRadii(ra, rb)) {
        if (gjkOut) *gjkOut = GjkResult{};
        return EpaResult{};
    }
    if (radii == 0.0) return penetration(shapeA, shapeB, options, nullptr, gjkOut);
    MarginPairOptions o;
    o.gjk = options.gjk;
    o.epa = options;
    const MarginPair p =
        marginPairOnCores(worldCore(shapeA), worldCore(shapeB), ra, rb, o, [](double x) { return x; });
    if (gjkOut) *gjkOut = detail::gjkOnShapes(p, ra, rb);
    if (p.how == MarginPairCase::InvalidInput) return p.gjk.status == GjkStatus::InvalidInput ? EpaResult{} : p.epa;
    EpaResult r = p.how == MarginPairCase::Epa ? p.epa : EpaResult{};
    r.normal = p.normal;
    r.pointA = p.pointA;
    r.pointB = p.pointB;
    if (!p.intersect) {
        r.status = EpaStatus::Separated;
        r.termination = EpaTermination::NotIntersecting;
        r.iterations = p.gjk.iterations;
        return r;
    }
    r.depth = p.depth;
    r.status = p.depth <= p.touchTolerance ? EpaStatus::Touching : EpaStatus::Penetrating;
    if (p.how == MarginPairCase::Epa) {
        r.lowerBound = p.epa.lowerBound + radii;
        r.upperBound = p.epa.upperBound + radii;
    } else {  // decided by GJK alone (crossed edges, or cores apart within the radii): EPA did not run
        r.termination = EpaTermination::DecidedByGjk;
        r.iterations = p.gjk.iterations;
        r.edgePairRefined = p.how == MarginPairCase::CrossedEdges;
        r.lowerBound = r.upperBound = r.depth;
    }
    return r;
}

}  // namespace cdlab
