#include "core/gjk_epa/epa.h"

#include <algorithm>
#include <cmath>

#include "core/base/accurate_cross.h"
#include "core/closest/closest_point.h"
#include "core/closest/edge_pair_distance.h"
#include "core/gjk_epa/feature_certificate.h"

namespace cdlab {

const char* nameOf(EpaStatus status) {
    switch (status) {
        case EpaStatus::Penetrating: return "Penetrating";
        case EpaStatus::Touching: return "Touching";
        case EpaStatus::Separated: return "Separated";
        case EpaStatus::InvalidInput: return "InvalidInput";
    }
    return "?";
}

const char* nameOf(EpaTermination termination) {
    switch (termination) {
        case EpaTermination::Converged: return "Converged";
        case EpaTermination::DuplicateSupport: return "DuplicateSupport";
        case EpaTermination::MaxIterations: return "MaxIterations";
        case EpaTermination::CapacityExceeded: return "CapacityExceeded";
        case EpaTermination::Degenerate: return "Degenerate";
        case EpaTermination::Touching: return "Touching";
        case EpaTermination::NotIntersecting: return "NotIntersecting";
        case EpaTermination::InvalidInput: return "InvalidInput";
        case EpaTermination::DecidedByGjk: return "DecidedByGjk";
    }
    return "?";
}

namespace detail {

namespace {
// A face whose doubled area is below this fraction of its squared longest edge has no reliable
// normal (the cross product is rounding noise): such a face is refused.
constexpr double kFlatFace = 1e-14;
}  // namespace

int EpaPolytope::addVertex(const EpaVertex& v) {
    if (vertexCount >= kMaxVertices) return -1;
    vertex[vertexCount] = v;
    scale = std::max(scale, v.w.norm());
    return vertexCount++;
}

bool EpaPolytope::plane(int i0, int i1, int i2, Vec3& normal, double& distance) const {
    const Vec3& p0 = vertex[i0].w;
    const Vec3& p1 = vertex[i1].w;
    const Vec3& p2 = vertex[i2].w;
    const Vec3 e0 = p1 - p0;  // opposite p2
    const Vec3 e1 = p2 - p1;  // opposite p0
    const Vec3 e2 = p0 - p2;  // opposite p1
    const double l0 = e0.squaredNorm();
    const double l1 = e1.squaredNorm();
    const double l2 = e2.squaredNorm();
    // n = e_i x e_j for any two edges (same vector in exact arithmetic); the rounding error is
    // a few ulps of |e_i||e_j|, so use the two shortest edges, i.e. the apex opposite the longest.
    Vec3 n;
    const Vec3* base;
    double longest;
    if (l0 >= l1 && l0 >= l2) {  // longest p0p1: apex p2
        n = e1.cross(e2);
        base = &p2;
        longest = l0;
    } else if (l1 >= l2) {  // longest p1p2: apex p0
        n = e2.cross(e0);
        base = &p0;
        longest = l1;
    } else {  // longest p2p0: apex p1
        n = e0.cross(e1);
        base = &p1;
        longest = l2;
    }
    double len = n.norm();
    if (!(len > kFlatFace * longest)) return false;
    // A sliver (the sine between the two edges below 1e-4: |n|^2 < 1e-8 l_i l_j, bounded here by
    // longest^2): the rounded cross product's direction errs by ~u / sine, its plane's distance by
    // ~u |w| / sine (depths 12% off on sliver faces of A − B). Error-free products (accurateCross)
    // give the normal to a few u whatever the width.
    if (len * len < 1e-8 * longest * longest) {
        n = accurateCross(p0, p1, p2);
        len = n.norm();
        if (!(len > 0.0)) return false;
    }
    normal = n / len;
    distance = normal.dot(*base);
    return true;
}

bool EpaPolytope::buildTetrahedron() {
    const Vec3& w0 = vertex[0].w;
    const double det = (vertex[1].w - w0).dot((vertex[2].w - w0).cross(vertex[3].w - w0));
    // det > 0: vertex 3 lies on the side of (0,1,2)'s right-hand normal, so (0,2,1) faces out.
    int t[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    if (det < 0) {
        for (auto& tri : t) std::swap(tri[1], tri[2]);
    }
    faceEnd = 4;
    liveCount = 4;
    freeCount = 0;
    for (int i = 0; i < 4; ++i) {
        EpaFace& F = face[i];
        for (int k = 0; k < 3; ++k) F.v[k] = t[i][k];
        F.live = true;
        if (!plane(F.v[0], F.v[1], F.v[2], F.normal, F.distance)) return false;
    }
    // Adjacency: edge e of face i (v[e] -> v[e+1]) meets the reversed edge of another face.
    // Every directed edge a -> b of the closed tetrahedron occurs once: index them in a 4x4 table.
    int edgeFace[4][4], edgeIndex[4][4];
    for (int i = 0; i < 4; ++i) {
        for (int e = 0; e < 3; ++e) {
            edgeFace[face[i].v[e]][face[i].v[(e + 1) % 3]] = i;
            edgeIndex[face[i].v[e]][face[i].v[(e + 1) % 3]] = e;
        }
    }
    for (int i = 0; i < 4; ++i) {
        for (int e = 0; e < 3; ++e) {
            const int a = face[i].v[e];
            const int b = face[i].v[(e + 1) % 3];
            face[i].adj[e] = edgeFace[b][a];
            face[i].adjEdge[e] = edgeIndex[b][a];
        }
    }
    return true;
}

int EpaPolytope::closestFace() const {
    int best = -1;
    double bestDistance = INFINITY;
    for (int i = 0; i < faceEnd; ++i) {
        if (face[i].live && face[i].distance < bestDistance) {
            bestDistance = face[i].distance;
            best = i;
        }
    }
    return best;
}

bool EpaPolytope::hasVertex(const Vec3& w) const {
    for (int i = 0; i < vertexCount; ++i)
        if (vertex[i].w == w) return true;
    return false;
}

// Depth-first walk over the faces visible from w (van den Bergen's silhouette): entering face f
// through its edge `edge`; a face not visible contributes that edge to the horizon. Visiting the
// other two edges in CCW order makes the horizon come out as one consecutive loop.
void EpaPolytope::silhouette(int f, int edge, const Vec3& w, double tol) {
    EpaFace& F = face[f];
    if (!F.live) return;  // already removed in this expansion
    if (F.normal.dot(w) - F.distance <= tol) {
        if (horizonCount >= kMaxFaces) {
            overflow = true;
            return;
        }
        horizonFace[horizonCount] = f;
        horizonEdge[horizonCount] = edge;
        ++horizonCount;
        return;
    }
    F.live = false;
    removed[removedCount++] = f;
    const int e1 = (edge + 1) % 3;
    const int e2 = (edge + 2) % 3;
    silhouette(F.adj[e1], F.adjEdge[e1], w, tol);
    silhouette(F.adj[e2], F.adjEdge[e2], w, tol);
}

EpaExpand EpaPolytope::expand(int seed, int vi, double visibleTolerance, EpaTraceStep* trace) {
    const Vec3& w = vertex[vi].w;
    horizonCount = 0;
    removedCount = 0;
    overflow = false;
    // The seed (nearest face) is visible by construction (its gap exceeded the tolerance).
    face[seed].live = false;
    removed[removedCount++] = seed;
    for (int e = 0; e < 3; ++e) silhouette(face[seed].adj[e], face[seed].adjEdge[e], w, visibleTolerance);

    auto rollback = [&](EpaExpand why) {
        for (int i = 0; i < removedCount; ++i) face[removed[i]].live = true;
        return why;
    };
    if (overflow || horizonCount < 3) return rollback(EpaExpand::Degenerate);
    const int available = freeCount + (kMaxFaces - faceEnd) + removedCount;
    if (horizonCount > available) return rollback(EpaExpand::Capacity);

    // New face k = (a_k, b_k, w) over horizon edge (g, j), which runs b_k -> a_k in face g.
    int va[kMaxFaces], vb[kMaxFaces], next[kMaxFaces];
    Vec3 normal[kMaxFaces];
    double distance[kMaxFaces];
    for (int k = 0; k < horizonCount; ++k) {
        const EpaFace& G = face[horizonFace[k]];
        const int j = horizonEdge[k];
        va[k] = G.v[(j + 1) % 3];
        vb[k] = G.v[j];
        if (!plane(va[k], vb[k], vi, normal[k], distance[k])) return rollback(EpaExpand::Degenerate);
    }
    // Face k's edge b_k -> w meets face m's edge w -> a_m where a_m = b_k. The walk gives the loop
    // in order (m = k + 1); search only if rounding made the visible region odd.
    for (int k = 0; k < horizonCount; ++k) {
        const int m = (k + 1) % horizonCount;
        if (va[m] == vb[k]) {
            next[k] = m;
            continue;
        }
        int found = -1;
        for (int q = 0; q < horizonCount; ++q) {
            if (va[q] == vb[k]) {
                if (found >= 0) return rollback(EpaExpand::Degenerate);  // not a simple loop
                found = q;
            }
        }
        if (found < 0) return rollback(EpaExpand::Degenerate);
        next[k] = found;
    }

    if (trace) {
        for (int i = 0; i < removedCount; ++i) {
            const EpaFace& R = face[removed[i]];
            trace->removedFaces.push_back({R.v[0], R.v[1], R.v[2]});
        }
        for (int k = 0; k < horizonCount; ++k) trace->horizon.push_back({va[k], vb[k]});
    }

    // Commit: free the removed faces, create the fan.
    for (int i = 0; i < removedCount; ++i) freeList[freeCount++] = removed[i];
    liveCount -= removedCount;
    int id[kMaxFaces];
    for (int k = 0; k < horizonCount; ++k) id[k] = freeCount > 0 ? freeList[--freeCount] : faceEnd++;
    for (int k = 0; k < horizonCount; ++k) {
        EpaFace& N = face[id[k]];
        N.v[0] = va[k];
        N.v[1] = vb[k];
        N.v[2] = vi;
        N.normal = normal[k];
        N.distance = distance[k];
        N.live = true;
        // edge 0 (a_k -> b_k) borders the surviving face g
        const int g = horizonFace[k];
        const int j = horizonEdge[k];
        N.adj[0] = g;
        N.adjEdge[0] = j;
        face[g].adj[j] = id[k];
        face[g].adjEdge[j] = 0;
    }
    for (int k = 0; k < horizonCount; ++k) {
        // edge 1 (b_k -> w) of face k with edge 2 (w -> a_m) of face m
        const int m = next[k];
        face[id[k]].adj[1] = id[m];
        face[id[k]].adjEdge[1] = 2;
        face[id[m]].adj[2] = id[k];
        face[id[m]].adjEdge[2] = 1;
    }
    liveCount += horizonCount;
    return EpaExpand::Ok;
}

namespace {
// Weights l1, l2 of p on the triangle w0 w1 w2 with unit normal n (p = w0 + l1 (w1 - w0) + l2 (w2 - w0)
// in the plane), by areas signed along n: l1 = [w0 p w2] / [w0 w1 w2], l2 = [w0 w1 p] / [w0 w1 w2].
// A sliver's rounded cross products err by ~u |w|^2, its area is ~sine |w|^2: there the areas come
// from error-free products (accurateCross), else they would put sum l_i w_i 0.03 from p on a 1e6
// face (tests/core/gjk_epa/epa_witness_test.cpp, the tiny sphere in a large polytope).
void faceWeights(const Vec3& n, const Vec3& w0, const Vec3& w1, const Vec3& w2, const Vec3& p, double& l1,
                 double& l2) {
    const Vec3 e1 = w1 - w0, e2 = w2 - w0;
    if (isSliver(e1, e2)) {
        const double total = n.dot(accurateCross(w0, w1, w2));
        l1 = n.dot(accurateCross(w0, p, w2)) / total;
        l2 = n.dot(accurateCross(w0, w1, p)) / total;
        return;
    }
    const double total = n.dot(e1.cross(e2));
    l1 = n.dot((p - w0).cross(e2)) / total;
    l2 = n.dot(e1.cross(p - w0)) / total;
}

bool convexWeights(double l1, double l2) { return l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0; }
}  // namespace

void EpaPolytope::witness(int f, double depth, Vec3& pointA, Vec3& pointB, EpaWitnessStep* out) const {
    const EpaFace& F = face[f];
    const Vec3 p = depth * F.normal;  // projection of the origin on the face plane
    double l1 = 0.0, l2 = 0.0;
    faceWeights(F.normal, vertex[F.v[0]].w, vertex[F.v[1]].w, vertex[F.v[2]].w, p, l1, l2);
    if (out) {
        out->projection = p;
        describeFace(f, l1, l2, out->nearest);
        out->covered = !convexWeights(l1, l2);
        if (!out->covered) out->used = out->nearest;
    }
    // Weights of a convex combination: pointA lies in conv(a0, a1, a2) ⊂ A, pointB in conv(b_i) ⊂ B,
    // and pointA − pointB = sum l_i w_i = p. Otherwise (NaN included) p lies outside face f: a
    // neighbouring face of A − B is coplanar with it (two faces of a box: golden/epa/box_box put p_B
    // 0.1 off B), and coveringFaceWitness finds the face that holds p.
    if (convexWeights(l1, l2)) weightedWitness(f, l1, l2, pointA, pointB);
    else coveringFaceWitness(p, pointA, pointB, out ? &out->used : nullptr);
    if (out) out->pointA = pointA, out->pointB = pointB;
}

void EpaPolytope::describeFace(int f, double l1, double l2, EpaWitnessFace& out) const {
    for (int k = 0; k < 3; ++k) {
        const EpaVertex& v = vertex[face[f].v[k]];
        out.w[k] = v.w, out.a[k] = v.a, out.b[k] = v.b;
    }
    out.weights = {1.0 - l1 - l2, l1, l2};
}

void EpaPolytope::weightedWitness(int f, double l1, double l2, Vec3& pointA, Vec3& pointB) const {
    const EpaVertex& v0 = vertex[face[f].v[0]];
    const EpaVertex& v1 = vertex[face[f].v[1]];
    const EpaVertex& v2 = vertex[face[f].v[2]];
    // pointA = a0 + l1 (a1 - a0) + l2 (a2 - a0): relative to one vertex, exact far from origin.
    pointA = v0.a + (l1 * (v1.a - v0.a) + l2 * (v2.a - v0.a));
    pointB = v0.b + (l1 * (v1.b - v0.b) + l2 * (v2.b - v0.b));
}

// The origin's projection p = depth · n on the nearest face's plane lies in the polytope P (for
// every face g: n_g · p = depth n_g · n <= depth <= d_g), hence on P's boundary in the union of the
// faces whose planes pass through p: the facet of P in that plane, of which face f is one triangle.
// The live face nearest p (exact region signs, closestPointOnTriangle) holds it up to rounding; its
// weights, clamped to a convex combination, put the witnesses on A and on B whatever the rounding,
// with pointA − pointB = the point of that face nearest p (= depth · n up to rounding).
// Test: tests/core/gjk_epa/epa_witness_test.cpp.
void EpaPolytope::coveringFaceWitness(const Vec3& p, Vec3& pointA, Vec3& pointB, EpaWitnessFace* used) const {
    int best = -1;
    ClosestPointOnTriangleResult bestPoint;
    bestPoint.distanceSquared = INFINITY;
    for (int g = 0; g < faceEnd; ++g) {
        const EpaFace& G = face[g];
        if (!G.live) continue;
        // The plane's gap bounds the triangle's distance from below: skip faces that cannot win.
        const double gap = G.distance - G.normal.dot(p);
        if (best >= 0 && gap * gap > bestPoint.distanceSquared) continue;
        const Triangle t{vertex[G.v[0]].w, vertex[G.v[1]].w, vertex[G.v[2]].w};
        const ClosestPointOnTriangleResult c = closestPointOnTriangle(p, t);
        if (c.distanceSquared < bestPoint.distanceSquared) best = g, bestPoint = c;
    }
    if (best < 0) return;
    const EpaFace& G = face[best];
    double l1 = bestPoint.barycentric[1], l2 = bestPoint.barycentric[2];
    // Inside the face: its weights by faceWeights (accurate on a sliver, where Ericson's are not).
    if (bestPoint.region == TriangleRegion::ABC) {
        double m1 = 0.0, m2 = 0.0;
        faceWeights(G.normal, vertex[G.v[0]].w, vertex[G.v[1]].w, vertex[G.v[2]].w, p, m1, m2);
        if (std::isfinite(m1) && std::isfinite(m2)) l1 = m1, l2 = m2;
    }
    // Clamped to a convex combination (they are one up to rounding).
    l1 = std::clamp(l1, 0.0, 1.0);
    l2 = std::clamp(l2, 0.0, 1.0 - l1);
    weightedWitness(best, l1, l2, pointA, pointB);
    if (used) describeFace(best, l1, l2, *used);
}

int EpaPolytope::snapshot(EpaTraceStep& step, int f) const {
    step.vertices.clear();
    step.faces.clear();
    for (int i = 0; i < vertexCount; ++i) step.vertices.push_back(vertex[i].w);
    int index = -1;
    for (int i = 0; i < faceEnd; ++i) {
        if (!face[i].live) continue;
        if (i == f) index = static_cast<int>(step.faces.size());
        step.faces.push_back({face[i].v[0], face[i].v[1], face[i].v[2]});
    }
    return index;
}

bool EpaPolytope::adjacencyConsistent() const {
    for (int f = 0; f < faceEnd; ++f) {
        if (!face[f].live) continue;
        for (int e = 0; e < 3; ++e) {
            const int g = face[f].adj[e], k = face[f].adjEdge[e];
            if (g < 0 || g >= faceEnd || k < 0 || k > 2 || !face[g].live) return false;
            if (face[g].adj[k] != f || face[g].adjEdge[k] != e) return false;
            // Edge e runs v[e] -> v[e+1]; the neighbour runs it back.
            if (face[g].v[k] != face[f].v[(e + 1) % 3] || face[g].v[(k + 1) % 3] != face[f].v[e]) return false;
        }
    }
    return true;
}

int epaSeed(const GjkSimplex& start, EpaVertex seed[4], EpaResult& r) {
    int n = 0;
    for (int i = 0; i < start.count && i < 4; ++i) {
        const GjkVertex& g = start.vertex[i];
        if (!g.w.allFinite() || !g.a.allFinite() || !g.b.allFinite()) return 0;
        bool dup = false;
        for (int j = 0; j < n; ++j) dup = dup || seed[j].w == g.w;
        if (!dup) seed[n++] = {g.w, g.a, g.b};
    }
    if (n == 0) return 0;
    Vec3 wv[4];
    for (int i = 0; i < n; ++i) wv[i] = seed[i].w;
    const SimplexClosest c = closestSignedVolumes(wv, n);
    EpaVertex kept[4];
    for (int k = 0; k < c.count; ++k) kept[k] = seed[c.index[k]];
    // Contact point for a touching answer: the point of the simplex nearest the origin.
    epaSimplexWitness(seed, c, r.pointA, r.pointB);
    for (int k = 0; k < c.count; ++k) seed[k] = kept[k];
    return c.count;
}

void EpaRecorder::start(int n) {
    static const char* kStartName[5] = {"", "point", "segment", "triangle", "tetrahedron"};
    if (trace_) trace_->start = std::string(kStartName[n]) + (n < 4 ? " blown up" : " from GJK");
}

void EpaRecorder::blowUp(const Vec3& direction, const Vec3& point) {
    if (!trace_) return;
    trace_->blowUpDirections.push_back(direction);
    trace_->blowUpPoints.push_back(point);
}

void EpaRecorder::witness(const EpaPolytope& poly, int f) {
    if (!trace_) return;
    Vec3 pointA, pointB;
    poly.witness(f, std::max(poly.face[f].distance, 0.0), pointA, pointB, &trace_->witness);
    trace_->witness.recorded = true;
}

EpaTraceStep* EpaRecorder::beginStep(int iteration, const EpaPolytope& poly, int f, const EpaVertex& s, double upper) {
    if (!trace_) return nullptr;
    const EpaFace& F = poly.face[f];
    step_ = &trace_->steps.emplace_back();
    step_->iteration = iteration;
    step_->closestFace = poly.snapshot(*step_, f);
    step_->closestNormal = F.normal;
    step_->closestDistance = F.distance;
    step_->closestPoint = F.distance * F.normal;
    step_->direction = F.normal;
    step_->support = s.w;
    step_->supportA = s.a;
    step_->supportB = s.b;
    step_->lowerBound = F.distance;
    step_->upperBound = upper;
    return step_;
}

void EpaRecorder::stepEndsLoop() {
    if (step_) step_->terminated = true;
}

void EpaRecorder::termination(EpaTermination why) {
    if (trace_) trace_->termination = why;
}

void epaSimplexWitness(const EpaVertex* v, const SimplexClosest& c, Vec3& pointA, Vec3& pointB) {
    const EpaVertex& v0 = v[c.index[0]];
    Vec3 da = Vec3::Zero();
    Vec3 db = Vec3::Zero();
    for (int k = 1; k < c.count; ++k) {
        da += c.lambda[k] * (v[c.index[k]].a - v0.a);
        db += c.lambda[k] * (v[c.index[k]].b - v0.b);
    }
    pointA = v0.a + da;
    pointB = v0.b + db;
}

bool epaRefineEdgePair(const EpaPolytope& poly, int f, EpaResult& r) {
    Vec3 a[3], b[3];
    int na = 0, nb = 0;
    for (int k = 0; k < 3; ++k) {
        const EpaVertex& v = poly.vertex[poly.face[f].v[k]];
        if (std::find(a, a + na, v.a) == a + na) a[na++] = v.a;
        if (std::find(b, b + nb, v.b) == b + nb) b[nb++] = v.b;
    }
    if (na != 2 || nb != 2) return false;
    const LinePairSeparation line = linePairSeparation(a[0], a[1], b[0], b[1]);
    if (!line.ok) return false;
    // The face is three corners of the parallelogram edgeA - edgeB and holds the origin's
    // projection, so the feet lie on both edges; 1e-6 allows for EPA's rounding.
    constexpr double kSlack = 1e-6;
    if (line.s < -kSlack || line.s > 1 + kSlack || line.t < -kSlack || line.t > 1 + kSlack) return false;
    // pointA - pointB = -separation * normal; EPA's normal points from A toward B.
    const bool aligned = line.normal.dot(poly.face[f].normal) >= 0.0;
    const double depth = aligned ? -line.separation : line.separation;
    const double size = std::max((a[1] - a[0]).norm(), (b[1] - b[0]).norm());
    if (!(std::abs(depth - r.depth) <= kSlack * size)) return false;
    r.depth = std::max(depth, 0.0);
    r.normal = aligned ? line.normal : Vec3(-line.normal);
    r.pointA = line.pointA;
    r.pointB = line.pointB;
    r.edgePairRefined = true;
    return true;
}

}  // namespace detail

}  // namespace cdlab
