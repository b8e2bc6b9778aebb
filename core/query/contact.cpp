// The contact query (core/query/contact.h). Moved from app/query/query_contact.cpp (`cdlab query`'s
// contact op) with its arithmetic, operation order and tie-breaking unchanged: every answer keeps
// its bits (tests/app/query/*contact*_test.cpp).
#include "core/query/contact.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>
#include <span>
#include <utility>

#include "core/closest/closest_point.h"
#include "core/closest/edge_pair_distance.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "core/query/touch.h"

namespace cdlab {

const char* nameOf(ContactMethod method) {
    switch (method) {
        case ContactMethod::Rounded: return "rounded";
        case ContactMethod::Curved: return "curved";
        case ContactMethod::PolytopePlane: return "polytope-plane";
        case ContactMethod::Sat: return "sat";
    }
    return "?";
}

const char* nameOf(ContactFeature::Type type) {
    switch (type) {
        case ContactFeature::Type::None: return "none";
        case ContactFeature::Type::Vertex: return "vertex";
        case ContactFeature::Type::Edge: return "edge";
        case ContactFeature::Type::Face: return "face";
        case ContactFeature::Type::Plane: return "plane";
        case ContactFeature::Type::Curved: return "curved";
    }
    return "none";
}

namespace {

using ShapeKind = QueryShape::Kind;

// A capsule's contact point is at an end when its segment parameter is within this of 0 or 1.
constexpr double kCapsuleEndSlack = 1e-9;
// A polytope face faces the contact normal when −(its outward normal)·n >= 1 − kFaceFacingSlack.
constexpr double kFaceFacingSlack = 1e-9;
// A capsule clipped to a face keeps the clip when its deepest point reaches the penetration's depth
// within the touching tolerance plus kFaceReachRelative of that depth.
constexpr double kFaceReachRelative = 1e-9;

// A bounded query shape as a convex polyhedron (world or local frame) and the map back to input vertices.
struct ContactHull {
    ConvexPolyhedron mesh;
    std::vector<int> inputIndex;  // hull vertex -> input vertex
};

// The convex hull of shape `which` (0: a, 1: b) of the query; on failure r's status is HullFailed.
// A hull that the default tolerance (4096 ulps of the coordinates plus the body's diagonal) finds
// flat is tried again at kThinHullEpsilonFactor ulps: a needle 1e-12 of its length wide is a solid
// for every other op (issue 41 (e)); a body flat within that stays refused, with the first message.
constexpr double kThinHullEpsilonFactor = 64.0;

std::optional<ContactHull> contactHull(const QueryShape& s, int which, ContactResult& r) {
    HullResult h = convexHull(s.vertices);
    if (h.status == HullStatus::AllCollinear || h.status == HullStatus::AllCoplanar) {
        HullOptions thin;
        thin.epsilonFactor = kThinHullEpsilonFactor;
        if (HullResult t = convexHull(s.vertices, thin); t.ok()) h = std::move(t);
    }
    if (!h.ok()) {
        r.status = ContactStatus::HullFailed;
        r.shape = which;
        r.message = h.message;
        return std::nullopt;
    }
    return ContactHull{std::move(h.polyhedron), std::move(h.inputIndex)};
}

// Translates the shape by -origin, then scales it by 2^k (a plane n·x = d becomes n·x = d - n·origin).
void toContactFrame(QueryShape& s, const ContactFrame& f) {
    for (Vec3& v : s.vertices) v -= f.origin;
    if (s.kind == ShapeKind::Plane) s.offset -= s.normal.dot(f.origin);
    scaleShape(s, f.exponent);
}

// A feature of the hull, by its input vertex indices.
ContactFeature hullFeature(const ContactHull& b, const FeatureRef& f) {
    ContactFeature out;
    std::vector<int>& v = out.vertices;
    if (f.type == FeatureType::Vertex) v = {f.index};
    else if (f.type == FeatureType::Edge) v = {b.mesh.edgeVertices(f.index).first, b.mesh.edgeVertices(f.index).second};
    else if (f.type == FeatureType::Face) v = b.mesh.faceVertices(f.index);
    for (int& i : v) i = b.inputIndex[i];
    switch (f.type) {
        case FeatureType::None: out.type = ContactFeature::Type::None; break;
        case FeatureType::Vertex: out.type = ContactFeature::Type::Vertex; break;
        case FeatureType::Edge: out.type = ContactFeature::Type::Edge; break;
        case FeatureType::Face: out.type = ContactFeature::Type::Face; break;
    }
    return out;
}

// Whether feature f of b holds every point of pts within tol (local units): a vertex within tol of
// each, an edge's segment, a face's polygon.
bool featureHolds(const ContactHull& b, const FeatureRef& f, std::span<const Vec3> pts, double tol) {
    const auto& v = b.mesh.vertices();
    for (const Vec3& p : pts) {
        if (f.type == FeatureType::Vertex) {
            if (!((p - v[std::size_t(f.index)].position).norm() <= tol)) return false;
        } else if (f.type == FeatureType::Edge) {
            const auto [i, j] = b.mesh.edgeVertices(f.index);
            const Segment s{v[std::size_t(i)].position, v[std::size_t(j)].position};
            if (!((p - closestPointOnSegment(p, s).point).norm() <= tol)) return false;
        } else if (f.type == FeatureType::Face) {
            // The distance to the polygon (convex: its fan's triangles), each triangle's normal in
            // double-double: a sliver face's normal from plain products tilts by ~u / its width
            // (contact_edge_edge_depth0: a needle's face held the clip's points only in exact terms).
            const std::vector<int> fv = b.mesh.faceVertices(f.index);
            if (fv.size() < 3) return false;
            const Vec3& q0 = v[std::size_t(fv[0])].position;
            double best = INFINITY;
            for (std::size_t k = 1; k + 1 < fv.size(); ++k)
                best = std::min(best, pointTriangleDistance(p, q0, v[std::size_t(fv[k])].position,
                                                            v[std::size_t(fv[k + 1])].position)
                                          .distance);
            if (!(best <= tol)) return false;
        } else {
            return false;
        }
    }
    return true;
}

// The feature of b that holds the reported points: `given` when it does, else the first vertex,
// edge or face that does (a face axis kept by preference whose manifold fell back to the touching
// pair; a separated pair whose support set is one triangle of a split quad while the closest point
// lies on the other). tol: 1e-9 of the body's bounding-box diagonal + 64 ulps of its input
// coordinates (`frame`: the local units' origin was subtracted with rounding).
// Test: cdlab stress "contact manifolds" ("feature holds point").
FeatureRef featureHolding(const ContactHull& b, const FeatureRef& given, std::span<const Vec3> pts, const Vec3& dir,
                          const ContactFrame& frame) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    double top = -INFINITY;
    for (const auto& x : b.mesh.vertices())
        lo = lo.cwiseMin(x.position), hi = hi.cwiseMax(x.position), top = std::max(top, dir.dot(x.position));
    const double rounding = 64 * DBL_EPSILON *
                            (std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) +
                             std::ldexp(frame.origin.cwiseAbs().maxCoeff(), frame.exponent));
    const double tol = 1e-9 * (hi - lo).norm() + rounding;
    if (pts.empty()) return given;
    // Only features of the support set along dir (a point near an edge lies on both its faces).
    const auto supporting = [&](const std::vector<int>& vs) {
        for (int v : vs)
            if (!(dir.dot(b.mesh.vertices()[std::size_t(v)].position) >= top - 2 * tol)) return false;
        return true;
    };
    // `given`, else the support set's vertex, edge or face holding the points, else any feature (a
    // touching pair along a face normal kept by preference meets the body away from its support set
    // along that normal: core/contact/contact_stages.cpp, exactTouchingPairAlong) — first to
    // rounding (1e-12 of the size), then to tol: a point inside a face 0.6 tol from one of its
    // edges is the face's, not the edge's (stress "contact manifolds" 600 s #19637).
    if (featureHolds(b, given, pts, tol)) return given;
    for (const double t : {1e-12 * (hi - lo).norm() + rounding, tol}) {
        for (const bool anywhere : {false, true}) {
            for (int i = 0; i < b.mesh.vertexCount(); ++i)
                if ((anywhere || supporting({i})) && featureHolds(b, {FeatureType::Vertex, i}, pts, t))
                    return {FeatureType::Vertex, i};
            for (int e = 0; e < b.mesh.edgeCount(); ++e) {
                const auto [i, j] = b.mesh.edgeVertices(e);
                if ((anywhere || supporting({i, j})) && featureHolds(b, {FeatureType::Edge, e}, pts, t))
                    return {FeatureType::Edge, e};
            }
            for (int f = 0; f < b.mesh.faceCount(); ++f)
                if ((anywhere || supporting(b.mesh.faceVertices(f))) && featureHolds(b, {FeatureType::Face, f}, pts, t))
                    return {FeatureType::Face, f};
        }
    }
    return given;
}

ContactFeature planeFeature() {
    ContactFeature f;
    f.type = ContactFeature::Type::Plane;
    return f;
}

// The support feature of a body in direction d: the vertices within tol of the maximum of d·x,
// as a vertex, an edge (two adjacent vertices) or the face holding them (core/contact/contact_plane.h
// does the same for -n̂; here reused by calling it with a plane through the support point).
FeatureRef supportFeatureOf(const ContactHull& b, const Vec3& d) {
    double top = -INFINITY;
    for (const auto& v : b.mesh.vertices()) top = std::max(top, d.dot(v.position));
    // The plane -d·x = -top touches the body from the side d (the body lies on its + side): the
    // closest feature to it is the support set.
    const PlaneContactResult r = contactPolyhedronPlane(b.mesh, Transform{}, Plane{-d, -top});
    return r.feature;
}

// Local contact points in the input's units, A and B swapped when `swap`.
std::vector<ContactPoint> worldPoints(std::span<const ContactPoint> pts, bool swap, const ContactFrame& frame) {
    std::vector<ContactPoint> out;
    for (const ContactPoint& c : pts) {
        const Vec3 pa = frame.toWorld(swap ? c.pointB : c.pointA), pb = frame.toWorld(swap ? c.pointA : c.pointB);
        out.push_back({pa, pb, frame.length(c.depth)});
    }
    return out;
}

// Polytope (body) vs plane; bodyIsA says which side of the query the body is on. `touch` is the
// touching rule's tolerance (local units): s_min > touch is separated, as for the distance query.
ContactResult bodyPlaneContact(const ContactHull& body, const QueryShape& plane, bool bodyIsA, int maxPoints,
                               PlaneContactTrace* trace, double touch, const ContactFrame& frame) {
    ContactResult out;
    out.method = ContactMethod::PolytopePlane;
    PlaneContactOptions opt;
    opt.maxPoints = maxPoints;
    const Plane local{plane.normal, plane.offset};
    PlaneContactResult r = contactPolyhedronPlane(body.mesh, Transform{}, local, opt, trace);
    if (r.status == PlaneContactStatus::InvalidInput) {
        out.status = ContactStatus::ContactFailed;
        out.message = r.message;
        return out;
    }
    const bool colliding = r.signedDistance <= touch;
    if (colliding && !r.colliding()) {  // the core's feature tolerance is below the rule's: widen it
        opt.tolerance = std::max(touch, r.signedDistance);
        r = contactPolyhedronPlane(body.mesh, Transform{}, local, opt, trace);
    }
    // Core: A = body, normal = -n̂ (body toward the half-space). Swapped when the plane is a.
    out.normal = bodyIsA ? r.normal : Vec3(-r.normal);
    out.colliding = colliding;
    if (colliding) {
        out.depth = frame.length(r.depth);
        out.points = worldPoints(r.manifold, !bodyIsA, frame);
    } else {
        std::vector<ContactPoint> closest;
        for (size_t i = 0; i < r.featurePoints.size(); ++i)
            closest.push_back({r.featurePoints[i], r.featurePointsOnPlane[i], 0.0});
        out.distance = frame.length(r.signedDistance);
        out.points = worldPoints(closest, !bodyIsA, frame);
    }
    const ContactFeature bodyFeature = hullFeature(body, r.feature);
    out.featureA = bodyIsA ? bodyFeature : planeFeature();
    out.featureB = bodyIsA ? planeFeature() : bodyFeature;
    return out;
}

// Separated polytopes: the distance and closest points by GJK; the features are the support sets
// of each body along the separating direction (they hold the closest points).
void separatedBodies(const ContactHull& a, const ContactHull& b, const GjkResult& g, const ContactFrame& frame,
                     ContactResult& out) {
    const Vec3 n = g.separatingAxis;
    out.colliding = false;
    out.distance = frame.length(g.distance);
    out.normal = n;
    out.points = {ContactPoint{frame.toWorld(g.pointA), frame.toWorld(g.pointB), 0.0}};
    out.featureA = hullFeature(a, featureHolding(a, supportFeatureOf(a, n), std::span<const Vec3>(&g.pointA, 1), n, frame));
    out.featureB = hullFeature(b, featureHolding(b, supportFeatureOf(b, -n), std::span<const Vec3>(&g.pointB, 1), -n, frame));
}

// Two polytopes: GJK decides (the touching rule, `touch` in local units); colliding pairs get the
// SAT manifold (Gregorius), the SAT trace is recorded either way. nearlyParallel: whether the SAT
// met nearly parallel edges (an answer that depends on the vertices' rounding).
ContactResult bodyBodyContact(const ContactHull& a, const ContactHull& b, int maxPoints, double maxEdgePairs,
                              SatContactTrace* trace, double touch, const ContactFrame& frame, bool& nearlyParallel) {
    ContactResult out;
    out.method = ContactMethod::Sat;
    const GjkResult g = gjkDistance(PolytopeShape(a.mesh.positions()), PolytopeShape(b.mesh.positions()));
    if (g.status == GjkStatus::InvalidInput) {
        out.status = ContactStatus::PairFailed;
        out.pairStatus = PairStatus::NonFiniteSupport;
        return out;
    }
    const bool colliding = g.intersect() || g.distance <= touch;
    if (!colliding && !trace) {  // no SAT needed: linear time
        separatedBodies(a, b, g, frame, out);
        return out;
    }
    if (double(a.mesh.edgeCount()) * double(b.mesh.edgeCount()) > maxEdgePairs) {
        out.status = ContactStatus::EdgePairsOverLimit;
        out.shape = 1;
        out.edgesA = a.mesh.edgeCount();
        out.edgesB = b.mesh.edgeCount();
        return out;
    }
    SatContactOptions opt;
    opt.maxPoints = maxPoints;
    // Every edge pair tested, as the traced query does: nearlyParallel (the re-run on exact
    // vertices) counts the nearly parallel pairs met, which the pruning could skip.
    opt.pruneEdgeArcs = false;
    SatContactResult r = contactPolyhedra(a.mesh, Transform{}, b.mesh, Transform{}, opt, trace);
    if (r.status == SatContactStatus::InvalidInput) {
        out.status = ContactStatus::ContactFailed;
        out.message = r.message;
        return out;
    }
    if (colliding && !r.colliding()) {  // rounding put the SAT just past its band: widen it to the rule's
        opt.tolerance = std::max(touch, r.separation);
        r = contactPolyhedra(a.mesh, Transform{}, b.mesh, Transform{}, opt, trace);
    }
    nearlyParallel = r.nearlyParallelEdgePairs > 0;
    if (!colliding) {
        separatedBodies(a, b, g, frame, out);
        return out;
    }
    out.colliding = true;
    out.depth = frame.length(r.depth);
    out.normal = r.normal;
    out.points = worldPoints(r.manifold, false, frame);
    out.axis = r.axisKind;
    std::vector<Vec3> onA, onB;
    for (const ContactPoint& c : r.manifold) onA.push_back(c.pointA), onB.push_back(c.pointB);
    out.featureA = hullFeature(a, featureHolding(a, r.featureA, onA, r.normal, frame));
    out.featureB = hullFeature(b, featureHolding(b, r.featureB, onB, Vec3(-r.normal), frame));
    return out;
}

// ---------------------------------------------------------------------------------------------
// Spheres and capsules (core/query/contact.h, "Spheres and capsules"), in the query's units.

bool isRounded(const QueryShape& s) { return s.kind == ShapeKind::Sphere || s.kind == ShapeKind::Capsule; }

// The core feature of a sphere or capsule under the core points `at` (one or two).
ContactFeature roundedFeature(const QueryShape& s, const std::vector<Vec3>& at) {
    ContactFeature f;
    if (s.kind == ShapeKind::Sphere) {
        f.type = ContactFeature::Type::Vertex;
        f.vertices = {0};
        return f;
    }
    const Vec3 a = s.vertices[0], ab = s.vertices[1] - a;
    const double len2 = ab.squaredNorm();
    bool end0 = false, end1 = false, inside = false;
    for (const Vec3& p : at) {
        const double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
        if (t <= kCapsuleEndSlack) end0 = true;
        else if (t >= 1 - kCapsuleEndSlack) end1 = true;
        else inside = true;
    }
    if (inside || (end0 && end1)) {
        f.type = ContactFeature::Type::Edge;
        f.vertices = {0, 1};
        return f;
    }
    f.type = ContactFeature::Type::Vertex;
    f.vertices = {end1 ? 1 : 0};
    return f;
}

// A contact point of the rounded (or curved) shape s, which the answer puts on side A when sIsA.
struct RoundedContact {
    Vec3 onS, onOther;  // on the rounded shape, on the other shape
    double depth;
    Vec3 core;  // the core point under onS
};

// The answer of a rounded or curved shape s: its points sorted deepest first (stable: ties keep
// their order) and cut to maxPoints; normal n from A toward B.
ContactResult roundedAnswer(ContactMethod method, bool colliding, double distanceOrDepth, const Vec3& n,
                            std::vector<RoundedContact> pts, bool sIsA, const ContactFeature& sFeature,
                            const ContactFeature& otherFeature, int maxPoints) {
    std::stable_sort(pts.begin(), pts.end(), [](const RoundedContact& x, const RoundedContact& y) { return x.depth > y.depth; });
    if (static_cast<int>(pts.size()) > maxPoints) pts.resize(maxPoints);
    ContactResult out;
    out.method = method;
    out.colliding = colliding;
    for (const RoundedContact& p : pts) {
        const Vec3 pa = sIsA ? p.onS : p.onOther, pb = sIsA ? p.onOther : p.onS;
        out.points.push_back({pa, pb, colliding ? p.depth : 0.0});
    }
    if (colliding) out.depth = distanceOrDepth;
    else out.distance = distanceOrDepth;
    out.normal = n;
    out.featureA = sIsA ? sFeature : otherFeature;
    out.featureB = sIsA ? otherFeature : sFeature;
    return out;
}

// A sphere or capsule s against the solid half-space n̂·x <= d̂ of `plane`.
ContactResult roundedPlane(const QueryShape& s, const QueryShape& plane, bool sIsA, int maxPoints) {
    const double m = plane.normal.norm();
    const Vec3 nh = plane.normal / m;
    const double dh = plane.offset / m;
    const double touch = planeTouchTolerance(dh, largestCoordinate(s) + s.radius);
    std::vector<RoundedContact> ends;
    double lowest = INFINITY;
    for (const Vec3& p : s.vertices) {
        const double center = nh.dot(p) - dh, gap = center - s.radius;  // the end sphere's lowest point
        lowest = std::min(lowest, gap);
        ends.push_back({p - s.radius * nh, p - center * nh, -gap, p});
    }
    const bool colliding = lowest <= touch;
    std::vector<RoundedContact> pts;
    for (const RoundedContact& e : ends)
        if (colliding ? -e.depth <= touch : -e.depth <= lowest + touch) pts.push_back(e);
    for (RoundedContact& p : pts) p.depth = std::max(p.depth, 0.0);
    if (pts.size() == 2 && (pts[0].core - pts[1].core).norm() == 0) pts.pop_back();  // a zero-length capsule
    std::vector<Vec3> cores;
    for (const RoundedContact& p : pts) cores.push_back(p.core);
    const Vec3 n = sIsA ? Vec3(-nh) : nh;  // from a toward b: the body toward the half-space, or back
    return roundedAnswer(ContactMethod::Rounded, colliding, colliding ? std::max(-lowest, 0.0) : lowest, n, pts, sIsA,
                         roundedFeature(s, cores), planeFeature(), maxPoints);
}

// The capsule's segment clipped to the side planes of `face` of the polytope, each clipped end whose
// sphere reaches the face (within `touch`) a contact point. Empty when none does.
std::vector<RoundedContact> capsuleOnFace(const QueryShape& capsule, const ContactHull& body, int face, double touch) {
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
    std::vector<RoundedContact> pts;
    for (double t : {t0, t1}) {
        const Vec3 q = p0 + t * (p1 - p0);
        const double center = nf.dot(q) - df, gap = center - capsule.radius;
        if (gap <= touch) pts.push_back({q - capsule.radius * nf, q - center * nf, std::max(-gap, 0.0), q});
        if (t0 == t1) break;
    }
    return pts;
}

// The face of the body whose outward normal is −fromS to rounding (the contact normal from the other
// shape is this face's normal), or −1. Ties go to the last face (`>=`).
int faceFacing(const ContactHull& body, const Vec3& fromS) {
    int face = -1;
    double best = 1.0 - kFaceFacingSlack;
    for (int f = 0; f < body.mesh.faceCount(); ++f) {
        const double c = -body.mesh.face(f).normal.dot(fromS);
        if (c >= best) best = c, face = f;
    }
    return face;
}

// The contact normal (from a toward b) when the points lie on the other body's face: that face's own
// outward normal, which points from the other body toward s (issue 21 §3: a face's normal from the
// input, not the rounded answer of EPA, whose direction may differ from it by the faceFacing slack, so
// that every point keeps pointA − pointB = depth·n exactly as the face gave it).
Vec3 faceNormalFromTo(const Vec3& outwardOfOther, bool sIsA) { return sIsA ? Vec3(-outwardOfOther) : outwardOfOther; }

// The answer of a rounded or curved pair: on a face, the face's normal and its points' depths; else the
// penetration query's deepest pair.
ContactResult onFaceOrDeepest(ContactMethod method, bool colliding, const PairResult& ans,
                              const std::optional<Vec3>& faceNormal, const std::vector<RoundedContact>& pts, bool sIsA,
                              const ContactFeature& featureS, const ContactFeature& featureOther, int maxPoints) {
    double depth = 0.0;
    for (const RoundedContact& p : pts) depth = std::max(depth, p.depth);
    if (!colliding) return roundedAnswer(method, false, ans.distance, ans.normal, pts, sIsA, featureS, featureOther, maxPoints);
    if (faceNormal) return roundedAnswer(method, true, depth, *faceNormal, pts, sIsA, featureS, featureOther, maxPoints);
    return roundedAnswer(method, true, std::max(depth, ans.depth), ans.normal, pts, sIsA, featureS, featureOther, maxPoints);
}

// The penetration query of the pair (s on side A when sIsA): the answer of every rounded and curved
// pair not on a face.
PairResult penetrationOfPair(const QueryShape& s, const QueryShape& other, bool sIsA) {
    PairOptions options;
    options.depth = true;
    return sIsA ? pairQuery(s, other, options) : pairQuery(other, s, options);
}

ContactResult pairFailed(PairStatus status) {
    ContactResult out;
    out.status = ContactStatus::PairFailed;
    out.pairStatus = status;
    return out;
}

ContactFeature curvedFeatureAt(const CurvedSolid& s, const std::vector<Vec3>& points) {
    ContactFeature f;
    f.type = ContactFeature::Type::Curved;
    f.curved = curvedFeature(s, points);
    return f;
}

// A sphere or capsule s against a bounded shape `other` (polytope, aabb, obb, sphere, capsule,
// cylinder, cone). `other` is shape 1 (b) when sIsA, else 0 (a): a failed hull is reported on it.
ContactResult roundedBounded(const QueryShape& s, const QueryShape& other, bool sIsA, int maxPoints) {
    const PairResult ans = penetrationOfPair(s, other, sIsA);
    if (ans.status != PairStatus::Ok) return pairFailed(ans.status);
    const double touch = touchTolerance(s, other);
    const bool colliding = ans.intersect || ans.distance <= touch;
    const Vec3 fromS = sIsA ? ans.normal : Vec3(-ans.normal);  // from s toward the other shape
    const Vec3 onS = sIsA ? ans.pointA : ans.pointB, onOther = sIsA ? ans.pointB : ans.pointA;
    std::vector<RoundedContact> pts = {{onS, onOther, colliding ? ans.depth : 0.0, Vec3(onS - s.radius * fromS)}};
    std::optional<Vec3> faceNormal;  // set when the points come from the other body's face
    ContactFeature otherFeature;
    if (isRounded(other)) {
        otherFeature = roundedFeature(other, {Vec3(onOther + other.radius * fromS)});
    } else if (other.isCurved()) {
        otherFeature = curvedFeatureAt(other.curved, {onOther});
    } else {
        ContactResult hullFailure;
        const std::optional<ContactHull> hull = contactHull(other, sIsA ? 1 : 0, hullFailure);
        if (!hull) return hullFailure;
        const ContactHull& body = *hull;
        const int face = faceFacing(body, fromS);
        if (colliding && s.kind == ShapeKind::Capsule && face >= 0) {
            std::vector<RoundedContact> clipped = capsuleOnFace(s, body, face, touch);
            double reach = 0.0;
            for (const RoundedContact& p : clipped) reach = std::max(reach, p.depth);
            // The face must hold the deepest point: a face split into triangles by a vertex 1e-9 off
            // its plane faces the normal as well as the whole face did, and one triangle's clip lost
            // the deeper end (depth 0.50 where the penetration is 0.55; query_contact_rounded_test
            // "a face split in two by a vertex 1e-9 off its plane"). Then the penetration's deepest
            // pair stands alone.
            if (!clipped.empty() && reach >= ans.depth - touch - kFaceReachRelative * ans.depth) {
                pts = clipped;
                faceNormal = faceNormalFromTo(body.mesh.face(face).normal, sIsA);
            }
        }
        otherFeature = face >= 0 ? hullFeature(body, {FeatureType::Face, face})
                                 : hullFeature(body, supportFeatureOf(body, Vec3(-fromS)));
    }
    std::vector<Vec3> cores;
    for (const RoundedContact& p : pts) cores.push_back(p.core);
    return onFaceOrDeepest(ContactMethod::Rounded, colliding, ans, faceNormal, pts, sIsA, roundedFeature(s, cores),
                           otherFeature, maxPoints);
}

// ---------------------------------------------------------------------------------------------
// Cylinders and cones (core/query/curved_contact.h), in the query's units: on the ground plane and
// on a polytope face that the contact normal is the normal of, their rims clipped to it; against
// anything else one point, the penetration query's deepest pair. Sphere and capsule against them:
// the rounded rules above.

std::vector<RoundedContact> roundedContacts(const std::vector<CurvedContactPoint>& pts) {
    std::vector<RoundedContact> out;
    for (const CurvedContactPoint& p : pts) out.push_back({p.onSolid, p.onFace, p.depth, p.onSolid});
    return out;
}

ContactFeature curvedFeatureOf(const QueryShape& s, const std::vector<RoundedContact>& pts) {
    std::vector<Vec3> at;
    for (const RoundedContact& p : pts) at.push_back(p.onS);
    return curvedFeatureAt(s.curved, at);
}

// A cylinder or cone s against the solid half-space n̂·x <= d̂ of `plane`.
ContactResult curvedPlane(const QueryShape& s, const QueryShape& plane, bool sIsA, int maxPoints) {
    const auto [nh, dh] = unitPlane(plane);
    const double touch = planeTouchTolerance(dh, largestCoordinate(s));
    const Vec3 low = s.curved.support(Vec3(-nh));
    const double lowest = nh.dot(low) - dh;  // signed height of the solid's lowest point
    const bool colliding = lowest <= touch;
    std::vector<RoundedContact> pts = {{low, Vec3(low - lowest * nh), std::max(-lowest, 0.0), low}};
    if (colliding) {
        std::vector<RoundedContact> manifold = roundedContacts(curvedOnFace(s.curved, ReferenceFace{nh, dh, {}}, maxPoints, touch));
        if (!manifold.empty()) pts = manifold;
    }
    const Vec3 n = sIsA ? Vec3(-nh) : nh;  // from a toward b: the body toward the half-space, or back
    return roundedAnswer(ContactMethod::Curved, colliding, colliding ? std::max(-lowest, 0.0) : lowest, n, pts, sIsA,
                         curvedFeatureOf(s, pts), planeFeature(), maxPoints);
}

// A cylinder or cone s against a polytope, aabb, obb, cylinder or cone `other` (shape 1 when sIsA,
// else 0).
ContactResult curvedBounded(const QueryShape& s, const QueryShape& other, bool sIsA, int maxPoints) {
    const PairResult ans = penetrationOfPair(s, other, sIsA);
    if (ans.status != PairStatus::Ok) return pairFailed(ans.status);
    const double touch = touchTolerance(s, other);
    const bool colliding = ans.intersect || ans.distance <= touch;
    const Vec3 fromS = sIsA ? ans.normal : Vec3(-ans.normal);  // from s toward the other shape
    const Vec3 onS = sIsA ? ans.pointA : ans.pointB, onOther = sIsA ? ans.pointB : ans.pointA;
    std::vector<RoundedContact> pts = {{onS, onOther, colliding ? ans.depth : 0.0, onS}};
    std::optional<Vec3> faceNormal;  // set when the points come from the other body's face
    ContactFeature otherFeature;
    if (other.isCurved()) {
        otherFeature = curvedFeatureAt(other.curved, {onOther});
    } else {
        ContactResult hullFailure;
        const std::optional<ContactHull> hull = contactHull(other, sIsA ? 1 : 0, hullFailure);
        if (!hull) return hullFailure;
        const ContactHull& body = *hull;
        const int face = faceFacing(body, fromS);
        if (colliding && face >= 0) {
            ReferenceFace ref{body.mesh.face(face).normal, body.mesh.face(face).offset, {}};
            for (int v : body.mesh.faceVertices(face)) ref.corners.push_back(body.mesh.position(v));
            std::vector<RoundedContact> manifold = roundedContacts(curvedOnFace(s.curved, ref, maxPoints, touch));
            if (!manifold.empty()) {
                pts = manifold;
                faceNormal = faceNormalFromTo(ref.normal, sIsA);
            }
        }
        otherFeature = face >= 0 ? hullFeature(body, {FeatureType::Face, face})
                                 : hullFeature(body, supportFeatureOf(body, Vec3(-fromS)));
    }
    return onFaceOrDeepest(ContactMethod::Curved, colliding, ans, faceNormal, pts, sIsA, curvedFeatureOf(s, pts),
                           otherFeature, maxPoints);
}

// The local frame of a polytope pair: the first body's first vertex as origin, and the power of two
// that brings the bodies' largest local coordinate into [0.5, 1). A plane does not set the scale:
// a unit box against a plane at offset 1e300 keeps its size (its depth is then ~1e300 local units;
// hostile_query_test "a box against a plane at offset 1e300 answers its depth").
ContactFrame contactFrameOf(const QueryShape& a, const QueryShape& b) {
    ContactFrame f;
    f.origin = (a.kind == ShapeKind::Plane ? b : a).vertices.front();
    double m = 0.0;
    for (const QueryShape* s : {&a, &b})
        for (const Vec3& v : s->vertices) m = std::max(m, (v - f.origin).cwiseAbs().maxCoeff());
    if (m > 0 && std::isfinite(m)) std::frexp(m, &f.exponent), f.exponent = -f.exponent;
    return f;
}

// x - o without rounding: Knuth's TwoSum of x and -o has error term 0.
bool exactDifference(double x, double o) {
    const double s = x - o, bb = s - x;
    return (x - (s - bb)) + (-o - bb) == 0.0;
}

// Two bodies' exact frame: contactFrameOf's, but origin 0 on each axis where some vertex minus the
// first vertex would round (subtracting 0 is exact; a difference that rounds means the bodies span
// more than half their distance from 0 on that axis, so their coordinates there are within a small
// factor of their extent anyway). Its local vertices are the input's exactly, up to the power of two.
ContactFrame exactContactFrameOf(const QueryShape& a, const QueryShape& b) {
    ContactFrame f = contactFrameOf(a, b);
    bool changed = false;
    for (int i = 0; i < 3; ++i) {
        bool exact = true;
        for (const QueryShape* s : {&a, &b})
            for (const Vec3& v : s->vertices) exact = exact && exactDifference(v[i], f.origin[i]);
        if (!exact) f.origin[i] = 0.0, changed = true;
    }
    if (!changed) return f;
    double m = 0.0;
    for (const QueryShape* s : {&a, &b})
        for (const Vec3& v : s->vertices) m = std::max(m, (v - f.origin).cwiseAbs().maxCoeff());
    f.exponent = 0;
    if (m > 0 && std::isfinite(m)) std::frexp(m, &f.exponent), f.exponent = -f.exponent;
    return f;
}

bool isSolidBody(const QueryShape& s) {
    return s.kind == ShapeKind::Polytope || s.kind == ShapeKind::Aabb || s.kind == ShapeKind::Obb;
}

// Two bodies already in `frame` (touch in its units): b's hull first, where both fail b's failure
// is the answer (as `cdlab query` built with GCC always answered, evaluating the two hulls as
// arguments right to left). vertexSensitive: a hull failed or the SAT met nearly parallel edges.
ContactResult bodiesInFrame(const QueryShape& a, const QueryShape& b, const ContactFrame& frame, double touch,
                            const ContactOptions& options, ContactTrace* trace, bool& vertexSensitive) {
    ContactResult r;
    vertexSensitive = true;
    const std::optional<ContactHull> hullB = contactHull(b, 1, r);
    if (!hullB) return r;
    const std::optional<ContactHull> hullA = contactHull(a, 0, r);
    if (!hullA) return r;
    vertexSensitive = false;
    return bodyBodyContact(*hullA, *hullB, options.maxPoints, options.maxSatEdgePairs, trace ? &trace->sat : nullptr,
                           touch, frame, vertexSensitive);
}

ContactResult failedOn(ContactStatus status, int shape) {
    ContactResult out;
    out.status = status;
    out.shape = shape;
    return out;
}

}  // namespace

ContactResult contactQuery(QueryShape a, QueryShape b, const ContactOptions& options, ContactTrace* trace) {
    if (trace) *trace = ContactTrace{};
    const int maxPoints = options.maxPoints;
    // The order of the checks is `cdlab query`'s (its errors name the first one met): per shape its
    // kind, then its vertex count; then two planes.
    int which = 0;
    for (const QueryShape* s : {&a, &b}) {
        if (!isSolidBody(*s) && !isRounded(*s) && !s->isCurved() && s->kind != ShapeKind::Plane)
            return failedOn(ContactStatus::UnsupportedShape, which);
        if (s->vertices.size() > options.maxHullVertices) return failedOn(ContactStatus::HullVerticesOverLimit, which);
        ++which;
    }
    if (a.kind == ShapeKind::Plane && b.kind == ShapeKind::Plane) return failedOn(ContactStatus::TwoPlanes, 1);
    if (isRounded(a) || isRounded(b)) {
        if (a.kind == ShapeKind::Plane) return roundedPlane(b, a, false, maxPoints);
        if (b.kind == ShapeKind::Plane) return roundedPlane(a, b, true, maxPoints);
        if (isRounded(a)) return roundedBounded(a, b, true, maxPoints);
        return roundedBounded(b, a, false, maxPoints);
    }
    if (a.isCurved() || b.isCurved()) {
        if (a.kind == ShapeKind::Plane) return curvedPlane(b, a, false, maxPoints);
        if (b.kind == ShapeKind::Plane) return curvedPlane(a, b, true, maxPoints);
        if (a.isCurved()) return curvedBounded(a, b, true, maxPoints);
        return curvedBounded(b, a, false, maxPoints);
    }

    // The touching rule's tolerance, from the shapes as given (world units).
    const QueryShape& plane = a.kind == ShapeKind::Plane ? a : b;
    const QueryShape& body = a.kind == ShapeKind::Plane ? b : a;
    double touch = 0.0;
    if (plane.kind == ShapeKind::Plane) {
        const double m = plane.normal.norm();
        touch = planeTouchTolerance(plane.offset / m, largestCoordinate(body));
    } else {
        touch = touchTolerance(a, b);
    }
    const double touchWorld = touch;
    const bool twoBodies = a.kind != ShapeKind::Plane && b.kind != ShapeKind::Plane;
    QueryShape aIn = twoBodies ? a : QueryShape{}, bIn = twoBodies ? b : QueryShape{};  // for a second frame
    const ContactFrame frame = contactFrameOf(a, b);
    if (trace) trace->frame = frame;
    toContactFrame(a, frame);
    toContactFrame(b, frame);
    if (plane.kind == ShapeKind::Plane && !std::isfinite((a.kind == ShapeKind::Plane ? a : b).offset))
        return failedOn(ContactStatus::PlaneTooFar, a.kind == ShapeKind::Plane ? 0 : 1);
    touch = std::ldexp(touch, frame.exponent);
    ContactResult r;
    if (b.kind == ShapeKind::Plane || a.kind == ShapeKind::Plane) {
        const bool bodyIsA = b.kind == ShapeKind::Plane;
        const std::optional<ContactHull> hull = contactHull(bodyIsA ? a : b, bodyIsA ? 0 : 1, r);
        if (!hull) return r;
        return bodyPlaneContact(*hull, bodyIsA ? b : a, bodyIsA, maxPoints, trace ? &trace->plane : nullptr, touch, frame);
    }
    bool vertexSensitive = false;
    r = bodiesInFrame(a, b, frame, touch, options, trace, vertexSensitive);
    // The frame's translation rounded some vertex, and the answer depends on that rounding: a hull
    // failed (its tolerance is relative to the coordinates, ~1e3 for a 2e-9 cube beside a large
    // body: issue 41 (e)) or the SAT met nearly parallel edges (their axis amplifies the vertices'
    // rounding by 1 / sine: issue 41 (b)). Again on the input's exact vertices; every other answer
    // keeps the first frame (and its bits).
    if (vertexSensitive) {
        const ContactFrame exact = exactContactFrameOf(aIn, bIn);
        if (exact.origin != frame.origin || exact.exponent != frame.exponent) {
            toContactFrame(aIn, exact);
            toContactFrame(bIn, exact);
            if (trace) *trace = ContactTrace{}, trace->frame = exact;
            r = bodiesInFrame(aIn, bIn, exact, std::ldexp(touchWorld, exact.exponent), options, trace, vertexSensitive);
        }
    }
    return r;
}

}  // namespace cdlab
