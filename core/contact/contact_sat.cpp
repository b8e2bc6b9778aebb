#include "core/contact/contact_sat.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/base/stack_arena.h"
#include "core/base/tolerances.h"
#include "core/contact/contact_stages.h"
#include "core/closest/closest_point.h"

namespace cdlab {

const char* nameOf(SatContactStatus status) {
    switch (status) {
        case SatContactStatus::Separated: return "Separated";
        case SatContactStatus::Touching: return "Touching";
        case SatContactStatus::Penetrating: return "Penetrating";
        case SatContactStatus::InvalidInput: return "InvalidInput";
    }
    return "InvalidInput";
}

const char* nameOf(SatAxisKind kind) {
    switch (kind) {
        case SatAxisKind::FaceA: return "face A";
        case SatAxisKind::FaceB: return "face B";
        case SatAxisKind::EdgeEdge: return "edge-edge";
        case SatAxisKind::Normal: return "normal";
    }
    return "face A";
}

namespace {

using Polygon = std::pmr::vector<Vec3>;

// A posed polyhedron in world orientation, positions relative to the common origin o. Its arrays
// live in the caller's scratch arena (no heap for bodies up to a few hundred vertices).
struct Posed {
    const ConvexPolyhedron* mesh = nullptr;
    std::pmr::vector<Vec3> x;    // vertices
    std::pmr::vector<Vec3> n;    // face normals (unit)
    std::pmr::vector<double> d;  // face offsets: n · x = d
    // Per edge: its vertices and faces, and the arc of its Gauss map (the two face normals as the
    // arc test takes them, and their cross product), read |E_A| x |E_B| times by the edge query.
    struct Edge {
        int v0, v1, f1, f2;
        Vec3 from, to, cross;
    };
    std::pmr::vector<Edge> edges;
    Vec3 center = Vec3::Zero();  // vertex mean (inside: convex)

    // sign: +1 for A (arc from n_f1 to n_f2), -1 for B (the negated normals: B's Gauss map is
    // reflected in A - B).
    Posed(const ConvexPolyhedron& m, const Transform& t, const Vec3& origin, double sign, std::pmr::memory_resource* memory)
        : mesh(&m), x(memory), n(memory), d(memory), edges(memory) {
        x.reserve(m.vertexCount());
        n.reserve(m.faceCount());
        d.reserve(m.faceCount());
        edges.reserve(m.edgeCount());
        const Mat3 r = t.rotation.toRotationMatrix();
        const Vec3 shift = t.position - origin;  // exact when t.position == origin
        for (const auto& v : m.vertices()) {
            x.push_back(r * v.position + shift);
            center += x.back();
        }
        center /= double(x.size());
        for (int f = 0; f < m.faceCount(); ++f) {
            n.push_back(r * m.face(f).normal);
            // Offset at the face's vertex mean (as the mesh does): rounding averages out.
            Vec3 c = Vec3::Zero();
            int k = 0;
            m.forEachFaceHalfEdge(f, [&](int h) {
                c += x[m.halfEdge(h).origin];
                ++k;
            });
            d.push_back(n.back().dot(c / double(k)));
        }
        for (int e = 0; e < m.edgeCount(); ++e) {
            const auto [v0, v1] = m.edgeVertices(e);
            const auto [f1, f2] = m.edgeFaces(e);
            const Vec3 from = sign * n[f1], to = sign * n[f2];
            edges.push_back({v0, v1, f1, f2, from, to, to.cross(from)});
        }
    }
    // min over vertices of dir · x (the support value in -dir, negated).
    double minProjection(const Vec3& dir) const {
        double m = INFINITY;
        for (const Vec3& p : x) m = std::min(m, dir.dot(p));
        return m;
    }
    void facePolygon(int f, Polygon& p) const {
        p.clear();
        mesh->forEachFaceHalfEdge(f, [&](int h) { p.push_back(x[mesh->halfEdge(h).origin]); });
    }
};

// Gregorius' arc test (file comment): do the Gauss-map arcs a→b (of A's edge, b x a given) and
// c→d (of B's edge, negated normals, d x c given) intersect? cba = c · (b x a) and dba = d · (b x a)
// come from `side`, the row of (-n_f) · (b x a) over B's faces f computed once per edge of A: the
// first test, which rejects most pairs, then costs no arithmetic per pair.
bool isMinkowskiFace(const Posed::Edge& ea, const Posed::Edge& eb, const double* side) {
    const double cba = side[eb.f1], dba = side[eb.f2];
    if (!(cba * dba < 0.0)) return false;  // the plane of arc a→b does not separate c and d
    const double adc = ea.from.dot(eb.cross), bdc = ea.to.dot(eb.cross);
    return adc * bdc < 0.0 && cba * bdc > 0.0;
}

// The best axis of each family and its index in the test order; every axis tested when traced.
struct SatQuery {
    std::vector<SatAxisRecord>* axes = nullptr;  // the trace's list, or none
    int tested = 0;
    detail::SatBestAxes best;
    int pruned = 0, parallel = 0;
    void count(const SatAxisRecord& rec) {
        if (axes) axes->push_back(rec);
        ++tested;
    }
};

// 1. Face axes of A, then of B (B's normal points from B toward A: the axis A→B is -n).
void queryFaceAxes(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                   SatQuery& q) {
    for (int f = 0; f < ma.faceCount(); ++f) {
        const SatAxisRecord rec{SatAxisKind::FaceA, f, -1, A.n[f], B.minProjection(A.n[f]) - A.d[f]};
        if (rec.separation > q.best.faceA.separation) q.best.faceA = rec, q.best.faceAIndex = q.tested;
        q.count(rec);
    }
    for (int f = 0; f < mb.faceCount(); ++f) {
        const SatAxisRecord rec{SatAxisKind::FaceB, -1, f, -B.n[f], A.minProjection(B.n[f]) - B.d[f]};
        if (rec.separation > q.best.faceB.separation) q.best.faceB = rec, q.best.faceBIndex = q.tested;
        q.count(rec);
    }
}

// 2. Edge pairs that form a face of the Minkowski difference (their Gauss-map arcs cross), the
// axis their cross product, oriented away from A.
void queryEdgeAxes(const Posed& A, const Posed& B, SatQuery& q) {
    // B's Gauss map as the arcs see it: the negated face normals (bit for bit the arcs' end points).
    std::pmr::vector<Vec3> negated(B.n.size(), Vec3::Zero(), B.n.get_allocator().resource());
    std::pmr::vector<double> side(B.n.size(), 0.0, B.n.get_allocator().resource());
    for (size_t f = 0; f < B.n.size(); ++f) negated[f] = -1.0 * B.n[f];
    for (int ea = 0; ea < static_cast<int>(A.edges.size()); ++ea) {
        const Posed::Edge& edgeA = A.edges[ea];
        const Vec3 da = A.x[edgeA.v1] - A.x[edgeA.v0];
        for (size_t f = 0; f < negated.size(); ++f) side[f] = negated[f].dot(edgeA.cross);
        for (int eb = 0; eb < static_cast<int>(B.edges.size()); ++eb) {
            const Posed::Edge& edgeB = B.edges[eb];
            if (!isMinkowskiFace(edgeA, edgeB, side.data())) {
                ++q.pruned;
                continue;
            }
            const Vec3 db = B.x[edgeB.v1] - B.x[edgeB.v0];
            Vec3 axis = da.cross(db);
            // Parallel edges (sin of the angle below 1e-9: the cross product is rounding noise);
            // their separating direction is a face normal, tested in step 1.
            const double len = axis.norm();
            if (!(len > 1e-9 * da.norm() * db.norm())) {
                ++q.parallel;
                continue;
            }
            axis /= len;
            if (axis.dot(A.x[edgeA.v0] - A.center) < 0.0) axis = -axis;  // away from A
            const SatAxisRecord rec{SatAxisKind::EdgeEdge, ea, eb, axis, axis.dot(B.x[edgeB.v0] - A.x[edgeA.v0])};
            if (rec.separation > q.best.edge.separation) q.best.edge = rec, q.best.edgeIndex = q.tested;
            q.count(rec);
        }
    }
}

// 4a. Edge–edge: one point, the closest points of the two edges.
void edgeContact(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                 const SatAxisRecord& best, const Vec3& origin, SatContactResult& r, SatContactTrace* trace) {
    const auto [a0, a1] = ma.edgeVertices(best.indexA);
    const auto [b0, b1] = mb.edgeVertices(best.indexB);
    const SegmentSegmentResult c = closestPointsSegmentSegment(Segment{A.x[a0], A.x[a1]}, Segment{B.x[b0], B.x[b1]});
    r.featureA = {FeatureType::Edge, best.indexA};
    r.featureB = {FeatureType::Edge, best.indexB};
    r.manifold.push_back({c.pointOnFirst + origin, c.pointOnSecond + origin, r.depth});
    if (trace) {
        trace->edgePointA = c.pointOnFirst + origin;
        trace->edgePointB = c.pointOnSecond + origin;
    }
}

// 4b. Face contact: reference face on A (FaceA) or B (FaceB); incident face = the other body's
// face most anti-parallel to the reference normal, clipped by the reference face's side planes.
void faceContact(const Posed& A, const Posed& B, const SatAxisRecord& best, const Vec3& origin, double tol,
                 const SatContactOptions& options, SatContactResult& r, SatContactTrace* trace,
                 std::pmr::memory_resource* memory) {
    const bool refOnA = best.kind == SatAxisKind::FaceA;
    const Posed& R = refOnA ? A : B;
    const Posed& I = refOnA ? B : A;
    const int rf = refOnA ? best.indexA : best.indexB;
    const Vec3 nr = R.n[rf];
    int inc = 0;
    for (int f = 1; f < I.mesh->faceCount(); ++f)
        if (I.n[f].dot(nr) < I.n[inc].dot(nr)) inc = f;
    Polygon refPoly(memory), incPoly(memory);
    R.facePolygon(rf, refPoly);
    I.facePolygon(inc, incPoly);
    if (trace) trace->referenceFace = rf, trace->incidentFace = inc;
    detail::clipIncidentFace(refPoly, nr, R.d[rf], incPoly, I.x, refOnA, origin, tol, options, r, trace, memory);
    r.featureA = {FeatureType::Face, refOnA ? rf : inc};
    r.featureB = {FeatureType::Face, refOnA ? inc : rf};
}

}  // namespace

// Gregorius, "The Separating Axis Test between Convex Polyhedra" (GDC 2013) and "Robust Contact
// Creation for Physics Simulations" (GDC 2015): face axes, edge axes pruned on the Gauss map,
// the axis chosen with a face preference, then the contact from clipping.
SatContactResult contactPolyhedra(const ConvexPolyhedron& ma, const Transform& ta, const ConvexPolyhedron& mb,
                                  const Transform& tb, const SatContactOptions& options, SatContactTrace* trace) {
    SatContactResult r;
    if (ma.empty() || mb.empty()) r.message = "empty polyhedron";
    else if (const std::string m = detail::poseProblem(ta); !m.empty()) r.message = "A: " + m;
    else if (const std::string m2 = detail::poseProblem(tb); !m2.empty()) r.message = "B: " + m2;
    if (!r.message.empty()) {
        r.separation = r.depth = NAN;
        return r;
    }
    if (trace) *trace = SatContactTrace{};
    const Vec3 origin = ta.position;
    // Scratch for both posed bodies, the edge query and the clipping: two 64-vertex hulls (~124
    // faces, ~186 edges each: ~50 KB) fit; larger bodies spill to the heap.
    StackArena<65536> arena;
    const Posed A(ma, ta, origin, 1.0, arena.resource()), B(mb, tb, origin, -1.0, arena.resource());
    double maxCoord = 0.0;
    for (const Vec3& p : B.x) maxCoord = std::max(maxCoord, p.cwiseAbs().maxCoeff());
    maxCoord += origin.cwiseAbs().maxCoeff();
    const double size = std::max((ma.boundsMax() - ma.boundsMin()).norm(), (mb.boundsMax() - mb.boundsMin()).norm());
    r.tolerance = detail::satTolerance(options, size, maxCoord);
    const double tol = r.tolerance;

    SatQuery q;
    if (trace) q.axes = &trace->axes;
    queryFaceAxes(ma, A, mb, B, q);
    queryEdgeAxes(A, B, q);
    const detail::SatChosenAxis c = detail::chooseSatAxis(q.best, tol, options);
    const SatAxisRecord& best = c.best;
    detail::recordChosenAxis(c, tol, r);
    if (trace) {
        trace->edgePairsTotal = ma.edgeCount() * mb.edgeCount();
        trace->edgePairsPruned = q.pruned;
        trace->edgePairsParallel = q.parallel;
        trace->bestFaceA = q.best.faceAIndex;
        trace->bestFaceB = q.best.faceBIndex;
        trace->bestEdgePair = q.best.edgeIndex;
        trace->chosen = c.chosen;
    }
    if (r.status == SatContactStatus::Separated) {
        if (best.kind == SatAxisKind::EdgeEdge)
            r.featureA = {FeatureType::Edge, best.indexA}, r.featureB = {FeatureType::Edge, best.indexB};
        else if (best.kind == SatAxisKind::FaceA) r.featureA = {FeatureType::Face, best.indexA};
        else r.featureB = {FeatureType::Face, best.indexB};
        return r;
    }
    if (best.kind == SatAxisKind::EdgeEdge) edgeContact(ma, A, mb, B, best, origin, r, trace);
    else faceContact(A, B, best, origin, tol, options, r, trace, arena.resource());
    return r;
}

}  // namespace cdlab
