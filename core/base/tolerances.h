// Machine epsilon and "k ulps", spelled once for all of core.
//
// Two constants, named for what they are (Higham, "Accuracy and Stability of Numerical
// Algorithms", 2nd ed., §2.1): the machine epsilon 2^-52 is the spacing of doubles at 1 (one ulp
// of 1, DBL_EPSILON); the unit roundoff u = 2^-53 is the relative error of one correctly rounded
// operation (half an ulp; Shewchuk's "epsilon"). "k ulps of m" in core always means
// k * kMachineEpsilon * |m|: an absolute bound, k spacings of doubles at the magnitude m.
//
// Index of the named tolerances of core (name — where — what it bounds). A tolerance is named once,
// in the header of the module that owns it (or, when only one file reads it, at the top of that
// file); one value with two meanings has two names. Relative ones multiply a size given where used.
//
//   base
//     kTouchRelative, minkowskiExtent() — base/touch_rule.h — the one touching rule of the pair queries.
//     kMachineEpsilon, kUnitRoundoff, ulps() — base/tolerances.h — the units every other bound uses.
//     kRounding, kInflate, kUnderflow — base/exact_predicates.h — the floating-point filter's
//         per-operation error (2u), its inflation for the bound's own rounding, the underflow floor.
//     kOrient2dBound, kOrient3dBound — base/orient.cpp — Shewchuk's errboundA of orient2d / orient3d.
//   geometry
//     kUnitNormalTolerance — geometry/polyhedron.h — | |n| - 1 | of a unit face normal in validate().
//     kMassPlanarTolerance — geometry/mass_properties.h — default face planarity, times the diagonal.
//     kMassDegenerateVolume — geometry/mass_properties.h — degenerate solid, times diagonal^3.
//     kDiskHalfThicknessRatio — geometry/polyhedron_presets.h — disk()'s default half thickness / radius.
//     kThin — geometry/convex_hull.cpp — sliver cones (apex within kThin eps of the base) not built.
//   overlap
//     kPolygonPlaneTolerance — overlap/polygon_tests.h — default plane distance of the 3D polygon tests.
//     kSatParallelEpsilon — overlap/sat_tests.cpp — added to |R_ij| (OBB-OBB, segment-box): parallel edges.
//   closest
//     kFeatureParallelRelative — closest/feature_distance.h — segment / polygon planes parallel.
//     kFeatureSnapRelative — closest/feature_distance.h — a closest point realized on a vertex or edge.
//     kFeatureDirectionSlope — closest/feature_distance.h — the closest-point direction's own rounding.
//     kUnstableNormalRelative — closest/feature_distance.h — normalUnstable below this x size.
//     kParallel, kZeroLength — closest/closest_point.cpp — segment pair parallel (a e sin^2 below
//         1e-14 a e); a segment shorter than the smallest normal double is a point.
//   gjk_epa
//     kEpaTouch, kEpaVisible, kEpaAbsGap — gjk_epa/epa_impl.h — origin on the boundary, face
//         visibility, the gap noise floor (relative to max |w|).
//     kCertificateUlps      — feature_certificate.h — rounding allowance of a support certificate,
//                             in ulps of the largest coordinate involved
//     kSeparationProofUlps  — feature_certificate.h — a distance lower bound above this many ulps
//                             proves separation
//     kInteriorFootMargin   — feature_certificate.h — a common perpendicular's foot parameter this
//                             near 0 or 1 is at the edge's end
//     kSliverSine2          — feature_certificate.h — squared sine of the edge angle below which a
//                             triangle is a sliver
//     kGjkCertifiedGap      — gjk_impl.h — relative gap of GJK's bounds within which a separated
//                             distance is certified
//     kEpaUnitNormal        — epa_impl.h — |n|² within this of 1: a unit normal (beside kEpaTouch,
//                             kEpaVisible, kEpaAbsGap: touching, visibility and gap floors in |w|)
//     kRefinementFloorUlps  — direction_refinement.h — rounding floor of g and its gradient, in ulps
//                             of the scale
//   cast
//     (none named: ray_cast.cpp and ray_cast_curved.cpp spell theirs where used.)
//   feature_walk
//     kRound — feature_walk/vclip_walk.cpp — 16 eps floor of a derivative test (noise, not a turn).
//   contact (contact/contact_tolerances.h)
//     kTouchingBandRelative — the automatic touching band, times the body size.
//     kParallelEdgeSine — edge pairs skipped as parallel (sine of their angle).
//     kPreciseEdgeSine — below it an edge axis is computed in long double (nearly parallel edges).
//     kFoldedEdgeSine — face normals of one edge opposite: a fold of a flat body.
//     kUnitQuaternionTolerance — | |q|^2 - 1 | of a usable pose rotation.
//     kManifoldTieRelative — manifold reduction: a score wins only when larger by more than this.
//     kSurfaceBandRelative — a point at most this x the deepest depth lies at the surface.
//   bounding
//     kWelzlExactRelative — bounding/bounding_sphere.h — Welzl trace: Exact within this, relative.
//     kOutsideRel, kDependentDet — bounding/bounding_sphere.cpp — a point outside the ball; an
//         affinely dependent support set.
//     kKdopCornerRelative — bounding/kdop.h — a k-DOP corner may violate another slab by this x size.
//     kSliverSine, kExtentPadUlps — bounding/bounding_volume_fit.cpp — zero-area triangle; OBB pad.
//   bvh
//     kBvMarginRelative, kFitSlackRelative, kParallelEpsilon — bvh/bvh.cpp — bounding-volume test
//         margin, OBB fit slack, OBB-OBB parallel-edge epsilon (the value of kSatParallelEpsilon).
//   spatial
//     kBspPlaneThickness — spatial/bsp_tree.h — default thick-plane width, times the input size.
//     kBspDegenerateArea — spatial/bsp_tree.h — zero-area polygon, |Newell normal| below this x L^2.
#pragma once

namespace cdlab {

/// 2^-52 = DBL_EPSILON = std::numeric_limits<double>::epsilon(): one ulp of 1.
inline constexpr double kMachineEpsilon = 0x1p-52;

/// 2^-53: the relative rounding error of one correctly rounded +, -, *, /, sqrt (half an ulp).
inline constexpr double kUnitRoundoff = 0x1p-53;

/// k ulps of the magnitude m: k * kMachineEpsilon * m (evaluated in that order, so a power-of-two
/// k gives the same bits as the spelled-out product).
constexpr double ulps(double k, double magnitude) { return k * kMachineEpsilon * magnitude; }

}  // namespace cdlab
