// The "contact" op of `cdlab query` (README "cdlab query"): the contact manifold of a polytope
// (polytope / aabb / obb) against a plane (core/contact/contact_plane.h) or another polytope (SAT with
// face clipping, core/contact/contact_sat.h), and of a sphere or capsule against any of them (below,
// "Spheres and capsules"); separated pairs answer the distance (GJK) and the closest features.
// "mass_properties" is answered by app/query/query_mass.h.
//
// Answer conventions (the same as "penetration"): normal n is a unit vector from A toward B;
// translating b by depth·n leaves the shapes touching; each contact point has point_a − point_b =
// depth·n (point_a: the point of A inside B, point_b: its projection on B's surface). A plane in
// this op is the solid half-space n·x <= d (a ground): a body below the plane is deep inside it.
// Features name the input vertices of the shape: {"type":"vertex"|"edge"|"face","vertices":[i,...]}
// (face vertices counter-clockwise seen from outside; aabb/obb corners are numbered with bit k of
// the index choosing the + side of axis k); the plane's feature is {"type":"plane"}.
//
// Touching or separated is decided by the touching rule of every op (core/base/touch_rule.h): for two
// polytopes by the GJK distance, for a polytope and a plane by the lowest signed vertex distance.
// The manifold itself (which vertices form the touching feature, which clipped points are kept)
// uses the core's feature tolerance. Everything is computed in a frame local to the bodies —
// translated to the first body's first vertex, then scaled by a power of two — so the rounding
// is relative to the bodies' extent, not to how far they are from the origin.
#include "app/query/query_contact.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>

#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "app/query/query_contact_curved.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_mass.h"
#include "app/query/query_ops.h"
#include "core/query/touch.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// A bounded query shape as a convex polyhedron (world frame) and the map back to input vertices.
struct HullBody {
    ConvexPolyhedron mesh;
    std::vector<int> inputIndex;  // hull vertex -> input vertex
};

HullBody makeHullBody(const QueryShape& s, const JsonNode& node) {
    HullResult h = convexHull(s.vertices);
    if (!h.ok()) node.fail(std::string("contact needs a solid polytope: its convex hull failed (") + h.message + ")");
    return {std::move(h.polyhedron), std::move(h.inputIndex)};
}

// The bodies' local frame: world = 2^-k · local + origin.
struct LocalFrame {
    Vec3 origin = Vec3::Zero();
    int k = 0;
    Vec3 toWorld(const Vec3& p) const { return Vec3(scaled(p, -k) + origin); }
    double length(double x) const { return std::ldexp(x, -k); }
};

// Translates the shape by -origin, then scales it by 2^k (a plane n·x = d becomes n·x = d - n·origin).
void toLocal(QueryShape& s, const LocalFrame& f) {
    for (Vec3& v : s.vertices) v -= f.origin;
    if (s.kind == Kind::Plane) s.offset -= s.normal.dot(f.origin);
    scaleShape(s, f.k);
}

// The input vertex indices of a feature of the hull.
std::vector<int> featureVertices(const HullBody& b, const FeatureRef& f) {
    std::vector<int> v;
    if (f.type == FeatureType::Vertex) v = {f.index};
    else if (f.type == FeatureType::Edge) v = {b.mesh.edgeVertices(f.index).first, b.mesh.edgeVertices(f.index).second};
    else if (f.type == FeatureType::Face) v = b.mesh.faceVertices(f.index);
    for (int& i : v) i = b.inputIndex[i];
    return v;
}
Json featureJson(const HullBody& b, const FeatureRef& f) {
    return {{"type", nameOf(f.type)}, {"vertices", featureVertices(b, f)}};
}

// The support feature of a body in direction d: the vertices within tol of the maximum of d·x,
// as a vertex, an edge (two adjacent vertices) or the face holding them (core/contact/contact_plane.h
// does the same for -n̂; here reused by calling it with a plane through the support point).
FeatureRef supportFeature(const HullBody& b, const Vec3& d) {
    double top = -INFINITY;
    for (const auto& v : b.mesh.vertices()) top = std::max(top, d.dot(v.position));
    // The plane -d·x = -top touches the body from the side d (the body lies on its + side): the
    // closest feature to it is the support set.
    const PlaneContactResult r = contactPolyhedronPlane(b.mesh, Transform{}, Plane{-d, -top});
    return r.feature;
}

Json pointsJson(std::span<const ContactPoint> pts, bool swap, const LocalFrame& frame) {
    Json out = Json::array();
    for (const ContactPoint& c : pts) {
        const Vec3 pa = frame.toWorld(swap ? c.pointB : c.pointA), pb = frame.toWorld(swap ? c.pointA : c.pointB);
        out.push_back({{"point_a", vecJson(pa)}, {"point_b", vecJson(pb)}, {"depth", frame.length(c.depth)}});
    }
    return out;
}

// Polytope (body) vs plane; bodyIsA says which side of the query the body is on. `touch` is the
// touching rule's tolerance (local units): s_min > touch is separated, as for the distance op.
Json bodyPlane(const HullBody& body, const QueryShape& plane, bool bodyIsA, int maxPoints, bool wantTrace, double touch,
               const LocalFrame& frame) {
    PlaneContactTrace trace;
    PlaneContactOptions opt;
    opt.maxPoints = maxPoints;
    const Plane local{plane.normal, plane.offset};
    PlaneContactResult r = contactPolyhedronPlane(body.mesh, Transform{}, local, opt, wantTrace ? &trace : nullptr);
    if (r.status == PlaneContactStatus::InvalidInput) throw InputError("query: contact: " + r.message);
    const bool colliding = r.signedDistance <= touch;
    if (colliding && !r.colliding()) {  // the core's feature tolerance is below the rule's: widen it
        opt.tolerance = std::max(touch, r.signedDistance);
        r = contactPolyhedronPlane(body.mesh, Transform{}, local, opt, wantTrace ? &trace : nullptr);
    }
    // Core: A = body, normal = -n̂ (body toward the half-space). Swapped when the plane is a.
    const Vec3 n = bodyIsA ? r.normal : Vec3(-r.normal);
    const Json bodyFeature = featureJson(body, r.feature), planeFeature = {{"type", "plane"}};
    Json out;
    if (colliding) {
        out = {{"colliding", true},
               {"depth", frame.length(r.depth)},
               {"normal", vecJson(n)},
               {"points", pointsJson(r.manifold, !bodyIsA, frame)}};
    } else {
        std::vector<ContactPoint> closest;
        for (size_t i = 0; i < r.featurePoints.size(); ++i)
            closest.push_back({r.featurePoints[i], r.featurePointsOnPlane[i], 0.0});
        Json pairs = Json::array();
        for (const Json& p : pointsJson(closest, !bodyIsA, frame))
            pairs.push_back({{"point_a", p["point_a"]}, {"point_b", p["point_b"]}});
        out = {{"colliding", false},
               {"distance", frame.length(r.signedDistance)},
               {"normal", vecJson(n)},
               {"closest", pairs}};
    }
    out["feature_a"] = bodyIsA ? bodyFeature : planeFeature;
    out["feature_b"] = bodyIsA ? planeFeature : bodyFeature;
    if (wantTrace) {
        Json depths = Json::array();
        for (double s : trace.vertexDistances) depths.push_back(frame.length(s));
        Json steps = Json::array();
        for (const auto& st : trace.reduction) steps.push_back({{"rule", st.rule}, {"candidate", st.chosen}});
        out["trace"] = {{"algorithm", "polytope-plane"},       {"vertex_signed_distances", depths},
                        {"crossings", trace.crossings.size()}, {"candidates", trace.candidates.size()},
                        {"polygon", trace.hull.size()},        {"reduction", steps}};
    }
    return out;
}

Json satTraceJson(const SatContactTrace& trace, const LocalFrame& frame) {
    Json axes = Json::array();
    for (const SatAxisRecord& x : trace.axes)
        axes.push_back({{"kind", nameOf(x.kind)},
                        {"a", x.indexA},
                        {"b", x.indexB},
                        {"axis", vecJson(x.axis)},
                        {"separation", frame.length(x.separation)}});
    return {{"algorithm", "sat"},
            {"axes", axes},
            {"edge_pairs", trace.edgePairsTotal},
            {"edge_pairs_pruned", trace.edgePairsPruned},
            {"edge_pairs_parallel", trace.edgePairsParallel},
            {"chosen", trace.chosen},
            {"reference_on_a", trace.referenceOnA},
            {"clip_steps", trace.clipSteps.size()},
            {"clipped_points", trace.clipped.size()}};
}

// Separated polytopes: the distance and closest points by GJK; the features are the support sets
// of each body along the separating direction (they hold the closest points).
Json separatedBodies(const HullBody& a, const HullBody& b, const GjkResult& g, const LocalFrame& frame) {
    const Vec3 n = g.separatingAxis;
    Json pair = {{"point_a", vecJson(frame.toWorld(g.pointA))}, {"point_b", vecJson(frame.toWorld(g.pointB))}};
    return {{"colliding", false},
            {"distance", frame.length(g.distance)},
            {"normal", vecJson(n)},
            {"closest", Json::array({pair})},
            {"feature_a", featureJson(a, supportFeature(a, n))},
            {"feature_b", featureJson(b, supportFeature(b, -n))}};
}

// Two polytopes: GJK decides (the touching rule, `touch` in local units); colliding pairs get the
// SAT manifold (Gregorius), the SAT trace is recorded either way.
Json bodyBody(const HullBody& a, const HullBody& b, int maxPoints, bool wantTrace, double touch, const LocalFrame& frame,
              const JsonNode& bNode) {
    const GjkResult g = gjkDistance(PolytopeShape(a.mesh.positions()), PolytopeShape(b.mesh.positions()));
    if (g.status == GjkStatus::InvalidInput) throw InputError("query: non-finite support point (coordinates overflow)");
    const bool colliding = g.intersect() || g.distance <= touch;
    if (!colliding && !wantTrace) return separatedBodies(a, b, g, frame);  // no SAT needed: linear time
    requireEdgePairsWithinLimit(a.mesh.edgeCount(), b.mesh.edgeCount(), bNode);
    SatContactTrace trace;
    SatContactOptions opt;
    opt.maxPoints = maxPoints;
    SatContactResult r = contactPolyhedra(a.mesh, Transform{}, b.mesh, Transform{}, opt, wantTrace ? &trace : nullptr);
    if (r.status == SatContactStatus::InvalidInput) throw InputError("query: contact: " + r.message);
    if (colliding && !r.colliding()) {  // rounding put the SAT just past its band: widen it to the rule's
        opt.tolerance = std::max(touch, r.separation);
        r = contactPolyhedra(a.mesh, Transform{}, b.mesh, Transform{}, opt, wantTrace ? &trace : nullptr);
    }
    Json out = colliding ? Json{{"colliding", true},
                                {"depth", frame.length(r.depth)},
                                {"normal", vecJson(r.normal)},
                                {"points", pointsJson(r.manifold, false, frame)},
                                {"axis", nameOf(r.axisKind)},
                                {"feature_a", featureJson(a, r.featureA)},
                                {"feature_b", featureJson(b, r.featureB)}}
                         : separatedBodies(a, b, g, frame);
    if (wantTrace) out["trace"] = satTraceJson(trace, frame);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Spheres and capsules (a point or segment core ⊕ ball(r)), in the query's units (issue 21 §2):
//   sphere – anything: one point, the penetration op's deepest pair (a plane: the solid half-space);
//   capsule – plane: each end of the segment whose sphere reaches the half-space (up to two points);
//   capsule – polytope: when the contact normal is a face normal of the polytope, the segment clipped
//     to that face's side planes, each clipped end whose sphere reaches the face a point (a capsule
//     lying on a face: both ends); otherwise one point;
//   capsule – sphere or capsule: one point.
// Features: a sphere is its centre, {"type":"vertex","vertices":[0]}; a capsule the end(s) or the
// segment holding its contact points ([0] = a, [1] = b).

bool rounded(const QueryShape& s) { return s.kind == Kind::Sphere || s.kind == Kind::Capsule; }

// The core feature of a sphere or capsule under the core points `at` (one or two).
Json roundedFeature(const QueryShape& s, const std::vector<Vec3>& at) {
    if (s.kind == Kind::Sphere) return {{"type", "vertex"}, {"vertices", {0}}};
    const Vec3 a = s.vertices[0], ab = s.vertices[1] - a;
    const double len2 = ab.squaredNorm();
    bool end0 = false, end1 = false, inside = false;
    for (const Vec3& p : at) {
        const double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
        if (t <= 1e-9) end0 = true;
        else if (t >= 1 - 1e-9) end1 = true;
        else inside = true;
    }
    if (inside || (end0 && end1)) return {{"type", "edge"}, {"vertices", {0, 1}}};
    return {{"type", "vertex"}, {"vertices", {end1 ? 1 : 0}}};
}

Json pointJson(const Vec3& pa, const Vec3& pb, double depth) {
    return {{"point_a", vecJson(pa)}, {"point_b", vecJson(pb)}, {"depth", cleanZero(depth)}};
}

// Contact points of the rounded shape `s` (side A when sIsA) with the answer's normal n (A toward B).
struct RoundedPoint {
    Vec3 onS, onOther;  // on the rounded shape, on the other shape
    double depth;
    Vec3 core;  // the core point under onS
};

Json roundedAnswer(bool colliding, double distanceOrDepth, const Vec3& n, std::vector<RoundedPoint> pts, bool sIsA,
                   const Json& sFeature, const Json& otherFeature, int maxPoints) {
    std::stable_sort(pts.begin(), pts.end(), [](const RoundedPoint& x, const RoundedPoint& y) { return x.depth > y.depth; });
    if (static_cast<int>(pts.size()) > maxPoints) pts.resize(maxPoints);
    Json points = Json::array();
    for (const RoundedPoint& p : pts) {
        const Vec3 pa = sIsA ? p.onS : p.onOther, pb = sIsA ? p.onOther : p.onS;
        if (colliding) points.push_back(pointJson(pa, pb, p.depth));
        else points.push_back({{"point_a", vecJson(pa)}, {"point_b", vecJson(pb)}});
    }
    Json out = colliding ? Json{{"colliding", true}, {"depth", cleanZero(distanceOrDepth)}, {"normal", vecJson(n)}, {"points", points}}
                         : Json{{"colliding", false}, {"distance", distanceOrDepth}, {"normal", vecJson(n)}, {"closest", points}};
    out["feature_a"] = sIsA ? sFeature : otherFeature;
    out["feature_b"] = sIsA ? otherFeature : sFeature;
    return out;
}

// A sphere or capsule s against the solid half-space n̂·x <= d̂ of `plane`.
Json roundedPlane(const QueryShape& s, const QueryShape& plane, bool sIsA, int maxPoints) {
    const double m = plane.normal.norm();
    const Vec3 nh = plane.normal / m;
    const double dh = plane.offset / m;
    const double touch = planeTouchTolerance(dh, largestCoordinate(s) + s.radius);
    std::vector<RoundedPoint> ends;
    double lowest = INFINITY;
    for (const Vec3& p : s.vertices) {
        const double center = nh.dot(p) - dh, gap = center - s.radius;  // the end sphere's lowest point
        lowest = std::min(lowest, gap);
        ends.push_back({p - s.radius * nh, p - center * nh, -gap, p});
    }
    const bool colliding = lowest <= touch;
    std::vector<RoundedPoint> pts;
    for (const RoundedPoint& e : ends)
        if (colliding ? -e.depth <= touch : -e.depth <= lowest + touch) pts.push_back(e);
    for (RoundedPoint& p : pts) p.depth = std::max(p.depth, 0.0);
    if (pts.size() == 2 && (pts[0].core - pts[1].core).norm() == 0) pts.pop_back();  // a zero-length capsule
    std::vector<Vec3> cores;
    for (const RoundedPoint& p : pts) cores.push_back(p.core);
    const Vec3 n = sIsA ? Vec3(-nh) : nh;  // from a toward b: the body toward the half-space, or back
    return roundedAnswer(colliding, colliding ? std::max(-lowest, 0.0) : lowest, n, pts, sIsA, roundedFeature(s, cores),
                         {{"type", "plane"}}, maxPoints);
}

// The capsule's segment clipped to the side planes of `face` of the polytope, each clipped end whose
// sphere reaches the face (within `touch`) a contact point. Empty when none does.
std::vector<RoundedPoint> capsuleOnFace(const QueryShape& capsule, const HullBody& body, int face, double touch) {
    const ConvexPolyhedron& mesh = body.mesh;
    const Vec3 nf = mesh.face(face).normal;
    const double df = mesh.face(face).offset;
    const Vec3 p0 = capsule.vertices[0], p1 = capsule.vertices[1];
    double t0 = 0.0, t1 = 1.0;
    const std::vector<int> loop = mesh.faceVertices(face);
    for (size_t k = 0; k < loop.size(); ++k) {
        const Vec3 v = mesh.position(loop[k]), w = mesh.position(loop[(k + 1) % loop.size()]);
        const Vec3 side = (w - v).cross(nf);  // outward in the face's plane (counter-clockwise from outside)
        const double s0 = side.dot(p0 - v), s1 = side.dot(p1 - v);
        if (s0 > 0 && s1 > 0) return {};
        if (s0 > 0) t0 = std::max(t0, s0 / (s0 - s1));
        if (s1 > 0) t1 = std::min(t1, s0 / (s0 - s1));
    }
    if (t0 > t1) return {};
    std::vector<RoundedPoint> pts;
    for (double t : {t0, t1}) {
        const Vec3 q = p0 + t * (p1 - p0);
        const double center = nf.dot(q) - df, gap = center - capsule.radius;
        if (gap <= touch) pts.push_back({q - capsule.radius * nf, q - center * nf, std::max(-gap, 0.0), q});
        if (t0 == t1) break;
    }
    return pts;
}

// The face of the body whose outward normal is −fromS to rounding (the contact normal from the other
// shape is this face's normal), or −1.
int faceFacing(const HullBody& body, const Vec3& fromS) {
    int face = -1;
    double best = 1.0 - 1e-9;
    for (int f = 0; f < body.mesh.faceCount(); ++f) {
        const double c = -body.mesh.face(f).normal.dot(fromS);
        if (c >= best) best = c, face = f;
    }
    return face;
}

// The contact normal (from a toward b) when the points lie on the other body's face: that face's own
// outward normal, which points from the other body toward s (issue 21 §3: a face's normal from the
// input, not the rounded answer of EPA, whose direction may differ from it by the faceFacing slack, so
// that every point keeps point_a − point_b = depth·n exactly as the face gave it).
Vec3 faceNormalFromTo(const Vec3& outwardOfOther, bool sIsA) { return sIsA ? Vec3(-outwardOfOther) : outwardOfOther; }

// The answer of a rounded or curved pair: on a face, the face's normal and its points' depths; else the
// penetration op's deepest pair.
Json onFaceOrDeepest(bool colliding, const ShapePairAnswer& ans, const std::optional<Vec3>& faceNormal,
                     const std::vector<RoundedPoint>& pts, bool sIsA, const Json& featureS, const Json& featureOther,
                     int maxPoints) {
    double depth = 0.0;
    for (const RoundedPoint& p : pts) depth = std::max(depth, p.depth);
    if (!colliding) return roundedAnswer(false, ans.distance, ans.normal, pts, sIsA, featureS, featureOther, maxPoints);
    if (faceNormal) return roundedAnswer(true, depth, *faceNormal, pts, sIsA, featureS, featureOther, maxPoints);
    return roundedAnswer(true, std::max(depth, ans.depth), ans.normal, pts, sIsA, featureS, featureOther, maxPoints);
}

// A sphere or capsule s against a bounded shape `other` (polytope, aabb, obb, sphere, capsule).
Json roundedBounded(const QueryShape& s, const QueryShape& other, bool sIsA, int maxPoints, const JsonNode& otherNode) {
    const ShapePairAnswer ans = sIsA ? penetrationOf(s, other) : penetrationOf(other, s);
    const double touch = touchTolerance(s, other);
    const bool colliding = ans.intersect || ans.distance <= touch;
    const Vec3 fromS = sIsA ? ans.normal : Vec3(-ans.normal);  // from s toward the other shape
    const Vec3 onS = sIsA ? ans.pointA : ans.pointB, onOther = sIsA ? ans.pointB : ans.pointA;
    std::vector<RoundedPoint> pts = {{onS, onOther, colliding ? ans.depth : 0.0, Vec3(onS - s.radius * fromS)}};
    std::optional<Vec3> faceNormal;  // set when the points come from the other body's face
    Json otherFeature;
    if (rounded(other)) {
        otherFeature = roundedFeature(other, {Vec3(onOther + other.radius * fromS)});
    } else if (other.isCurved()) {
        otherFeature = curvedFeature(other.curved, {onOther});
    } else {
        const HullBody body = makeHullBody(other, otherNode);
        const int face = faceFacing(body, fromS);
        if (colliding && s.kind == Kind::Capsule && face >= 0) {
            std::vector<RoundedPoint> clipped = capsuleOnFace(s, body, face, touch);
            double reach = 0.0;
            for (const RoundedPoint& p : clipped) reach = std::max(reach, p.depth);
            // The face must hold the deepest point: a face split into triangles by a vertex 1e-9 off
            // its plane faces the normal as well as the whole face did, and one triangle's clip lost
            // the deeper end (depth 0.50 where the penetration is 0.55). Then the penetration's
            // deepest pair stands alone.
            if (!clipped.empty() && reach >= ans.depth - touch - 1e-9 * ans.depth) {
                pts = clipped;
                faceNormal = faceNormalFromTo(body.mesh.face(face).normal, sIsA);
            }
        }
        otherFeature = face >= 0 ? featureJson(body, {FeatureType::Face, face})
                                 : featureJson(body, supportFeature(body, Vec3(-fromS)));
    }
    std::vector<Vec3> cores;
    for (const RoundedPoint& p : pts) cores.push_back(p.core);
    return onFaceOrDeepest(colliding, ans, faceNormal, pts, sIsA, roundedFeature(s, cores), otherFeature, maxPoints);
}

// ---------------------------------------------------------------------------------------------
// Cylinders and cones (query_contact_curved.h), in the query's units: on the ground plane and on a
// polytope face that the contact normal is the normal of, their rims clipped to it; against
// anything else one point, the penetration op's deepest pair. Sphere and capsule against them:
// the rounded rules above.

std::vector<RoundedPoint> roundedPoints(const std::vector<CurvedContactPoint>& pts) {
    std::vector<RoundedPoint> out;
    for (const CurvedContactPoint& p : pts) out.push_back({p.onSolid, p.onFace, p.depth, p.onSolid});
    return out;
}

Json curvedFeatureOf(const QueryShape& s, const std::vector<RoundedPoint>& pts) {
    std::vector<Vec3> at;
    for (const RoundedPoint& p : pts) at.push_back(p.onS);
    return curvedFeature(s.curved, at);
}

// A cylinder or cone s against the solid half-space n̂·x <= d̂ of `plane`.
Json curvedPlane(const QueryShape& s, const QueryShape& plane, bool sIsA, int maxPoints) {
    const auto [nh, dh] = unitPlane(plane);
    const double touch = planeTouchTolerance(dh, largestCoordinate(s));
    const Vec3 low = s.curved.support(Vec3(-nh));
    const double lowest = nh.dot(low) - dh;  // signed height of the solid's lowest point
    const bool colliding = lowest <= touch;
    std::vector<RoundedPoint> pts = {{low, Vec3(low - lowest * nh), std::max(-lowest, 0.0), low}};
    if (colliding) {
        std::vector<RoundedPoint> manifold = roundedPoints(curvedOnFace(s.curved, ReferenceFace{nh, dh, {}}, maxPoints, touch));
        if (!manifold.empty()) pts = manifold;
    }
    const Vec3 n = sIsA ? Vec3(-nh) : nh;  // from a toward b: the body toward the half-space, or back
    return roundedAnswer(colliding, colliding ? std::max(-lowest, 0.0) : lowest, n, pts, sIsA, curvedFeatureOf(s, pts),
                         {{"type", "plane"}}, maxPoints);
}

// A cylinder or cone s against a polytope, aabb, obb, cylinder or cone `other`.
Json curvedBounded(const QueryShape& s, const QueryShape& other, bool sIsA, int maxPoints, const JsonNode& otherNode) {
    const ShapePairAnswer ans = sIsA ? penetrationOf(s, other) : penetrationOf(other, s);
    const double touch = touchTolerance(s, other);
    const bool colliding = ans.intersect || ans.distance <= touch;
    const Vec3 fromS = sIsA ? ans.normal : Vec3(-ans.normal);  // from s toward the other shape
    const Vec3 onS = sIsA ? ans.pointA : ans.pointB, onOther = sIsA ? ans.pointB : ans.pointA;
    std::vector<RoundedPoint> pts = {{onS, onOther, colliding ? ans.depth : 0.0, onS}};
    std::optional<Vec3> faceNormal;  // set when the points come from the other body's face
    Json otherFeature;
    if (other.isCurved()) {
        otherFeature = curvedFeature(other.curved, {onOther});
    } else {
        const HullBody body = makeHullBody(other, otherNode);
        const int face = faceFacing(body, fromS);
        if (colliding && face >= 0) {
            ReferenceFace ref{body.mesh.face(face).normal, body.mesh.face(face).offset, {}};
            for (int v : body.mesh.faceVertices(face)) ref.corners.push_back(body.mesh.position(v));
            std::vector<RoundedPoint> manifold = roundedPoints(curvedOnFace(s.curved, ref, maxPoints, touch));
            if (!manifold.empty()) {
                pts = manifold;
                faceNormal = faceNormalFromTo(ref.normal, sIsA);
            }
        }
        otherFeature = face >= 0 ? featureJson(body, {FeatureType::Face, face})
                                 : featureJson(body, supportFeature(body, Vec3(-fromS)));
    }
    return onFaceOrDeepest(colliding, ans, faceNormal, pts, sIsA, curvedFeatureOf(s, pts), otherFeature, maxPoints);
}

// The local frame of a contact query: the first body's first vertex as origin, and the power of two
// that brings the bodies' largest local coordinate into [0.5, 1). A plane does not set the scale:
// a unit box against a plane at offset 1e300 keeps its size (its depth is then ~1e300 local units).
LocalFrame contactFrame(const QueryShape& a, const QueryShape& b) {
    LocalFrame f;
    f.origin = (a.kind == Kind::Plane ? b : a).vertices.front();
    double m = 0.0;
    for (const QueryShape* s : {&a, &b})
        for (const Vec3& v : s->vertices) m = std::max(m, (v - f.origin).cwiseAbs().maxCoeff());
    if (m > 0 && std::isfinite(m)) std::frexp(m, &f.k), f.k = -f.k;
    return f;
}

Json contactQuery(ObjectReader& r) {
    JsonNode an = r.get("a"), bn = r.get("b");
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    int maxPoints = 4;
    if (auto m = r.find("max_points")) maxPoints = m->asInt(1, 64);
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    const auto solid = [](const QueryShape& s) {
        return s.kind == Kind::Polytope || s.kind == Kind::Aabb || s.kind == Kind::Obb;
    };
    for (const auto& [s, node] : {std::pair{&a, &an}, std::pair{&b, &bn}}) {
        if (!solid(*s) && !rounded(*s) && !s->isCurved() && s->kind != Kind::Plane)
            node->fail(std::string("contact supports polytope, aabb, obb, sphere, capsule, cylinder, cone and plane "
                                   "shapes, not ") +
                       nameOf(s->kind));
        requireHullVerticesWithinLimit(s->vertices.size(), "contact", *node);
    }
    if (a.kind == Kind::Plane && b.kind == Kind::Plane)
        bn.fail("contact needs at least one bounded shape (two planes given)");
    if (rounded(a) || rounded(b)) {
        Json out;
        if (a.kind == Kind::Plane) out = roundedPlane(b, a, false, maxPoints);
        else if (b.kind == Kind::Plane) out = roundedPlane(a, b, true, maxPoints);
        else if (rounded(a)) out = roundedBounded(a, b, true, maxPoints, bn);
        else out = roundedBounded(b, a, false, maxPoints, an);
        if (wantTrace) out["trace"] = {{"algorithm", "rounded"}};
        requireFiniteAnswer(out);
        return out;
    }
    if (a.isCurved() || b.isCurved()) {
        Json out;
        if (a.kind == Kind::Plane) out = curvedPlane(b, a, false, maxPoints);
        else if (b.kind == Kind::Plane) out = curvedPlane(a, b, true, maxPoints);
        else if (a.isCurved()) out = curvedBounded(a, b, true, maxPoints, bn);
        else out = curvedBounded(b, a, false, maxPoints, an);
        if (wantTrace) out["trace"] = {{"algorithm", "curved"}};
        requireFiniteAnswer(out);
        return out;
    }

    // The touching rule's tolerance, from the shapes as given (world units).
    const QueryShape& plane = a.kind == Kind::Plane ? a : b;
    const QueryShape& body = a.kind == Kind::Plane ? b : a;
    double touch = 0.0;
    if (plane.kind == Kind::Plane) {
        const double m = plane.normal.norm();
        touch = planeTouchTolerance(plane.offset / m, largestCoordinate(body));
    } else {
        touch = touchTolerance(a, b);
    }
    const LocalFrame frame = contactFrame(a, b);
    toLocal(a, frame);
    toLocal(b, frame);
    if (plane.kind == Kind::Plane && !std::isfinite((a.kind == Kind::Plane ? a : b).offset))
        (a.kind == Kind::Plane ? an : bn)
            .fail("the plane is farther from the body than double precision spans (offset / body size above ~1e308)");
    touch = std::ldexp(touch, frame.k);
    Json out;
    if (b.kind == Kind::Plane) out = bodyPlane(makeHullBody(a, an), b, true, maxPoints, wantTrace, touch, frame);
    else if (a.kind == Kind::Plane) out = bodyPlane(makeHullBody(b, bn), a, false, maxPoints, wantTrace, touch, frame);
    else out = bodyBody(makeHullBody(a, an), makeHullBody(b, bn), maxPoints, wantTrace, touch, frame, bn);
    requireFiniteAnswer(out);
    return out;
}

}  // namespace

Json answerContactQuery(const std::string& op, ObjectReader& reader) {
    if (op == "mass_properties") return answerMassPropertiesQuery(reader);
    return contactQuery(reader);
}

}  // namespace cdlab::demos
