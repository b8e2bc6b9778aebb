// The "contact" op of `cdlab query` (docs/query.md): the query's JSON read into core's
// contact query (core/query/contact.h: polytopes against planes and polytopes, spheres, capsules,
// cylinders and cones; its file comment states the conventions and the touching rule) and its result,
// traces and errors written back as JSON. "mass_properties" is answered by app/query/query_mass.h.
//
// Answer: {"colliding":true,"depth","normal","points":[{"point_a","point_b","depth"}...],
// "feature_a","feature_b"} (two polytopes also "axis"), or {"colliding":false,"distance","normal",
// "closest":[{"point_a","point_b"}...],"feature_a","feature_b"}; with "trace", the algorithm's
// record ("polytope-plane", "sat") or its name alone ("rounded", "curved"). Features name the input
// vertices of the shape: {"type":"vertex"|"edge"|"face","vertices":[i,...]}; the plane's is
// {"type":"plane"}; a cylinder's or cone's {"type":"cap"|"rim","end":"top"|"bottom"},
// {"type":"side"} or {"type":"apex"} (core/query/curved_contact.h).
#include "app/query/query_contact.h"

#include <string>

#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_mass.h"
#include "app/query/query_shapes.h"
#include "core/query/contact.h"

namespace cdlab::demos {

namespace {

// A feature of a contact answer: {"type":"vertex"|"edge"|"face","vertices":[i,...]}, {"type":"plane"},
// or a cylinder's or cone's {"type":"cap"|"rim","end":"top"|"bottom"}, {"type":"side"}, {"type":"apex"}.
Json contactFeatureJson(const ContactFeature& f) {
    if (f.type == ContactFeature::Type::Plane) return {{"type", "plane"}};
    if (f.type == ContactFeature::Type::Curved) {
        if (f.curved.end == CurvedFeature::End::None) return {{"type", nameOf(f.curved.type)}};
        return {{"type", nameOf(f.curved.type)}, {"end", nameOf(f.curved.end)}};
    }
    return {{"type", nameOf(f.type)}, {"vertices", f.vertices}};
}

Json polytopePlaneTraceJson(const PlaneContactTrace& trace, const ContactFrame& frame) {
    Json depths = Json::array();
    for (double s : trace.vertexDistances) depths.push_back(frame.length(s));
    Json steps = Json::array();
    for (const auto& st : trace.reduction) steps.push_back({{"rule", st.rule}, {"candidate", st.chosen}});
    return {{"algorithm", nameOf(ContactMethod::PolytopePlane)},
            {"vertex_signed_distances", depths},
            {"crossings", trace.crossings.size()},
            {"candidates", trace.candidates.size()},
            {"polygon", trace.hull.size()},
            {"reduction", steps}};
}

Json satTraceJson(const SatContactTrace& trace, const ContactFrame& frame) {
    Json axes = Json::array();
    for (const SatAxisRecord& x : trace.axes)
        axes.push_back({{"kind", nameOf(x.kind)},
                        {"a", x.indexA},
                        {"b", x.indexB},
                        {"axis", vecJson(x.axis)},
                        {"separation", frame.length(x.separation)}});
    return {{"algorithm", nameOf(ContactMethod::Sat)},
            {"axes", axes},
            {"edge_pairs", trace.edgePairsTotal},
            {"edge_pairs_pruned", trace.edgePairsPruned},
            {"edge_pairs_parallel", trace.edgePairsParallel},
            {"chosen", trace.chosen},
            {"reference_on_a", trace.referenceOnA},
            {"clip_steps", trace.clipSteps.size()},
            {"clipped_points", trace.clipped.size()}};
}

// Raises the query's error for a contact query that has no answer, at the JSON node of the shape
// it is about: the same messages, at the same paths, as when the app checked them itself
// (tests/app/query/query_contact_test.cpp "errors", query_contact_rounded_test.cpp "shapes it does
// not take", hostile_query_test.cpp: the hull-vertex and edge-pair limits).
[[noreturn]] void failContact(const ContactResult& c, const QueryShape& a, const QueryShape& b, const JsonNode& an,
                              const JsonNode& bn) {
    const QueryShape& s = c.shape == 0 ? a : b;
    const JsonNode& node = c.shape == 0 ? an : bn;
    switch (c.status) {
        case ContactStatus::Ok: break;
        case ContactStatus::UnsupportedShape:
            node.fail(std::string("contact supports polytope, aabb, obb, sphere, capsule, cylinder, cone and plane "
                                  "shapes, not ") +
                      nameOf(s.kind));
        case ContactStatus::HullVerticesOverLimit: requireHullVerticesWithinLimit(s.vertices.size(), "contact", node); break;
        case ContactStatus::TwoPlanes: node.fail("contact needs at least one bounded shape (two planes given)");
        case ContactStatus::PairFailed: throw InputError(std::string("query: ") + describe(c.pairStatus));
        case ContactStatus::HullFailed:
            node.fail(std::string("contact needs a solid polytope: its convex hull failed (") + c.message + ")");
        case ContactStatus::PlaneTooFar:
            node.fail("the plane is farther from the body than double precision spans (offset / body size above ~1e308)");
        case ContactStatus::EdgePairsOverLimit: requireEdgePairsWithinLimit(c.edgesA, c.edgesB, node); break;
        case ContactStatus::ContactFailed: throw InputError("query: contact: " + c.message);
    }
    throw InputError("query: contact: no answer");  // unreachable: the limits above are core's options
}

// The answer: colliding, depth, normal, points (with their depths) and the features; separated,
// distance, normal, the closest pairs and the features. Rounded and curved answers print a depth of
// -0 as 0 (cleanZero); polytope answers print their lengths as the local frame gives them back.
Json contactJson(const ContactResult& c) {
    const bool roundedOrCurved = c.method == ContactMethod::Rounded || c.method == ContactMethod::Curved;
    const auto depthOf = [&](double x) { return roundedOrCurved ? cleanZero(x) : x; };
    Json points = Json::array();
    for (const ContactPoint& p : c.points) {
        if (c.colliding)
            points.push_back({{"point_a", vecJson(p.pointA)}, {"point_b", vecJson(p.pointB)}, {"depth", depthOf(p.depth)}});
        else points.push_back({{"point_a", vecJson(p.pointA)}, {"point_b", vecJson(p.pointB)}});
    }
    Json out = c.colliding ? Json{{"colliding", true}, {"depth", depthOf(c.depth)}, {"normal", vecJson(c.normal)}, {"points", points}}
                           : Json{{"colliding", false}, {"distance", c.distance}, {"normal", vecJson(c.normal)}, {"closest", points}};
    if (c.axis) out["axis"] = nameOf(*c.axis);
    out["feature_a"] = contactFeatureJson(c.featureA);
    out["feature_b"] = contactFeatureJson(c.featureB);
    return out;
}

Json contactAnswer(ObjectReader& r) {
    JsonNode an = r.get("a"), bn = r.get("b");
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    ContactOptions options;
    if (auto m = r.find("max_points")) options.maxPoints = m->asInt(1, 64);
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    options.maxHullVertices = kMaxHullVertices;
    options.maxSatEdgePairs = kMaxSatEdgePairs;
    ContactTrace trace;
    const ContactResult c = contactQuery(a, b, options, wantTrace ? &trace : nullptr);
    if (c.status != ContactStatus::Ok) failContact(c, a, b, an, bn);
    Json out = contactJson(c);
    if (wantTrace) {
        if (c.method == ContactMethod::PolytopePlane) out["trace"] = polytopePlaneTraceJson(trace.plane, trace.frame);
        else if (c.method == ContactMethod::Sat) out["trace"] = satTraceJson(trace.sat, trace.frame);
        else out["trace"] = {{"algorithm", nameOf(c.method)}};
    }
    requireFiniteAnswer(out);
    return out;
}

}  // namespace

Json answerContactQuery(const std::string& op, ObjectReader& reader) {
    if (op == "mass_properties") return answerMassPropertiesQuery(reader);
    return contactAnswer(reader);
}

}  // namespace cdlab::demos
