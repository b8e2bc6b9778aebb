// Closest points on segments, triangles and tetrahedra, with the Voronoi region (the feature of
// the simplex whose relative interior holds the closest point).
//
// Sources: C. Ericson, "Real-Time Collision Detection" (2005): §5.1.2 (point-segment),
// §5.1.5 ClosestPtPointTriangle, §5.1.6 ClosestPtPointTetrahedron, §5.1.9
// ClosestPtSegmentSegment. Exact signs: Shewchuk 1997 (see core/base/exact_predicates.h).
//
// Region choice is EXACT for segments, triangles and tetrahedra, for every finite input (any mix
// of magnitudes, subnormals included): every sign Ericson tests (d1..d6, va, vb, vc, and for
// tetrahedra the orientations) is the sign the exact real value of that expression on the input
// doubles has (filter, then expansions, then BigDyadic where expansions could underflow or
// overflow: core/base/exact_predicates.h). Boundary ties follow Ericson's `<=` tests: a vertex region
// wins over an edge, an edge over a face, a face over the inside.
//
// The returned point (and weights) for that region:
//  - vertex: the vertex itself, exactly (weights exactly 0 and 1);
//  - a query with any coordinate outside the plain range (nonzero and of magnitude below 2^-200
//    or from 2^241 on: exact::inExpansionRange): the exact closest point, a rational function of
//    the inputs, evaluated in BigDyadic and rounded once per coordinate: within one ulp (half an
//    ulp plus a relative 3 * 2^-63; exact where it is a double; at most 2^-1075 more where
//    subnormal), kept within the feature's bounding box; weights likewise (they sum to 1 before
//    rounding). E.g. p = (0.2, 0.2, 1e85)
//    over the unit triangle gives (0.2, 0.2, 0) exactly. Costs tens of microseconds;
//  - otherwise (the common case): double arithmetic from the nearest feature vertex,
//    no overflow or underflow possible. Edge: the projection from the nearer endpoint e, error a
//    few ulps of max(|point|, |p - e|). Face: the projection onto the plane from the nearest
//    vertex o, error a few ulps of max(|point|, |p - o| / sin of the angle between the edges at o)
//    (the normal's direction error, times the height). Accurate relative to the distance when p
//    is near the simplex; for p far above a tilted face (|p - o| >> its size) the point's error
//    can exceed the face's size.
// distanceSquared is |p - point|^2 in double: it overflows to +inf for distances above ~1.3e154
// and loses precision below ~1.5e-154 (the square of the distance is not representable).
// All functions work in the caller's frame and units; distanceSquared is in units^2.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/base/types.h"

namespace cdlab {

/// Features of a segment ab: its endpoints and its interior.
enum class SegmentRegion { A, B, AB };
/// Features of a triangle abc: 3 vertices, 3 edges, the face.
enum class TriangleRegion { A, B, C, AB, BC, CA, ABC };
/// Features of a tetrahedron abcd: 4 vertices, 6 edges, 4 faces, the inside (ABCD).
enum class TetrahedronRegion { A, B, C, D, AB, AC, AD, BC, BD, CD, ABC, ABD, ACD, BCD, ABCD };

/// "A", "B", "AB".
const char* nameOf(SegmentRegion region);
/// "A", "B", "C", "AB", "BC", "CA", "ABC".
const char* nameOf(TriangleRegion region);
/// "A".."D", "AB", "AC", "AD", "BC", "BD", "CD", "ABC", "ABD", "ACD", "BCD", "ABCD".
const char* nameOf(TetrahedronRegion region);

/// What kind of input a closest-point query saw.
enum class SimplexStatus {
    Regular,     ///< non-degenerate simplex: exact Ericson region choice
    Degenerate,  ///< collinear triangle / coplanar tetrahedron: answer over the lower-dimensional point set
    NonFinite,   ///< NaN or infinite input: outputs are NaN (point, weights, distance); region is A
};

// ---------------------------------------------------------------------------------------------
// Segments

struct ClosestPointOnSegmentResult {
    Vec3 point = Vec3::Zero();  ///< closest point of the segment, = a + t (b - a)
    double t = 0.0;             ///< parameter in [0, 1]; exactly 0 for region A, 1 for region B
    SegmentRegion region = SegmentRegion::A;
    double distanceSquared = 0.0;  ///< |p - point|^2
};

/// Closest point of segment s to p (Ericson §5.1.2). Region choice is exact (signs of
/// (p-a)·(b-a) and (p-b)·(a-b)); a zero-length segment gives region A. NaN input: NaN outputs.
ClosestPointOnSegmentResult closestPointOnSegment(const Vec3& p, const Segment& s);

struct SegmentSegmentResult {
    double s = 0.0;                     ///< parameter on the first segment, in [0, 1]
    double t = 0.0;                     ///< parameter on the second segment, in [0, 1]
    Vec3 pointOnFirst = Vec3::Zero();   ///< first.a + s (first.b - first.a)
    Vec3 pointOnSecond = Vec3::Zero();  ///< second.a + t (second.b - second.a)
    double distanceSquared = 0.0;       ///< |pointOnFirst - pointOnSecond|^2
    bool parallel = false;              ///< directions parallel to rounding: one of many closest pairs
    bool degenerate = false;            ///< at least one segment has (numerically) zero length
};

/// Closest pair between two segments (Ericson §5.1.9 ClosestPtSegmentSegment). Parallel and
/// nearly parallel segments (sin^2 of the angle below ~1e-14, where the 2x2 system is rounding
/// noise) return the best of the four endpoint-to-segment pairs; zero-length segments reduce to
/// point-segment queries. Not exact; accurate to rounding of the well-conditioned case.
SegmentSegmentResult closestPointsSegmentSegment(const Segment& first, const Segment& second);

// ---------------------------------------------------------------------------------------------
// Traces (optional, recorded in every build type)

/// One sign evaluated during an exact region choice.
struct PredicateSign {
    const char* name = "";       ///< e.g. "d1", "d4-d3", "vc" (triangle) or "(p-a).(b-a)" (tetrahedron)
    const char* formula = "";    ///< the exact expression, ASCII, e.g. "(b-a).(p-a)"
    double value = 0.0;          ///< value in plain double arithmetic (what naive code would test)
    int sign = 0;                ///< sign (-1, 0, +1) of the EXACT value; the one the decision used
    bool exactFallback = false;  ///< the double error bound straddled 0: exact arithmetic decided
};

/// One region test of Ericson's sequence: the candidate region, the conjunction tested, the
/// terms evaluated in order (the && short-circuits, so termCount may be smaller than the
/// number of terms in `condition`), and the outcome.
template <class Region, int MaxTerms>
struct RegionTest {
    Region candidate{};
    const char* condition = "";
    std::array<PredicateSign, MaxTerms> terms{};
    int termCount = 0;
    bool accepted = false;
};

// ---------------------------------------------------------------------------------------------
// Triangles

struct ClosestPointOnTriangleResult {
    Vec3 point = Vec3::Zero();                  ///< closest point of the (closed, solid) triangle
    TriangleRegion region = TriangleRegion::A;  ///< feature whose relative interior holds point
    Vec3 barycentric = Vec3::UnitX();  ///< (u, v, w): point = u a + v b + w c, u+v+w = 1 (to rounding), all >= 0
    double distanceSquared = 0.0;      ///< |p - point|^2
    SimplexStatus status = SimplexStatus::Regular;
};

/// Trace of closestPointOnTriangle: Ericson's region tests in his order, up to the accepted one.
/// For a Degenerate triangle `tests` is empty and the answer comes from the edges.
struct ClosestPointTrace {
    std::vector<RegionTest<TriangleRegion, 3>> tests;
    ClosestPointOnTriangleResult result;  ///< the returned result (copy)
};

/// Closest point of triangle t to p and its Voronoi region (Ericson §5.1.5, exact signs).
/// Degenerate (collinear / repeated vertices, exactly): closest point over the triangle's point
/// set (a segment or a point), region = the vertex if the closest point is exactly one, otherwise
/// the edge spanning the set; never NaN for finite input.
ClosestPointOnTriangleResult closestPointOnTriangle(const Vec3& p, const Triangle& t,
                                                    ClosestPointTrace* trace = nullptr);

// ---------------------------------------------------------------------------------------------
// Tetrahedra

struct ClosestPointOnTetrahedronResult {
    Vec3 point = Vec3::Zero();                               ///< closest point of the solid tetrahedron (p if inside)
    TetrahedronRegion region = TetrahedronRegion::A;         ///< feature whose relative interior holds point
    Eigen::Vector4d barycentric = Eigen::Vector4d::UnitX();  ///< weights of a, b, c, d (sum 1 to rounding, all >= 0)
    double distanceSquared = 0.0;                            ///< |p - point|^2 (0 inside)
    SimplexStatus status = SimplexStatus::Regular;
};

/// Trace of closestPointOnTetrahedron: region tests in the order vertices (A..D), edges (AB, AC,
/// AD, BC, BD, CD), faces (ABC, ABD, ACD, BCD), up to the accepted one (none if inside).
struct TetrahedronTrace {
    std::vector<RegionTest<TetrahedronRegion, 4>> tests;
    ClosestPointOnTetrahedronResult result;
};

/// Closest point of the solid tetrahedron t to p and its Voronoi region ("point vs 3D simplex";
/// Ericson §5.1.6 reorganised as closed-region tests by increasing dimension, all signs exact).
/// A vertex region is {(p-x)·(y-x) <= 0 for the 3 other y}; an edge xy region adds the two
/// in-face side tests edgeSide(x,y,z,p) <= 0 for the two faces at the edge; a face region is
/// "p not strictly inside its plane" and p projecting into the closed face. The first accepted
/// region is the feature whose relative interior holds the closest point.
/// Degenerate (coplanar, exactly): the best of the four faces; never NaN for finite input.
ClosestPointOnTetrahedronResult closestPointOnTetrahedron(const Vec3& p, const Tetrahedron& t,
                                                          TetrahedronTrace* trace = nullptr);

}  // namespace cdlab
