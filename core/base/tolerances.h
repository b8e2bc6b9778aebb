// Machine epsilon and "k ulps", spelled once for all of core.
//
// Two constants, named for what they are (Higham, "Accuracy and Stability of Numerical
// Algorithms", 2nd ed., §2.1): the machine epsilon 2^-52 is the spacing of doubles at 1 (one ulp
// of 1, DBL_EPSILON); the unit roundoff u = 2^-53 is the relative error of one correctly rounded
// operation (half an ulp; Shewchuk's "epsilon"). "k ulps of m" in core always means
// k * kMachineEpsilon * |m|: an absolute bound, k spacings of doubles at the magnitude m.
//
// Index of the named tolerances of core/gjk_epa (name — header — meaning):
//   kCertificateUlps      — feature_certificate.h — rounding allowance of a support certificate,
//                           in ulps of the largest coordinate involved
//   kSeparationProofUlps  — feature_certificate.h — a distance lower bound above this many ulps
//                           proves separation
//   kInteriorFootMargin   — feature_certificate.h — a common perpendicular's foot parameter this
//                           near 0 or 1 is at the edge's end
//   kSliverSine2          — feature_certificate.h — squared sine of the edge angle below which a
//                           triangle is a sliver
//   kGjkCertifiedGap      — gjk_impl.h — relative gap of GJK's bounds within which a separated
//                           distance is certified
//   kEpaUnitNormal        — epa_impl.h — |n|² within this of 1: a unit normal (beside kEpaTouch,
//                           kEpaVisible, kEpaAbsGap: touching, visibility and gap floors in |w|)
//   kRefinementFloorUlps  — direction_refinement.h — rounding floor of g and its gradient, in ulps
//                           of the scale
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
