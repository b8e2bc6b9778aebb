// `cdlab query` with method "lin_canny": polyhedral shapes become convex hulls (coplanar faces
// merged, as for "vclip"), then one cold Lin–Canny walk (core/lin_canny.h).
#include "demos/lib/query_lin_canny.h"

#include <cmath>
#include <vector>

#include "core/convex_hull.h"
#include "core/lin_canny.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// -0 prints as "-0.0"; answers print +0 instead.
double clean(double x) { return x == 0 ? 0.0 : x; }
Json vecJson(const Vec3& v) { return Json::array({clean(v.x()), clean(v.y()), clean(v.z())}); }

// Exact power-of-two rescaling so the largest coordinate is in [0.5, 1) (as the GJK and V-Clip
// answers do): no underflow of squared distances at 1e-300, no overflow at 1e300; exact both ways.
int normalisingExponent(const QueryShape& a, const QueryShape& b) {
    double m = 0;
    for (const QueryShape* s : {&a, &b})
        for (const Vec3& v : s->vertices) m = std::max(m, v.cwiseAbs().maxCoeff());
    if (m == 0) return 0;
    int e;
    std::frexp(m, &e);
    return -e;
}

VClipPolyhedron polyhedronOf(const QueryShape& s, int k, const JsonNode& node) {
    if (s.kind != Kind::Polytope && s.kind != Kind::Aabb && s.kind != Kind::Obb)
        node.fail(std::string("method 'lin_canny' needs polyhedra (polytope, aabb, obb), got ") + toString(s.kind));
    std::vector<Vec3> points;
    points.reserve(s.vertices.size());
    for (const Vec3& v : s.vertices) points.push_back(v.unaryExpr([k](double x) { return std::ldexp(x, k); }));
    const HullResult hull = convexHull(points);
    if (!hull.ok())
        node.fail(std::string("method 'lin_canny' needs a solid polyhedron (4 points not in one plane); the hull is ") +
                  statusName(hull.status) + (hull.message.empty() ? "" : ": " + hull.message));
    VClipBuild built = buildVClipPolyhedron(hull.polyhedron);
    if (!built.ok()) node.fail("method 'lin_canny': " + built.message);
    return std::move(built.polyhedron);
}

Json featureJson(const VClipFeature& f) { return {{"type", toString(f.type)}, {"index", f.index}}; }

Json traceJson(const LinCannyTrace& t) {
    Json steps = Json::array();
    for (const LinCannyTraceStep& s : t.steps) {
        Json step = {{"step", s.step},
                     {"state", contactTypeName(s.state)},
                     {"feature_a", featureJson(s.featureA)},
                     {"feature_b", featureJson(s.featureB)},
                     {"kind", toString(s.kind)},
                     {"rule", s.rule},
                     {"distance_before", s.distanceBefore}};
        if (s.kind == VClipStepKind::Update || s.kind == VClipStepKind::Aborted) {
            step["updated"] = s.updatedBody == 0 ? "a" : "b";
            step["to"] = featureJson(s.to);
            step["distance_after"] = s.distanceAfter;
            step["local_minimum"] = s.localMinimum;
        }
        steps.push_back(step);
    }
    Json out = {{"algorithm", "lin_canny"}, {"status", statusName(t.status)}, {"steps", steps}};
    if (t.status == LinCannyStatus::CycleDetected) out["cycle_length"] = t.cycleLength;
    return out;
}

}  // namespace

Json answerLinCannyQuery(const std::string& op, const QueryShape& a, const QueryShape& b, const JsonNode& aNode,
                         const JsonNode& bNode, bool wantTrace) {
    const int k = normalisingExponent(a, b);
    const VClipPolyhedron pa = polyhedronOf(a, k, aNode), pb = polyhedronOf(b, k, bNode);
    LinCannyTrace trace;
    // The hulls are built from world coordinates: both poses are the identity.
    const LinCannyResult r = linCanny(pa, Transform{}, pb, Transform{}, nullptr, {}, wantTrace ? &trace : nullptr);
    if (r.status == LinCannyStatus::CycleDetected) throw InputError("lin_canny: cycle detected (penetrating?)");
    if (r.status != LinCannyStatus::Separated && r.status != LinCannyStatus::Penetrating)
        throw InputError("query: lin_canny failed (" + std::string(statusName(r.status)) + "): " + r.message);
    const auto unscale = [k](double x) { return std::ldexp(x, -k); };
    Json out;
    if (r.intersect) {
        // Lin–Canny finds that the bodies meet, not a depth: the verdict only.
        out = op == "distance" ? Json{{"intersect", true}, {"distance", 0.0}} : Json{{"intersect", true}};
    } else {
        const double distance = unscale(r.distance);
        const Vec3 pA = r.pointA.unaryExpr(unscale), pB = r.pointB.unaryExpr(unscale);
        if (!std::isfinite(distance) || !pA.allFinite() || !pB.allFinite())
            throw InputError("query: the answer overflows double precision (coordinates too large)");
        out = {{"intersect", false}, {"distance", distance}};
        if (op == "penetration") out["normal"] = vecJson(r.normal);
        out["point_a"] = vecJson(pA);
        out["point_b"] = vecJson(pB);
    }
    // Trace coordinates are those of the normalised problem: world = unit * trace value.
    if (wantTrace) out["trace"] = {{"unit", std::ldexp(1.0, -k)}, {"algorithms", Json::array({traceJson(trace)})}};
    return out;
}

}  // namespace cdlab::demos
