// `raycast` and `time_of_impact` (README "cdlab query"): the core casts (core/cast/) on the query's
// shapes, normalised by powers of two like every other op, and planes in closed form.
#include "app/query/query_cast.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/cast/ray_cast.h"
#include "core/cast/ray_cast_curved.h"
#include "core/cast/time_of_impact.h"
#include "core/geometry/convex_hull.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_ops.h"
#include "core/query/touch.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// The exponent k with 2^k · m in [0.5, 1) (0 for m = 0).
int exponentOf(double m) {
    int e = 0;
    if (m > 0 && std::isfinite(m)) std::frexp(m, &e);
    return -e;
}

QueryShape pointShape(const Vec3& p) {
    QueryShape s;
    s.kind = Kind::Point;
    s.vertices = {p};
    return s;
}

// Candidate feature vertices as JSON: indices into the shape's vertices (raycast), or [i, j] pairs
// of a's and b's vertices (time_of_impact: the Minkowski difference point b_j − a_i).
Json castTraceJson(const ConvexCastTrace& trace, double tScale, double lengthScale, int pairedWith) {
    Json candidates = Json::array();
    for (const ConvexCastCandidate& c : trace.candidates) {
        Json vertices = Json::array();
        for (int i = 0; i < c.count; ++i) {
            if (pairedWith > 0) vertices.push_back({c.index[i] / pairedWith, c.index[i] % pairedWith});
            else vertices.push_back(c.index[i]);
        }
        if (std::isfinite(c.t * tScale))
            candidates.push_back({{"feature", nameOf(c.feature)}, {"vertices", vertices}, {"t", c.t * tScale}});
    }
    Json out = {{"algorithm", "ray_cast"}, {"core_dimension", trace.coreDimension}, {"core_vertices", trace.coreVertices}};
    // A window or gap that overflows in the query's units (a direction of 1e-300) is left out, never null.
    if (std::isfinite(trace.tEnd * tScale)) out["t_end"] = trace.tEnd * tScale;
    if (std::isfinite(trace.gap * lengthScale)) out["gap"] = trace.gap * lengthScale;
    out["candidates"] = candidates;
    return out;
}

// ---------------------------------------------------------------------------------------------
// raycast

struct CastAnswer {
    bool hit = false, inside = false;
    double t = 0;
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    Json trace;
};

// The plane n·x = d as a two-sided surface: crossed where the signed distance changes sign.
CastAnswer rayPlane(const Vec3& o, const Vec3& d, const QueryShape& plane, double maxT, bool wantTrace) {
    const auto [n, offset] = unitPlane(plane);
    const double s0 = n.dot(o) - offset, slope = n.dot(d);
    CastAnswer ans;
    if (wantTrace) ans.trace = {{"algorithm", "ray_plane"}, {"signed_distance", s0}, {"slope", slope}};
    if (std::abs(s0) <= planeTouchTolerance(offset, o.cwiseAbs().maxCoeff())) {
        ans.hit = ans.inside = true;
        ans.point = o;
        return ans;
    }
    if (slope == 0 || (s0 > 0) == (slope > 0)) return ans;  // parallel, or moving away
    const double t = -s0 / slope;
    if (!(t <= maxT)) return ans;
    ans.hit = true;
    ans.t = t;
    ans.point = o + t * d;
    ans.normal = s0 > 0 ? n : Vec3(-n);  // the side the ray comes from
    return ans;
}

// A cylinder or cone in its own frame (core/cast/ray_cast_curved.h): t is the same there.
CastAnswer rayCurved(const Vec3& o, const Vec3& d, const QueryShape& shape, double maxT, double touch, bool wantTrace) {
    const CurvedSolid& c = shape.curved;
    const Ray local{c.rotation.transpose() * (o - c.center), c.rotation.transpose() * d};
    ConvexCastOptions options;
    options.maxT = maxT;
    options.touchTolerance = touch;
    const ConvexCastHit h = c.cone ? castRayCone(local, c.halfHeight, c.radius, options)
                                   : castRayCylinder(local, c.halfHeight, c.radius, options);
    CastAnswer ans{h.hit, h.inside, h.t, o + h.t * d, c.rotation * h.normal, Json()};
    if (h.inside) ans.point = o;
    if (wantTrace) ans.trace = {{"algorithm", c.cone ? "ray_cone" : "ray_cylinder"}};
    return ans;
}

Json answerRaycast(ObjectReader& r) {
    JsonNode rayNode = r.get("ray");
    ObjectReader rr(rayNode);
    const Vec3 origin = rr.get("origin").asVec3();
    JsonNode dn = rr.get("direction");
    const Vec3 direction = dn.asVec3();
    rr.finish();
    if (direction.isZero(0.0)) dn.fail("ray direction must be non-zero");
    JsonNode sn = r.get("shape");
    QueryShape shape = parseQueryShape(sn);
    if (shape.kind == Kind::Ray) sn.fail("raycast: the shape cannot be a ray (expected a bounded shape, plane or triangle)");
    double maxT = std::numeric_limits<double>::infinity();
    if (auto m = r.find("max_t")) maxT = m->asNonNegative();
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();

    // Exact power-of-two scaling: d' = 2^e d has its largest coordinate in [0.5, 1), lengths are
    // multiplied by 2^k; the scaled ray o' + t' d' is 2^k (o + t d) for t = t' 2^(e-k).
    const int e = exponentOf(direction.cwiseAbs().maxCoeff());
    QueryShape o = pointShape(origin);
    const int k = normalisingExponent(o, shape);
    scaleShape(o, k);
    scaleShape(shape, k);
    const Vec3 d = scaled(direction, e);
    const double scaledMaxT = std::ldexp(maxT, k - e);
    CastAnswer ans;
    if (shape.kind == Kind::Plane) {
        ans = rayPlane(o.vertices[0], d, shape, scaledMaxT, wantTrace);
    } else if (shape.isCurved()) {
        ans = rayCurved(o.vertices[0], d, shape, scaledMaxT, touchTolerance(o, shape), wantTrace);
    } else {
        ConvexCastOptions options;
        options.maxT = scaledMaxT;
        options.touchTolerance = touchTolerance(o, shape);
        ConvexCastTrace trace;
        const ConvexCastHit h = castRayRoundedHull(Ray{o.vertices[0], d}, shape.vertices, shape.radius, options,
                                                   wantTrace ? &trace : nullptr);
        ans = {h.hit, h.inside, h.t, h.point, h.normal, Json()};
        if (wantTrace) ans.trace = castTraceJson(trace, std::ldexp(1.0, e - k), std::ldexp(1.0, -k), 0);
    }
    Json out;
    if (!ans.hit) out = {{"hit", false}};
    else if (ans.inside) out = {{"hit", true}, {"t", 0.0}, {"point", vecJson(origin)}, {"inside", true}};
    else {
        const double t = std::ldexp(ans.t, e - k);
        const Vec3 point = scaled(ans.point, -k);
        if (!std::isfinite(t) || !point.allFinite())
            throw InputError("query: the answer overflows double precision (t or the hit point too large)");
        out = {{"hit", true}, {"t", cleanZero(t)}, {"point", vecJson(point)}, {"normal", vecJson(ans.normal)}};
    }
    if (wantTrace) out["trace"] = ans.trace;
    requireFiniteAnswer(out);
    return out;
}

// ---------------------------------------------------------------------------------------------
// time_of_impact

struct ImpactAnswer {
    TimeOfImpactResult result;
    Json trace;
};

// A plane and a bounded shape: the shape's span of signed distances moves at the rate n̂·(m_s − m_p).
ImpactAnswer planeImpact(const QueryShape& plane, const Vec3& planeMotion, const QueryShape& s, const Vec3& motion,
                         bool wantTrace) {
    const PlaneSpan span = planeSpan(plane, s);
    const Vec3 n = unitPlane(plane).n;
    const double rate = n.dot(motion - planeMotion);
    ImpactAnswer ans;
    TimeOfImpactResult& res = ans.result;
    if (wantTrace) ans.trace = {{"algorithm", "plane_span"}, {"low", span.lo}, {"high", span.hi}, {"rate", rate}};
    if (span.lo <= span.touch && span.hi >= -span.touch) {
        res.hit = res.initiallyOverlapping = true;
        return ans;
    }
    const bool above = span.lo > span.touch;
    const double gap = above ? span.lo : -span.hi;
    const double closing = above ? -rate : rate;
    if (!(closing > 0) || gap > closing) return ans;  // never reached, or not before t = 1
    res.hit = true;
    res.t = gap / closing;
    res.normal = above ? n : Vec3(-n);  // from the plane toward the shape
    res.pointA = res.pointB = (above ? span.lowPoint : span.highPoint) + res.t * motion;
    return ans;
}

// The shape's hull vertices (the Minkowski difference needs no interior points), with their indices
// into the shape's vertices; a flat or tiny shape keeps all its points.
std::vector<int> hullVertexIndices(const QueryShape& s) {
    std::vector<int> all(s.vertices.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    if (s.vertices.size() <= 8) return all;
    const HullResult hull = convexHull(s.vertices);
    if (hull.status != HullStatus::Ok) return all;
    std::vector<int> kept = hull.inputIndex;
    std::sort(kept.begin(), kept.end());
    return kept;
}

ImpactAnswer boundedImpact(const QueryShape& a, const Vec3& ma, const QueryShape& b, const Vec3& mb, bool wantTrace,
                           double lengthScale, const JsonNode& bn) {
    const std::vector<int> ia = hullVertexIndices(a), ib = hullVertexIndices(b);
    if (double(ia.size()) * double(ib.size()) > double(kMaxHullVertices))
        bn.fail("time_of_impact: the Minkowski difference of the two hulls has " + std::to_string(ia.size()) + " x " +
                std::to_string(ib.size()) + " points, over the limit of " + std::to_string(kMaxHullVertices));
    std::vector<Vec3> pa, pb;
    for (int i : ia) pa.push_back(a.vertices[i]);
    for (int j : ib) pb.push_back(b.vertices[j]);
    TimeOfImpactOptions options;
    options.touchTolerance = touchTolerance(a, b);
    ConvexCastTrace trace;
    ImpactAnswer ans;
    ans.result = translationalTimeOfImpact(pa, a.radius, ma, pb, b.radius, mb, options, wantTrace ? &trace : nullptr);
    if (wantTrace) {
        // Difference point k is b's hull vertex k % |ib| minus a's k / |ib|: name them in the input's indices.
        for (ConvexCastCandidate& c : trace.candidates)
            for (int i = 0; i < c.count; ++i)
                c.index[i] = ia[c.index[i] / int(ib.size())] * int(b.vertices.size()) + ib[c.index[i] % int(ib.size())];
        ans.trace = castTraceJson(trace, 1.0, lengthScale, int(b.vertices.size()));
    }
    return ans;
}

QueryShape translated(QueryShape s, const Vec3& offset) {
    for (Vec3& v : s.vertices) v += offset;
    s.curved.center += offset;
    return s;
}

// A cylinder or cone moving against a bounded shape: conservative advancement (Mirtich 1996 §2.3;
// van den Bergen 2004 §4 for the translational case) on the distance of the two moved shapes,
// taken from the distance op (GJK and its polish, query_ops.h). For translations the distance
// φ(t) = dist(t·(m_a − m_b), B − A) is convex in t, so the tangent step t += φ / (−φ') with
// φ' = n·(m_b − m_a) (n the unit axis from a toward b) never passes the first contact: it climbs to
// it from below, quadratically where the path crosses the surface, and a path that only comes
// near stops when φ' turns non-negative or t passes 1. Contact: φ at or below the touching rule.
ImpactAnswer curvedImpact(const QueryShape& a, const Vec3& ma, const QueryShape& b, const Vec3& mb, bool wantTrace,
                          double lengthScale) {
    ImpactAnswer ans;
    TimeOfImpactResult& res = ans.result;
    Json steps = Json::array();
    double t = 0, lastT = 0;
    ShapePairAnswer last;  // the last separated state (its normal and points name the contact)
    for (int iteration = 0; iteration < 500; ++iteration) {
        const ShapePairAnswer now = shapePairAnswer(translated(a, t * ma), translated(b, t * mb), false);
        if (wantTrace) steps.push_back({{"t", t}, {"distance", now.intersect ? 0.0 : now.distance * lengthScale}});
        if (now.intersect) {
            res.hit = true;
            res.t = t;
            res.initiallyOverlapping = t == 0;
            if (res.initiallyOverlapping) break;
            // The touching points: the closest pair of a state just before t, moved on to t. The
            // last state may be a whole step back (one step reaches a flat face), and its points,
            // moved, drift apart by the step times the sideways motion; 1e-10 back, they do not.
            for (const double back : {1e-10, 1e-8, 1e-6, 1e-4}) {
                if (t - back <= lastT) break;
                const ShapePairAnswer near =
                    shapePairAnswer(translated(a, (t - back) * ma), translated(b, (t - back) * mb), false);
                if (!near.intersect) {
                    last = near, lastT = t - back;
                    break;
                }
            }
            res.normal = last.normal;
            res.pointA = last.pointA + (t - lastT) * ma;
            res.pointB = last.pointB + (t - lastT) * mb;
            break;
        }
        const double closing = now.normal.dot(ma - mb);
        if (!(closing > 0)) break;  // moving apart along the axis: the convex distance only grows
        const double next = t + now.distance / closing;
        last = now, lastT = t;
        if (!(next <= 1)) break;
        if (next <= t) {  // below the rounding of t: the contact is here
            res.hit = true;
            res.t = t;
            res.normal = now.normal;
            res.pointA = now.pointA;
            res.pointB = now.pointB;
            break;
        }
        t = next;
    }
    if (wantTrace) ans.trace = {{"algorithm", "conservative_advancement"}, {"steps", steps}};
    return ans;
}

}  // namespace

Json answerCastQuery(const std::string& op, ObjectReader& r) {
    if (op == "raycast") return answerRaycast(r);

    JsonNode an = r.get("a"), bn = r.get("b");
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    for (const auto& [s, node] : {std::pair{&a, &an}, std::pair{&b, &bn}})
    {
        if (s->kind == Kind::Ray) node->fail("time_of_impact: a ray is not a moving shape (expected a bounded shape or plane)");
    }
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) bn.fail("time_of_impact: two planes (one shape must be bounded)");
    Vec3 ma = Vec3::Zero(), mb = Vec3::Zero();
    if (auto m = r.find("motion_a")) ma = m->asVec3();
    if (auto m = r.find("motion_b")) mb = m->asVec3();
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();

    // One power of two for the shapes and the motions: t is unchanged by it.
    const int k = std::min(normalisingExponent(a, b), exponentOf(std::max(ma.cwiseAbs().maxCoeff(), mb.cwiseAbs().maxCoeff())));
    scaleShape(a, k);
    scaleShape(b, k);
    const Vec3 sma = scaled(ma, k), smb = scaled(mb, k);
    ImpactAnswer ans;
    if (a.kind == Kind::Plane) ans = planeImpact(a, sma, b, smb, wantTrace);
    else if (b.kind == Kind::Plane) {
        ans = planeImpact(b, smb, a, sma, wantTrace);
        ans.result.normal = -ans.result.normal;  // from a (the shape) toward b (the plane)
    } else if (a.isCurved() || b.isCurved()) {
        ans = curvedImpact(a, sma, b, smb, wantTrace, std::ldexp(1.0, -k));
    } else {
        ans = boundedImpact(a, sma, b, smb, wantTrace, std::ldexp(1.0, -k), bn);
    }
    const TimeOfImpactResult& res = ans.result;
    Json out;
    if (!res.hit) out = {{"hit", false}};
    else if (res.initiallyOverlapping) out = {{"hit", true}, {"t", 0.0}, {"initially_overlapping", true}};
    else {
        const Vec3 pa = scaled(res.pointA, -k), pb = scaled(res.pointB, -k);
        if (!pa.allFinite() || !pb.allFinite()) throw InputError("query: the answer overflows double precision");
        out = {{"hit", true},
               {"t", cleanZero(res.t)},
               {"normal", vecJson(res.normal)},
               {"point_a", vecJson(pa)},
               {"point_b", vecJson(pb)}};
    }
    if (wantTrace) out["trace"] = ans.trace;
    requireFiniteAnswer(out);
    return out;
}

}  // namespace cdlab::demos
