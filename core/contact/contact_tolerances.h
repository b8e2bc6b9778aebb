// The tolerances the contact generators of core/contact share, each named once (core/base/
// tolerances.h lists them with every other named tolerance of core).
#pragma once

namespace cdlab {

/// The automatic touching band, relative to the body size (SAT: the larger body diagonal; plane:
/// the body's bounding-box diagonal), before 64 ulps of the coordinates are added: ~1e7 ulps of
/// the coordinates (far above the rounding of support values and signed distances, for offsets up
/// to 1e6 x the size) and far below any modelled tilt.
inline constexpr double kTouchingBandRelative = 1e-9;

/// Parallel edges: |e_A x e_B| at most this times |e_A| |e_B| (the sine of their angle). The cross
/// product is then rounding noise and the separating direction is a face normal, tested anyway.
inline constexpr double kParallelEdgeSine = 1e-9;

/// Nearly parallel edges: below this sine the edge axis is computed in long double (the double
/// cross product's direction is off by ~1e-16 / sine, its separation by that times the body size:
/// 1e-11 of the size here, far below the touching band kTouchingBandRelative).
inline constexpr double kPreciseEdgeSine = 1e-5;

/// Unit face normals of one edge within this (|n_1 x n_2|) of opposite: a fold of a flat body, not a
/// dihedral edge (a unit normal is unit to ~1e-16; any modelled dihedral angle is far larger).
inline constexpr double kFoldedEdgeSine = 1e-12;

/// A pose's rotation is a unit quaternion when | |q|^2 - 1 | is at most this: far above the
/// rounding drift of an integrated rotation (~1e-15 per multiplication), far below a typo-level error.
inline constexpr double kUnitQuaternionTolerance = 1e-6;

/// Manifold reduction ties: a score replaces the best so far only when larger by more than this
/// times |best| (rounding), so exact ties go to the first in input order whatever the rounding.
inline constexpr double kManifoldTieRelative = 1e-9;

/// The surface band of a contact polygon: a point with depth at most this times the deepest depth
/// lies at the surface (up to the rounding of the depths); deeper points are submerged.
inline constexpr double kSurfaceBandRelative = 1e-9;

}  // namespace cdlab
