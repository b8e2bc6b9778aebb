// `raycast` and `time_of_impact` (docs/query.md): the query's JSON read into core's casts on
// the query's shapes (core/query/cast.h), their answers and traces written back as JSON.
#include "app/query/query_cast.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_shapes.h"
#include "core/query/cast.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

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

Json rayTraceJson(const RayCastQueryTrace& t) {
    switch (t.algorithm) {
        case RayCastQueryTrace::Algorithm::RayPlane:
            return {{"algorithm", "ray_plane"}, {"signed_distance", t.signedDistance}, {"slope", t.slope}};
        case RayCastQueryTrace::Algorithm::RayCylinder: return {{"algorithm", "ray_cylinder"}};
        case RayCastQueryTrace::Algorithm::RayCone: return {{"algorithm", "ray_cone"}};
        case RayCastQueryTrace::Algorithm::RayCast: break;
    }
    return castTraceJson(t.cast, std::ldexp(1.0, t.tExponent), std::ldexp(1.0, t.lengthExponent), 0);
}

Json impactTraceJson(const ImpactQueryTrace& t) {
    switch (t.algorithm) {
        case ImpactQueryTrace::Algorithm::PlaneSpan:
            return {{"algorithm", "plane_span"}, {"low", t.low}, {"high", t.high}, {"rate", t.rate}};
        case ImpactQueryTrace::Algorithm::ConservativeAdvancement: {
            Json steps = Json::array();
            for (const ImpactQueryTrace::Step& s : t.steps) steps.push_back({{"t", s.t}, {"distance", s.distance}});
            return {{"algorithm", "conservative_advancement"}, {"steps", steps}};
        }
        case ImpactQueryTrace::Algorithm::RayCast: break;
    }
    return castTraceJson(t.cast, std::ldexp(1.0, t.tExponent), std::ldexp(1.0, t.lengthExponent), t.pairedWith);
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

    RayCastQueryTrace trace;
    const RayCastQueryResult ans = rayCastQuery(origin, direction, std::move(shape), maxT, wantTrace ? &trace : nullptr);
    if (ans.status != PairStatus::Ok)
        throw InputError("query: the answer overflows double precision (t or the hit point too large)");
    Json out;
    if (!ans.hit) out = {{"hit", false}};
    else if (ans.inside) out = {{"hit", true}, {"t", 0.0}, {"point", vecJson(ans.point)}, {"inside", true}};
    else out = {{"hit", true}, {"t", cleanZero(ans.t)}, {"point", vecJson(ans.point)}, {"normal", vecJson(ans.normal)}};
    if (wantTrace) out["trace"] = rayTraceJson(trace);
    requireFiniteAnswer(out);
    return out;
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

    ImpactQueryOptions options;
    options.maxDifferencePoints = kMaxHullVertices;
    ImpactQueryTrace trace;
    const ImpactQueryResult ans = timeOfImpactQuery(std::move(a), ma, std::move(b), mb, options, wantTrace ? &trace : nullptr);
    if (ans.status == PairStatus::WorkLimit)
        bn.fail("time_of_impact: the Minkowski difference of the two hulls has " + std::to_string(ans.hullA) + " x " +
                std::to_string(ans.hullB) + " points, over the limit of " + std::to_string(kMaxHullVertices));
    if (ans.pairFailed) throw InputError(std::string("query: ") + describe(ans.status));
    if (ans.status != PairStatus::Ok) throw InputError("query: the answer overflows double precision");
    const TimeOfImpactResult& res = ans.result;
    Json out;
    if (!res.hit) out = {{"hit", false}};
    else if (res.initiallyOverlapping) out = {{"hit", true}, {"t", 0.0}, {"initially_overlapping", true}};
    else
        out = {{"hit", true},
               {"t", cleanZero(res.t)},
               {"normal", vecJson(res.normal)},
               {"point_a", vecJson(res.pointA)},
               {"point_b", vecJson(res.pointB)}};
    if (wantTrace) out["trace"] = impactTraceJson(trace);
    requireFiniteAnswer(out);
    return out;
}

}  // namespace cdlab::demos
