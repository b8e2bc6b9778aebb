// GJK's machinery behind core/gjk_epa/gjk.h (include that header, not this one): support
// evaluation with hints, the loop (gjkRun), the answer from the terminal simplex (gjkFinish), and
// the feature-pair checks that certify or overturn a doubtful answer (precision checks in
// core/gjk_epa/feature_certificate.h), and the entry points' bodies.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/base/accurate_cross.h"
#include "core/base/tolerances.h"
#include "core/closest/edge_pair_distance.h"
#include "core/gjk_epa/feature_certificate.h"
#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/gjk_boolean.h"
#include "core/gjk_epa/simplex_solver.h"

namespace cdlab {

namespace detail {

/// Witness points sum lambda_i a_i, written relative to vertex 0 (pointA = a_0 + sum lambda_i
/// (a_i - a_0)) so that far-from-origin shapes (offsets 1e6) lose no digits to the offset.
void gjkWitness(const GjkSimplex& s, Vec3& pointA, Vec3& pointB);

/// Trace recording for gjkRun, one call per event of the loop; without a trace every call is a
/// no-op, so the loop reads as the algorithm and the untraced run does no trace work.
class GjkRecorder {
public:
    explicit GjkRecorder(GjkTrace* trace) : trace_(trace) {}
    /// A new iteration: direction -v, the support point, the bounds and the gap test, and the
    /// simplex W before w joins it (kept slots: all of W).
    void beginStep(int iteration, const Vec3& v, const GjkVertex& support, double lowerBound, double upperBound,
                   double gapTest, const GjkSimplex& s);
    /// W + {w}: the n = |W| + 1 vertices the solver reduces.
    void candidate(const GjkSimplex& s, int n);
    /// The sub-simplex c kept out of W + {w}, with v and the witnesses of `reduced` (c compacted).
    void reduction(const SimplexClosest& c, const GjkSimplex& reduced);
    /// This step ended the loop.
    void stepEndsLoop();
    void termination(GjkTermination why);

private:
    GjkTrace* trace_;
    GjkTraceStep* step_ = nullptr;
};

/// A separated distance is certified when its lower bound is within this relative gap of it: a
/// converged run's gap is relativeTolerance (1e-13); a stop on a duplicate support or on no
/// progress can leave |v| far above the distance.
inline constexpr double kGjkCertifiedGap = 1e-9;

/// The most an edge simplex's accurate normal may turn GJK's axis -v / |v| (radians) and replace it
/// (gjkFinish): v's own direction errs by ~u |w| / |v|; more than this is not rounding.
inline constexpr double kGjkEdgeAxisTurn = 1e-9;
/// ... and at most this many ulps of the simplex's extent over |v| (the rounding of v's direction;
/// tests/core/gjk_epa/margins_test.cpp "nearly parallel capsules").
inline constexpr double kGjkEdgeAxisTurnUlps = 0x1p20;

/// A support point within this many ulps of the extent (plus kGjkEdgeAxisTurn times its offset from
/// the edge) of the edge's plane lies in that plane: the edge and it span a face of A − B (gjkFinish).
inline constexpr double kGjkFacePlaneUlps = 16.0;

/// The tilt (radians) of gjkFinish's probes for a face through a terminal edge: far above rounding,
/// far below the angle between two faces of a box or a mesh.
inline constexpr double kGjkFaceProbe = 0x1p-20;

/// True when a separated answer may be off by more than rounding of L: the terminal triangle is
/// a sliver (isSliver: two nearly parallel edges, normal error ~u / angle) or GJK stopped without
/// certifying the distance (lower bound below (1 − kGjkCertifiedGap) |v|: duplicate support or no
/// progress).
bool gjkNeedsEdgePairs(const GjkSimplex& s, const GjkResult& r);

/// Every two points of A with every two points of B among the simplex's vertices, as accurate
/// segment-segment distances (core/closest/edge_pair_distance.h), or the point-triangle distance when
/// the simplex has one point of one shape and three of the other; sorted by distance, returns
/// the count (<= kGjkMaxEdgePairCandidates, <= kGjkMaxEdgePairCandidatesOfTriangle for a triangle;
/// feature_certificate.h). Each is a distance between subsets of A and B: an upper bound of the
/// true distance.
int gjkEdgePairCandidates(const GjkSimplex& s, EdgePairDistance* out);

/// A certified edge-pair candidate e becomes the separated answer: distance e.distance, bounds
/// [min(lower, e.distance), e.distance], e's witnesses and axis (status is the caller's).
inline void gjkAdoptEdgePair(const EdgePairDistance& e, double lower, GjkResult& r) {
    r.distance = e.distance;
    r.upperBound = e.distance;
    r.lowerBound = std::min(lower, e.distance);
    r.pointA = e.pointA;
    r.pointB = e.pointB;
    r.separatingAxis = e.axis;
    r.edgePairRefined = true;
}

/// Replace a doubtful separated answer (gjkNeedsEdgePairs) by the smallest edge-pair distance
/// that the supports certify: with axis d of that pair, d . (s_B(-d) - s_A(d)) is a lower bound
/// of the distance; when it equals the pair's distance up to rounding, that distance is exact.
/// Uncertified candidates (e.g. crossed edges of penetrating shapes) change nothing.
template <class A, class B>
void gjkRefineEdgePairs(const A& shapeA, const B& shapeB, const GjkSimplex& s, GjkResult& r) {
    if (!gjkNeedsEdgePairs(s, r)) return;
    // Separated: the terminal simplex is at most a triangle.
    EdgePairDistance candidate[kGjkMaxEdgePairCandidatesOfTriangle];
    const int n = gjkEdgePairCandidates(s, candidate);
    for (int i = 0; i < n; ++i) {
        const EdgePairDistance& e = candidate[i];
        if (!(e.distance > 0.0)) continue;  // touching edges give no axis to certify
        const SupportCertificate c = supportCertificate(shapeA, shapeB, e.axis, e.pointA, e.pointB);
        const double lower = c.lowerBoundAlong(e.axis);
        if (!c.certifiesDistance(lower, e.distance)) continue;
        gjkAdoptEdgePair(e, lower, r);
        return;
    }
}

/// Edge pairs among a simplex's points: distinct points of A (at most 3) and of B.
int gjkSimplexShapePoints(const GjkSimplex& s, Vec3* a, int& na, Vec3* b, int& nb);

/// A doubtful separated answer that no edge pair certified (gjkRefineEdgePairs) may be a shallow
/// penetration: two nearly parallel edges whose ridges cross by less than the rounding of GJK's
/// sliver simplex (~u L / angle). For each edge of A and edge of B among the simplex's points
/// whose lines' common perpendicular has its feet inside both edges, and along whose normal n
/// (oriented like GJK's axis, from A toward B) both edges are extreme in their shapes — so the
/// parallelogram edge_a ⊕ (−edge_b) is a face of A − B and the origin projects inside it — the side
/// of the origin is decided from the lines' separation in double-double arithmetic
/// (core/closest/edge_pair_distance.h): behind the face by more than rounding, the shapes
/// intersect, by that depth along n (the nearest face of A − B: the others are a body's size away).
/// The first crossing found goes to `out`. A pure function of the points and the shapes' supports:
/// crossedEdgePenetration reruns it on the terminal simplex and gets the same bits.
template <class A, class B>
bool gjkCrossedAmong(const A& shapeA, const B& shapeB, const Vec3* a, int na, const Vec3* b, int nb,
                     EdgePairCrossing& out) {
    // Decided: intersecting, the face through pointA - pointB with normal n (out of A − B) at depth.
    const auto decide = [&](const Vec3& n, const Vec3& pointA, const Vec3& pointB) {
        const double separation = n.dot(pointB - pointA);
        const SupportCertificate c = supportCertificate(shapeA, shapeB, n, pointA, pointB);
        const double tol = c.tolerance();
        // Both features extreme along n (the face supports A − B), the origin behind it.
        if (!c.featuresExtreme(n, pointA, pointB, tol) || !(separation < -tol)) return false;
        // And A − B reaching past the origin the other way (min over A − B of n·x below 0): a thin
        // A − B has both orientations of the face "extreme", and behind one of them is not inside.
        const Vec3 lowA = shapeA.support(Vec3(-n)), highB = shapeB.support(n);
        if (!(n.dot(lowA) - n.dot(highB) < -tol)) return false;
        out.depth = -separation;
        out.normal = n;
        out.pointA = pointA;
        out.pointB = pointB;
        return true;
    };
    // Edge of A against edge of B: the lines' common perpendicular, feet strictly inside both edges
    // (the origin projects into the face's interior).
    const bool edgesCross = forEachInteriorEdgePair(a, na, b, nb, [&](const LinePairSeparation& p) {
        // The orientation out of A − B is the one along which both edges are extreme (decide
        // checks it): GJK's axis from a sliver may point either way.
        return decide(p.normal, p.pointA, p.pointB) || decide(Vec3(-p.normal), p.pointA, p.pointB);
    });
    if (edgesCross) return true;
    // A point of one shape against a (sliver) face of the other, the face normal from accurateCross;
    // the origin projects inside the face of A − B when the point projects inside the face.
    const auto pointFace = [&](const Vec3& f0, const Vec3& f1, const Vec3& f2, const Vec3& point, bool faceOfA) {
        const Vec3 c = accurateCross(f0, f1, f2);
        const double len = c.norm();
        if (!(len > 0.0)) return false;
        const Vec3 n = c / len;
        const Vec3 q = point - n * n.dot(point - f0);  // the point projected on the face's plane
        const Vec3 f[3] = {f0, f1, f2};
        for (int e = 0; e < 3; ++e)
            if (accurateCross(f[e], f[(e + 1) % 3], q).dot(c) < 0.0) return false;
        // Either orientation: decide keeps the one along which both features are extreme.
        return faceOfA ? decide(n, q, point) || decide(Vec3(-n), q, point)
                       : decide(n, point, q) || decide(Vec3(-n), point, q);
    };
    for (int i = 0; i < na; ++i)
        for (int j = i + 1; j < na; ++j)
            for (int k = j + 1; k < na; ++k)
                for (int q = 0; q < nb; ++q)
                    if (pointFace(a[i], a[j], a[k], b[q], true)) return true;
    for (int i = 0; i < nb; ++i)
        for (int j = i + 1; j < nb; ++j)
            for (int k = j + 1; k < nb; ++k)
                for (int q = 0; q < na; ++q)
                    if (pointFace(b[i], b[j], b[k], a[q], false)) return true;
    return false;
}

/// gjkCrossedAmong on the distinct points of A and of B among the simplex's vertices.
template <class A, class B>
bool gjkCrossingOfSimplex(const A& shapeA, const B& shapeB, const GjkSimplex& s, EdgePairCrossing& out) {
    Vec3 a[8], b[8];
    int na = 0, nb = 0;
    gjkSimplexShapePoints(s, a, na, b, nb);
    return gjkCrossedAmong(shapeA, shapeB, a, na, b, nb, out);
}

/// A doubtful separated answer (no edge pair certified it) whose simplex holds a crossing edge pair
/// (gjkCrossedAmong) becomes intersecting: status Intersecting, termination EdgePairCrossed,
/// distance 0, the crossing's deepest points as pointA / pointB. Its depth and normal are not kept:
/// crossedEdgePenetration recomputes them from the simplex (the same decision, the same bits).
template <class A, class B>
void gjkDecideCrossedEdges(const A& shapeA, const B& shapeB, const GjkSimplex& s, GjkResult& r) {
    if (r.intersect() || r.edgePairRefined || !gjkNeedsEdgePairs(s, r)) return;
    EdgePairCrossing crossing;
    if (!gjkCrossingOfSimplex(shapeA, shapeB, s, crossing)) return;
    r.status = GjkStatus::Intersecting;
    r.termination = GjkTermination::EdgePairCrossed;
    r.distance = 0.0;
    r.upperBound = 0.0;
    r.separatingAxis.setZero();
    r.pointA = crossing.pointA;
    r.pointB = crossing.pointB;
}

/// The converse: GJK stopped with the origin in a flat terminal simplex (a sliver tetrahedron or
/// triangle of nearly parallel edges, whose rounded volume can put the origin inside) although a
/// feature pair of its points certifies a positive distance (gjkRefineEdgePairs' certificate: the
/// supports along the pair's axis are that distance apart, up to rounding): the shapes are apart.
template <class A, class B>
void gjkDecideFlatIntersection(const A& shapeA, const B& shapeB, const GjkSimplex& s, GjkResult& r) {
    if (!r.intersect() || s.count < 3) return;
    const Vec3 e1 = s.vertex[1].w - s.vertex[0].w, e2 = s.vertex[2].w - s.vertex[0].w;
    const Vec3 n = e1.cross(e2);
    bool flat = isSliverCross(n, e1, e2);
    if (s.count == 4) {
        const Vec3 e3 = s.vertex[3].w - s.vertex[0].w;
        flat = flat || std::abs(n.dot(e3)) < 1e-3 * std::sqrt(e1.squaredNorm() * e2.squaredNorm() * e3.squaredNorm());
    }
    if (!flat) return;
    EdgePairDistance candidate[kGjkMaxEdgePairCandidates];
    const int count = gjkEdgePairCandidates(s, candidate);
    for (int i = count - 1; i >= 0; --i) {  // the largest certified distance: a separating axis
        const EdgePairDistance& e = candidate[i];
        if (!(e.distance > 0.0)) continue;
        const SupportCertificate c = supportCertificate(shapeA, shapeB, e.axis, e.pointA, e.pointB);
        const double lower = c.lowerBoundAlong(e.axis);
        if (!c.certifiesDistance(lower, e.distance) || !c.provesSeparation(lower)) continue;
        r.status = GjkStatus::Separated;
        gjkAdoptEdgePair(e, lower, r);
        return;
    }
}

/// Support of `shape` along d, through the shape's hinted overload support(d, hint) when it has
/// one (PolytopeShape: hill climbing restarts at the previous answer, see core/geometry/shapes.h).
template <class S>
inline Vec3 hintedSupport(const S& shape, const Vec3& d, int& hint) {
    if constexpr (requires { shape.support(d, hint); }) {
        return shape.support(d, hint);
    } else {
        return shape.support(d);
    }
}

/// Support hints of both shapes for one query (-1: cold start).
struct SupportHints {
    int a = -1;
    int b = -1;
};

template <class A, class B>
inline void gjkSupport(const A& shapeA, const B& shapeB, const Vec3& d, GjkVertex& out, SupportHints& hints) {
    out.direction = d;
    out.a = hintedSupport(shapeA, d, hints.a);
    out.b = hintedSupport(shapeB, Vec3(-d), hints.b);
    out.w = out.a - out.b;  // exact (Sterbenz) when a and b are within a factor 2 per coordinate
}

template <class A, class B>
inline void gjkSupport(const A& shapeA, const B& shapeB, const Vec3& d, GjkVertex& out) {
    SupportHints cold;
    gjkSupport(shapeA, shapeB, d, out, cold);
}

/// Keep the sub-simplex `c` of s (indices ascending, so compaction in place is safe).
inline void gjkCompact(GjkSimplex& s, const SimplexClosest& c) {
    for (int k = 0; k < c.count; ++k) {
        if (c.index[k] != k) s.vertex[k] = s.vertex[c.index[k]];
        s.lambda[k] = c.lambda[k];
    }
    s.count = c.count;
}

/// The result from the terminal simplex s and its closest point v (van den Bergen §4.3): the
/// distance |v| and the axis -v / |v|, a face's normal when the simplex is a triangle, edge-pair
/// refinement when asked for. v is the sub-algorithm's own (along the face normal, or from
/// error-free products, where sum lambda_i w_i errs by ~u |w| against a far smaller |v|); the
/// witnesses are sum lambda_i a_i and sum lambda_i b_i, each on its shape (pointB = pointA - v would put
/// pointB 1e-6 of the size off B where a sliver's weights are poor). The result's termination is
/// `why`, or EdgePairCrossed when a doubtful "apart" turns out to be a crossed edge pair.
template <class A, class B>
void gjkFinish(const A& shapeA, const B& shapeB, const GjkOptions& options, const GjkSimplex& s, GjkTermination why,
               const Vec3& v, GjkResult& r) {
    r.termination = why;
    if (why == GjkTermination::InvalidInput) {
        r.status = GjkStatus::InvalidInput;
        return;
    }
    detail::gjkWitness(s, r.pointA, r.pointB);
    if (why == GjkTermination::OriginInSimplex) {
        r.status = GjkStatus::Intersecting;
        r.distance = 0.0;
        r.upperBound = 0.0;
        r.separatingAxis.setZero();
        if (options.refineEdgePairs) gjkDecideFlatIntersection(shapeA, shapeB, s, r);
        return;
    }
    r.status = GjkStatus::Separated;
    r.distance = v.norm();
    r.upperBound = r.distance;
    r.separatingAxis = -v / r.distance;
    if (s.count == 3) {
        // Face region: the triangle normal is a better axis than v, whose direction carries
        // an error of ~eps |w| / |v| when the distance is small against the shapes' size. The
        // normal from accurateCross (the exact cross product rounded once): points sharing a
        // coordinate exactly (a face of a box axis-aligned in the input) give that axis exactly.
        Vec3 n = accurateCross(s.vertex[0].w, s.vertex[1].w, s.vertex[2].w);
        const double len = n.norm();
        if (len > 0.0) {
            n /= len;
            if (n.dot(v) < 0.0) n = -n;
            if (n.dot(v) > 0.5 * r.distance) r.separatingAxis = -n;  // sanity: same side
        }
    } else if (s.count == 2 && s.lambda[0] > 0.0 && s.lambda[1] > 0.0) {
        // Edge region: -v is w0 less its component along e = w1 - w0, i.e. ((w0 x e) x e) / (|e|² |v|),
        // with w0 x e from accurateCross (exact, rounded once): when w0 and w1 share a coordinate
        // exactly (a box's face diagonal: a sphere centre over it), the axis has that coordinate
        // exactly 0 — -v / |v| carried the rounding of the weights there (1e-14, issue 41). Kept only
        // within kGjkEdgeAxisTurn of -v / |v| (rounding; anything more is not this edge's normal).
        const Vec3 &w0 = s.vertex[0].w, &w1 = s.vertex[1].w;
        const Vec3 e = w1 - w0;
        Vec3 n = accurateCross(w0, w1, Vec3::Zero()).cross(e);  // (w0 x e) x e ∝ -v
        const double len = n.norm();
        // The turn rounding explains: v's direction errs by ~u |w| / |v|. A turn of θ moves
        // pointA − pointB off −distance · axis by θ · distance, so a fixed 1e-9 rad put two nearly
        // parallel capsules' witnesses 1.06 × the 1e-9 L tolerance off (stress "spheres and
        // capsules" #29372: the thin parallelogram's face normal, not its edge's, taken).
        const double wExtent = std::max(w0.cwiseAbs().maxCoeff(), w1.cwiseAbs().maxCoeff());
        const double turn = std::min(kGjkEdgeAxisTurn, ulps(kGjkEdgeAxisTurnUlps, wExtent) / r.distance);
        if (len > 0.0 && std::isfinite(len)) {
            n /= len;
            if ((n - r.separatingAxis).squaredNorm() <= turn * turn) {
                r.separatingAxis = n;
                // The edge may lie in a face of A − B that holds the origin's projection up to
                // rounding (a sphere centre over a box face's diagonal: GJK's triangle lost its third
                // point to the weights' rounding, then stopped on a duplicate support). The supports
                // along n tilted by kGjkFaceProbe to either side of the edge (t = n x e) reach that
                // face's other points, on the edge's plane up to rounding (along n itself the tie with
                // the edge's ends is decided by rounding); the face's accurate normal is then the axis:
                // exact for a face axis-aligned in the input.
                const Vec3 t = n.cross(e).normalized();
                for (const double side : {1.0, -1.0}) {
                    GjkVertex third;
                    gjkSupport(shapeA, shapeB, Vec3((n + side * kGjkFaceProbe * t).normalized()), third);
                    const Vec3& w2 = third.w;
                    const double extent = std::max({w0.cwiseAbs().maxCoeff(), w1.cwiseAbs().maxCoeff(),
                                                    w2.cwiseAbs().maxCoeff()});
                    // On the edge's plane: up to rounding and the turn allowed (n itself is the
                    // edge's normal, off the face's by the origin's offset from the edge's line).
                    const double offPlane = std::abs(n.dot(w2 - w0));
                    if (!w2.allFinite() || w2 == w0 || w2 == w1 ||
                        !(offPlane <= turn * (w2 - w0).norm() + ulps(kGjkFacePlaneUlps, extent)))
                        continue;
                    Vec3 f = accurateCross(w0, w1, w2);
                    const double flen = f.norm();
                    if (!(flen > 0.0) || !std::isfinite(flen)) continue;
                    f /= flen;
                    if (f.dot(n) < 0.0) f = -f;
                    if ((f - n).squaredNorm() > turn * turn) continue;
                    r.separatingAxis = f;
                    break;
                }
            }
        }
    }
    if (options.refineEdgePairs && s.count >= 2) {
        gjkRefineEdgePairs(shapeA, shapeB, s, r);
        // A boolean query's separating axis (v·w > 0) is a proof of separation: a penetration of
        // depth δ would make v·w <= -δ |v|, far beyond rounding. So is any lower bound v·w / |v|
        // above the rounding of the supports' dot products (~u |a|, |b|): a converged run's
        // certificate (a thin A − B has both orientations of a crossed pair's face "extreme", and the
        // crossed-edge decision would call such a pair intersecting). Only the other stops are doubtful.
        double extent = 0.0;
        for (int i = 0; i < s.count; ++i)
            extent = std::max({extent, s.vertex[i].a.cwiseAbs().maxCoeff(), s.vertex[i].b.cwiseAbs().maxCoeff()});
        const bool certified =
            why == GjkTermination::SeparatingAxis || r.lowerBound > ulps(kSeparationProofUlps, extent);
        if (!certified) gjkDecideCrossedEdges(shapeA, shapeB, s, r);
    }
}

/// The initial simplex in s with its closest point c: the warm start's directions re-evaluated
/// as supports of the current shapes (duplicates dropped, then reduced), or one support point
/// along +x. False when a support is not finite.
template <class A, class B>
bool gjkStartSimplex(const A& shapeA, const B& shapeB, const GjkOptions& options, GjkSimplex& s, SupportHints& hints,
                     SimplexClosest& c) {
    if (options.warmStart && options.warmStart->count > 0) {
        int n = 0;
        for (int i = 0; i < options.warmStart->count && i < 4; ++i) {
            gjkSupport(shapeA, shapeB, options.warmStart->vertex[i].direction, s.vertex[n], hints);
            bool dup = false;
            for (int j = 0; j < n; ++j) dup = dup || (s.vertex[j].w == s.vertex[n].w);
            if (!dup) ++n;
        }
        s.count = n;
        Vec3 wv[4];
        for (int i = 0; i < n; ++i) {
            if (!s.vertex[i].w.allFinite()) {
                s.count = 0;
                return false;
            }
            wv[i] = s.vertex[i].w;
        }
        c = closestOnSimplex(wv, n, options.solver);
        gjkCompact(s, c);
        return true;
    }
    gjkSupport(shapeA, shapeB, Vec3::UnitX(), s.vertex[0], hints);
    s.lambda[0] = 1.0;
    s.count = 1;
    if (!s.vertex[0].w.allFinite()) return false;
    c.count = 1;
    c.v = s.vertex[0].w;
    return true;
}

/// GJK (Gilbert, Johnson, Keerthi 1988; van den Bergen, "Collision Detection in Interactive 3D
/// Environments", §4.3): v is the point of the simplex W nearest the origin; each iteration adds
/// the support point w of A − B along -v and keeps the smallest sub-simplex of W + {w} that holds
/// the new nearest point, until the bounds v·w / |v| <= distance <= |v| meet.
template <class A, class B>
GjkResult gjkRun(const A& shapeA, const B& shapeB, const GjkOptions& options, GjkTrace* trace, bool booleanQuery) {
    // v = 0 up to rounding: |v|² <= kTouch² max|w_i|². Computing v from vertices of size |w|
    // leaves an error of a few ulps of |w|; below 1e-14 |w| the origin is on the simplex.
    constexpr double kTouch2 = 1e-14 * 1e-14;
    GjkResult r;
    // The simplex lives in r.simplex: W + {w} is built in slot s.count and reduced in place, so
    // no vertex is copied unless the solver drops one before it.
    GjkSimplex& s = r.simplex;
    GjkRecorder record(trace);
    Vec3 v = Vec3::Zero();  // the closest point of the simplex in slots 0..s.count-1
    const auto finish = [&](GjkTermination why) {
        gjkFinish(shapeA, shapeB, options, s, why, v, r);
        record.termination(r.termination);  // the result's: EdgePairCrossed replaces the loop's stop
        return r;
    };
    SupportHints hints;
    SimplexClosest c;
    if (!gjkStartSimplex(shapeA, shapeB, options, s, hints, c)) return finish(GjkTermination::InvalidInput);
    v = c.v;
    double vv = v.squaredNorm();
    double maxW2 = 0.0;
    for (int i = 0; i < s.count; ++i) maxW2 = std::max(maxW2, s.vertex[i].w.squaredNorm());
    if (s.count == 4 || vv <= kTouch2 * maxW2) return finish(GjkTermination::OriginInSimplex);

    const double eps = options.relativeTolerance;
    constexpr int kMaxStalls = 4;  // consecutive steps without a new best |v| in doubles
    int stalls = 0;
    double bestVV = vv;
    Vec3 wv[4];
    for (int iter = 1;; ++iter) {
        r.iterations = iter;
        // The new support point goes into the free slot s.count (the simplex has at most 3
        // vertices here: a full tetrahedron ended the loop).
        GjkVertex& sup = s.vertex[s.count];
        gjkSupport(shapeA, shapeB, Vec3(-v), sup, hints);
        if (!sup.w.allFinite()) return finish(GjkTermination::InvalidInput);
        const double vw = v.dot(sup.w);
        const double gapTest = vv - vw;  // = |v| (upper - lower) when vw > 0
        const double vNorm = std::sqrt(vv);
        if (vw > 0.0) r.lowerBound = std::max(r.lowerBound, vw / vNorm);
        r.upperBound = vNorm;
        record.beginStep(iter, v, sup, r.lowerBound, r.upperBound, gapTest, s);
        // Boolean query: v·w > 0 means the plane through w orthogonal to v separates C from the
        // origin, i.e. -v is a separating axis. Early-out before converging on the distance.
        if (booleanQuery && vw > 0.0) {
            record.stepEndsLoop();
            return finish(GjkTermination::SeparatingAxis);
        }
        // Progress test (van den Bergen §4.3.5): |v|² - v·w <= eps |v|² bounds the relative
        // distance error by eps. Also true when w brings nothing new (v·w >= |v|²).
        if (gapTest <= eps * vv) {
            record.stepEndsLoop();
            return finish(GjkTermination::Converged);
        }
        // Duplicate support point: the simplex cannot change, exit to avoid cycling.
        bool dup = false;
        for (int i = 0; i < s.count; ++i) dup = dup || (s.vertex[i].w == sup.w);
        if (dup) {
            record.stepEndsLoop();
            return finish(GjkTermination::DuplicateSupport);
        }
        // W + {w}, then its closest sub-simplex.
        const int n = s.count + 1;
        for (int i = 0; i < n; ++i) wv[i] = s.vertex[i].w;
        c = closestOnSimplex(wv, n, options.solver);
        const double vvNew = c.v.squaredNorm();
        record.candidate(s, n);
        maxW2 = std::max(maxW2, sup.w.squaredNorm());
        if (c.count == 4 || vvNew <= kTouch2 * maxW2) {
            gjkCompact(s, c);
            record.reduction(c, s);
            record.stepEndsLoop();
            return finish(GjkTermination::OriginInSimplex);
        }
        // |v| must strictly decrease; if rounding stalls it, keep the previous (better) simplex
        // (still slots 0..count-1 with their weights: the new point in slot count is dropped).
        // Except while the gap test has not converged and the new simplex keeps w: then a decrease
        // may be real but below rounding (a new face through v's edge, tilted from v's normal by
        // ~1e-6: |v| drops by 1e-12 of itself), and stopping there would answer "apart by |v|" for an
        // origin on the hull (a flat body whose sliver face holds the origin), or 40% long. A few
        // such steps go on with the new simplex, as exact arithmetic would.
        // (|v| is computed to ~u max|w|: a new |v| within 16 u max|w| above the best so far is a
        // stall.) Progress is a new best |v|, so a triangle <-> edge alternation cannot reset the
        // count; a reduction that drops the new point changes nothing and is no stall.
        const bool decreased = vvNew < bestVV;
        const auto withinRounding = [&] {
            const double band = 16.0 * kUnitRoundoff * std::sqrt(maxW2), upper = std::sqrt(bestVV) + band;
            return vvNew <= upper * upper;
        };
        const bool keepsNewPoint = c.index[c.count - 1] == n - 1;
        const bool roundingStall = !decreased && stalls < kMaxStalls && keepsNewPoint && withinRounding();
        if (!decreased && !roundingStall) {
            if (trace) {
                GjkSimplex reduced = s;
                gjkCompact(reduced, c);
                record.reduction(c, reduced);
            }
            record.stepEndsLoop();
            return finish(GjkTermination::NoProgress);
        }
        stalls = decreased ? 0 : stalls + 1;
        bestVV = std::min(bestVV, vvNew);
        gjkCompact(s, c);
        record.reduction(c, s);
        v = c.v;
        vv = vvNew;
        if (iter >= options.maxIterations) return finish(GjkTermination::MaxIterations);
    }
}

}  // namespace detail

template <SupportMapping A, SupportMapping B>
GjkResult gjkDistance(const A& shapeA, const B& shapeB, const GjkOptions& options, GjkTrace* trace) {
    return detail::gjkRun(shapeA, shapeB, options, trace, false);
}

template <SupportMapping A, SupportMapping B>
bool gjkIntersect(const A& shapeA, const B& shapeB, const GjkOptions& options, GjkTrace* trace, GjkResult* result) {
    if (!trace && !options.warmStart) {
        detail::SupportHints hints;
        int iterations = 0;
        Vec3 a0, b0, start;
        const bool haveStart = detail::anyPointOf(shapeA, a0) && detail::anyPointOf(shapeB, b0);
        if (haveStart) start = a0 - b0;
        const detail::QuickBoolean quick = detail::gjkQuickBoolean(
            [&](const Vec3& d, Vec3& w) {
                w = detail::hintedSupport(shapeA, d, hints.a) - detail::hintedSupport(shapeB, Vec3(-d), hints.b);
            },
            iterations, haveStart ? &start : nullptr);
        if (quick != detail::QuickBoolean::Undecided) {
            const bool hit = quick == detail::QuickBoolean::Intersecting;
            if (result) {
                *result = GjkResult{};
                result->status = hit ? GjkStatus::Intersecting : GjkStatus::Separated;
                result->termination = hit ? GjkTermination::OriginInSimplex : GjkTermination::SeparatingAxis;
                result->iterations = iterations;
            }
            return hit;
        }
    }
    GjkResult r = detail::gjkRun(shapeA, shapeB, options, trace, true);
    if (result) *result = r;
    return r.intersect();
}

template <SupportMapping A, SupportMapping B>
std::optional<EdgePairCrossing> crossedEdgePenetration(const A& shapeA, const B& shapeB, const GjkResult& g) {
    if (g.termination != GjkTermination::EdgePairCrossed) return std::nullopt;
    EdgePairCrossing crossing;
    if (!detail::gjkCrossingOfSimplex(shapeA, shapeB, g.simplex, crossing)) return std::nullopt;
    return crossing;
}

}  // namespace cdlab
