// Precision checks shared by GJK's and EPA's feature-pair refinements (core/gjk_epa/gjk_impl.h,
// core/gjk_epa/gjk.cpp, core/gjk_epa/epa_impl.h): one home for each threshold and certificate.
//
// A feature pair of the terminal simplex or polytope (an edge of A with an edge of B, or a point of
// one shape with a face of the other) proposes a plane of A − B with unit normal n through
// pointA − pointB. The shapes' supports s_A(n), s_B(−n) certify it, up to the rounding of their
// dot products (kCertificateUlps ulps of the largest coordinate involved):
//   - both features extreme along n (featuresExtreme): the plane supports A − B;
//   - d·s_B(−d) − d·s_A(d) (lowerBoundAlong) is a lower bound of the distance along any unit d, so a
//     candidate distance it reaches (certifiesDistance) is the distance.
// Tests: tests/core/gjk_epa/gjk_test.cpp "sliver faces: the full loop's verdict is the exact hull
// test's and its distance is exact"; tests/core/gjk_epa/epa_test.cpp "sliver faces: the depth is
// the nearest facet's, against an exact facet enumeration"; tests/core/closest/
// edge_pair_distance_test.cpp "GJK on wedges with nearly parallel ridges: distance = gap to
// rounding"; tests/app/stress/nearly_parallel_edges_test.cpp "nearly parallel edges: crossing by
// 1e-9 of the size is intersecting, with the nearest face's depth".
#pragma once

#include <algorithm>

#include "core/base/tolerances.h"
#include "core/base/types.h"
#include "core/closest/edge_pair_distance.h"

namespace cdlab::detail {

/// Rounding allowance of a support certificate, in ulps of the largest coordinate involved: the two
/// support dot products and the candidate's axis carry a few u each (32 ulps = 64 unit roundoffs).
inline constexpr double kCertificateUlps = 32;

/// A separation proof: a lower bound of the distance above this many ulps of the coordinates is
/// beyond the rounding of the supports' dot products (twice the certificate allowance).
inline constexpr double kSeparationProofUlps = 64;

/// The feet of two lines' common perpendicular count as inside both edges when their parameters
/// s, t lie in (margin, 1 − margin): the origin then projects into the interior of the face
/// edge_a ⊕ (−edge_b) of A − B, clear of its boundary by more than the feet's rounding; a foot at
/// an end is a contact of that end point, left to the point–face candidates.
inline constexpr double kInteriorFootMargin = 1e-9;

/// A triangle with edges e1, e2 is a sliver when |e1 x e2|² < kSliverSine2 |e1|² |e2|² (the sine of
/// their angle below 1e-3): its normal from rounded differences errs by more than 1e3 u.
inline constexpr double kSliverSine2 = 1e-6;

/// Room for gjkEdgePairCandidates' answer on any simplex: a tetrahedron has at most 4 distinct
/// points of each shape, C(4,2) x C(4,2) = 36 edge pairs (the point–triangle candidate needs one
/// point of a shape, hence no edge pair of it), rounded up.
inline constexpr int kGjkMaxEdgePairCandidates = 40;

/// Room for gjkEdgePairCandidates' answer on a separated terminal simplex, at most a triangle
/// (a tetrahedron ends GJK as OriginInSimplex): at most 3 distinct points of each shape,
/// C(3,2) x C(3,2) = 9 edge pairs, or one point–triangle candidate (one point of a shape, no edge).
inline constexpr int kGjkMaxEdgePairCandidatesOfTriangle = 9;

/// True when face or triangle edges e1, e2 with cross product `cross` (= e1 x e2) make a sliver.
inline bool isSliverCross(const Vec3& cross, const Vec3& e1, const Vec3& e2) {
    return cross.squaredNorm() < kSliverSine2 * e1.squaredNorm() * e2.squaredNorm();
}

/// True when the triangle with edges e1, e2 is a sliver (kSliverSine2).
inline bool isSliver(const Vec3& e1, const Vec3& e2) { return isSliverCross(e1.cross(e2), e1, e2); }

/// The largest coordinate magnitude of the two supports and the two feature points: the scale of
/// the rounding of every dot product a certificate takes.
inline double certificateMagnitude(const Vec3& sa, const Vec3& sb, const Vec3& pointA, const Vec3& pointB) {
    return std::max({sa.cwiseAbs().maxCoeff(), sb.cwiseAbs().maxCoeff(), pointA.cwiseAbs().maxCoeff(),
                     pointB.cwiseAbs().maxCoeff()});
}

/// The supports along a candidate's normal n, sa = s_A(n) and sb = s_B(−n), with the magnitude
/// their certificate's rounding scales with.
struct SupportCertificate {
    Vec3 sa;
    Vec3 sb;
    double magnitude = 0.0;

    /// The rounding allowance: kCertificateUlps ulps of the magnitude.
    double tolerance() const { return ulps(kCertificateUlps, magnitude); }
    /// d·s_B(−d) − d·s_A(d) for the unit axis d = n (from A toward B): a lower bound of the distance.
    double lowerBoundAlong(const Vec3& axis) const { return axis.dot(sb) - axis.dot(sa); }
    /// A candidate distance is certified when the lower bound reaches it up to rounding.
    bool certifiesDistance(double lower, double distance) const { return lower >= distance - tolerance(); }
    /// A lower bound beyond rounding (kSeparationProofUlps): the shapes are apart.
    bool provesSeparation(double lower) const { return lower > ulps(kSeparationProofUlps, magnitude); }
    /// Both features extreme along n up to `tol`: no point of A beyond pointA, none of B below
    /// pointB, so the plane through pointA − pointB supports A − B.
    bool featuresExtreme(const Vec3& n, const Vec3& pointA, const Vec3& pointB, double tol) const {
        return (sa - pointA).dot(n) <= tol && (pointB - sb).dot(n) <= tol;
    }
};

/// The certificate of a feature pair with points pointA (on A) and pointB (on B) along n.
template <class A, class B>
SupportCertificate supportCertificate(const A& shapeA, const B& shapeB, const Vec3& n, const Vec3& pointA,
                                      const Vec3& pointB) {
    const Vec3 sa = shapeA.support(n), sb = shapeB.support(Vec3(-n));
    return {sa, sb, certificateMagnitude(sa, sb, pointA, pointB)};
}

/// The certificate of a plane with normal n alone (no feature points): its magnitude is the
/// supports' largest coordinate.
template <class A, class B>
SupportCertificate supportCertificate(const A& shapeA, const B& shapeB, const Vec3& n) {
    const Vec3 sa = shapeA.support(n), sb = shapeB.support(Vec3(-n));
    return {sa, sb, std::max(sa.cwiseAbs().maxCoeff(), sb.cwiseAbs().maxCoeff())};
}

/// The feet of the common perpendicular strictly inside both edges (kInteriorFootMargin).
inline bool feetInsideBothEdges(const LinePairSeparation& p) {
    return p.s > kInteriorFootMargin && p.s < 1 - kInteriorFootMargin && p.t > kInteriorFootMargin &&
           p.t < 1 - kInteriorFootMargin;
}

/// Every edge a[i]a[j] (i < j) of A against every edge b[k]b[l] (k < l) of B whose lines' common
/// perpendicular (linePairSeparation, double-double) has its feet strictly inside both edges, in
/// that order: visit(p) for each, until one returns true (then true).
template <class Visit>
bool forEachInteriorEdgePair(const Vec3* a, int na, const Vec3* b, int nb, Visit&& visit) {
    for (int i = 0; i < na; ++i)
        for (int j = i + 1; j < na; ++j)
            for (int k = 0; k < nb; ++k)
                for (int l = k + 1; l < nb; ++l) {
                    const LinePairSeparation p = linePairSeparation(a[i], a[j], b[k], b[l]);
                    if (!p.ok || !feetInsideBothEdges(p)) continue;
                    if (visit(p)) return true;
                }
    return false;
}

}  // namespace cdlab::detail
