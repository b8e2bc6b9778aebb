#include "core/contact/contact_box.h"

#include <algorithm>
#include <cassert>
#include <array>
#include <bit>
#include <cmath>
#include <memory_resource>

#include "core/base/tolerances.h"
#include "core/closest/closest_point.h"
#include "core/contact/contact_stages.h"
#include "core/contact/contact_tolerances.h"

namespace cdlab {

namespace {

// presets::box numbering (tests/core/contact/contact_box_test.cpp compares these with the preset):
// corner k has bit i set when it lies on the + side of axis i; face f = 2 i (+ side) or 2 i + 1
// (- side) of axis i, corners counter-clockwise from outside; edges in the preset's order.
constexpr int kFaceCorners[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
constexpr int kEdgeCorners[12][2] = {{1, 3}, {3, 7}, {7, 5}, {5, 1}, {0, 4}, {4, 6},
                                     {6, 2}, {2, 0}, {6, 7}, {3, 2}, {0, 1}, {5, 4}};

// The edges meeting at each corner, one bit per edge of kEdgeCorners.
constexpr std::array<unsigned, 8> kCornerEdges = [] {
    std::array<unsigned, 8> m{};
    for (int e = 0; e < 12; ++e) m[kEdgeCorners[e][0]] |= 1u << e, m[kEdgeCorners[e][1]] |= 1u << e;
    return m;
}();

int edgeOf(int u, int v) {
    for (int e = 0; e < 12; ++e)
        if ((kEdgeCorners[e][0] == u && kEdgeCorners[e][1] == v) || (kEdgeCorners[e][0] == v && kEdgeCorners[e][1] == u))
            return e;
    return -1;
}

// Finite, positive and at most 1e150: beyond, |h| and the separations overflow double precision.
// (Two comparisons a coefficient, both false for NaN: cheaper than Eigen's allFinite, which GCC
// calls out of line.)
bool validExtents(const Vec3& h) {
    const auto valid = [](double x) { return x > 0.0 && x <= 1e150; };
    return valid(h.x()) && valid(h.y()) && valid(h.z());
}

// A box in world orientation, positions relative to a common origin. Corners are built on demand
// (cornerAt: c ± h_x x̂ ± h_y ŷ ± h_z ẑ added in that order; the general functions' rotation * v +
// position agrees to an ulp): a face contact needs the incident face's four, an edge contact the
// two edges' four, a plane contact those at or below the plane's tolerance.
struct PosedBox {
    std::array<Vec3, 3> axis;  // unit axes (the rotation's columns)
    std::array<Vec3, 3> e;     // h_i axis_i
    Vec3 h;                    // half extents
    Vec3 center;

    PosedBox(const Vec3& halfExtents, const Transform& t, const Vec3& origin) : h(halfExtents) {
        const Mat3 r = t.rotation.toRotationMatrix();
        center = t.position - origin;  // exact when t.position == origin
        for (int i = 0; i < 3; ++i) axis[i] = r.col(i), e[i] = h[i] * axis[i];
    }
    Vec3 cornerAt(int k) const {
        const Vec3 a = (k & 1) ? Vec3(center + e[0]) : Vec3(center - e[0]);
        const Vec3 b = (k & 2) ? Vec3(a + e[1]) : Vec3(a - e[1]);
        return (k & 4) ? Vec3(b + e[2]) : Vec3(b - e[2]);
    }
    std::array<Vec3, 8> corners() const {
        std::array<Vec3, 8> x;
        for (int k = 0; k < 8; ++k) x[k] = cornerAt(k);
        return x;
    }
    // max_k |corner_k| over every coordinate, bounded as |c| + Σ |e_i| (an upper bound, within
    // rounding: it only sizes the tolerance's rounding term).
    double maxCoord() const {
        return (center.cwiseAbs() + e[0].cwiseAbs() + e[1].cwiseAbs() + e[2].cwiseAbs()).maxCoeff();
    }
    Vec3 faceNormal(int f) const { return (f & 1) ? Vec3(-axis[f / 2]) : axis[f / 2]; }
    // The corner with bit i set where u · axis_i >= 0 (extreme along u), bit `free` cleared.
    int extremeCorner(const Vec3& u, int free) const {
        int k = 0;
        for (int i = 0; i < 3; ++i)
            if (i != free && u.dot(axis[i]) >= 0.0) k |= 1 << i;
        return k;
    }
    // The edge along axis i extreme along u.
    int extremeEdge(const Vec3& u, int i) const {
        const int k = extremeCorner(u, i);
        return edgeOf(k, k | (1 << i));
    }
    void facePolygon(int f, std::array<Vec3, 4>& p) const {
        for (int j = 0; j < 4; ++j) p[j] = cornerAt(kFaceCorners[f][j]);
    }
};

// Steps 1 and 2 of contactPolyhedra on two boxes, in A's frame (Ericson §4.4.1): C = R_A^T R_B
// holds B's axes in A's frame, tA = R_A^T t, tB = R_B^T t. Face axes of A, then of B, then the nine
// edge pairs, in that order (the trace numbering of contactPolyhedra's face axes). For
// L = a_i x b_j (i1, i2 and j1, j2 the other two axes, cyclic): |L| = |(C(i1,j), C(i2,j))|,
// L · t = C(i1,j) tA(i2) - C(i2,j) tA(i1), rA(L) = hA(i1) |C(i2,j)| + hA(i2) |C(i1,j)|,
// rB(L) = hB(j1) |C(i,j2)| + hB(j2) |C(i,j1)|.
// Kept out of line: inlined into contactBoxBox by GCC 12 it measured ~8 % slower a call.
[[gnu::noinline]] detail::SatBestAxes queryBoxAxes(const PosedBox& A, const PosedBox& B) {
    detail::SatBestAxes best;
    const Vec3 t = B.center - A.center;
    Mat3 C;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) C(i, j) = A.axis[i].dot(B.axis[j]);
    const Mat3 absC = C.cwiseAbs();
    const Vec3 tA(A.axis[0].dot(t), A.axis[1].dot(t), A.axis[2].dot(t));
    const Vec3 tB(B.axis[0].dot(t), B.axis[1].dot(t), B.axis[2].dot(t));
    const Vec3 &ha = A.h, &hb = B.h;
    // Every separation first, then the first largest of each family: the 15 axes are independent,
    // so their square roots and divisions overlap, and no branch waits on one of them.
    double faceSep[2][6];
    for (int f = 0; f < 6; ++f) {  // A's face f: plane n · x = n · c_A + hA_i
        const int i = f / 2;
        faceSep[0][f] = ((f & 1) ? -tA(i) : tA(i)) - ha(i) - hb.dot(absC.row(i));
    }
    for (int f = 0; f < 6; ++f) {  // B's face f, axis A→B = -n
        const int j = f / 2;
        faceSep[1][f] = ((f & 1) ? tB(j) : -tB(j)) - hb(j) - ha.dot(absC.col(j));
    }
    const auto firstLargest = [](const double* sep, int count) {
        int k = 0;
        for (int m = 1; m < count; ++m)
            if (sep[m] > sep[k]) k = m;
        return k;
    };
    const int fa = firstLargest(faceSep[0], 6), fb = firstLargest(faceSep[1], 6);
    if (faceSep[0][fa] > best.faceA.separation)  // NaN: no record, as a failed comparison
        best.faceA = {SatAxisKind::FaceA, fa, -1, A.faceNormal(fa), faceSep[0][fa]}, best.faceAIndex = fa;
    if (faceSep[1][fb] > best.faceB.separation)
        best.faceB = {SatAxisKind::FaceB, -1, fb, Vec3(-B.faceNormal(fb)), faceSep[1][fb]}, best.faceBIndex = 6 + fb;
    double edgeSep[9];
    for (int i = 0; i < 3; ++i) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double len = std::sqrt(C(i1, j) * C(i1, j) + C(i2, j) * C(i2, j));  // entries <= 1: no overflow
            const double proj = C(i1, j) * tA(i2) - C(i2, j) * tA(i1);
            const double rA = ha(i1) * absC(i2, j) + ha(i2) * absC(i1, j);
            const double rB = hb(j1) * absC(i, j2) + hb(j2) * absC(i, j1);
            // Parallel edges (|a_i x b_j| <= kParallelEdgeSine, contactPolyhedra's test) give a face axis: not tested.
            edgeSep[3 * i + j] =
                len > kParallelEdgeSine ? (std::abs(proj) - rA - rB) / len : -INFINITY;  // toward B: sign of proj
        }
    }
    const int e = firstLargest(edgeSep, 9);
    int edgeI = -1, edgeJ = -1;
    if (edgeSep[e] > best.edge.separation) {
        best.edge.separation = edgeSep[e], edgeI = e / 3, edgeJ = e % 3;
        best.edgeIndex = 12;  // the trace's numbering: the non-parallel pairs before it
        for (int m = 0; m < e; ++m) best.edgeIndex += edgeSep[m] > -INFINITY;
    }
    if (edgeI >= 0) {  // the winning pair's world axis and the two edges extreme along it
        Vec3 u = A.axis[edgeI].cross(B.axis[edgeJ]).normalized();
        if (u.dot(t) < 0.0) u = -u;
        best.edge.axis = u;
        best.edge.indexA = A.extremeEdge(u, edgeI);
        best.edge.indexB = B.extremeEdge(-u, edgeJ);
    }
    return best;
}

// reduceContactPolygon's rules (core/contact/contact_manifold.cpp, file comment of
// contact_manifold.h) for maxPoints 1 to 4 on n <= 14 points given by their in-plane coordinates xy
// and depths: rule 0 (rim points dropped), then the deepest, the farthest from it, the largest
// triangle, the point adding the most area, each rule taking submerged points before surface ones
// and breaking ties to kManifoldTieRelative by input order. The general reduction
// projects onto the plane in 3D; here the plane's own coordinates are given, so the decisions are
// the same up to rounding (tests/core/contact/contact_box_test.cpp compares the manifolds).
ContactIndices reduceFacePoints(const double (*xy)[2], const double* depth, int n, int maxPoints) {
    assert(n >= 1 && n <= 14 && maxPoints >= 1 && maxPoints <= 4);
    const auto greater = [](double score, double best) { return score > best + kManifoldTieRelative * std::abs(best); };
    const auto dist2 = [&](int i, int j) {
        const double dx = xy[i][0] - xy[j][0], dy = xy[i][1] - xy[j][1];
        return dx * dx + dy * dy;
    };
    const auto cross = [&](int o, int a, int b) {  // twice the signed area of (o, a, b)
        return (xy[a][0] - xy[o][0]) * (xy[b][1] - xy[o][1]) - (xy[a][1] - xy[o][1]) * (xy[b][0] - xy[o][0]);
    };
    double deepest = 0.0;
    for (int i = 0; i < n; ++i) deepest = std::max(deepest, depth[i]);
    const double surface = kSurfaceBandRelative * deepest, reach = deepest * deepest;
    int kept[14] = {}, count = 0;
    for (int i = 0; i < n; ++i) {
        bool rim = false;
        if (depth[i] <= surface)
            for (int k = 0; k < n && !rim; ++k) rim = depth[k] > surface && dist2(i, k) <= reach;
        if (!rim) kept[count++] = i;
    }
    ContactIndices keep;
    int best = kept[0];
    for (int k = 1; k < count; ++k)
        if (greater(depth[kept[k]], depth[best])) best = kept[k];
    keep.push_back(best);
    if (maxPoints >= count) {  // every point left, the deepest first, then input order
        for (int k = 0; k < count; ++k)
            if (kept[k] != best) keep.push_back(kept[k]);
        return keep;
    }
    bool taken[14] = {};
    taken[best] = true;
    const auto pick = [&](const auto& score) {
        for (bool tier : {true, false}) {
            int chosen = -1;
            double bestScore = 0.0;
            for (int k = 0; k < count; ++k) {
                const int i = kept[k];
                if (taken[i] || (depth[i] > surface) != tier) continue;
                const double sc = score(i);
                if (greater(sc, bestScore)) chosen = i, bestScore = sc;
            }
            if (chosen >= 0) return chosen;
        }
        return -1;
    };
    const auto take = [&](int i) {
        if (i < 0) return false;
        keep.push_back(i);
        taken[i] = true;
        return static_cast<int>(keep.size()) < maxPoints;
    };
    const int p0 = keep[0];
    if (maxPoints == 1 || !take(pick([&](int i) { return dist2(i, p0); }))) return keep;
    const int p1 = keep[1];
    if (!take(pick([&](int i) { return std::abs(cross(p0, p1, i)); }))) return keep;
    // The triangle counter-clockwise; a point outside edge (a, b) adds the area -cross(a, b, q).
    int t[3] = {p0, p1, keep[2]};
    if (cross(p0, p1, keep[2]) < 0) std::swap(t[1], t[2]);
    take(pick([&](int i) {
        double added = 0.0;
        for (int e = 0; e < 3; ++e) added = std::max(added, -cross(t[e], t[(e + 1) % 3], i));
        return added;
    }));
    return keep;
}

// The incident face of I clipped to the reference face rf of R, in R's frame: the side planes are
// |q_u| <= h_u and |q_v| <= h_v (u, v the face's two other axes), so each clip is one coordinate
// against a constant (Bullet's btBoxBoxDetector clips the same rectangle, intersectRectQuad2), in
// the order of the reference face's edges as clipIncidentFace takes them. A point keeps its R-frame
// coordinates q and its world position, both interpolated at the crossing. Kept: points with
// s = σ q_a - h_a <= tol (σ q_a the height over R's centre along the face normal), as
// clipIncidentFace keeps them; reduced by reduceFacePoints in (q_u, q_v) when maxPoints is 1 to 4.
// Returns false when nothing is kept: the caller then takes clipIncidentFace, whose fallbacks handle
// it (tests/core/contact/contact_box_test.cpp compares the manifolds with the general SAT's).
bool clipBoxFaces(const PosedBox& R, int rf, const PosedBox& I, int inc, bool refOnA, const Vec3& origin, double tol,
                  const SatContactOptions& options, SatContactResult& r) {
    struct Point {
        double q[3];
        Vec3 p;
    };
    const int a = rf / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const double sigma = (rf & 1) ? -1.0 : 1.0;
    Point buf[2][12];
    int count = 4;
    for (int j = 0; j < 4; ++j) {
        const Vec3 p = I.cornerAt(kFaceCorners[inc][j]);
        const Vec3 rel = p - R.center;
        buf[0][j] = {{R.axis[0].dot(rel), R.axis[1].dot(rel), R.axis[2].dot(rel)}, p};
    }
    // Four clips, one per edge of the reference face: edge k runs along axis m (its corners differ
    // in bit m), so its side plane bounds the third axis c at the corners' side of it. A quad gains
    // at most one point a clip: 8 points at most (12 slots).
    int cur = 0;
    for (int k = 0; k < 4 && count > 0; ++k) {
        const int c0 = kFaceCorners[rf][k], c1 = kFaceCorners[rf][(k + 1) % 4];
        const int c = 3 - a - std::countr_zero(static_cast<unsigned>(c0 ^ c1));
        const double sign = (c0 >> c) & 1 ? 1.0 : -1.0, limit = R.h[c];
        const Point* in = buf[cur];
        Point* out = buf[cur ^ 1];
        int n = 0;
        double sp = sign * in[0].q[c] - limit;
        const double s0 = sp;
        for (int i = 0; i < count; ++i) {
            const Point& P = in[i];
            const Point& Q = in[i + 1 == count ? 0 : i + 1];
            const double sq = i + 1 == count ? s0 : sign * Q.q[c] - limit;
            if (sp <= 0.0) out[n++] = P;
            if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
                const double t = sp / (sp - sq);
                Point& X = out[n++];
                for (int m = 0; m < 3; ++m) X.q[m] = P.q[m] + t * (Q.q[m] - P.q[m]);
                X.p = P.p + t * (Q.p - P.p);
            }
            sp = sq;
        }
        count = n;
        cur ^= 1;
    }
    const Vec3 nr = R.faceNormal(rf);
    FixedCapacityVector<ContactPoint, 12> kept;
    double xy[12][2], depth[12];
    for (int i = 0; i < count; ++i) {
        const Point& P = buf[cur][i];
        const double s = sigma * P.q[a] - R.h[a];
        if (s > tol) continue;
        const Vec3 onRef = P.p - s * nr;
        xy[kept.size()][0] = P.q[u], xy[kept.size()][1] = P.q[v], depth[kept.size()] = -s;
        kept.push_back(refOnA ? ContactPoint{onRef + origin, P.p + origin, -s} : ContactPoint{P.p + origin, onRef + origin, -s});
    }
    if (kept.empty()) return false;
    const int maxPoints = options.maxPoints;
    const ContactIndices chosen = maxPoints >= 1 && maxPoints <= 4
                                      ? reduceFacePoints(xy, depth, static_cast<int>(kept.size()), maxPoints)
                                      : reduceContactPolygon(kept, nr, maxPoints);
    for (int i : chosen) r.manifold.push_back(kept[i]);
    return true;
}

// ---- Box–plane stages ----

// The box's plane contact candidates, in contactPolyhedronPlane's order (submerged corners, then the
// edges crossing the plane at depth 0), with rule 0 of reduceContactPolygon applied when `rim` is
// set: a depth-0 point within the deepest depth, in the plane, of a submerged point is dropped.
// A crossing on edge (u, v), u below, lies t = s_u / (s_u - s_v) along it; its in-plane distance from
// u's projection is |t| |P e| with |P e|² = |e|² - (s_v - s_u)² and |e| = 2 h_m (the edge runs
// along box axis m), so the common steep edge is recognised as u's rim before its point is built.
// pointB = x - s n̂ lies on the plane by construction: differences of pointB are in-plane.
using BoxCandidates = FixedCapacityVector<ContactPoint, 14>;  // corners + crossings: 13 at most, even with tol < 0

// depth: the deepest corner's, max(0, -min s_k). box: the posed box (corners built on demand).
BoxCandidates boxPlaneCandidates(const PosedBox& box, const std::array<double, 8>& s, const Vec3& n, double d,
                                 double tol, double depth, bool rim) {
    const double surface = kSurfaceBandRelative * depth, reach = depth * depth;
    std::array<Vec3, 8> x;        // the corners at or below tol (the others are not built)
    std::array<Vec3, 8> submerged;  // pointB of the corners below the surface band
    int deep = 0;
    unsigned belowEdges = 0, aboveEdges = 0;  // the edges at a corner beyond -tol / +tol
    for (int k = 0; k < 8; ++k) {
        if (s[k] < -tol) belowEdges |= kCornerEdges[k];
        if (s[k] > tol) {
            aboveEdges |= kCornerEdges[k];
            continue;
        }
        x[k] = box.cornerAt(k);
        if (-s[k] > surface) submerged[deep++] = x[k] - s[k] * n;  // candidates (tol may be negative) below the band
    }
    const auto isRim = [&](const Vec3& pointB) {
        if (!rim) return false;
        for (int j = 0; j < deep; ++j)
            if ((pointB - submerged[j]).squaredNorm() <= reach) return true;
        return false;
    };

    BoxCandidates cand;
    for (int k = 0; k < 8; ++k) {
        if (s[k] > tol) continue;
        const ContactPoint c{x[k], x[k] - s[k] * n, std::max(0.0, -s[k])};
        if (c.depth > surface || !isRim(c.pointB)) cand.push_back(c);  // touching corners can be rim too
    }
    // Edges with one corner below and the other above (no corner is both), in the preset's order.
    for (unsigned crossing = belowEdges & aboveEdges; crossing; crossing &= crossing - 1) {
        const int e = std::countr_zero(crossing);
        int u = kEdgeCorners[e][0], v = kEdgeCorners[e][1];
        if (s[u] > s[v]) std::swap(u, v);
        const int m = std::countr_zero(static_cast<unsigned>(u ^ v));  // the edge runs along axis m
        const double ds = s[v] - s[u], edge = 2.0 * box.h[m];
        const double t = s[u] / (s[u] - s[v]);  // both beyond tol: no division by ~0
        // |t| |P e| <= depth with |P e|² = |e|² - ds², compared relative to |e| (boxes of 1e80 or
        // 1e-100 would overflow or underflow the squares of lengths): t² (1 - a)(1 + a) <= (depth / |e|)²
        // with a = ds / |e| <= 1. A ratio that overflows compares as +inf: |P e| <= |e| < depth, rim.
        const double a = std::min(ds / edge, 1.0), ratio = depth / edge;
        if (rim && s[u] <= tol && -s[u] > surface && t * t * ((1.0 - a) * (1.0 + a)) <= ratio * ratio)
            continue;  // u's rim (u is submerged)
        const Vec3 step = (u & (1 << m)) ? Vec3(-2.0 * box.e[m]) : Vec3(2.0 * box.e[m]);  // x_v - x_u
        const Vec3 p = (s[u] <= tol ? x[u] : box.cornerAt(u)) + t * step;  // tol < 0: u may be unbuilt
        const Vec3 pointB = p - (n.dot(p) - d) * n;
        if (!isRim(pointB)) cand.push_back({p, pointB, 0.0});
    }
    return cand;
}

}  // namespace

SatContactResult contactBoxBox(const Vec3& ha, const Transform& ta, const Vec3& hb, const Transform& tb,
                               const SatContactOptions& options) {
    SatContactResult r;
    if (!validExtents(ha)) r.message = "A: box half extents must be finite, > 0 and at most 1e150";
    else if (!validExtents(hb)) r.message = "B: box half extents must be finite, > 0 and at most 1e150";
    else if (const char* m = detail::poseProblem(ta); *m) r.message = std::string("A: ") + m;
    else if (const char* m2 = detail::poseProblem(tb); *m2) r.message = std::string("B: ") + m2;
    if (!r.message.empty()) {
        r.separation = r.depth = NAN;
        return r;
    }
    const Vec3 origin = ta.position;
    const PosedBox A(ha, ta, origin), B(hb, tb, origin);
    const double maxCoord = B.maxCoord() + origin.cwiseAbs().maxCoeff();
    r.tolerance = detail::satTolerance(options, 2.0 * std::max(ha.norm(), hb.norm()), maxCoord);
    const double tol = r.tolerance;

    const detail::SatChosenAxis c = detail::chooseSatAxis(queryBoxAxes(A, B), tol, options);
    if (!std::isfinite(tol) || (c.best.indexA < 0 && c.best.indexB < 0)) {  // positions near the double limit
        r.message = "the boxes' coordinates overflow double precision";
        r.separation = r.depth = NAN;
        return r;
    }
    const SatAxisRecord& best = c.best;
    detail::recordChosenAxis(c, tol, r);
    if (best.kind == SatAxisKind::EdgeEdge) {
        r.featureA = {FeatureType::Edge, best.indexA};
        r.featureB = {FeatureType::Edge, best.indexB};
        if (r.status == SatContactStatus::Separated) return r;
        const Segment ea{A.cornerAt(kEdgeCorners[best.indexA][0]), A.cornerAt(kEdgeCorners[best.indexA][1])};
        const Segment eb{B.cornerAt(kEdgeCorners[best.indexB][0]), B.cornerAt(kEdgeCorners[best.indexB][1])};
        const SegmentSegmentResult cp = closestPointsSegmentSegment(ea, eb);
        r.manifold.push_back({cp.pointOnFirst + origin, cp.pointOnSecond + origin, r.depth});
        return r;
    }
    const bool refOnA = best.kind == SatAxisKind::FaceA;
    const int rf = refOnA ? best.indexA : best.indexB;
    if (r.status == SatContactStatus::Separated) {
        (refOnA ? r.featureA : r.featureB) = {FeatureType::Face, rf};
        return r;
    }
    const PosedBox& R = refOnA ? A : B;
    const PosedBox& I = refOnA ? B : A;
    const Vec3 nr = R.faceNormal(rf);
    int inc = 0;  // the incident face: the most anti-parallel to nr (first of ties, as contactPolyhedra)
    for (int f = 1; f < 6; ++f)
        if (I.faceNormal(f).dot(nr) < I.faceNormal(inc).dot(nr)) inc = f;
    r.featureA = {FeatureType::Face, refOnA ? rf : inc};
    r.featureB = {FeatureType::Face, refOnA ? inc : rf};
    if (clipBoxFaces(R, rf, I, inc, refOnA, origin, tol, options, r)) return r;
    std::array<Vec3, 4> refPoly, incPoly;
    R.facePolygon(rf, refPoly);
    I.facePolygon(inc, incPoly);
    // Side planes of the reference face: edge k runs along box axis m (its corners differ in bit
    // m only), so |e x nr| = |e| = 2 h_m and no square root is needed.
    std::array<Plane, 4> sides;
    for (int k = 0; k < 4; ++k) {
        const int c0 = kFaceCorners[rf][k], c1 = kFaceCorners[rf][(k + 1) % 4];
        const int m = std::countr_zero(static_cast<unsigned>(c0 ^ c1));
        const Vec3 sn = (refPoly[(k + 1) % 4] - refPoly[k]).cross(nr) / (2.0 * R.h[m]);
        sides[k] = Plane{sn, sn.dot(refPoly[k])};
    }
    // Quads clip to at most 8 points: the inline buffers of clipIncidentFace, never the resource.
    detail::clipIncidentFace(refPoly, nr, nr.dot(R.center) + R.h[rf / 2], incPoly, I.corners(), R.corners(), refOnA, origin, tol,
                             options, r, nullptr, std::pmr::null_memory_resource(), sides);
    return r;
}

BoxPlaneContact contactBoxPlane(const Vec3& h, const Transform& pose, const Plane& plane,
                                const PlaneContactOptions& options) {
    BoxPlaneContact r;
    Vec3 n;
    double d = 0.0;
    r.message = validExtents(h) ? detail::unitPlane(plane, n, d) : "box half extents must be finite, > 0 and at most 1e150";
    if (!*r.message) r.message = detail::poseProblem(pose);
    if (!*r.message && options.tolerance && !std::isfinite(*options.tolerance)) r.message = "tolerance is not finite";
    if (*r.message) {
        r.signedDistance = NAN;
        return r;
    }
    r.normal = -n;
    // Signed corner distances s_k = (n̂ · c - d̂) ± n̂ · e_0 ± n̂ · e_1 ± n̂ · e_2 (e_i = h_i x̂_i), the
    // sums in cornerAt's order: no corner is built for a distance. Against long double on 200k
    // random poses this form's error is at or below that of n̂ · x_k - d̂ over built corners
    // (6.2e-16 against 8.4e-16 at unit scale, 3.8e-14 against 4.5e-14 with the box 100 away).
    const PosedBox box(h, pose, Vec3::Zero());
    const double delta = n.dot(box.center) - d;
    const double m0 = n.dot(box.e[0]), m1 = n.dot(box.e[1]), m2 = n.dot(box.e[2]);
    std::array<double, 8> s;
    for (int k = 0; k < 8; ++k) {
        const double a = (k & 1) ? delta + m0 : delta - m0;
        const double b = (k & 2) ? a + m1 : a - m1;
        s[k] = (k & 4) ? b + m2 : b - m2;
    }
    int low = 0;  // the first lowest corner
    double sLow = s[0];
    for (int k = 1; k < 8; ++k) {
        const bool lower = s[k] < sLow;
        low = lower ? k : low;
        sLow = lower ? s[k] : sLow;
    }
    const double maxCoord = std::max(std::abs(d), box.maxCoord());  // max |corner coordinate|, to rounding
    r.deepestVertex = low;
    r.tolerance = options.tolerance && *options.tolerance >= 0.0
                      ? *options.tolerance
                      : options.relativeTolerance * 2.0 * h.norm() + ulps(64, maxCoord);
    const double tol = r.tolerance;
    if (!std::isfinite(sLow) || !std::isfinite(tol)) {  // a pose or plane near the double limit
        r.status = PlaneContactStatus::InvalidInput;
        r.message = "the box's coordinates overflow double precision";
        r.signedDistance = NAN;
        return r;
    }
    r.signedDistance = sLow;
    r.depth = std::max(0.0, -sLow);
    r.status = sLow > tol     ? PlaneContactStatus::Separated
               : sLow >= -tol ? PlaneContactStatus::Touching
                              : PlaneContactStatus::Penetrating;
    if (!r.colliding()) return r;

    // The reduction as reduceContactPolygon, its rule 0 done with the candidates (maxPoints <= 0
    // keeps every candidate). When what is left fits, every point, the deepest first (first of
    // ties), then input order; else the rules, whose rule 0 then drops nothing more.
    const int maxPoints = options.maxPoints;
    const BoxCandidates cand = boxPlaneCandidates(box, s, n, d, tol, r.depth, maxPoints > 0);
    const int count = static_cast<int>(cand.size());
    if (maxPoints <= 0 || maxPoints > 4) {
        for (int i : reduceContactPolygon(cand, n, maxPoints)) r.manifold.push_back(cand[i]);
        return r;
    }
    if (count <= maxPoints) {  // every candidate: the deepest first (first of ties), then input order
        for (int i : deepestFirst(cand)) r.manifold.push_back(cand[i]);
        return r;
    }
    // The rules on the plane's coordinates (any orthonormal basis of it: the scores are lengths and
    // areas in the plane).
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    double xy[14][2], depths[14];
    for (int i = 0; i < count; ++i) xy[i][0] = t1.dot(cand[i].pointB), xy[i][1] = t2.dot(cand[i].pointB), depths[i] = cand[i].depth;
    for (int i : reduceFacePoints(xy, depths, count, maxPoints)) r.manifold.push_back(cand[i]);
    return r;
}

}  // namespace cdlab
