// Exact mass properties of a solid polyhedron of uniform density: volume, centre of mass and the
// inertia tensor about the centre of mass.
//
// Method: the divergence theorem over a tetrahedron decomposition, as in Mirtich, "Fast and
// Accurate Computation of Polyhedral Mass Properties", JGT 1(2), 1996, and in its simpler
// tetrahedron form (Eberly, "Polyhedral Mass Properties (Revisited)", Geometric Tools 2002;
// Tonon, "Explicit Exact Formulas for the 3-D Tetrahedron Inertia Tensor in Terms of its Vertex
// Coordinates", J. Math. Stat. 1(1), 2004). Every face is fanned into triangles (v0, vi, vi+1) and
// each triangle with a reference point r spans a signed tetrahedron; with a = v0 - r, b = vi - r,
// c = vi+1 - r and D = a · (b × c) (six times its signed volume):
//   ∫ 1     = D / 6
//   ∫ x     = D / 24  (a + b + c)                                   (x relative to r)
//   ∫ x xᵀ  = D / 120 (a aᵀ + b bᵀ + c cᵀ + (a+b+c)(a+b+c)ᵀ)
// Summed over a closed, outward-oriented surface the tetrahedra outside the solid cancel, for any r;
// r = the vertex mean keeps the terms small when the solid sits far from the origin (1e6 offsets).
// Then volume V = Σ∫1, centre c = r + Σ∫x / V, covariance about c: C = Σ∫xxᵀ − V d dᵀ (d = c − r),
// inertia I = ρ (tr(C) 1 − C). All results are exact up to rounding: no quadrature.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

/// Default planarTolerance, relative to the bounding-box diagonal (see MassPropertiesOptions): far
/// above what convexHull() leaves, far below any modelled feature.
inline constexpr double kMassPlanarTolerance = 1e-9;
/// Degenerate solid: volume at most this times diagonal^3 (far below any real solid, a 1 x 1 x 1e-4
/// slab being 1e-4 of it, and above the rounding of a flat one).
inline constexpr double kMassDegenerateVolume = 1e-12;

enum class MassStatus {
    Ok,                  ///< every output is meaningful
    NonFinite,           ///< a NaN / Inf coordinate or density; index = the vertex (-1: density)
    NonPositiveDensity,  ///< density <= 0
    BadFace,             ///< a face with < 3 vertices or an index out of range; index = the face
    OpenSurface,         ///< a directed edge without its opposite, or used twice: not a closed oriented surface
    NonPlanarFace,       ///< a face vertex off the face's Newell plane by more than the tolerance; index = the face
    Degenerate,          ///< volume <= tolerance: flat, empty or inside-out (faces clockwise from outside)
};

/// Name of a status, e.g. "NonPlanarFace".
const char* nameOf(MassStatus status);

struct MassPropertiesOptions {
    double density = 1.0;  ///< mass per unit volume (> 0)
    /// Face planarity tolerance relative to the solid's size: a face vertex may sit up to
    /// planarTolerance * (bounding-box diagonal) off its face plane, plus 64 DBL_EPSILON * max|coord|
    /// for coordinate rounding at large offsets. 1e-9 is far above what convexHull() leaves (faces
    /// planar within ~1e-12 of the scale) and far below any modelled feature; a non-planar face has
    /// no unique solid (its fan triangulation picks one), hence the error.
    double planarTolerance = kMassPlanarTolerance;
};

struct MassProperties {
    MassStatus status = MassStatus::Degenerate;
    std::string message;               ///< one line; empty when Ok
    int index = -1;                    ///< the offending vertex / face, as the status says
    double volume = 0.0;               ///< length^3
    double mass = 0.0;                 ///< density * volume
    Vec3 centerOfMass = Vec3::Zero();  ///< same frame as the input vertices
    Mat3 inertia = Mat3::Zero();       ///< about centerOfMass, axes of the input frame; mass * length^2
    bool ok() const { return status == MassStatus::Ok; }
};

/// Mass properties of the solid bounded by the closed surface `faces` (vertex-index cycles,
/// counter-clockwise seen from outside; any polygon size, convex or not, must be planar).
/// Frame and units are those of `positions`. Outputs other than status/message/index are
/// meaningful only when ok().
MassProperties computeMassProperties(const std::vector<Vec3>& positions, const std::vector<std::vector<int>>& faces,
                                     const MassPropertiesOptions& options = {});

/// Same for a half-edge polyhedron (its body frame). An empty polyhedron is Degenerate.
MassProperties computeMassProperties(const ConvexPolyhedron& polyhedron, const MassPropertiesOptions& options = {});

/// The inertia tensor `inertia` (about the centre of mass) moved to the point p, same axes
/// (parallel-axis theorem, Steiner): I + m ((d·d) 1 − d dᵀ), d = p − centre. Units mass * length^2.
Mat3 inertiaAboutPoint(const Mat3& inertia, double mass, const Vec3& centerOfMass, const Vec3& point);

}  // namespace cdlab
