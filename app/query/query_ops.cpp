// Shape-pair queries. Every bounded query shape is conv(core points) ⊕ ball(radius) (sphere: a
// point core, capsule: a segment core), so GJK and EPA run on the polytope cores — where they
// terminate exactly — and the radii are added in closed form:
//   distance(A, B)    = distance(coreA, coreB) - rA - rB            (when positive)
//   depth(A, B)       = rA + rB - distance(coreA, coreB)            (cores apart, shapes overlapping)
//                     = depth(coreA, coreB) + rA + rB               (cores overlapping)
// with the normal of the core query in both cases (van den Bergen 2003, §4.3.7 "margins").
// Rays are clipped to the segment that provably holds the answer; planes are handled in closed
// form by their support values.
#include "app/query/query_ops.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/base/primitives.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/direction_refinement.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "core/overlap/sat_tests.h"
#include "app/query/query_compound.h"
#include "app/query/query_feature_walk.h"
#include "app/query/query_json.h"
#include "app/query/query_plane.h"
#include "app/query/query_shapes.h"
#include "app/query/query_tolerance.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

struct PairAnswer {
    bool intersect = false;
    double distance = 0;  // separated: > 0
    double depth = 0;     // intersecting: >= 0
    Vec3 normal = Vec3::UnitX();
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    bool hasWitness = false;  // separated: closest points / overlapping: deepest points
    Json trace;
    int traceExponent = 0;  // trace coordinates are 2^traceExponent times those of the query
    Vec3 traceOrigin = Vec3::Zero();  // ... less this point (support points; differences are unmoved)
};

Json gjkTraceJson(const GjkTrace& t) {
    Json steps = Json::array();
    for (const GjkTraceStep& s : t.steps) {
        Json simplex = Json::array();
        for (int i = 0; i < s.simplexCount; ++i) simplex.push_back(vecJson(s.simplex[i].w));
        steps.push_back({{"iteration", s.iteration},
                         {"simplex", simplex},
                         {"direction", vecJson(s.direction)},
                         {"support", vecJson(s.support.w)},
                         {"support_a", vecJson(s.support.a)},
                         {"support_b", vecJson(s.support.b)},
                         {"region", slotLetters(s.keptSlots)},
                         {"v", vecJson(s.v)},
                         {"lower_bound", s.lowerBound},
                         {"upper_bound", s.upperBound},
                         {"terminated", s.terminated}});
    }
    return {{"algorithm", "gjk"}, {"termination", nameOf(t.termination)}, {"steps", steps}};
}

Json epaTraceJson(const EpaTrace& t) {
    Json steps = Json::array();
    for (const EpaTraceStep& s : t.steps)
        steps.push_back({{"iteration", s.iteration},
                         {"vertices", s.vertices.size()},
                         {"faces", s.faces.size()},
                         {"closest_normal", vecJson(s.closestNormal)},
                         {"closest_distance", s.closestDistance},
                         {"support", vecJson(s.support)},
                         {"removed_faces", s.removedFaces.size()},
                         {"horizon_edges", s.horizon.size()},
                         {"lower_bound", s.lowerBound},
                         {"upper_bound", s.upperBound}});
    return {{"algorithm", "epa"}, {"start", t.start}, {"termination", nameOf(t.termination)}, {"steps", steps}};
}

// Multiplies every length of a GJK / EPA trace (points, directions, bounds, distances) by `unit`:
// the algorithms ran on the query scaled by a power of two, the trace is given in world units;
// the support points of A and B (not their differences) get `origin` back (see pairOrigin).
void toWorldUnits(Json& algorithms, double unit, const Vec3& origin) {
    static const char* const kLengths[] = {"simplex",     "direction",   "support",         "support_a", "support_b",
                                           "v",           "lower_bound", "upper_bound",     "closest_distance"};
    const std::function<void(Json&)> scale = [&](Json& j) {
        if (j.is_number()) j = cleanZero(j.get<double>() * unit);
        else if (j.is_array())
            for (Json& x : j) scale(x);
    };
    for (Json& algorithm : algorithms)
        for (Json& step : algorithm["steps"]) {
            for (const char* key : kLengths)
                if (step.contains(key)) scale(step[key]);
            if (origin.isZero(0.0)) continue;
            for (const char* key : {"support_a", "support_b"})
                if (step.contains(key) && step[key].is_array() && step[key].size() == 3)
                    for (int i = 0; i < 3; ++i) step[key][i] = cleanZero(step[key][i].get<double>() + origin[i]);
        }
}

// ---------------------------------------------------------------------------------------------
// Bounded pairs: GJK / EPA on the cores, radii in closed form.

std::vector<Vec3> scaledPoints(const std::vector<Vec3>& points, int k) {
    std::vector<Vec3> out;
    out.reserve(points.size());
    for (const Vec3& v : points) out.push_back(scaled(v, k));
    return out;
}

CurvedSolid scaledCurved(CurvedSolid c, int k) {
    c.center = scaled(c.center, k);
    c.halfHeight = std::ldexp(c.halfHeight, k);
    c.radius = std::ldexp(c.radius, k);
    return c;
}

// A curved core's GJK axis or EPA normal m polished to the minimum of g(m) = h_A(m) + h_B(−m)
// (core/gjk_epa/direction_refinement.h; value = g: −distance or the depth), with the points that
// realise it: a side's support point where it is unique (a smooth patch or a vertex), the other's at
// g along m from it; where neither is unique (a face against a face), GJK's or EPA's points moved
// onto the two support planes. GJK's simplex on a flat cap is a few rim points, so its witness
// can sit 1e-8 across the cap even where its distance is exact. Cores scaled to coordinates below 1.
template <class CoreA, class CoreB>
void polishCurved(const CoreA& ca, const CoreB& cb, Vec3& m, double& value, Vec3& pointA, Vec3& pointB,
                  double lowerBound, double upperBound) {
    // The bounds' relative gap ε leaves the direction ~sqrt(ε) off on a smooth patch (g is
    // quadratic at its minimum): the pattern search starts there.
    const double gap = upperBound > 0 ? std::max(upperBound - lowerBound, 0.0) / upperBound : 1.0;
    const DirectionRefinement r = refineDirection(ca, cb, m, 1.0, std::clamp(4 * std::sqrt(gap), 1e-10, 1e-3));
    if (r.steps > 0) {
        m = r.direction;
        value = r.value;
    }
    // Unique: turning the direction by 1e-9 moves the support point by ~1e-9 (times a radius of
    // curvature below ~2), where a face or a flat cap would let it jump across.
    const auto unique = [](const auto& shape, const Vec3& d) {
        const Vec3 s = shape.support(d);
        const Vec3 t1 = d.unitOrthogonal(), t2 = d.cross(t1);
        for (const Vec3& t : {t1, Vec3(-t1), t2, Vec3(-t2)})
            if ((Vec3(shape.support(Vec3((d + 1e-9 * t).normalized()))) - s).norm() > 1e-6) return false;
        return true;
    };
    if (unique(ca, m)) {
        pointA = ca.support(m);
        pointB = pointA - value * m;
    } else if (unique(cb, Vec3(-m))) {
        pointB = cb.support(Vec3(-m));
        pointA = pointB + value * m;
    } else {
        const Vec3 c = 0.5 * (pointA + pointB);
        pointA = c + (m.dot(Vec3(ca.support(m))) - m.dot(c)) * m;
        pointB = pointA - value * m;
    }
}

// GJK and EPA on the two cores ca and cb, already scaled by 2^kc (see boundedPair).
template <class CoreA, class CoreB>
PairAnswer boundedPairOnCores(const CoreA& ca, const CoreB& cb, int kc, const QueryShape& a, const QueryShape& b,
                              bool wantDepth, bool wantTrace, const Vec3* initial) {
    const auto unscale = [kc](double x) { return std::ldexp(x, -kc); };
    const auto unscaleVec = [&](const Vec3& v) { return Vec3(v.unaryExpr(unscale)); };
    const double radii = a.radius + b.radius;
    const double touch = touchTolerance(a, b);  // the touching rule of every op (query_tolerance.h)
    PairAnswer ans;
    ans.traceExponent = kc;
    GjkTrace gtrace;
    GjkOptions gjkOptions;
    GjkSimplex start;  // one vertex: its direction is re-evaluated as the first support (a warm start)
    if (initial) {
        start.count = 1;
        start.vertex[0].direction = *initial;
        gjkOptions.warmStart = &start;
    }
    GjkResult g = gjkDistance(ca, cb, gjkOptions, wantTrace ? &gtrace : nullptr);
    if (g.status == GjkStatus::InvalidInput) throw InputError("query: non-finite support point (coordinates overflow)");
    if (wantTrace) ans.trace = Json::array({gjkTraceJson(gtrace)});
    constexpr bool curved = std::is_same_v<CoreA, CurvedSolid> || std::is_same_v<CoreB, CurvedSolid>;
    if (curved && !g.intersect) {
        // GJK stops ~1e-8 short on a smooth patch (its simplex shrinks to nearly equal points).
        double value = -g.distance;
        polishCurved(ca, cb, g.separatingAxis, value, g.pointA, g.pointB, g.lowerBound, g.upperBound);
        g.distance = std::max(-value, 0.0);
        g.intersect = value >= 0;  // the cores touch: no EPA needed, depth 0 along the axis
    }
    const double coreDistance = unscale(g.distance);
    const Vec3 coreA = unscaleVec(g.pointA), coreB = unscaleVec(g.pointB);

    if (!g.intersect && coreDistance > radii + touch) {  // separated
        ans.distance = coreDistance - radii;
        ans.normal = g.separatingAxis;  // unit, from A toward B
        ans.pointA = coreA + a.radius * ans.normal;
        ans.pointB = coreB - b.radius * ans.normal;
        ans.hasWitness = true;
        return ans;
    }
    ans.intersect = true;
    if (!wantDepth) return ans;
    if (g.edgePairCrossed) {
        // Nearly parallel edges crossing by less than GJK's sliver rounding, decided exactly in
        // core (gjkDecideCrossedEdges): the face of A − B they span is the nearest one.
        ans.depth = unscale(g.crossedDepth) + radii;
        ans.normal = g.crossedNormal;
        ans.pointA = coreA + a.radius * ans.normal;
        ans.pointB = coreB - b.radius * ans.normal;
        ans.hasWitness = true;
        return ans;
    }
    if ((!g.intersect && coreDistance > 0) || (curved && g.separatingAxis.squaredNorm() > 0)) {
        // Cores apart, rounded shapes overlapping (or touching): the core axis is the normal, however
        // close the cores (GJK's closest points near the origin come from error-free products: its
        // axis holds to a few ulps). EPA needs a simplex holding the origin: cores 3e-14 apart sent
        // there gave two capsules 0.33 deep where they are 0.1.
        ans.depth = std::max(radii - coreDistance, 0.0);
        ans.normal = g.separatingAxis;
    } else {
        EpaTrace etrace;
        // Curved cores: EPA to 1e-10 and the polish below for the last digits; asked for 1e-13
        // on a smooth patch, EPA's faces turn to slivers first and the polytope loses its shape.
        EpaOptions epaOptions;
        if constexpr (curved) epaOptions.relativeTolerance = 1e-10;
        EpaResult e = epaPenetration(ca, cb, g.simplex, epaOptions, wantTrace ? &etrace : nullptr);
        if (e.status == EpaStatus::InvalidInput) throw InputError("query: penetration failed: invalid support points");
        if (wantTrace) ans.trace.push_back(epaTraceJson(etrace));
        if constexpr (curved) {  // EPA's polytope needs ever more faces on a smooth patch
            double value = e.depth;
            polishCurved(ca, cb, e.normal, value, e.pointA, e.pointB, e.lowerBound, e.upperBound);
            e.depth = std::max(value, 0.0);
        }
        // Core's EPA always gives a unit normal (a degenerate start falls back to the axis of least
        // overlap inside epaPenetration).
        ans.depth = unscale(e.depth) + radii;
        ans.normal = e.normal;
        // Deepest points of the cores, pushed out by the radii along the normal. Cores that only touch
        // or cross (their own depth within the touching band: two segments, a flat difference) have
        // no deepest points for EPA to find — its blown-up start put them 0.4 off a capsule —, but
        // GJK's common point is where they meet.
        const bool coresMeet = unscale(e.depth) <= kTouchRelative * minkowskiExtent(boundingPoints(a), boundingPoints(b));
        ans.pointA = (coresMeet ? coreA : unscaleVec(e.pointA)) + a.radius * ans.normal;
        ans.pointB = (coresMeet ? coreB : unscaleVec(e.pointB)) - b.radius * ans.normal;
        ans.hasWitness = true;
        return ans;
    }
    ans.pointA = coreA + a.radius * ans.normal;
    ans.pointB = coreB - b.radius * ans.normal;
    ans.hasWitness = true;
    return ans;
}

// Where the pair is moved before GJK / EPA: along each axis on which the pair's box lies within a
// factor 2 of one of its ends (far from the origin for its size), that end; elsewhere 0. Every
// coordinate then subtracts exactly (Sterbenz), and the vertex loops' d · x round relative to the
// pair's size rather than to its distance from the origin: at 1e9 a capsule core 1e-6 long had its
// nearer end chosen by rounding (depth 3.2e-8 off, a 2.5e-9 overlap answered separated).
Vec3 pairOrigin(const QueryShape& a, const QueryShape& b) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const QueryShape* s : {&a, &b})
        for (const Vec3& p : boundingPoints(*s)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
        if (lo[i] > 0 && hi[i] <= 2 * lo[i]) c[i] = lo[i];
        else if (hi[i] < 0 && lo[i] >= 2 * hi[i]) c[i] = hi[i];
    }
    return c;
}

QueryShape movedBy(QueryShape s, const Vec3& c) {
    for (Vec3& v : s.vertices) v -= c;
    s.curved.center -= c;
    return s;
}

PairAnswer boundedPairNearOrigin(const QueryShape& a, const QueryShape& b, bool wantDepth, bool wantTrace,
                                 const Vec3* initial);

// initial: GJK's first search direction (the query's "initial_direction"), else its default start.
PairAnswer boundedPair(const QueryShape& a, const QueryShape& b, bool wantDepth, bool wantTrace,
                       const Vec3* initial = nullptr) {
    const Vec3 c = pairOrigin(a, b);
    if (c.isZero(0.0)) return boundedPairNearOrigin(a, b, wantDepth, wantTrace, initial);
    PairAnswer ans = boundedPairNearOrigin(movedBy(a, c), movedBy(b, c), wantDepth, wantTrace, initial);
    ans.pointA += c;
    ans.pointB += c;
    ans.traceOrigin = c;
    return ans;
}

PairAnswer boundedPairNearOrigin(const QueryShape& a, const QueryShape& b, bool wantDepth, bool wantTrace,
                                 const Vec3* initial) {
    // The cores get their own exact power-of-two scaling: the query as a whole is normalised by
    // its largest coordinate or radius, and a radius 1e300 times the core size would leave the
    // cores at 1e-300, where GJK's squared norms underflow (found by fuzzing). Core results are
    // scaled back before the radii are added, so the radii never see the core exponent.
    const double cs = std::max(largestCoordinate(a), largestCoordinate(b));  // of the cores (radii excluded)
    int kc = 0;
    if (cs > 0) std::frexp(cs, &kc), kc = -kc;
    // And the pair's own extent (its Minkowski difference) kept above 2^-300 where the coordinates
    // allow it (up to 2^400): two shapes 1e170 from the origin and 1 apart, scaled to coordinates
    // below 1, left the difference at 2^-565, whose squared norms underflow (GJK answered touching).
    if (const double ext = minkowskiExtent(boundingPoints(a), boundingPoints(b)); cs > 0 && ext > 0) {
        int ee = 0, ec = 0;
        std::frexp(ext, &ee);
        std::frexp(cs, &ec);
        kc = std::min(std::max(kc, -300 - ee), 400 - ec);
    }
    // A core is its points (vertex loop support, first maximal vertex: deterministic ties;
    // non-extreme points are harmless) or a cylinder / cone (closed-form support).
    const auto withCore = [kc](const QueryShape& s, const auto& run) {
        if (s.isCurved()) return run(scaledCurved(s.curved, kc));
        return run(PolytopeShape(scaledPoints(s.vertices, kc)));
    };
    return withCore(a, [&](const auto& ca) {
        return withCore(b, [&](const auto& cb) {
            return boundedPairOnCores(ca, cb, kc, a, b, wantDepth, wantTrace, initial);
        });
    });
}

// ---------------------------------------------------------------------------------------------
// Planes: the signed distances of a bounded shape to the plane span [lo, hi] (closed form).

// a = plane, b = bounded shape. Normal convention: translating b by depth * normal separates.
PairAnswer planeBounded(const QueryShape& plane, const QueryShape& s) {
    const Vec3 n = unitPlane(plane).n;
    PlaneSpan span = planeSpan(plane, s);
    PairAnswer ans;
    ans.hasWitness = true;
    if (span.lo > span.touch || span.hi < -span.touch) {
        const bool above = span.lo > span.touch;
        ans.distance = above ? span.lo : -span.hi;
        ans.pointB = above ? span.lowPoint : span.highPoint;
        ans.normal = above ? n : Vec3(-n);
        ans.pointA = ans.pointB - ans.distance * ans.normal;
        return ans;
    }
    ans.intersect = true;
    // Push b off the plane to whichever side is nearer (the plane is a surface, not a half-space).
    if (-span.lo <= span.hi) {
        ans.depth = std::max(-span.lo, 0.0);  // touching within the tolerance: depth 0
        ans.normal = n;
        ans.pointB = span.lowPoint;
    } else {
        ans.depth = std::max(span.hi, 0.0);
        ans.normal = -n;
        ans.pointB = span.highPoint;
    }
    ans.pointA = ans.pointB + ans.depth * ans.normal;
    return ans;
}

PairAnswer planePlane(const QueryShape& a, const QueryShape& b, bool wantDepth) {
    const auto [na, da] = unitPlane(a);
    const auto [nb, db] = unitPlane(b);
    PairAnswer ans;
    // Parallel to rounding: |na x nb| below ~10 ulps.
    if (na.cross(nb).norm() > 1e-15) {
        ans.intersect = true;
        if (wantDepth)
            throw InputError(
                "query: penetration of two non-parallel planes is unbounded (no translation separates them)");
        return ans;
    }
    const double sign = na.dot(nb) > 0 ? 1.0 : -1.0;
    const double gap = sign * db - da;  // b's offset along na minus a's
    ans.hasWitness = true;
    ans.pointA = da * na;
    // The gap is rounded relative to the offsets (the touching rule, query_tolerance.h).
    if (std::abs(gap) > kTouchRelative * std::max(std::abs(da), std::abs(db))) {
        ans.distance = std::abs(gap);
        ans.normal = gap > 0 ? na : Vec3(-na);
        ans.pointB = ans.pointA + ans.distance * ans.normal;
        return ans;
    }
    ans.intersect = true;
    ans.depth = 0;
    ans.normal = na;
    ans.pointB = ans.pointA;
    return ans;
}

// ---------------------------------------------------------------------------------------------
// Rays.

// The part of the ray that can hold the answer against a bounded shape s: t in [0, tEnd].
// Closest point: beyond tFar (the largest projection of s on the ray) moving back brings the ray
// point nearer to every point of s, so t* <= tFar. Penetration: the clipped segment must not
// escape backwards more cheaply than the ray can; a lateral escape costs at most the diameter of
// s, so extending the segment by twice that diameter past tFar keeps the depth the ray's.
QueryShape clipRay(const QueryShape& ray, const QueryShape& s) {
    const double dd = ray.direction.squaredNorm();
    double tFar = 0;
    Vec3 center = Vec3::Zero();
    // A cylinder's or cone's bounding box corners stand for it: both bounds only grow.
    std::vector<Vec3> points = s.vertices;
    if (s.isCurved()) {
        Vec3 lo, hi;
        s.curved.bounds(lo, hi);
        points.clear();
        for (int i = 0; i < 8; ++i) points.push_back(Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z()));
    }
    for (const Vec3& v : points) {
        tFar = std::max(tFar, ray.direction.dot(v - ray.origin) / dd);
        center += v;
    }
    center /= double(points.size());
    double diameter = 0;
    for (const Vec3& v : points) diameter = std::max(diameter, 2 * (v - center).norm());
    diameter += 2 * s.radius;
    tFar += s.radius / std::sqrt(dd);
    const double tEnd = tFar + 2 * (diameter + 1e-9 * (1 + tFar * std::sqrt(dd))) / std::sqrt(dd);
    QueryShape seg;
    seg.kind = Kind::Segment;
    seg.vertices = {ray.origin, ray.origin + tEnd * ray.direction};
    return seg;
}

PairAnswer rayPlane(const QueryShape& ray, const QueryShape& plane) {
    const auto [n, d] = unitPlane(plane);
    const double s0 = n.dot(ray.origin) - d;
    const double slope = n.dot(ray.direction);
    PairAnswer ans;
    ans.hasWitness = true;
    const bool onPlane = std::abs(s0) <= planeTouchTolerance(d, ray.origin.cwiseAbs().maxCoeff());
    const bool reaches = onPlane || (s0 > 0 ? slope < 0 : slope > 0);
    ans.pointA = ray.origin;
    if (!reaches) {
        ans.distance = std::abs(s0);
        ans.normal = s0 > 0 ? Vec3(-n) : n;  // from the ray toward the plane
        ans.pointB = ray.origin + ans.distance * ans.normal;
        return ans;
    }
    ans.intersect = true;
    // The ray reaches the plane: translating the plane (B) onto the ray's origin leaves them
    // touching, and no shorter translation does.
    ans.depth = onPlane ? 0.0 : std::abs(s0);
    ans.normal = s0 >= 0 ? n : Vec3(-n);
    ans.pointB = onPlane ? ray.origin : Vec3(ray.origin - s0 * n);
    return ans;
}

PairAnswer rayRay(const QueryShape& a, const QueryShape& b) {
    // Minimise |oa + s da - ob - t db| over s, t >= 0: the unconstrained optimum if feasible,
    // else the best of the boundary cases s = 0 or t = 0 (each a point-ray problem). Everything is
    // computed relative to oa, so the rounding is relative to the distances involved, not to the
    // coordinates (two rays crossing at x = 1e15 cross, they do not miss by 0.1).
    const Vec3 r = a.origin - b.origin;  // ob = oa - r
    auto pointRay = [](const Vec3& p, const Vec3& o, const Vec3& d) {
        double t = std::max(0.0, d.dot(p - o) / d.squaredNorm());
        return Vec3(o + t * d);
    };
    struct Cand {
        Vec3 pa, pb;
    };  // relative to oa
    std::vector<Cand> cands;
    const double A = a.direction.squaredNorm(), B = a.direction.dot(b.direction), C = b.direction.squaredNorm();
    const double D = a.direction.dot(r), E = b.direction.dot(r);
    const double det = A * C - B * B;
    if (det > 1e-14 * A * C) {
        double s = (B * E - C * D) / det, t = (A * E - B * D) / det;
        if (s >= 0 && t >= 0) cands.push_back({s * a.direction, t * b.direction - r});
    }
    cands.push_back({Vec3::Zero(), pointRay(Vec3::Zero(), -r, b.direction)});
    cands.push_back({pointRay(-r, Vec3::Zero(), a.direction), -r});
    const Cand* best = &cands[0];
    for (const Cand& c : cands)
        if ((c.pa - c.pb).squaredNorm() < (best->pa - best->pb).squaredNorm()) best = &c;
    PairAnswer ans;
    ans.hasWitness = true;
    ans.pointA = a.origin + best->pa;
    ans.pointB = a.origin + best->pb;
    const double dist = (best->pa - best->pb).norm();
    const double extent =
        std::max({r.cwiseAbs().maxCoeff(), best->pa.cwiseAbs().maxCoeff(), best->pb.cwiseAbs().maxCoeff()});
    if (dist > kTouchRelative * extent) {  // the touching rule (query_tolerance.h)
        ans.distance = dist;
        ans.normal = (best->pb - best->pa) / dist;
        return ans;
    }
    // Crossing or overlapping rays: a sideways nudge separates them, depth 0.
    ans.intersect = true;
    ans.depth = 0;
    Vec3 n = a.direction.cross(b.direction);
    ans.normal = n.squaredNorm() > 0 ? Vec3(n.normalized()) : a.direction.unitOrthogonal();
    return ans;
}

PairAnswer swapped(PairAnswer x) {
    std::swap(x.pointA, x.pointB);
    x.normal = -x.normal;
    return x;
}

PairAnswer solvePair(const QueryShape& a, const QueryShape& b, bool wantDepth, bool wantTrace,
                     const Vec3* initial = nullptr) {
    if (a.bounded() && b.bounded()) return boundedPair(a, b, wantDepth, wantTrace, initial);
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) return planePlane(a, b, wantDepth);
    if (a.kind == Kind::Plane && b.bounded()) return planeBounded(a, b);
    if (b.kind == Kind::Plane && a.bounded()) return swapped(planeBounded(b, a));
    if (a.kind == Kind::Ray && b.kind == Kind::Ray) return rayRay(a, b);
    if (a.kind == Kind::Ray && b.kind == Kind::Plane) return rayPlane(a, b);
    if (b.kind == Kind::Ray && a.kind == Kind::Plane) return swapped(rayPlane(b, a));
    if (a.kind == Kind::Ray) return boundedPair(clipRay(a, b), b, wantDepth, wantTrace);
    return boundedPair(a, clipRay(b, a), wantDepth, wantTrace);
}

bool isBox(const QueryShape& s) { return s.kind == Kind::Aabb || s.kind == Kind::Obb; }

Obb toObb(const QueryShape& s) {
    // Box corners are stored with bit i of the index choosing +/- along axis i.
    const Vec3 c = (s.vertices[0] + s.vertices[7]) * 0.5;
    Mat3 axes;
    Vec3 half;
    for (int i = 0; i < 3; ++i) {
        // Half an edge. stableNorm: extents of 1e160 or 1e-170 would overflow or underflow the
        // squared norm, and a box of zero extents on an axis keeps that coordinate axis.
        Vec3 e = (s.vertices[1 << i] - s.vertices[0]) * 0.5;
        half[i] = e.stableNorm();
        axes.col(i) = half[i] > 0 ? Vec3(e / half[i]) : Vec3::Unit(i);
    }
    return Obb{c, half, axes};
}

// The exponent e of the largest |coordinate| of v (v = f 2^e, f in [0.5, 1)).
int largestExponentOf(const Vec3& v) {
    int e = 0;
    std::frexp(v.cwiseAbs().maxCoeff(), &e);
    return e;
}

// Back to the query's units from the normalised problem (lengths times 2^-k, exact).
void unscaleAnswer(PairAnswer& ans, int k) {
    const auto unscale = [k](double x) { return std::ldexp(x, -k); };
    ans.distance = unscale(ans.distance);
    ans.depth = unscale(ans.depth);
    ans.pointA = ans.pointA.unaryExpr(unscale);
    ans.pointB = ans.pointB.unaryExpr(unscale);
    if (!std::isfinite(ans.distance) || !std::isfinite(ans.depth) || !ans.pointA.allFinite() || !ans.pointB.allFinite())
        throw InputError("query: the answer overflows double precision (coordinates too large)");
}

}  // namespace

ShapePairAnswer penetrationOf(QueryShape a, QueryShape b) { return shapePairAnswer(std::move(a), std::move(b), true); }

ShapePairAnswer shapePairAnswer(QueryShape a, QueryShape b, bool wantDepth) {
    const int k = normalisingExponent(a, b);
    scaleShape(a, k);
    scaleShape(b, k);
    PairAnswer ans = solvePair(a, b, wantDepth, false);
    unscaleAnswer(ans, k);
    return {ans.intersect, ans.distance, ans.depth, ans.normal, ans.pointA, ans.pointB};
}

Json answerShapeQuery(const std::string& op, ObjectReader& r) {
    JsonNode an = r.get("a"), bn = r.get("b");
    if (isCompoundOrMesh(an) || isCompoundOrMesh(bn)) return answerCompoundQuery(op, r, an, bn);
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    std::string method = "gjk";
    if (auto m = r.find("method")) {
        method = op == "intersect" ? m->asEnum({"gjk", "sat"}) : m->asEnum({"gjk", "vclip", "lin_canny"});
        if (method == "sat" && !(isBox(a) && isBox(b))) m->fail("method 'sat' needs two boxes (aabb or obb)");
    }
    const bool wantTrace = r.boolOr("trace", false);
    std::optional<Vec3> initial;
    if (auto d = r.find("initial_direction")) {
        // GJK's first support direction, so that a student's run can be compared from step 1.
        initial = d->asVec3();
        if (initial->isZero(0.0)) d->fail("initial_direction must be non-zero");
        if (method != "gjk") d->fail("initial_direction is GJK's; method '" + method + "' has no such start");
        if (!(a.bounded() && b.bounded())) d->fail("initial_direction needs two bounded shapes (GJK runs on them)");
        *initial = scaled(*initial, -largestExponentOf(*initial));  // the same direction, no overflow
    }
    r.finish();

    if (method == "vclip" || method == "lin_canny") return answerFeatureWalkQuery(op, method, a, b, an, bn, wantTrace);

    const int k = normalisingExponent(a, b);
    scaleShape(a, k);
    scaleShape(b, k);
    if (method == "sat") {  // on the normalised boxes: half extents neither overflow nor underflow
        SatTrace trace;
        const Obb boxA = toObb(a), boxB = toObb(b);
        for (const Obb* box : {&boxA, &boxB})
            if (!box->axes.allFinite() || !box->halfExtents.allFinite())
                throw InputError("query: method 'sat': the box's axes overflow double precision");
        SatResult s = testObbObb(boxA, boxB, wantTrace ? &trace : nullptr);
        Json out = {{"intersect", s.hit}};
        if (wantTrace) {  // intervals in the query's units
            const auto world = [k](double x) { return cleanZero(std::ldexp(x, -k)); };
            Json axes = Json::array();
            for (const SatAxisStep& st : trace.steps)
                axes.push_back({{"axis", vecJson(st.axis)},
                                {"a", {world(st.minA), world(st.maxA)}},
                                {"b", {world(st.minB), world(st.maxB)}},
                                {"separating", st.separating}});
            out["trace"] = {{"algorithm", "sat"}, {"axes", axes}};
        }
        return out;
    }

    const bool wantDepth = op == "penetration";
    PairAnswer ans = solvePair(a, b, wantDepth, wantTrace, initial ? &*initial : nullptr);
    unscaleAnswer(ans, k);
    Json out;
    if (op == "intersect") {
        out = {{"intersect", ans.intersect}};
    } else if (op == "distance") {
        if (ans.intersect) out = {{"intersect", true}, {"distance", 0.0}};
        else
            out = {{"intersect", false},
                   {"distance", ans.distance},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
    } else {  // penetration
        if (ans.intersect)
            out = {{"intersect", true},
                   {"depth", ans.depth},
                   {"normal", vecJson(ans.normal)},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
        else
            out = {{"intersect", false},
                   {"distance", ans.distance},
                   {"normal", vecJson(ans.normal)},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
    }
    // The algorithms ran on the query scaled by a power of two (exact); the trace is in world units
    // (of the cores: spheres and capsules without their radii), "unit" 1 = world = unit * value.
    if (wantTrace && !ans.trace.is_null()) {
        toWorldUnits(ans.trace, std::ldexp(1.0, -k - ans.traceExponent), Vec3(std::ldexp(1.0, -k) * ans.traceOrigin));
        out["trace"] = {{"unit", 1.0}, {"algorithms", ans.trace}};
    }
    return out;
}

}  // namespace cdlab::demos
