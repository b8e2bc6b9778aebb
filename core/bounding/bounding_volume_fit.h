// Fitting boxes to points and triangles: the axis-aligned box (AABB) and the oriented box (OBB)
// whose axes are the principal axes of a covariance matrix.
//
// Sources: C. Ericson, "Real-Time Collision Detection" (2005) §4.2 (AABB), §4.4.3 (OBB from the
// covariance of the points / of the triangles); S. Gottschalk, M. Lin, D. Manocha, "OBBTree: A
// Hierarchical Structure for Rapid Interference Detection", SIGGRAPH 1996 §4 (the area-weighted
// continuous covariance over the triangles' surface, so that the fit does not depend on how
// densely a region is tessellated).
//
// Overlap tests for these boxes are in core/overlap/sat_tests.h (testAabbAabb, testObbObb).
//
// Frame and units: the caller's (world) frame and length unit. Volumes are in units^3.
// Non-finite input: points (or triangles with a non-finite vertex) that are NaN or infinite are
// SKIPPED; the box is fitted to the finite rest and the trace counts what was skipped. With no
// finite point left, fitAabb returns the empty box (min = +inf, max = -inf: every SAT test
// reports no hit) and the OBB fits return an Obb with NaN center (also no hit anywhere).
// Containment: fitAabb is exact (min / max of the coordinates). The OBB fits contain every
// input point up to rounding in the projection onto the axes and back (a few ulp of the
// coordinates' magnitude; see bounding_volume_fit.cpp).
#pragma once

#include <span>

#include "core/base/primitives.h"

namespace cdlab {

/// Which covariance gave the axes of an OBB fit.
enum class ObbFitMethod {
    TriangleCovariance,  ///< area-weighted continuous covariance of the triangles (Gottschalk 1996)
    PointCovariance,     ///< covariance of the (vertex) points, each point weight 1
    AxisAligned,         ///< no spread at all (a single point / all coincident): identity axes
    Empty,               ///< no finite input: the box is NaN (no hit in every test)
};

/// "TriangleCovariance", "PointCovariance", "AxisAligned", "Empty".
const char* nameOf(ObbFitMethod method);

/// What an OBB fit computed, for demos and tests (recorded in every build type).
struct ObbFitTrace {
    ObbFitMethod method = ObbFitMethod::Empty;
    Vec3 mean = Vec3::Zero();         ///< mean of the distribution (area centroid for triangles)
    Mat3 covariance = Mat3::Zero();   ///< covariance matrix whose eigenvectors gave the axes
    Vec3 eigenvalues = Vec3::Zero();  ///< in the order of the box axes (descending)
    double totalArea = 0.0;           ///< sum of triangle areas (triangle fit only)
    int skippedNonFinite = 0;         ///< points / triangles skipped for a NaN or inf coordinate
};

/// Smallest axis-aligned box holding every finite point (exact). Empty input: min = +inf,
/// max = -inf.
Aabb fitAabb(std::span<const Vec3> points);

/// Smallest axis-aligned box holding every vertex of every triangle with finite vertices (exact).
Aabb fitAabb(std::span<const Triangle> triangles);

/// OBB with the principal axes of the point covariance (Ericson §4.4.3): axes = eigenvectors of
/// C = 1/n sum (p - m)(p - m)^T, ordered by descending eigenvalue (column 0 the major axis),
/// right-handed; extents = the points' projections on the axes. A repeated eigenvalue still
/// gives orthonormal axes (any basis of the eigenspace). All points coincident: identity axes.
Obb fitObbCovariance(std::span<const Vec3> points, ObbFitTrace* trace = nullptr);

/// OBB with the principal axes of the triangles' area-weighted continuous covariance
/// (Gottschalk et al. 1996 §4; Ericson §4.4.3): with area A_i, centroid c_i and vertices p, q, r,
///   C_jk = sum_i A_i / 12 (9 c_ij c_ik + p_j p_k + q_j q_k + r_j r_k) / A - m_j m_k,
///   m = sum_i A_i c_i / A, A = sum_i A_i;
/// extents from the vertices projected on the axes. Zero total area (all triangles degenerate)
/// falls back to the point covariance of the vertices, then to identity axes.
Obb fitObbTriangles(std::span<const Triangle> triangles, ObbFitTrace* trace = nullptr);

/// The AABB of `box` after the rigid motion `pose` (Arvo, "Transforming Axis-Aligned Bounding
/// Boxes", Graphics Gems 1990; Ericson §4.2.6): centre moved by the pose, half extents |R| h. It
/// bounds the moved box, hence everything the old box held, without revisiting the points, but is
/// looser than refitting them (up to √2 in 2D at 45° for a square; the aabb_refit figure). Exact
/// up to rounding of R c + t and |R| h. An empty box stays empty.
Aabb transformAabb(const Aabb& box, const Transform& pose);

/// Volume of an AABB (units^3); 0 for a flat or empty box, NaN for NaN input.
double volume(const Aabb& box);

/// Volume of an OBB, 8 * hx * hy * hz (units^3); 0 when a half extent is negative.
double volume(const Obb& box);

/// True iff p lies in the closed OBB, with every |axes^T (p - center)|_i <= halfExtents_i + slack.
bool contains(const Obb& box, const Vec3& p, double slack = 0.0);

/// True iff p lies in the closed AABB, widened by slack on every side.
bool contains(const Aabb& box, const Vec3& p, double slack = 0.0);

}  // namespace cdlab
