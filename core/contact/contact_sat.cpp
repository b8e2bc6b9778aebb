#include "core/contact/contact_sat.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

#include "core/base/stack_arena.h"
#include "core/base/tolerances.h"
#include "core/contact/contact_stages.h"
#include "core/closest/closest_point.h"
#include "core/closest/edge_pair_distance.h"

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
// live in the caller's scratch arena (no heap for bodies up to a few hundred vertices); the
// topology (edges, vertex neighbours, face vertex lists) is the mesh's own, flattened once when
// the mesh was built.
struct Posed {
    const ConvexPolyhedron* mesh = nullptr;
    std::pmr::vector<Vec3> x;    // vertices
    std::pmr::vector<Vec3> n;    // face normals (unit)
    std::pmr::vector<double> d;  // face offsets: n · x = d
    const std::vector<ConvexPolyhedron::EdgeEnds>* edges = nullptr;  // the mesh's edge vertices and faces
    // Per edge, the arc of its Gauss map (the two face normals as the arc test takes them, and their
    // cross product), read |E_A| x |E_B| times by the all-pairs edge test; built for that test only
    // (buildArcs), the arc walk reads the normals.
    struct Arc {
        Vec3 from, to, cross;
    };
    std::pmr::vector<Arc> arcs;
    double sign = 1.0;
    Vec3 center = Vec3::Zero();  // vertex mean (inside: convex)
    // The radius of a ball about `center` inside the body (its least distance to a face plane; 0 on
    // a flat body, whose rounding can put the mean a hair outside): the prunings' bounds.
    double inradius = INFINITY;
    // The edge vectors w - v of the vertex adjacency (ConvexPolyhedron::neighbors(), same slots) in
    // world orientation, for the arc walks of the untraced query over B's graph. They are rotated
    // body-frame differences, free of the rounding of B's offset from A (the arc tests of the
    // traced query use normals only, so neither depends on where the bodies are).
    Mat3 rotation = Mat3::Identity();
    std::pmr::vector<Vec3> neighborStep;
    bool flat = false;  // an edge whose two faces are opposite (a body without volume): no Gauss arc

    // sign: +1 for A (arc from n_f1 to n_f2), -1 for B (the negated normals: B's Gauss map is
    // reflected in A - B).
    Posed(const ConvexPolyhedron& m, const Transform& t, const Vec3& origin, double sign, std::pmr::memory_resource* memory)
        : mesh(&m), x(memory), n(memory), d(memory), edges(&m.edgeEnds()), arcs(memory), sign(sign),
          neighborStep(memory) {
        x.reserve(m.vertexCount());
        n.reserve(m.faceCount());
        d.reserve(m.faceCount());
        const Mat3 r = t.rotation.toRotationMatrix();
        rotation = r;
        const Vec3 shift = t.position - origin;  // exact when t.position == origin
        for (const auto& v : m.vertices()) {
            x.push_back(r * v.position + shift);
            center += x.back();
        }
        center /= double(x.size());
        for (int f = 0; f < m.faceCount(); ++f) {
            n.push_back(r * m.face(f).normal);
            // Offset at the face's vertex mean (as the mesh does): rounding averages out.
            const int begin = m.faceVertexStart()[f], end = m.faceVertexStart()[f + 1];
            Vec3 c = Vec3::Zero();
            for (int k = begin; k < end; ++k) c += x[m.faceVertexIds()[k]];
            d.push_back(n.back().dot(c / double(end - begin)));
            inradius = std::min(inradius, d.back() - n.back().dot(center));
        }
        inradius = std::max(inradius, 0.0);
        // Unit normals within kFoldedEdgeSine of opposite: a fold of a flat body, not a dihedral edge.
        // (Equal normals, two coplanar faces of a triangulated mesh, are fine: a point arc.)
        for (const ConvexPolyhedron::EdgeEnds& e : *edges)
            flat = flat || (n[e.f1].dot(n[e.f2]) < 0.0 && !(n[e.f2].cross(n[e.f1]).norm() > kFoldedEdgeSine));
    }
    void buildArcs() {
        if (!arcs.empty()) return;
        arcs.reserve(edges->size());
        for (const ConvexPolyhedron::EdgeEnds& e : *edges) {
            const Vec3 from = sign * n[e.f1], to = sign * n[e.f2];
            arcs.push_back({from, to, to.cross(from)});
        }
    }
    void buildAdjacency() {
        neighborStep.resize(mesh->neighbors().size());
        for (size_t k = 0; k < neighborStep.size(); ++k) neighborStep[k] = rotation * mesh->neighbors()[k].step;
    }
    // The vertex minimising dir · x (the support along -dir), the first of exact ties.
    int minVertex(const Vec3& dir) const {
        int best = 0;
        double m = dir.dot(x[0]);
        for (int i = 1; i < static_cast<int>(x.size()); ++i)
            if (const double s = dir.dot(x[i]); s < m) m = s, best = i;
        return best;
    }
    // The same by steepest descent over the vertex graph from `start` (each step lowers dir · x
    // strictly, so it ends, at a local minimum: the minimum, the body being convex).
    int descend(const Vec3& dir, int start) const {
        const std::vector<int>& first = mesh->neighborStart();
        const std::vector<ConvexPolyhedron::Neighbor>& nb = mesh->neighbors();
        int v = start;
        double m = dir.dot(x[v]);
        for (;;) {
            int next = -1;
            for (int k = first[v]; k < first[v + 1]; ++k)
                if (const double s = dir.dot(x[nb[k].vertex]); s < m) m = s, next = nb[k].vertex;
            if (next < 0) return v;
            v = next;
        }
    }
    void facePolygon(int f, Polygon& p) const {
        p.clear();
        for (int k = mesh->faceVertexStart()[f]; k < mesh->faceVertexStart()[f + 1]; ++k)
            p.push_back(x[mesh->faceVertexIds()[k]]);
    }
};

// Gregorius' arc test (file comment): do the Gauss-map arcs a→b (of A's edge, b x a given) and
// c→d (of B's edge, negated normals, d x c given) intersect? cba = c · (b x a) and dba = d · (b x a)
// come from `side`, the row of (-n_f) · (b x a) over B's faces f computed once per edge of A: the
// first test, which rejects most pairs, then costs no arithmetic per pair.
bool isMinkowskiFace(const Posed::Arc& ea, const ConvexPolyhedron::EdgeEnds& edgeB, const Posed::Arc& eb,
                     const double* side) {
    const double cba = side[edgeB.f1], dba = side[edgeB.f2];
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
    int nearlyParallel = 0;  // pairs whose axis was computed in long double
    double gapSlack = 0.0;   // considerEdgePair: how far a pair's value may exceed its axis's gap (tol)
    void count(const SatAxisRecord& rec) {
        if (axes) axes->push_back(rec);
        ++tested;
    }
};

// A face axis into the family's best: the larger separation wins, an exact tie goes to the lower
// face index (the brute-force loop's order, whatever order the faces were visited in).
// Face f of P with Q's support s along -n_f (P = A: axis n_f; P = B: axis -n_f, A→B).
void considerFaceAxis(const Posed& P, const Posed& Q, bool pIsA, int f, int s, SatQuery& q) {
    const double separation = P.n[f].dot(Q.x[s]) - P.d[f];
    const SatAxisRecord rec = pIsA ? SatAxisRecord{SatAxisKind::FaceA, f, -1, P.n[f], separation}
                                   : SatAxisRecord{SatAxisKind::FaceB, -1, f, -P.n[f], separation};
    SatAxisRecord& best = pIsA ? q.best.faceA : q.best.faceB;
    const int bestFace = pIsA ? best.indexA : best.indexB;
    if (rec.separation > best.separation || (rec.separation == best.separation && f < bestFace))
        best = rec, (pIsA ? q.best.faceAIndex : q.best.faceBIndex) = q.tested;
    q.count(rec);
}

// 1. Face axes of A, then of B (B's normal points from B toward A: the axis A→B is -n), every
// vertex of the other body projected on every face normal. supportOfB[f]: the vertex of B that
// realises face f of A's separation (B's support along -n_f), where the edge walk starts.
void queryFaceAxes(const Posed& A, const Posed& B, SatQuery& q, std::pmr::vector<int>& supportOfB) {
    for (int f = 0; f < A.mesh->faceCount(); ++f) {
        supportOfB[f] = B.minVertex(A.n[f]);
        considerFaceAxis(A, B, true, f, supportOfB[f], q);
    }
    for (int f = 0; f < B.mesh->faceCount(); ++f) considerFaceAxis(B, A, false, f, A.minVertex(B.n[f]), q);
}

// Q's supports along -n_f for the faces f of P (the vertex realising face f's separation), found
// by descent; where the face pruning skipped a face, only the vertex its descent would start from
// is kept, and the support is found when the edge walk asks for it (of()).
struct FaceSupports {
    std::pmr::vector<int> vertex;  // the support, -1 where not found yet
    std::pmr::vector<int> start;   // where its descent starts
    FaceSupports(int faces, std::pmr::memory_resource* memory) : vertex(faces, -1, memory), start(faces, -1, memory) {}
    int of(const Posed& P, const Posed& Q, int f) {
        if (vertex[f] < 0) vertex[f] = start[f] >= 0 ? Q.descend(P.n[f], start[f]) : Q.minVertex(P.n[f]);
        return vertex[f];
    }
};

// 1, untraced: the same supports found by descent over the other body's vertex graph, faces
// visited breadth first across their edges and each descent started at the support of the face it
// was reached from (adjacent normals have nearby supports: a step or two of ~6 neighbours instead
// of every vertex). A linear function's local minimum over a convex polytope's vertex graph is its
// minimum, so the supports are the loop's (up to ties within rounding).
// With `prune`, the visit starts at the face of largest bound and skips the descent of a face whose
// separation is bounded below its family's best so far: min_Q n_f · x <= n_f · c_Q − r_Q (the ball
// of radius r_Q about Q's vertex mean c_Q lies in Q), plus `margin` (pruneMargin in contactPolyhedra)
// and 1e-12 of the terms for the rounding; such a face cannot be the family's best (the larger
// separation wins), so the family's best is the unpruned one's (tests/core/contact/
// contact_sat_test.cpp, untraced = traced).
void queryFaceAxesByDescent(const Posed& P, const Posed& Q, bool pIsA, SatQuery& q, FaceSupports& supportOfQ,
                            bool prune, double margin, std::pmr::memory_resource* memory) {
    const ConvexPolyhedron& mp = *P.mesh;
    const int faces = mp.faceCount();
    std::pmr::vector<double> bound(memory);
    int first = 0;
    if (prune) {
        const double rQ = Q.inradius;
        bound.resize(faces);
        for (int f = 0; f < faces; ++f) {
            const double c = P.n[f].dot(Q.center);
            bound[f] = c - rQ - P.d[f] + margin + 1e-12 * (std::abs(c) + rQ + std::abs(P.d[f]));
            if (bound[f] > bound[first]) first = f;
        }
    }
    const SatAxisRecord& best = pIsA ? q.best.faceA : q.best.faceB;
    std::pmr::vector<int> queue(memory);
    queue.reserve(faces);
    supportOfQ.vertex[first] = Q.minVertex(P.n[first]);
    queue.push_back(first);
    // A face is reached once it has a support or a descent start (every reached face but the first
    // gets a start >= 0: its parent's support, or the parent's own start).
    for (size_t head = 0; head < queue.size(); ++head) {
        const int f = queue[head];
        if (supportOfQ.vertex[f] < 0 && !(prune && bound[f] < best.separation))
            supportOfQ.vertex[f] = Q.descend(P.n[f], supportOfQ.start[f]);
        const int s = supportOfQ.vertex[f];
        if (s >= 0) considerFaceAxis(P, Q, pIsA, f, s, q);
        for (int k = mp.faceVertexStart()[f]; k < mp.faceVertexStart()[f + 1]; ++k) {
            const int g = mp.faceAcross()[k];
            if (supportOfQ.vertex[g] >= 0 || supportOfQ.start[g] >= 0) continue;
            supportOfQ.start[g] = s >= 0 ? s : supportOfQ.start[f];
            queue.push_back(g);
        }
    }
}

// Gregorius' arc test (file comment) row for edge `edgeA`: side[f] = (-n_f) · (b x a) over B's faces.
void arcSideRow(const Posed::Arc& arcA, const Posed& B, std::pmr::vector<double>& side) {
    for (size_t f = 0; f < B.n.size(); ++f) side[f] = (-1.0 * B.n[f]).dot(arcA.cross);
}

// An edge pair whose arcs cross: its axis e_A x e_B oriented away from A, unless the edges are
// parallel (sin of the angle at most kParallelEdgeSine: the cross product is rounding noise; their separating
// direction is a face normal, tested in step 1). The larger separation wins; an exact tie goes to
// the lower (edge of A, edge of B) pair, the brute-force loop's order.
void considerEdgePair(const Posed& A, const Posed& B, int ea, int eb, SatQuery& q) {
    const ConvexPolyhedron::EdgeEnds& edgeA = (*A.edges)[ea];
    const ConvexPolyhedron::EdgeEnds& edgeB = (*B.edges)[eb];
    const Vec3 da = A.x[edgeA.v1] - A.x[edgeA.v0];
    const Vec3 db = B.x[edgeB.v1] - B.x[edgeB.v0];
    Vec3 axis = da.cross(db);
    const double len = axis.norm();
    if (!(len > kParallelEdgeSine * da.norm() * db.norm())) {
        ++q.parallel;
        return;
    }
    if (len > kPreciseEdgeSine * da.norm() * db.norm()) {
        axis /= len;
    } else {
        // Nearly parallel: the double cross product's direction is off by ~1e-16 / sine (the
        // rounding of da, db and of the products), its separation by that times the body size.
        // The same from the vertices in long double (exact differences, 64-bit products).
        ++q.nearlyParallel;
        const auto diff = [](const Vec3& p, const Vec3& o) {
            return std::array<long double, 3>{(long double)p.x() - o.x(), (long double)p.y() - o.y(),
                                              (long double)p.z() - o.z()};
        };
        const auto u = diff(A.x[edgeA.v1], A.x[edgeA.v0]), w = diff(B.x[edgeB.v1], B.x[edgeB.v0]);
        const long double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const long double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const long double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        const long double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        if (!(lc > kParallelEdgeSine * lu * lw)) {
            ++q.parallel;
            return;
        }
        axis = Vec3(double(c[0] / lc), double(c[1] / lc), double(c[2] / lc));
    }
    if (axis.dot(A.x[edgeA.v0] - A.center) < 0.0) axis = -axis;  // away from A
    SatAxisRecord rec{SatAxisKind::EdgeEdge, ea, eb, axis, axis.dot(B.x[edgeB.v0] - A.x[edgeA.v0])};
    SatAxisRecord& best = q.best.edge;
    if (rec.separation > best.separation) {
        // The pair's value is the gap between the bodies' supports along its axis only when its
        // arcs cross; the arcs of a thin body's faces, rounded, can admit a pair whose arcs do not,
        // and its value can then exceed every true gap (a 2e-6-thin plate 1e5 from the origin: +0.18
        // where the bodies overlap by 0.113; tests/core/contact/contact_exactness_test.cpp "a far
        // pair with nearly parallel edges"). Before it becomes the family's best, its value is
        // checked against the gap along its axis, which replaces it when lower by more than tol.
        double maxA = -INFINITY, minB = INFINITY;
        for (const Vec3& x : A.x) maxA = std::max(maxA, axis.dot(x));
        for (const Vec3& x : B.x) minB = std::min(minB, axis.dot(x));
        if (rec.separation > minB - maxA + q.gapSlack) rec.separation = minB - maxA;
    }
    if (rec.separation > best.separation ||
        (rec.separation == best.separation && (ea < best.indexA || (ea == best.indexA && eb < best.indexB))))
        best = rec, q.best.edgeIndex = q.tested;
    q.count(rec);
}

// 2. Edge pairs that form a face of the Minkowski difference (their Gauss-map arcs cross): every
// edge of A against every edge of B by Gregorius' test (both bodies' arcs built).
void queryEdgeAxesOfEdge(const Posed& A, const Posed& B, int ea, std::pmr::vector<double>& side, SatQuery& q) {
    arcSideRow(A.arcs[ea], B, side);
    for (int eb = 0; eb < static_cast<int>(B.arcs.size()); ++eb) {
        if (isMinkowskiFace(A.arcs[ea], (*B.edges)[eb], B.arcs[eb], side.data())) considerEdgePair(A, B, ea, eb, q);
        else ++q.pruned;
    }
}

void queryEdgeAxes(Posed& A, Posed& B, SatQuery& q) {
    A.buildArcs();
    B.buildArcs();
    std::pmr::vector<double> side(B.n.size(), 0.0, B.n.get_allocator().resource());
    for (int ea = 0; ea < static_cast<int>(A.arcs.size()); ++ea) queryEdgeAxesOfEdge(A, B, ea, side, q);
}

// 2, untraced: the edges of B whose arcs cross the arc of A's edge ea, found by walking that arc
// through the vertex regions of B's reflected Gauss map (the overlay of the two Gauss maps,
// Gregorius GDC 2013; de Berg et al. §2.3 for the overlay): along m(t) = a + t (b - a), a and b the
// normals of ea's two faces, the current vertex v of B minimises m(t) · x (it starts at face a's
// support, found by the face query); a neighbour w takes over where m(t) · (w - v) turns negative,
// at t_w = a · (w - v) / ((a - b) · (w - v)) for (b - a) · (w - v) < 0, the earliest first (a tie
// goes to the steeper: the region entered just after). Each boundary crossed for 0 < t < 1 is a B
// edge whose arc crosses ea's: the pairs the all-pairs test keeps, in O(crossings x degree) instead
// of O(|E_B|). Crossings at t = 0 or 1 (a Gauss-map vertex on the arc) are face axes, tested in
// step 1. Returns false when the walk does not end at face b's support (rounding in a degenerate
// overlay): the caller tests ea against every edge of B instead.
bool walkEdgeArc(const Posed& A, const Posed& B, int ea, int start, int end, double tol, SatQuery& q) {
    const ConvexPolyhedron& mb = *B.mesh;
    const ConvexPolyhedron::EdgeEnds& edgeA = (*A.edges)[ea];
    const Vec3& a = A.n[edgeA.f1];
    const Vec3& b = A.n[edgeA.f2];
    const Vec3 ab = b - a;
    const std::vector<int>& first = mb.neighborStart();
    const std::vector<ConvexPolyhedron::Neighbor>& nb = mb.neighbors();
    int v = start;
    double t = 0.0;
    // Every step lowers (m(t) · x, its slope) lexicographically, so no vertex comes back in exact
    // arithmetic; the bound stops a rounding cycle.
    for (int steps = 0; steps <= mb.edgeCount(); ++steps) {
        // The earliest t_w = rise / run (run > 0), compared as fractions: one division per step.
        int next = -1, crossed = -1;
        double riseNext = 1.0, runNext = 0.0;  // t = +inf
        for (int k = first[v]; k < first[v + 1]; ++k) {
            const int w = nb[k].vertex;
            const Vec3& step = B.neighborStep[k];
            const double run = -ab.dot(step);
            if (!(run > 0.0)) continue;
            double rise = a.dot(step);
            if (rise < t * run) rise = t * run;  // t_w = max(t, rise / run)
            const double lhs = rise * runNext, rhs = riseNext * run;
            if (lhs < rhs || (lhs == rhs && run > runNext))
                next = w, crossed = nb[k].edge, riseNext = rise, runNext = run;
        }
        const double tNext = next < 0 ? INFINITY : riseNext / runNext;
        if (tNext >= 1.0) return v == end || b.dot(B.x[v]) <= b.dot(B.x[end]) + tol;
        if (tNext > 0.0) considerEdgePair(A, B, ea, crossed, q);
        v = next;
        t = tNext;
    }
    return false;
}

// endTol: how far along b the walk's last vertex may be above face b's support (rounding of the
// support values; the default touching band, whatever the caller's tolerance).
// pruneBelow: an edge of A whose pairs are all bounded below it is skipped (SatContactOptions::
// pruneEdgeArcs; -inf: none). The bound: for u on the arc of ea (a to b, the normals of its faces),
// the pair's separation min_B u · x − u · x_e (x_e on ea, A's support along u) is at most
// u · w − r_B with w = c_B − x_e (the ball of radius r_B about c_B lies in B), and u · w is at most
// |w_p| (w projected on the arc's plane) where w_p's direction lies inside the arc, else
// max(a · w, b · w). Computed with a margin (pruneMargin in contactPolyhedra) + 1e-12 |w|_1 for
// its rounding and the faces' planarity. The same with w
// from x_e to B's supports along -a and -b (min_B u · x <= u · x_s for any point x_s of B).
void queryEdgeAxesByWalk(Posed& A, Posed& B, FaceSupports& supportOfB, double endTol, double pruneBelow, double margin,
                         SatQuery& q) {
    std::pmr::vector<double> side(B.n.get_allocator().resource());
    const double rB = B.inradius;
    for (int ea = 0; ea < static_cast<int>(A.edges->size()); ++ea) {
        const ConvexPolyhedron::EdgeEnds& edgeA = (*A.edges)[ea];
        if (pruneBelow > -INFINITY) {
            const Vec3& a = A.n[edgeA.f1];
            const Vec3& b = A.n[edgeA.f2];
            const double c = a.dot(b);
            const Vec3& xe = A.x[edgeA.v0];
            // max over the arc of u · w, plus its rounding margin
            const auto reach = [&](const Vec3& w) {
                const double aw = a.dot(w), bw = b.dot(w);
                double m = std::max(aw, bw);
                if (bw - c * aw > 0.0 && aw - c * bw > 0.0) {  // the maximiser over the circle is on the arc
                    const double s2 = 1.0 - c * c;
                    m = s2 > 1e-12 ? std::sqrt(std::max(0.0, (aw * aw + bw * bw - 2.0 * c * aw * bw) / s2)) : w.norm();
                }
                return m + margin + 1e-12 * w.lpNorm<1>();
            };
            // min_B u · x is at most u · c_B - r_B, and at most u · x_s for B's supports x_s along
            // -a and -b (exact at the arc's ends: there the bound is the face axis's separation).
            if (reach(B.center - xe) - rB < pruneBelow || reach(B.x[supportOfB.of(A, B, edgeA.f1)] - xe) < pruneBelow ||
                reach(B.x[supportOfB.of(A, B, edgeA.f2)] - xe) < pruneBelow)
                continue;
        }
        // Both ends in one vertex region of B (one vertex s lowest along a and along b): then
        // (w - s) · m(t) >= 0 for every neighbour w and every m(t) = a + t (b - a), 0 <= t <= 1,
        // so no B edge crosses the arc. The walk would find the same in exact arithmetic; with
        // rounding, when a B edge is parallel to face b (resting or equally rotated bodies), it could
        // take a spurious crossing just below t = 1 and test a pair whose arcs do not cross, a few
        // ulps from the face axis's separation (a reviewer's 24,000 pairs: 1,162 degenerate poses
        // differ by up to 1.6e-14 in separation, 26 separated ones in the reported axis).
        const int s1 = supportOfB.of(A, B, edgeA.f1), s2 = supportOfB.of(A, B, edgeA.f2);
        if (s1 == s2) continue;
        if (walkEdgeArc(A, B, ea, s1, s2, endTol, q)) continue;
        // Every pair of ea (a pair the walk already took is taken again: no change to the best).
        A.buildArcs();
        B.buildArcs();
        side.resize(B.n.size());
        queryEdgeAxesOfEdge(A, B, ea, side, q);
    }
}

// 4a. Edge–edge: one point, the closest points of the two edges.
void edgeContact(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                 const SatAxisRecord& best, const Vec3& origin, double tol, SatContactResult& r,
                 SatContactTrace* trace) {
    const auto [a0, a1] = ma.edgeVertices(best.indexA);
    const auto [b0, b1] = mb.edgeVertices(best.indexB);
    SegmentSegmentResult c = closestPointsSegmentSegment(Segment{A.x[a0], A.x[a1]}, Segment{B.x[b0], B.x[b1]});
    // The crossing edges' common perpendicular in double-double: its feet stay on both edges when
    // the edges are nearly parallel, where the double closest points slide along them (issue 41:
    // point_b 2.3e-4 off B on a 1e4 pair; tests/app/query/exact_reproducers_test.cpp).
    const LinePairSeparation lp = linePairSeparation(A.x[a0], A.x[a1], B.x[b0], B.x[b1]);
    if (lp.ok && lp.s >= 0.0 && lp.s <= 1.0 && lp.t >= 0.0 && lp.t <= 1.0 && lp.pointA.allFinite() &&
        lp.pointB.allFinite())
        c.pointOnFirst = lp.pointA, c.pointOnSecond = lp.pointB;
    // Nearly parallel edges: their closest points are ill-conditioned along the edges (a shift of
    // either along its edge changes their distance little), and can disagree with the axis by far
    // more than the touching band (issue 41 (d): 0.75 of the size). Then the point of A stays and
    // B's is its translate by -depth · n, so pointA - pointB = depth · n as everywhere else.
    if (!((c.pointOnFirst - c.pointOnSecond - r.depth * r.normal).norm() <= tol))
        c.pointOnSecond = c.pointOnFirst - r.depth * r.normal;
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
// touchingFallback: as clipIncidentFace's.
void faceContact(const Posed& A, const Posed& B, const SatAxisRecord& best, const Vec3& origin, double tol,
                 const SatContactOptions& options, SatContactResult& r, SatContactTrace* trace,
                 std::pmr::memory_resource* memory, bool touchingFallback = true) {
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
    detail::clipIncidentFace(refPoly, nr, R.d[rf], incPoly, I.x, R.x, refOnA, origin, tol, options, r, trace,
                             memory, {}, touchingFallback);
    r.featureA = {FeatureType::Face, refOnA ? rf : inc};
    r.featureB = {FeatureType::Face, refOnA ? inc : rf};
}

// A face axis (the least, or kept) whose clip still keeps nothing: the bodies meet beside the
// reference face, where its touching pair lies on features outside the support set along its
// normal (an edge of A under "face A": cdlab stress "contact manifolds" 600 s #11574, #29170,
// touching within the band). The best edge pair answers when its overlap is within the
// contract's bound (depth <= least overlap · (1 + faceBiasRelative) + faceBiasAbsolute + tol);
// otherwise the face keeps the touching pair (core/contact/contact_stages.cpp).
void edgeAxisForEmptyClip(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                          const SatQuery& q, double maxSep, const Vec3& origin, double tol, double size,
                          double maxCoord, const SatContactOptions& options, SatContactResult& r,
                          SatContactTrace* trace) {
    if (q.best.edge.indexA < 0) return;
    const double bound = maxSep - options.faceBiasRelative * std::abs(maxSep) -
                         std::max(0.0, options.faceBiasAbsolute) - tol;
    if (q.best.edge.separation >= bound) {
        SatContactResult e = r;
        e.manifold.clear();
        e.clipKeptNothing = false;
        detail::SatChosenAxis ce;
        ce.best = q.best.edge;
        ce.chosen = q.best.edgeIndex;
        ce.maxSep = maxSep;
        detail::recordChosenAxis(ce, tol, e);
        edgeContact(ma, A, mb, B, ce.best, origin, tol, e, nullptr);
        // Only when its points lie on both edges (nearly parallel edges move B's point off its
        // edge onto pointA − depth · n: the face's touching pair is then the better answer,
        // stress "contact manifolds" #2523) and differ by depth · n to rounding (the edge axis's
        // normal, rounded from nearly parallel edges, turned 4e-13 rad off the points' common
        // perpendicular, 1.7 × the 1e-9 L tolerance at coordinates 2.4e5: 600 s #36100).
        const auto onEdge = [&](const ConvexPolyhedron& m, const Posed& P, int edge, const Vec3& p) {
            const auto [i, j] = m.edgeVertices(edge);
            const Vec3 local = p - origin;
            return (local - closestPointOnSegment(local, Segment{P.x[std::size_t(i)], P.x[std::size_t(j)]}).point)
                       .norm() <= tol;
        };
        const double rounding = 1e-12 * size + 16 * DBL_EPSILON * maxCoord;
        if (e.manifold.size() == 1 && onEdge(ma, A, ce.best.indexA, e.manifold[0].pointA) &&
            onEdge(mb, B, ce.best.indexB, e.manifold[0].pointB) &&
            (e.manifold[0].pointA - e.manifold[0].pointB - e.depth * e.normal).norm() <= rounding) {
            r = std::move(e);
            if (trace) {
                trace->chosen = ce.chosen;
                trace->edgePointA = r.manifold[0].pointA;
                trace->edgePointB = r.manifold[0].pointB;
            }
        }
    }
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
    // faces, 372 adjacency slots each: ~14 KB a body, ~27 KB with the arcs of the all-pairs test)
    // fit; larger bodies spill to the heap.
    StackArena<98304> arena;
    Posed A(ma, ta, origin, 1.0, arena.resource()), B(mb, tb, origin, -1.0, arena.resource());
    double maxCoord = 0.0;
    for (const Vec3& p : B.x) maxCoord = std::max(maxCoord, p.cwiseAbs().maxCoeff());
    maxCoord += origin.cwiseAbs().maxCoeff();
    const Vec3 loA = ma.boundsMin(), hiA = ma.boundsMax(), loB = mb.boundsMin(), hiB = mb.boundsMax();
    const double size = std::max((hiA - loA).norm(), (hiB - loB).norm());
    r.tolerance = detail::satTolerance(options, size, maxCoord);
    const double tol = r.tolerance;

    SatQuery q;
    q.gapSlack = tol;
    FaceSupports supportOfB(ma.faceCount(), arena.resource()), supportOfA(mb.faceCount(), arena.resource());
    // A body without volume has edges whose Gauss arcs are half circles with opposite ends: no arc
    // to walk (every region of the other body ties halfway), while the all-pairs test drops them.
    if (trace || A.flat || B.flat) {
        // Traced: every face axis and every edge pair in index order, the pruning counted.
        if (trace) q.axes = &trace->axes;
        queryFaceAxes(A, B, q, supportOfB.vertex);
        queryEdgeAxes(A, B, q);
    } else {
        B.buildAdjacency();  // the walk steps over B's vertex graph (A's steps are not read)
        // The prunings' bounds take the ball about a body's vertex mean inside its face planes, and
        // a valid mesh's faces are planar only within its scale tolerance (65536 ulps of its own
        // body-frame coordinates and diagonal, core/geometry/polyhedron.h: a mesh stored 1e6 from its
        // body origin may be posed near the world's): twice the larger, tol, and the rounding of the
        // posed coordinates (tests/core/contact/contact_sat_test.cpp, "a ridge far from its body origin").
        const double planarity = std::max(ConvexPolyhedron::scaleTolerance(loA, hiA), ConvexPolyhedron::scaleTolerance(loB, hiB));
        const double pruneMargin = tol + 2.0 * planarity + ulps(131072.0, maxCoord + size);
        queryFaceAxesByDescent(A, B, true, q, supportOfB, options.pruneFaceAxes, pruneMargin, arena.resource());
        queryFaceAxesByDescent(B, A, false, q, supportOfA, options.pruneFaceAxes, pruneMargin, arena.resource());
        // Edges bounded below what the choice of axis can use (chooseSatAxis, edgeAxisForEmptyClip:
        // an edge pair matters only at or above the face axes' best less the preference and tol).
        const double faceBest = std::max(q.best.faceA.separation, q.best.faceB.separation);
        // A negative relative bias lets an edge win below the face axes' best (chooseSatAxis takes
        // it as given): no pruning then (a reviewer's 84,000 poses at -0.02 to -1: 426 answers moved).
        const double pruneBelow = options.pruneEdgeArcs && options.faceBiasRelative >= 0.0
                                      ? faceBest - options.faceBiasRelative * std::abs(faceBest) -
                                            std::max(0.0, options.faceBiasAbsolute) - tol
                                      : -INFINITY;
        queryEdgeAxesByWalk(A, B, supportOfB, detail::satTolerance(SatContactOptions{}, size, maxCoord),
                            std::isnan(pruneBelow) ? -INFINITY : pruneBelow, pruneMargin, q);
    }
    r.axesTested = q.tested;
    r.nearlyParallelEdgePairs = q.nearlyParallel;
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
    // A face kept by the preference whose clip kept no point does not meet the other body where the
    // bodies touch (its touching pair is then off its normal: cdlab stress "contact manifolds",
    // point_a − point_b off depth_i · n by up to 6e-5 L): the least-overlap axis answers instead.
    // That axis is known before the clip, so when it differs the clip skips its touching-pair
    // stand-in, which the retry would discard (1.7 % of the bench's hull pairs; each cost a hull of
    // the vertex differences, half of the set's time). Traced runs keep it: the trace shows it.
    detail::SatChosenAxis c2;
    bool retry = false;
    if (options.faceBiasRelative > 0 || options.faceBiasAbsolute > 0) {
        SatContactOptions least = options;
        least.faceBiasRelative = least.faceBiasAbsolute = 0.0;
        c2 = detail::chooseSatAxis(q.best, tol, least);
        retry = c2.chosen != c.chosen;
    }
    if (best.kind == SatAxisKind::EdgeEdge) edgeContact(ma, A, mb, B, best, origin, tol, r, trace);
    else faceContact(A, B, best, origin, tol, options, r, trace, arena.resource(), trace || !retry);
    if (r.clipKeptNothing && retry) {
        r.manifold.clear();
        r.featureA = r.featureB = FeatureRef{};
        r.clipKeptNothing = false;
        detail::recordChosenAxis(c2, tol, r);
        if (trace) trace->chosen = c2.chosen;
        if (c2.best.kind == SatAxisKind::EdgeEdge) edgeContact(ma, A, mb, B, c2.best, origin, tol, r, trace);
        else faceContact(A, B, c2.best, origin, tol, options, r, trace, arena.resource());
    }
    if (r.clipKeptNothing) edgeAxisForEmptyClip(ma, A, mb, B, q, c.maxSep, origin, tol, size, maxCoord, options, r, trace);
    return r;
}

}  // namespace cdlab
