// `cdlab query` distance / penetration with method "vclip" or "lin_canny": the query's shapes handed
// to core's feature walks (core/query/feature_walk.h), their answers and traces written as JSON.
#include "app/query/query_feature_walk.h"

#include <cmath>
#include <vector>

#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "core/query/feature_walk.h"
#include "core/query/touch.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// The shape's body for the walk, or a clear error at its node (the kind, the vertex limit, the hull
// and the V-Clip build, in that order).
WalkBody bodyOf(const QueryShape& s, int k, const JsonNode& node, const std::string& method) {
    if (s.kind != Kind::Polytope && s.kind != Kind::Aabb && s.kind != Kind::Obb)
        node.fail("method '" + method + "' needs polyhedra (polytope, aabb, obb), got " + nameOf(s.kind));
    requireHullVerticesWithinLimit(s.vertices.size(), method.c_str(), node);
    WalkBody body = walkBodyOf(s, k);
    if (body.status == WalkBody::Status::DegenerateHull)
        node.fail("method '" + method + "' needs a solid polyhedron (4 points not in one plane); the hull is " +
                  nameOf(body.hullStatus) + (body.message.empty() ? "" : ": " + body.message));
    if (body.status != WalkBody::Status::Ok) node.fail("method '" + method + "': " + body.message);
    return body;
}

Json featureJson(const VClipFeature& f) { return {{"type", nameOf(f.type)}, {"index", f.index}}; }

// One step of either walk (VClipTraceStep or LinCannyTraceStep: the same fields); the update
// fields when the step moved a feature.
template <class Step>
Json walkStepJson(const Step& s, bool moved) {
    Json step = {{"step", s.step},
                 {"state", nameOf(s.state)},
                 {"feature_a", featureJson(s.featureA)},
                 {"feature_b", featureJson(s.featureB)},
                 {"kind", nameOf(s.kind)},
                 {"rule", s.rule},
                 {"distance_before", s.distanceBefore}};
    if (moved) {
        step["updated"] = s.updatedBody == 0 ? "a" : "b";
        step["to"] = featureJson(s.to);
        step["distance_after"] = s.distanceAfter;
        step["local_minimum"] = s.localMinimum;
    }
    return step;
}

Json traceJson(const VClipTrace& t) {
    Json steps = Json::array();
    for (const VClipTraceStep& s : t.steps) steps.push_back(walkStepJson(s, s.kind == VClipStepKind::Update));
    return {{"algorithm", "vclip"}, {"status", nameOf(t.status)}, {"steps", steps}};
}

// Lin–Canny's aborted step (a cycle) has moved a feature too.
Json traceJson(const LinCannyTrace& t) {
    Json steps = Json::array();
    for (const LinCannyTraceStep& s : t.steps)
        steps.push_back(walkStepJson(s, s.kind == VClipStepKind::Update || s.kind == VClipStepKind::Aborted));
    Json out = {{"algorithm", "lin_canny"}, {"status", nameOf(t.status)}, {"steps", steps}};
    if (t.status == LinCannyStatus::CycleDetected) out["cycle_length"] = t.cycleLength;
    return out;
}

// The walk's answer as JSON: a walk finds that the bodies meet, not a depth (the verdict only).
Json walkAnswer(const std::string& op, const WalkPairResult& r) {
    if (r.intersect) return op == "distance" ? Json{{"intersect", true}, {"distance", 0.0}} : Json{{"intersect", true}};
    Json out = {{"intersect", false}, {"distance", r.distance}};
    if (op == "penetration") out["normal"] = vecJson(r.normal);
    out["point_a"] = vecJson(r.pointA);
    out["point_b"] = vecJson(r.pointB);
    return out;
}

}  // namespace

Json answerFeatureWalkQuery(const std::string& op, const std::string& method, const QueryShape& a, const QueryShape& b,
                            const JsonNode& aNode, const JsonNode& bNode, bool wantTrace) {
    const int k = normalisingExponent(a, b);
    const double touch = std::ldexp(touchTolerance(a, b), k);
    const WalkBody pa = bodyOf(a, k, aNode, method), pb = bodyOf(b, k, bNode, method);
    const bool linCanny = method == "lin_canny";
    VClipTrace vt;
    LinCannyTrace lt;
    const WalkPairResult r = walkPair(pa, pb, k, touch, linCanny, wantTrace && !linCanny ? &vt : nullptr,
                                      wantTrace && linCanny ? &lt : nullptr);
    if (r.cycle) throw InputError("lin_canny: cycle detected (penetrating?)");
    if (r.status == PairStatus::InvalidInput)
        throw InputError("query: " + method + " failed (" + r.walkStatus + "): " + r.message);
    if (r.status != PairStatus::Ok) throw InputError("query: the answer overflows double precision (coordinates too large)");
    Json out = walkAnswer(op, r), trace;
    if (wantTrace) trace = linCanny ? traceJson(lt) : traceJson(vt);
    // Trace coordinates are those of the normalised problem: world = unit * trace value.
    if (wantTrace) out["trace"] = {{"unit", std::ldexp(1.0, -k)}, {"algorithms", Json::array({trace})}};
    return out;
}

}  // namespace cdlab::demos
