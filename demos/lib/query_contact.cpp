// The "contact" op of `cdlab query` (README "cdlab query"): the contact manifold of a polytope
// (polytope / aabb / obb) against a plane (core/contact_plane.h) or another polytope (SAT with
// face clipping, core/contact_sat.h); separated pairs answer the distance (GJK) and the closest
// features. "mass_properties" is answered by demos/lib/query_mass.h.
//
// Answer conventions (the same as "penetration"): normal n is a unit vector from A toward B;
// translating b by depth·n leaves the shapes touching; each contact point has point_a − point_b =
// depth·n (point_a: the point of A inside B, point_b: its projection on B's surface). A plane in
// this op is the solid half-space n·x <= d (a ground): a body below the plane is deep inside it.
// Features name the input vertices of the shape: {"type":"vertex"|"edge"|"face","vertices":[i,...]}
// (face vertices counter-clockwise seen from outside; aabb/obb corners are numbered with bit k of
// the index choosing the + side of axis k); the plane's feature is {"type":"plane"}.
#include "demos/lib/query_contact.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/contact_plane.h"
#include "core/contact_sat.h"
#include "core/convex_hull.h"
#include "core/gjk.h"
#include "core/shapes.h"
#include "demos/lib/query_mass.h"
#include "demos/lib/query_shapes.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

double clean(double x) { return x == 0 ? 0.0 : x; }  // -0 prints as "-0.0"
Json vecJson(const Vec3& v) { return Json::array({clean(v.x()), clean(v.y()), clean(v.z())}); }

// A bounded query shape as a convex polyhedron (world frame) and the map back to input vertices.
struct Body {
    ConvexPolyhedron mesh;
    std::vector<int> inputIndex;  // hull vertex -> input vertex
};

Body makeBody(const QueryShape& s, const JsonNode& node) {
    HullResult h = convexHull(s.vertices);
    if (!h.ok()) node.fail(std::string("contact needs a solid polytope: its convex hull failed (") + h.message + ")");
    return {std::move(h.polyhedron), std::move(h.inputIndex)};
}

// Exact rescaling by 2^k so the largest coordinate is in [0.5, 1) (the same normalisation as the
// shape-pair ops in query_ops.cpp): no underflow / overflow, answers scale back exactly.
int normalisingExponent(const QueryShape& a, const QueryShape& b) {
    double m = 0;
    for (const QueryShape* s : {&a, &b}) {
        for (const Vec3& v : s->vertices) m = std::max(m, v.cwiseAbs().maxCoeff());
        if (s->kind == Kind::Plane) m = std::max(m, std::abs(s->offset) / s->normal.norm());
    }
    if (m == 0 || !std::isfinite(m)) return 0;
    int e;
    std::frexp(m, &e);
    return -e;
}
void scaleShape(QueryShape& s, int k) {
    for (Vec3& v : s.vertices) v = v.unaryExpr([k](double x) { return std::ldexp(x, k); });
    s.offset = std::ldexp(s.offset, k);  // n·(2^k x) = 2^k d
}

// The input vertex indices of a feature of the hull.
std::vector<int> featureVertices(const Body& b, const FeatureRef& f) {
    std::vector<int> v;
    if (f.type == FeatureType::Vertex) v = {f.index};
    else if (f.type == FeatureType::Edge) v = {b.mesh.edgeVertices(f.index).first, b.mesh.edgeVertices(f.index).second};
    else if (f.type == FeatureType::Face) v = b.mesh.faceVertices(f.index);
    for (int& i : v) i = b.inputIndex[i];
    return v;
}
Json featureJson(const Body& b, const FeatureRef& f) {
    return {{"type", featureTypeName(f.type)}, {"vertices", featureVertices(b, f)}};
}

// The support feature of a body in direction d: the vertices within tol of the maximum of d·x,
// as a vertex, an edge (two adjacent vertices) or the face holding them (core/contact_plane.h
// does the same for -n̂; here reused by calling it with a plane through the support point).
FeatureRef supportFeature(const Body& b, const Vec3& d) {
    double top = -INFINITY;
    for (const auto& v : b.mesh.vertices()) top = std::max(top, d.dot(v.position));
    // The plane -d·x = -top touches the body from the side d (the body lies on its + side): the
    // closest feature to it is the support set.
    const PlaneContactResult r = contactPolyhedronPlane(b.mesh, Transform{}, Plane{-d, -top});
    return r.feature;
}

Json pointsJson(const std::vector<ContactPoint>& pts, bool swap, double unit) {
    Json out = Json::array();
    for (const ContactPoint& c : pts) {
        const Vec3 pa = (swap ? c.pointB : c.pointA) * unit, pb = (swap ? c.pointA : c.pointB) * unit;
        out.push_back({{"point_a", vecJson(pa)}, {"point_b", vecJson(pb)}, {"depth", c.depth * unit}});
    }
    return out;
}

void checkFinite(const Json& j) {
    if (j.is_number() && !std::isfinite(j.get<double>()))
        throw InputError("query: the answer overflows double precision (coordinates too large)");
    if (j.is_array() || j.is_object())
        for (const Json& x : j) checkFinite(x);
}

// Polytope (body) vs plane; bodyIsA says which side of the query the body is on.
Json bodyPlane(const Body& body, const QueryShape& plane, bool bodyIsA, int maxPoints, bool wantTrace, double unit) {
    PlaneContactTrace trace;
    PlaneContactOptions opt;
    opt.maxPoints = maxPoints;
    const PlaneContactResult r = contactPolyhedronPlane(body.mesh, Transform{}, Plane{plane.normal, plane.offset}, opt,
                                                        wantTrace ? &trace : nullptr);
    if (r.status == PlaneContactStatus::InvalidInput) throw InputError("query: contact: " + r.message);
    // Core: A = body, normal = -n̂ (body toward the half-space). Swapped when the plane is a.
    const Vec3 n = bodyIsA ? r.normal : Vec3(-r.normal);
    const Json bodyFeature = featureJson(body, r.feature), planeFeature = {{"type", "plane"}};
    Json out;
    if (r.colliding()) {
        out = {{"colliding", true}, {"depth", r.depth * unit}, {"normal", vecJson(n)},
               {"points", pointsJson(r.manifold, !bodyIsA, unit)}};
    } else {
        std::vector<ContactPoint> closest;
        for (size_t i = 0; i < r.featurePoints.size(); ++i) closest.push_back({r.featurePoints[i], r.featurePointsOnPlane[i], 0.0});
        Json pairs = Json::array();
        for (const Json& p : pointsJson(closest, !bodyIsA, unit)) pairs.push_back({{"point_a", p["point_a"]}, {"point_b", p["point_b"]}});
        out = {{"colliding", false}, {"distance", r.signedDistance * unit}, {"normal", vecJson(n)}, {"closest", pairs}};
    }
    out["feature_a"] = bodyIsA ? bodyFeature : planeFeature;
    out["feature_b"] = bodyIsA ? planeFeature : bodyFeature;
    if (wantTrace) {
        Json depths = Json::array();
        for (double s : trace.vertexDistances) depths.push_back(s * unit);
        Json steps = Json::array();
        for (const auto& st : trace.reduction) steps.push_back({{"rule", st.rule}, {"candidate", st.chosen}});
        out["trace"] = {{"algorithm", "polytope-plane"}, {"vertex_signed_distances", depths},
                        {"crossings", trace.crossings.size()}, {"candidates", trace.candidates.size()},
                        {"polygon", trace.hull.size()}, {"reduction", steps}};
    }
    return out;
}

Json bodyBody(const Body& a, const Body& b, int maxPoints, bool wantTrace, double unit) {
    SatContactTrace trace;
    SatContactOptions opt;
    opt.maxPoints = maxPoints;
    const SatContactResult r = contactPolyhedra(a.mesh, Transform{}, b.mesh, Transform{}, opt, wantTrace ? &trace : nullptr);
    if (r.status == SatContactStatus::InvalidInput) throw InputError("query: contact: " + r.message);
    Json out;
    if (r.colliding()) {
        out = {{"colliding", true}, {"depth", r.depth * unit}, {"normal", vecJson(r.normal)},
               {"points", pointsJson(r.manifold, false, unit)}, {"axis", axisKindName(r.axisKind)},
               {"feature_a", featureJson(a, r.featureA)}, {"feature_b", featureJson(b, r.featureB)}};
    } else {
        // Separated: the exact distance and closest points by GJK; the features are the support
        // sets of each body along the separating direction (they hold the closest points).
        const PolytopeShape sa(a.mesh.positions()), sb(b.mesh.positions());
        const GjkResult g = gjkDistance(sa, sb);
        if (g.status == GjkStatus::InvalidInput) throw InputError("query: non-finite support point (coordinates overflow)");
        const Vec3 n = g.distance > 0 ? g.separatingAxis : r.normal;
        Json pair = {{"point_a", vecJson(g.pointA * unit)}, {"point_b", vecJson(g.pointB * unit)}};
        out = {{"colliding", false}, {"distance", g.distance * unit}, {"normal", vecJson(n)},
               {"closest", Json::array({pair})}, {"feature_a", featureJson(a, supportFeature(a, n))},
               {"feature_b", featureJson(b, supportFeature(b, -n))}};
    }
    if (wantTrace) {
        Json axes = Json::array();
        for (const SatAxisRecord& x : trace.axes)
            axes.push_back({{"kind", axisKindName(x.kind)}, {"a", x.indexA}, {"b", x.indexB}, {"axis", vecJson(x.axis)},
                            {"separation", x.separation * unit}});
        out["trace"] = {{"algorithm", "sat"}, {"axes", axes}, {"edge_pairs", trace.edgePairsTotal},
                        {"edge_pairs_pruned", trace.edgePairsPruned}, {"edge_pairs_parallel", trace.edgePairsParallel},
                        {"chosen", trace.chosen}, {"reference_on_a", trace.referenceOnA},
                        {"clip_steps", trace.clipSteps.size()}, {"clipped_points", trace.clipped.size()}};
    }
    return out;
}

Json contactQuery(ObjectReader& r) {
    JsonNode an = r.get("a"), bn = r.get("b");
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    int maxPoints = 4;
    if (auto m = r.find("max_points")) maxPoints = m->asInt(1, 64);
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    const auto solid = [](const QueryShape& s) { return s.kind == Kind::Polytope || s.kind == Kind::Aabb || s.kind == Kind::Obb; };
    for (const auto& [s, node] : {std::pair{&a, &an}, std::pair{&b, &bn}})
        if (!solid(*s) && s->kind != Kind::Plane)
            node->fail(std::string("contact supports polytope, aabb, obb and plane shapes, not ") + toString(s->kind));
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) bn.fail("contact needs at least one polytope (two planes given)");

    const int k = normalisingExponent(a, b);
    scaleShape(a, k);
    scaleShape(b, k);
    const double unit = std::ldexp(1.0, -k);
    Json out;
    if (b.kind == Kind::Plane) out = bodyPlane(makeBody(a, an), b, true, maxPoints, wantTrace, unit);
    else if (a.kind == Kind::Plane) out = bodyPlane(makeBody(b, bn), a, false, maxPoints, wantTrace, unit);
    else out = bodyBody(makeBody(a, an), makeBody(b, bn), maxPoints, wantTrace, unit);
    checkFinite(out);
    return out;
}

}  // namespace

Json answerContactQuery(const std::string& op, ObjectReader& reader) {
    if (op == "mass_properties") return answerMassPropertiesQuery(reader);
    return contactQuery(reader);
}

}  // namespace cdlab::demos
