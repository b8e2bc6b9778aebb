// EPA's machinery behind core/gjk_epa/epa.h (include that header, not this one): the polytope in
// fixed arrays, its three stages (seed from GJK's simplex, blow-up to a tetrahedron, expansion),
// the answer from the final face with its edge-pair refinements (precision checks in
// core/gjk_epa/feature_certificate.h), the fallback for degenerate starts, and the entry points'
// bodies.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

#include "core/base/accurate_cross.h"
#include "core/base/double_double.h"
#include "core/base/tolerances.h"
#include "core/closest/edge_pair_distance.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/feature_certificate.h"
#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/touching_pair.h"
#include "core/gjk_epa/simplex_solver.h"

namespace cdlab {

namespace detail {

struct EpaVertex {
    Vec3 w, a, b;
};

struct EpaFace {
    int v[3];         // vertex ids, CCW seen from outside; edge e runs v[e] -> v[(e+1)%3]
    int adj[3];       // face across edge e
    int adjEdge[3];   // index of that edge in the neighbour
    Vec3 normal;      // outward unit normal
    double distance;  // normal · (any vertex): signed distance of the plane from the origin
    bool live;
};

enum class EpaExpand { Ok, Degenerate, Capacity };

/// Convex polytope with fixed capacity (no heap). Non-template part of EPA.
class EpaPolytope {
public:
    static constexpr int kMaxVertices = 128;
    static constexpr int kMaxFaces = 256;

    EpaVertex vertex[kMaxVertices];
    int vertexCount = 0;
    EpaFace face[kMaxFaces];
    int faceEnd = 0;  // slots [0, faceEnd) have been used; dead ones sit in the free list
    int liveCount = 0;
    double scale = 0.0;  // max |w| over the vertices: the length scale for absolute tolerances

    int addVertex(const EpaVertex& v);
    /// Tetrahedron on vertices 0..3, oriented outward. False if a face has zero area.
    bool buildTetrahedron();
    /// Live face with the smallest distance, -1 if none.
    int closestFace() const;
    /// True if w equals a vertex of the polytope exactly.
    bool hasVertex(const Vec3& w) const;
    /// Remove all faces visible from vertex vi (flood fill from `seed`, which must be visible)
    /// and fan the horizon to vi. On failure the removed faces are restored (rollback).
    EpaExpand expand(int seed, int vi, double visibleTolerance, EpaTraceStep* trace);
    /// Witness points of the origin's projection p = depth * normal on face f: p = sum l_i w_i,
    /// pointA = sum l_i a_i, pointB = sum l_i b_i with weights l_i >= 0 summing to 1, from face f
    /// when they hold there, else from the coplanar face that holds p (coveringFaceWitness). So
    /// pointA lies on A, pointB on B and pointA − pointB = depth * normal up to rounding
    /// (tests/core/gjk_epa/epa_witness_test.cpp).
    /// `out` (traced queries) gets the faces and weights used.
    void witness(int f, double depth, Vec3& pointA, Vec3& pointB, EpaWitnessStep* out = nullptr) const;
    /// Witnesses from the live face nearest p, with clamped weights (the fallback of witness()).
    void coveringFaceWitness(const Vec3& p, Vec3& pointA, Vec3& pointB, EpaWitnessFace* used = nullptr) const;
    /// Face f's points and the given weights, for a trace.
    void describeFace(int f, double l1, double l2, EpaWitnessFace& out) const;
    /// pointA = sum l_i a_i, pointB = sum l_i b_i over face f's vertices (l0 = 1 - l1 - l2).
    void weightedWitness(int f, double l1, double l2, Vec3& pointA, Vec3& pointB) const;
    /// Record vertices and live faces into a trace step; returns the index of face f in it.
    int snapshot(EpaTraceStep& step, int f) const;
    /// The invariant of the face graph: every live face's neighbour across edge e is live, names
    /// it back (adj / adjEdge) and runs the same edge the other way. Checked by assert() after
    /// every change (on in the sanitizer build, compiled away in Release).
    bool adjacencyConsistent() const;

private:
    int freeList[kMaxFaces];
    int freeCount = 0;
    int horizonFace[kMaxFaces];
    int horizonEdge[kMaxFaces];
    int horizonCount = 0;
    int removed[kMaxFaces];
    int removedCount = 0;
    bool overflow = false;

    bool plane(int i0, int i1, int i2, Vec3& normal, double& distance) const;
    void silhouette(int f, int edge, const Vec3& w, double tol);
};

/// Contact point of GJK's terminal simplex (for touching contacts).
void epaSimplexWitness(const EpaVertex* v, const SimplexClosest& c, Vec3& pointA, Vec3& pointB);

/// Final face f spanning exactly two points of A and two of B: depth, normal and witnesses from
/// the lines' common perpendicular (EpaOptions::refineEdgePairs). Refused (false, r not written)
/// when the feet leave the edges or the depth moves by more than EPA's rounding could explain;
/// the caller still certifies the plane with the supports.
bool epaRefineEdgePair(const EpaPolytope& poly, int f, EpaResult& r);

/// Trace recording for epaPenetration, one call per event; without a trace every call is a no-op.
class EpaRecorder {
public:
    explicit EpaRecorder(EpaTrace* trace) : trace_(trace) {}
    /// How the first tetrahedron is made from GJK's n-vertex simplex.
    void start(int n);
    void blowUp(const Vec3& direction, const Vec3& point);
    /// The witness step of the answer from face f at depth max(distance, 0) (EpaWitnessStep).
    void witness(const EpaPolytope& poly, int f);
    /// A new iteration: the polytope, its face f nearest the origin and the support point s
    /// along f's normal, with the bounds. Returns the step for the expansion to fill (or null).
    EpaTraceStep* beginStep(int iteration, const EpaPolytope& poly, int f, const EpaVertex& s, double upper);
    /// This step ended the loop.
    void stepEndsLoop();
    void termination(EpaTermination why);

private:
    EpaTrace* trace_;
    EpaTraceStep* step_ = nullptr;
};

// Absolute tolerances relative to the polytope's scale max|w|: a support value, face distance
// or plane test carries a rounding error of a few ulps of |w| (Sterbenz keeps w itself exact).
inline constexpr double kEpaTouch = 1e-14;          // origin within 1e-14 |w| of the boundary: touching
inline constexpr double kEpaVisible = 1e-14;        // w above a face plane by less than this: not visible
inline constexpr double kEpaAbsGap = ulps(4, 1.0);  // gap noise floor (4 ulps of |w|)
// A normal whose squared length is within this of 1 is unit (a normalized vector is a few u off);
// one further off (normalized from a vector that underflowed to zero) sends the answer to the
// support fallback.
inline constexpr double kEpaUnitNormal = 1e-9;

/// True when n is a unit normal up to kEpaUnitNormal.
inline bool epaIsUnitNormal(const Vec3& n) { return std::abs(n.squaredNorm() - 1.0) <= kEpaUnitNormal; }

/// Stage 1: the distinct finite vertices of GJK's simplex, reduced to the smallest sub-simplex
/// that holds the origin (a flat tetrahedron becomes a triangle, etc.); r's witnesses become the
/// simplex point nearest the origin (the contact of a touching answer). Returns the vertex count
/// in seed, 0 for invalid input.
int epaSeed(const GjkSimplex& start, EpaVertex seed[4], EpaResult& r);

/// The outcome of blowing up the seed to a tetrahedron.
enum class EpaBlowUp { Tetrahedron, Touching, InvalidInput };

/// Stage 2: blow a point / segment / triangle up to a tetrahedron, adding the support point along
/// a direction orthogonal to its affine hull. If that support value is ~0, the whole of A − B lies
/// behind the plane through the origin orthogonal to d: the origin is on the boundary, the shapes
/// touch with normal d (r is then the touching answer).
template <class Support>
EpaBlowUp epaBlowUp(const Support& support, EpaVertex seed[4], int n, double& scale, EpaRecorder& record,
                    EpaResult& r) {
    for (; n < 4; ++n) {
        Vec3 d;
        if (n == 1) {
            d = Vec3::UnitX();
        } else if (n == 2) {
            // Perpendicular to the segment via the axis it is least aligned with.
            const Vec3 u = seed[1].w - seed[0].w;
            int k = 0;
            if (std::abs(u[1]) < std::abs(u[k])) k = 1;
            if (std::abs(u[2]) < std::abs(u[k])) k = 2;
            d = u.cross(Vec3::Unit(k)).normalized();
        } else {
            d = (seed[1].w - seed[0].w).cross(seed[2].w - seed[0].w).normalized();
        }
        support(d, seed[n]);
        if (!seed[n].w.allFinite()) return EpaBlowUp::InvalidInput;
        const double h = d.dot(seed[n].w);
        record.blowUp(d, seed[n].w);
        scale = std::max(scale, seed[n].w.norm());
        if (!(h > kEpaTouch * scale)) {
            r.status = EpaStatus::Touching;
            r.depth = 0.0;
            r.normal = d;
            r.lowerBound = 0.0;
            r.upperBound = std::max(h, 0.0);
            return EpaBlowUp::Touching;
        }
    }
    return EpaBlowUp::Tetrahedron;
}

/// Stage 3 (van den Bergen §4.3.8; Ericson §9.5.3): expand the polytope at its face nearest the
/// origin by the support point along that face's normal, until the support value h and the
/// face's distance agree (the depth lies between them) or the polytope cannot grow. r.iterations
/// and the bounds follow the loop; `upper` is the smallest h seen, `nearest` the face it ended on
/// (-1 when it ended without one).
template <class Support>
EpaTermination epaExpandLoop(const Support& support, const EpaOptions& options, EpaPolytope& poly, double& scale,
                             EpaRecorder& record, EpaResult& r, double& upper, int& nearest) {
    upper = INFINITY;
    nearest = -1;
    for (int iter = 1; iter <= options.maxIterations; ++iter) {
        r.iterations = iter;
        const int f = poly.closestFace();
        if (f < 0) return EpaTermination::Degenerate;
        nearest = f;
        const EpaFace& F = poly.face[f];
        const double lower = F.distance;
        EpaVertex s;
        support(F.normal, s);
        if (!s.w.allFinite()) return EpaTermination::InvalidInput;
        const double h = F.normal.dot(s.w);
        upper = std::min(upper, h);
        r.lowerBound = lower;
        r.upperBound = upper;
        EpaTraceStep* step = record.beginStep(iter, poly, f, s, upper);
        scale = std::max({scale, poly.scale, s.w.norm()});
        // Relative gap: h(n_F) - d_F bounds both the depth error and |h(n) - depth| of the
        // reported normal. The absolute floor stops at the rounding level of near-zero depths.
        if (h - lower <= std::max(options.relativeTolerance * std::abs(h), kEpaAbsGap * scale)) {
            record.stepEndsLoop();
            return EpaTermination::Converged;
        }
        // Support point already on the polytope: the polytope cannot grow, exit to avoid cycling.
        if (poly.hasVertex(s.w)) {
            record.stepEndsLoop();
            return EpaTermination::DuplicateSupport;
        }
        const int vi = poly.addVertex(s);
        if (vi < 0) {
            record.stepEndsLoop();
            return EpaTermination::CapacityExceeded;
        }
        const EpaExpand e = poly.expand(f, vi, kEpaVisible * scale, step);
        if (e != EpaExpand::Ok) {
            --poly.vertexCount;  // expansion rolled back: drop the unused vertex
            record.stepEndsLoop();
            return e == EpaExpand::Capacity ? EpaTermination::CapacityExceeded : EpaTermination::Degenerate;
        }
        assert(poly.adjacencyConsistent());
        nearest = -1;
    }
    return EpaTermination::MaxIterations;
}

/// True when face f is a sliver (isSliver): its normal, from rounded differences, errs by more
/// than 1e3 u.
inline bool epaIsSliver(const EpaPolytope& poly, int f) {
    const EpaFace& F = poly.face[f];
    const Vec3 e1 = poly.vertex[F.v[1]].w - poly.vertex[F.v[0]].w, e2 = poly.vertex[F.v[2]].w - poly.vertex[F.v[0]].w;
    return isSliver(e1, e2);
}

/// An uncertified sliver answer (nearly parallel edges whose faces of A − B EPA's rounded
/// polytope may miss altogether): every edge of A and edge of B among the points of the faces
/// within `near` of the origin, as lines in double-double arithmetic (linePairSeparation); where
/// the feet lie inside both edges and both edges are extreme along the lines' normal n (oriented
/// out of A − B), the parallelogram they span is a face of A − B at depth (pointA − pointB)·n:
/// an exact support value, never below the penetration depth. The least one replaces r when smaller.
template <class A, class B>
void epaCrossedEdgePairs(const A& shapeA, const B& shapeB, const EpaPolytope& poly, double near, EpaResult& r) {
    constexpr int kMax = 8;  // distinct points per shape (a sliver's neighbourhood has 2..4)
    Vec3 a[kMax], b[kMax];
    int na = 0, nb = 0;
    for (int g = 0; g < poly.faceEnd; ++g) {
        if (!poly.face[g].live || !(poly.face[g].distance <= near)) continue;
        for (int k = 0; k < 3; ++k) {
            const EpaVertex& v = poly.vertex[poly.face[g].v[k]];
            if (na < kMax && std::find(a, a + na, v.a) == a + na) a[na++] = v.a;
            if (nb < kMax && std::find(b, b + nb, v.b) == b + nb) b[nb++] = v.b;
        }
    }
    // A candidate plane of A − B with unit normal n (out of A − B) through pointA − pointB: kept
    // when both shapes' supports certify it and it is nearer than the answer so far.
    const auto offer = [&](const Vec3& n, double depth, const Vec3& pointA, const Vec3& pointB) {
        if (!(depth >= 0.0 && depth < r.depth) || !n.allFinite()) return;
        const SupportCertificate c = supportCertificate(shapeA, shapeB, n, pointA, pointB);
        if (!c.featuresExtreme(n, pointA, pointB, c.tolerance())) return;
        r.depth = r.lowerBound = r.upperBound = depth;
        r.normal = n;
        r.pointA = pointA;
        r.pointB = pointB;
        r.edgePairRefined = true;
    };
    // Edge of A against edge of B: the lines' common perpendicular, feet strictly inside both edges.
    forEachInteriorEdgePair(a, na, b, nb, [&](const LinePairSeparation& p) {
        const double sign = p.separation <= 0.0 ? 1.0 : -1.0;  // n out of A − B: (pA − pB)·n >= 0
        offer(sign * p.normal, -sign * p.separation, p.pointA, p.pointB);
        return false;  // every pair is offered
    });
    // A point of one shape against a (sliver) face of the other: the face normal from
    // accurateCross (a few ulps in direction whatever the sliver's width).
    const auto faceCandidates = [&](const Vec3* face, int nf, const Vec3* pts, int np, bool faceOfA) {
        for (int i = 0; i < nf; ++i)
            for (int j = i + 1; j < nf; ++j)
                for (int k = j + 1; k < nf; ++k) {
                    const Vec3 c = accurateCross(face[i], face[j], face[k]);
                    const double len = c.norm();
                    if (!(len > 0.0)) continue;
                    for (int q = 0; q < np; ++q) {
                        // w = a − b on the plane; n out of A − B: w·n >= 0.
                        const Vec3 w = faceOfA ? Vec3(face[i] - pts[q]) : Vec3(pts[q] - face[i]);
                        Vec3 n = c / len;
                        if (w.dot(n) < 0.0) n = -n;
                        const double depth = w.dot(n);
                        if (faceOfA) offer(n, depth, Vec3(pts[q] + depth * n), pts[q]);
                        else offer(n, depth, pts[q], Vec3(pts[q] - depth * n));
                    }
                }
    };
    faceCandidates(a, na, b, nb, true);
    faceCandidates(b, nb, a, na, false);
}

/// The answer from the polytope's face f: depth (clamped at 0: the origin may sit a rounding
/// error outside), normal and witnesses; with options.refineEdgePairs, a face spanning two edges
/// is replaced by the edges' common perpendicular when the supports certify that plane as a face
/// of A − B (h_C(n) = n·(s_A(n) - s_B(-n)) bounds the depth from above; equal to the refined
/// depth up to rounding, the depth is exact).
template <class A, class B>
void epaAnswerFromFace(const A& shapeA, const B& shapeB, const EpaOptions& options, const EpaPolytope& poly, int f,
                       double upper, EpaResult& r) {
    const EpaFace& F = poly.face[f];
    r.depth = std::max(F.distance, 0.0);
    r.normal = F.normal;
    r.lowerBound = F.distance;
    r.upperBound = upper;
    poly.witness(f, r.depth, r.pointA, r.pointB);
    if (!options.refineEdgePairs) return;
    // A face certified as a face of A − B: its refined depth is exact, and no face of A − B is
    // nearer than the penetration depth, so the least certified depth is never below it.
    const auto certified = [&](int g, EpaResult& out) {
        out = r;
        if (!epaRefineEdgePair(poly, g, out)) return false;
        const Vec3& n = out.normal;
        const SupportCertificate c = supportCertificate(shapeA, shapeB, n);
        const double h = n.dot(c.sa) - n.dot(c.sb);  // h_C(n), an upper bound of the depth
        return h <= out.depth + c.tolerance();
    };
    EpaResult refined;
    if (certified(f, refined)) r = refined;
    // Nearly parallel edges make sliver faces whose rounded distances err by ~u scale / angle: the
    // nearest face by the rounded distances may not be the nearest one. Every face within that
    // error of it (up to 1e-6 scale: angles down to ~1e-10) is refined too; the least certified wins.
    // Slivers near the answer (nearly parallel edges): the nearest face of A − B may be missing from
    // the polytope altogether (EPA stops on a duplicate support first); then it is sought among
    // the near faces' points.
    const double slack = 1e-6 * poly.scale;
    bool sliverNear = epaIsSliver(poly, f);
    for (int g = 0; g < poly.faceEnd; ++g) {
        if (g == f || !poly.face[g].live || !(poly.face[g].distance <= F.distance + slack)) continue;
        if (certified(g, refined) && refined.depth < r.depth) r = refined;
        sliverNear = sliverNear || epaIsSliver(poly, g);
    }
    if (sliverNear) epaCrossedEdgePairs(shapeA, shapeB, poly, F.distance + slack, r);
}

/// n·(sa − sb) with the differences exact and the products and sums in double-double: the support
/// overlap along n to a few ulps of itself, not of |sa| (far shapes, tiny overlaps).
inline double epaOverlapAlong(const Vec3& n, const Vec3& sa, const Vec3& sb) {
    dd::DoubleDouble acc{0.0, 0.0};
    for (int i = 0; i < 3; ++i) acc = acc + dd::DoubleDouble{n[i], 0.0} * dd::exactDifference(sa[i], sb[i]);
    return acc.hi + acc.lo;
}

/// Witnesses of a fallback answer (unit n, depth d): the touching pair along n (touching_pair.h).
/// Where GJK does not separate them the support points stay: pointB = s_B(−n), pointA = pointB +
/// d·n. Tests: tests/core/gjk_epa/epa_fallback_witness_test.cpp (a 1e-9 square in the face of a
/// 1e5 tetrahedron; a 1e-6 body beside a 1e3 one).
template <class A, class B>
void epaFallbackWitness(const A& shapeA, const B& shapeB, EpaResult& r) {
    const Vec3 sa = shapeA.support(r.normal), sb = shapeB.support(Vec3(-r.normal));
    r.pointB = sb;
    r.pointA = sb + r.depth * r.normal;
    const double M = std::max(sa.cwiseAbs().maxCoeff(), sb.cwiseAbs().maxCoeff());
    touchingPairAlong(shapeA, shapeB, r.normal, r.depth, M, r.pointA, r.pointB);
}

/// A degenerate start (a zero-volume polytope, or a blow-up direction that underflowed: a start
/// segment 1e-160 long, cores 1e300 long and 1 wide) or a degenerate expansion leaves no
/// trustworthy face: the answer is then the direction of least support overlap
/// n·s_A(n) − n·s_B(−n) among the normal it had (when unit), the six coordinate axes, the live
/// faces' normals of the polytope `poly` (when given) and the face normals and edge-pair cross
/// products of the distinct shape points on its vertices (accurateCross: a sliver's or a far
/// face's normal to a few ulps), with that overlap as the depth — a unit normal and a depth that
/// separates (an upper bound of the least one), never "touching" for shapes that overlap.
/// Witnesses: epaFallbackWitness.
template <class A, class B>
void epaSupportFallback(const A& shapeA, const B& shapeB, EpaResult& r, const EpaPolytope* poly = nullptr) {
    double best = INFINITY;
    const bool haveNormal = epaIsUnitNormal(r.normal);
    const Vec3 given = r.normal;
    const auto offer = [&](const Vec3& n) {
        if (!n.allFinite() || !epaIsUnitNormal(n)) return;
        const Vec3 sb = shapeB.support(Vec3(-n));
        const Vec3 sa = shapeA.support(n);
        const double overlap = epaOverlapAlong(n, sa, sb);
        if (overlap < best) best = overlap, r.normal = n;
    };
    // The given normal both ways (a flat start's face normal has no outward side), then the axes.
    for (int i = haveNormal ? -2 : 0; i < 6; ++i)
        offer(i < 0 ? Vec3(i == -2 ? given : Vec3(-given)) : Vec3((i % 2 ? -1.0 : 1.0) * Vec3::Unit(i / 2)));
    constexpr int kMax = 8;  // distinct points per shape taken from the polytope
    Vec3 a[kMax], b[kMax];
    int na = 0, nb = 0;
    if (poly) {
        for (int g = 0; g < poly->faceEnd; ++g) {
            if (!poly->face[g].live) continue;
            offer(poly->face[g].normal);
            offer(Vec3(-poly->face[g].normal));
        }
        for (int k = 0; k < poly->vertexCount; ++k) {
            const EpaVertex& v = poly->vertex[k];
            if (na < kMax && std::find(a, a + na, v.a) == a + na) a[na++] = v.a;
            if (nb < kMax && std::find(b, b + nb, v.b) == b + nb) b[nb++] = v.b;
        }
        const auto faces = [&](const Vec3* p, int np) {
            for (int i = 0; i < np; ++i)
                for (int j = i + 1; j < np; ++j)
                    for (int k = j + 1; k < np; ++k) {
                        const Vec3 n = accurateCross(p[i], p[j], p[k]).normalized();
                        offer(n);
                        offer(Vec3(-n));
                    }
        };
        faces(a, na);
        faces(b, nb);
        for (int i = 0; i < na; ++i)
            for (int j = i + 1; j < na; ++j)
                for (int k = 0; k < nb; ++k)
                    for (int l = k + 1; l < nb; ++l) {
                        const Vec3 n = (a[j] - a[i]).cross(b[l] - b[k]).normalized();
                        offer(n);
                        offer(Vec3(-n));
                    }
    }
    r.depth = std::max(best, 0.0);
    r.pointA = r.pointB + r.depth * r.normal;
    if (best < INFINITY) epaFallbackWitness(shapeA, shapeB, r);
    r.lowerBound = 0.0;
    r.upperBound = r.depth;
    r.status = r.depth > 0 ? EpaStatus::Penetrating : EpaStatus::Touching;
}

}  // namespace detail

template <SupportMapping A, SupportMapping B>
EpaResult epaPenetration(const A& shapeA, const B& shapeB, const GjkSimplex& start, const EpaOptions& options,
                         EpaTrace* trace) {
    EpaResult r;
    detail::EpaPolytope poly;
    detail::EpaRecorder record(trace);
    // Plain (cold) supports: successive EPA directions are face normals far apart, so starting a
    // hill climb at the previous answer costs more than the shape's own seeds (measured).
    const auto support = [&](const Vec3& d, detail::EpaVertex& out) {
        out.a = shapeA.support(d);
        out.b = shapeB.support(-d);
        out.w = out.a - out.b;
    };
    const auto stop = [&](EpaTermination why) {
        r.termination = why;
        record.termination(why);
        r.vertexCount = poly.vertexCount;
        r.faceCount = poly.liveCount;
        if (why == EpaTermination::Degenerate ||
            (why != EpaTermination::InvalidInput && !detail::epaIsUnitNormal(r.normal)))
            detail::epaSupportFallback(shapeA, shapeB, r, &poly);
        return r;
    };

    detail::EpaVertex seed[4];
    const int n = detail::epaSeed(start, seed, r);
    if (n == 0) return stop(EpaTermination::InvalidInput);
    double scale = 0.0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, seed[i].w.norm());
    record.start(n);

    switch (detail::epaBlowUp(support, seed, n, scale, record, r)) {
        case detail::EpaBlowUp::InvalidInput: return stop(EpaTermination::InvalidInput);
        case detail::EpaBlowUp::Touching: return stop(EpaTermination::Touching);
        case detail::EpaBlowUp::Tetrahedron: break;
    }
    for (int i = 0; i < 4; ++i) poly.addVertex(seed[i]);
    if (!poly.buildTetrahedron()) {
        // Zero-volume start although every blow-up step gained height: only possible with
        // values at the rounding floor. Report touching along the first face's normal.
        // (The normal from error-free products: a sliver start's rounded cross product is off by
        // ~u / sine, and the fallback's depth along it by ~u |w| / sine.)
        r.status = EpaStatus::Touching;
        r.normal = accurateCross(seed[0].w, seed[1].w, seed[2].w).normalized();
        if (!r.normal.allFinite()) r.normal = Vec3::UnitX();
        return stop(EpaTermination::Degenerate);
    }
    assert(poly.adjacencyConsistent());

    double upper = INFINITY;
    int f = -1;
    const EpaTermination why = detail::epaExpandLoop(support, options, poly, scale, record, r, upper, f);
    if (why == EpaTermination::InvalidInput) return stop(why);
    if (f < 0) f = poly.closestFace();
    if (f < 0) {
        r.status = EpaStatus::Touching;
        return stop(EpaTermination::Degenerate);
    }
    detail::epaAnswerFromFace(shapeA, shapeB, options, poly, f, upper, r);
    record.witness(poly, f);
    r.status = r.depth <= detail::kEpaTouch * scale ? EpaStatus::Touching : EpaStatus::Penetrating;
    // A duplicate support on a rounded polytope (a needle 1e-7 wide and 1e3 long, issue 41) can
    // stop on a face that is no face of A − B: the overlap along its normal is far above its depth.
    // Such an uncertified answer goes to the support fallback (least overlap over the polytope's
    // normals and its points' faces and edge pairs, which holds this normal too).
    if (why == EpaTermination::DuplicateSupport) {
        const double h =
            detail::epaOverlapAlong(r.normal, shapeA.support(r.normal), shapeB.support(Vec3(-r.normal)));
        if (h - r.depth > std::max(1e-6 * std::abs(h), 1e3 * detail::kEpaAbsGap * scale))
            detail::epaSupportFallback(shapeA, shapeB, r, &poly);
    }
    return stop(why);
}

template <SupportMapping A, SupportMapping B>
EpaResult penetration(const A& shapeA, const B& shapeB, const EpaOptions& options, EpaTrace* trace, GjkResult* gjkOut) {
    const GjkResult g = gjkDistance(shapeA, shapeB, options.gjk);
    if (gjkOut) *gjkOut = g;
    if (g.status == GjkStatus::InvalidInput) {
        EpaResult r;
        if (trace) trace->termination = EpaTermination::InvalidInput;
        return r;
    }
    if (!g.intersect()) {
        EpaResult r;
        r.status = EpaStatus::Separated;
        r.termination = EpaTermination::NotIntersecting;
        r.normal = g.separatingAxis;
        r.pointA = g.pointA;
        r.pointB = g.pointB;
        if (trace) trace->termination = r.termination;
        return r;
    }
    // A shallow crossing of nearly parallel edges, decided exactly by GJK: its simplex does not hold
    // the origin, and the crossing's face is the nearest one.
    if (const std::optional<EdgePairCrossing> c = crossedEdgePenetration(shapeA, shapeB, g)) {
        EpaResult r;
        r.status = EpaStatus::Penetrating;
        r.termination = EpaTermination::DecidedByGjk;
        r.depth = r.lowerBound = r.upperBound = c->depth;
        r.normal = c->normal;
        r.pointA = c->pointA;
        r.pointB = c->pointB;
        r.edgePairRefined = true;
        if (trace) trace->termination = r.termination;
        return r;
    }
    return epaPenetration(shapeA, shapeB, g.simplex, options, trace);
}

}  // namespace cdlab
