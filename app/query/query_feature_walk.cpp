// `cdlab query` distance / penetration with method "vclip" (Mirtich 1998, core/feature_walk/vclip.h):
// polyhedral shapes become convex hulls (coplanar faces merged), then one cold V-Clip walk.
// "lin_canny" (Lin & Canny 1991) walks the same hulls with core/feature_walk/lin_canny.h; both answer alike.
#include "app/query/query_feature_walk.h"

#include <cmath>
#include <vector>

#include "core/feature_walk/lin_canny.h"
#include "core/feature_walk/vclip.h"
#include "core/geometry/convex_hull.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "core/query/touch.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// The shape's hull as a V-Clip polyhedron (normalised coordinates) in a body frame centred at
// `origin` (its first vertex, normalised), or a clear error at its node. Far from the world
// origin (offsets 1e4 x the size) the body frame keeps the plane offsets small: v - origin is
// exact for the shape's own vertices (Sterbenz), so the distance loses no digits to the offset.
VClipPolyhedron polyhedronOf(const QueryShape& s, int k, const JsonNode& node, Vec3& origin,
                             const std::string& method) {
    if (s.kind != Kind::Polytope && s.kind != Kind::Aabb && s.kind != Kind::Obb)
        node.fail("method '" + method + "' needs polyhedra (polytope, aabb, obb), got " + nameOf(s.kind));
    requireHullVerticesWithinLimit(s.vertices.size(), method.c_str(), node);
    std::vector<Vec3> points;
    points.reserve(s.vertices.size());
    origin = scaled(s.vertices.front(), k);
    for (const Vec3& v : s.vertices) points.push_back(scaled(v, k) - origin);
    const HullResult hull = convexHull(points);
    if (!hull.ok())
        node.fail("method '" + method + "' needs a solid polyhedron (4 points not in one plane); the hull is " +
                  nameOf(hull.status) + (hull.message.empty() ? "" : ": " + hull.message));
    VClipBuild built = buildVClipPolyhedron(hull.polyhedron);
    if (!built.ok()) node.fail("method '" + method + "': " + built.message);
    return std::move(built.polyhedron);
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

// The answer of either walk (VClipResult or LinCannyResult: the same fields), scaled back by 2^-k.
// `touch` (normalised units) is the touching rule shared with GJK (core/base/touch_rule.h): a walk that
// ends at a distance within it reports touching, as every other op does.
template <class Result>
Json walkAnswer(const std::string& op, const Result& r, int k, double touch) {
    const auto unscale = [k](double x) { return std::ldexp(x, -k); };
    if (r.intersect || r.distance <= touch)  // the walk finds that the bodies meet, not a depth: the verdict only
        return op == "distance" ? Json{{"intersect", true}, {"distance", 0.0}} : Json{{"intersect", true}};
    const double distance = unscale(r.distance);
    const Vec3 pA = r.pointA.unaryExpr(unscale), pB = r.pointB.unaryExpr(unscale);
    if (!std::isfinite(distance) || !pA.allFinite() || !pB.allFinite())
        throw InputError("query: the answer overflows double precision (coordinates too large)");
    Json out = {{"intersect", false}, {"distance", distance}};
    if (op == "penetration") out["normal"] = vecJson(r.normal);
    out["point_a"] = vecJson(pA);
    out["point_b"] = vecJson(pB);
    return out;
}

}  // namespace

Json answerFeatureWalkQuery(const std::string& op, const std::string& method, const QueryShape& a, const QueryShape& b,
                            const JsonNode& aNode, const JsonNode& bNode, bool wantTrace) {
    const int k = normalisingExponent(a, b);
    const double touch = std::ldexp(touchTolerance(a, b), k);
    Transform poseA, poseB;  // translations to the body-frame origins
    const VClipPolyhedron pa = polyhedronOf(a, k, aNode, poseA.position, method),
                          pb = polyhedronOf(b, k, bNode, poseB.position, method);
    Json out, trace;
    if (method == "lin_canny") {
        LinCannyTrace t;
        const LinCannyResult r = linCanny(pa, poseA, pb, poseB, nullptr, {}, wantTrace ? &t : nullptr);
        if (r.status == LinCannyStatus::CycleDetected) throw InputError("lin_canny: cycle detected (penetrating?)");
        if (r.status != LinCannyStatus::Separated && r.status != LinCannyStatus::Penetrating)
            throw InputError("query: lin_canny failed (" + std::string(nameOf(r.status)) + "): " + r.message);
        out = walkAnswer(op, r, k, touch);
        if (wantTrace) trace = traceJson(t);
    } else {
        VClipTrace t;
        const VClipResult r = vclip(pa, poseA, pb, poseB, nullptr, {}, wantTrace ? &t : nullptr);
        if (r.status != VClipStatus::Separated && r.status != VClipStatus::Penetrating)
            throw InputError("query: vclip failed (" + std::string(nameOf(r.status)) + "): " + r.message);
        out = walkAnswer(op, r, k, touch);
        if (wantTrace) trace = traceJson(t);
    }
    // Trace coordinates are those of the normalised problem: world = unit * trace value.
    if (wantTrace) out["trace"] = {{"unit", std::ldexp(1.0, -k)}, {"algorithms", Json::array({trace})}};
    return out;
}

}  // namespace cdlab::demos
