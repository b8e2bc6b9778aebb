// Pair queries (core/query/pair.h). Every bounded shape is conv(core points) ⊕ ball(radius), so GJK
// and EPA run on the polytope cores — where they terminate exactly — and the radii are added in
// closed form (core/gjk_epa/margins.h; van den Bergen 2003, §4.3.7 "margins"). Rays are clipped to
// the segment that provably holds the answer; planes are handled in closed form by their support
// values. Tests: tests/core/query/pair_query_test.cpp, the query corpus (tests/app/query) and the
// exact oracles of tests/app/query/query_exactness_test.cpp.
#include "core/query/pair.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/direction_refinement.h"
#include "core/gjk_epa/margins.h"
#include "core/query/touch.h"

namespace cdlab {

const char* describe(PairStatus status) {
    switch (status) {
        case PairStatus::Ok: return "ok";
        case PairStatus::NonFiniteSupport: return "non-finite support point (coordinates overflow)";
        case PairStatus::EpaFailed: return "penetration failed: invalid support points";
        case PairStatus::UnboundedPenetration:
            return "penetration of two non-parallel planes is unbounded (no translation separates them)";
        case PairStatus::Overflow: return "the answer overflows double precision (coordinates too large)";
        case PairStatus::InvalidInput: return "shapes of kinds the operation does not take, or a zero initial direction";
        case PairStatus::WorkLimit: return "the work asked for is over the operation's limit";
    }
    return "?";
}

namespace {

using Kind = QueryShape::Kind;

// A pair answer in the normalised units, with where its trace's coordinates are.
struct Solved {
    PairResult r;
    int traceExponent = 0;            // trace coordinates are 2^traceExponent times the solved pair's
    Vec3 traceOrigin = Vec3::Zero();  // ... less this point (support points; differences are unmoved)
};

Solved failed(PairStatus status) {
    Solved s;
    s.r.status = status;
    return s;
}

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
// A support point is unique along d when turning d by kUniqueTurn moves it by at most
// kUniqueMove (~1e-9 times a radius of curvature below ~2 on a smooth patch; a face or a flat cap
// lets it jump across, by the face's size).
constexpr double kUniqueTurn = 1e-9;
constexpr double kUniqueMove = 1e-6;
// The polish's first step: 4 sqrt(gap) of the bounds, within [1e-10, 1e-3] radians.
constexpr double kPolishStepMin = 1e-10, kPolishStepMax = 1e-3;

template <class CoreA, class CoreB>
struct CurvedPolish {
    static constexpr bool active = true;
    const CoreA& ca;
    const CoreB& cb;

    void operator()(Vec3& m, double& value, Vec3& pointA, Vec3& pointB, double lowerBound, double upperBound) const {
        // The bounds' relative gap ε leaves the direction ~sqrt(ε) off on a smooth patch (g is
        // quadratic at its minimum): the pattern search starts there.
        const double gap = upperBound > 0 ? std::max(upperBound - lowerBound, 0.0) / upperBound : 1.0;
        const DirectionRefinement r = refineDirection(ca, cb, m, 1.0, std::clamp(4 * std::sqrt(gap), kPolishStepMin, kPolishStepMax));
        if (r.steps > 0) {
            m = r.direction;
            value = r.value;
        }
        const auto unique = [](const auto& shape, const Vec3& d) {
            const Vec3 s = shape.support(d);
            const Vec3 t1 = d.unitOrthogonal(), t2 = d.cross(t1);
            for (const Vec3& t : {t1, Vec3(-t1), t2, Vec3(-t2)})
                if ((Vec3(shape.support(Vec3((d + kUniqueTurn * t).normalized()))) - s).norm() > kUniqueMove) return false;
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
};

// GJK and EPA on the two cores ca and cb, already scaled by 2^kc (see boundedPair).
template <class CoreA, class CoreB>
Solved boundedPairOnCores(const CoreA& ca, const CoreB& cb, int kc, const QueryShape& a, const QueryShape& b,
                          bool wantDepth, PairTrace* trace, const Vec3* initial) {
    constexpr bool curved = std::is_same_v<CoreA, CurvedSolid> || std::is_same_v<CoreB, CurvedSolid>;
    MarginPairOptions o;
    o.depth = wantDepth;
    o.minkowskiExtent = minkowskiExtent(boundingPoints(a), boundingPoints(b));
    GjkSimplex start;  // one vertex: its direction is re-evaluated as the first support (a warm start)
    if (initial) {
        start.count = 1;
        start.vertex[0].direction = *initial;
        o.gjk.warmStart = &start;
    }
    // Curved cores: EPA to 1e-10 and the polish for the last digits; asked for 1e-13 on a smooth
    // patch, EPA's faces turn to slivers first and the polytope loses its shape.
    if constexpr (curved) o.epa.relativeTolerance = 1e-10;
    if (trace) {
        o.gjkTrace = &trace->gjk;
        o.epaTrace = &trace->epa;
    }
    const auto unscale = [kc](double x) { return std::ldexp(x, -kc); };
    MarginPair p;
    if constexpr (curved) p = marginPairOnCores(ca, cb, a.radius, b.radius, o, unscale, CurvedPolish<CoreA, CoreB>{ca, cb});
    else p = marginPairOnCores(ca, cb, a.radius, b.radius, o, unscale);
    if (trace) {
        trace->gjkRan = true;
        trace->epaRan = p.how == MarginPairCase::Epa;
    }
    Solved s;
    s.traceExponent = kc;
    if (p.how == MarginPairCase::InvalidInput)
        return failed(p.gjk.status == GjkStatus::InvalidInput ? PairStatus::NonFiniteSupport : PairStatus::EpaFailed);
    s.r.intersect = p.intersect;
    s.r.distance = p.distance;
    s.r.depth = p.depth;
    s.r.normal = p.normal;
    s.r.pointA = p.pointA;
    s.r.pointB = p.pointB;
    s.r.hasWitness = p.how != MarginPairCase::Overlapping;
    return s;
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

Solved boundedPairNearOrigin(const QueryShape& a, const QueryShape& b, bool wantDepth, PairTrace* trace,
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
        return withCore(b, [&](const auto& cb) { return boundedPairOnCores(ca, cb, kc, a, b, wantDepth, trace, initial); });
    });
}

// initial: GJK's first search direction, else its default start.
Solved boundedPair(const QueryShape& a, const QueryShape& b, bool wantDepth, PairTrace* trace,
                   const Vec3* initial = nullptr) {
    const Vec3 c = pairOrigin(a, b);
    if (c.isZero(0.0)) return boundedPairNearOrigin(a, b, wantDepth, trace, initial);
    Solved s = boundedPairNearOrigin(movedBy(a, c), movedBy(b, c), wantDepth, trace, initial);
    s.r.pointA += c;
    s.r.pointB += c;
    s.traceOrigin = c;
    return s;
}

// a = plane, b = bounded shape. Normal convention: translating b by depth * normal separates.
Solved planeBounded(const QueryShape& plane, const QueryShape& s) {
    const Vec3 n = unitPlane(plane).n;
    PlaneSpan span = planeSpan(plane, s);
    Solved out;
    PairResult& ans = out.r;
    ans.hasWitness = true;
    if (span.lo > span.touch || span.hi < -span.touch) {
        const bool above = span.lo > span.touch;
        ans.distance = above ? span.lo : -span.hi;
        ans.pointB = above ? span.lowPoint : span.highPoint;
        ans.normal = above ? n : Vec3(-n);
        ans.pointA = ans.pointB - ans.distance * ans.normal;
        return out;
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
    return out;
}

// Parallel to rounding: |na × nb| below ~10 ulps.
constexpr double kParallelPlanesSine = 1e-15;

Solved planePlane(const QueryShape& a, const QueryShape& b, bool wantDepth) {
    const auto [na, da] = unitPlane(a);
    const auto [nb, db] = unitPlane(b);
    Solved out;
    PairResult& ans = out.r;
    if (na.cross(nb).norm() > kParallelPlanesSine) {
        if (wantDepth) return failed(PairStatus::UnboundedPenetration);
        ans.intersect = true;
        return out;
    }
    const double sign = na.dot(nb) > 0 ? 1.0 : -1.0;
    const double gap = sign * db - da;  // b's offset along na minus a's
    ans.hasWitness = true;
    ans.pointA = da * na;
    // The gap is rounded relative to the offsets (the plane's touching rule, core/query/touch.h).
    if (std::abs(gap) > kTouchRelative * std::max(std::abs(da), std::abs(db))) {
        ans.distance = std::abs(gap);
        ans.normal = gap > 0 ? na : Vec3(-na);
        ans.pointB = ans.pointA + ans.distance * ans.normal;
        return out;
    }
    ans.intersect = true;
    ans.depth = 0;
    ans.normal = na;
    ans.pointB = ans.pointA;
    return out;
}

// Slack added to the clipped ray's end, relative to its length: covers the rounding of tFar and the
// diameter (a few ulps), so the segment never ends short of the answer.
constexpr double kClipSlackRelative = 1e-9;

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
    const double tEnd = tFar + 2 * (diameter + kClipSlackRelative * (1 + tFar * std::sqrt(dd))) / std::sqrt(dd);
    return QueryShape::segment(ray.origin, ray.origin + tEnd * ray.direction);
}

Solved rayPlane(const QueryShape& ray, const QueryShape& plane) {
    const auto [n, d] = unitPlane(plane);
    const double s0 = n.dot(ray.origin) - d;
    const double slope = n.dot(ray.direction);
    Solved out;
    PairResult& ans = out.r;
    ans.hasWitness = true;
    const bool onPlane = std::abs(s0) <= planeTouchTolerance(d, ray.origin.cwiseAbs().maxCoeff());
    const bool reaches = onPlane || (s0 > 0 ? slope < 0 : slope > 0);
    ans.pointA = ray.origin;
    if (!reaches) {
        ans.distance = std::abs(s0);
        ans.normal = s0 > 0 ? Vec3(-n) : n;  // from the ray toward the plane
        ans.pointB = ray.origin + ans.distance * ans.normal;
        return out;
    }
    ans.intersect = true;
    // The ray reaches the plane: translating the plane (B) onto the ray's origin leaves them
    // touching, and no shorter translation does.
    ans.depth = onPlane ? 0.0 : std::abs(s0);
    ans.normal = s0 >= 0 ? n : Vec3(-n);
    ans.pointB = onPlane ? ray.origin : Vec3(ray.origin - s0 * n);
    return out;
}

// Two rays' lines are parallel when the Gram determinant is below this fraction of |da|²|db|².
constexpr double kParallelRaysGram = 1e-14;

Solved rayRay(const QueryShape& a, const QueryShape& b) {
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
    if (det > kParallelRaysGram * A * C) {
        double s = (B * E - C * D) / det, t = (A * E - B * D) / det;
        if (s >= 0 && t >= 0) cands.push_back({s * a.direction, t * b.direction - r});
    }
    cands.push_back({Vec3::Zero(), pointRay(Vec3::Zero(), -r, b.direction)});
    cands.push_back({pointRay(-r, Vec3::Zero(), a.direction), -r});
    const Cand* best = &cands[0];
    for (const Cand& c : cands)
        if ((c.pa - c.pb).squaredNorm() < (best->pa - best->pb).squaredNorm()) best = &c;
    Solved out;
    PairResult& ans = out.r;
    ans.hasWitness = true;
    ans.pointA = a.origin + best->pa;
    ans.pointB = a.origin + best->pb;
    const double dist = (best->pa - best->pb).norm();
    const double extent =
        std::max({r.cwiseAbs().maxCoeff(), best->pa.cwiseAbs().maxCoeff(), best->pb.cwiseAbs().maxCoeff()});
    if (dist > kTouchRelative * extent) {  // the touching rule (core/base/touch_rule.h)
        ans.distance = dist;
        ans.normal = (best->pb - best->pa) / dist;
        return out;
    }
    // Crossing or overlapping rays: a sideways nudge separates them, depth 0.
    ans.intersect = true;
    ans.depth = 0;
    Vec3 n = a.direction.cross(b.direction);
    ans.normal = n.squaredNorm() > 0 ? Vec3(n.normalized()) : a.direction.unitOrthogonal();
    return out;
}

Solved swapped(Solved x) {
    std::swap(x.r.pointA, x.r.pointB);
    x.r.normal = -x.r.normal;
    return x;
}

Solved solvePair(const QueryShape& a, const QueryShape& b, bool wantDepth, PairTrace* trace, const Vec3* initial) {
    if (a.bounded() && b.bounded()) return boundedPair(a, b, wantDepth, trace, initial);
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) return planePlane(a, b, wantDepth);
    if (a.kind == Kind::Plane && b.bounded()) return planeBounded(a, b);
    if (b.kind == Kind::Plane && a.bounded()) return swapped(planeBounded(b, a));
    if (a.kind == Kind::Ray && b.kind == Kind::Ray) return rayRay(a, b);
    if (a.kind == Kind::Ray && b.kind == Kind::Plane) return rayPlane(a, b);
    if (b.kind == Kind::Ray && a.kind == Kind::Plane) return swapped(rayPlane(b, a));
    if (a.kind == Kind::Ray) return boundedPair(clipRay(a, b), b, wantDepth, trace);
    return boundedPair(a, clipRay(b, a), wantDepth, trace);
}

}  // namespace

PairResult pairQuery(QueryShape a, QueryShape b, const PairOptions& options, PairTrace* trace) {
    if (options.initialDirection && options.initialDirection->isZero(0.0)) {
        PairResult invalid;
        invalid.status = PairStatus::InvalidInput;
        return invalid;
    }
    const int k = normalisingExponent(a, b);
    scaleShape(a, k);
    scaleShape(b, k);
    std::optional<Vec3> initial = options.initialDirection;
    if (initial) *initial = scaled(*initial, -largestExponent(*initial));  // the same direction, no overflow
    Solved s = solvePair(a, b, options.depth, trace, initial ? &*initial : nullptr);
    PairResult& ans = s.r;
    if (ans.status != PairStatus::Ok) return ans;
    // Back to the input's units from the normalised problem (lengths times 2^-k, exact).
    const auto unscale = [k](double x) { return std::ldexp(x, -k); };
    ans.distance = unscale(ans.distance);
    ans.depth = unscale(ans.depth);
    ans.pointA = ans.pointA.unaryExpr(unscale);
    ans.pointB = ans.pointB.unaryExpr(unscale);
    if (!std::isfinite(ans.distance) || !std::isfinite(ans.depth) || !ans.pointA.allFinite() || !ans.pointB.allFinite()) {
        ans.status = PairStatus::Overflow;
        return ans;
    }
    if (trace) {
        trace->unit = std::ldexp(1.0, -k - s.traceExponent);
        trace->origin = Vec3(std::ldexp(1.0, -k) * s.traceOrigin);
    }
    return ans;
}

Obb obbOfBoxShape(const QueryShape& s) {
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

BoxSatResult boxPairSat(QueryShape a, QueryShape b, SatTrace* trace) {
    BoxSatResult out;
    for (const QueryShape* s : {&a, &b})
        if ((s->kind != Kind::Aabb && s->kind != Kind::Obb) || s->vertices.size() != 8) {
            out.status = PairStatus::InvalidInput;
            return out;
        }
    // On the normalised boxes: half extents neither overflow nor underflow.
    const int k = normalisingExponent(a, b);
    scaleShape(a, k);
    scaleShape(b, k);
    out.exponent = -k;
    const Obb boxA = obbOfBoxShape(a), boxB = obbOfBoxShape(b);
    for (const Obb* box : {&boxA, &boxB})
        if (!box->axes.allFinite() || !box->halfExtents.allFinite()) {
            out.status = PairStatus::Overflow;
            return out;
        }
    out.intersect = testObbObb(boxA, boxB, trace).hit;
    return out;
}

}  // namespace cdlab
