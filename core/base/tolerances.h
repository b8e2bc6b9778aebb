// Machine epsilon and "k ulps", spelled once for all of core.
//
// Two constants, named for what they are (Higham, "Accuracy and Stability of Numerical
// Algorithms", 2nd ed., §2.1): the machine epsilon 2^-52 is the spacing of doubles at 1 (one ulp
// of 1, DBL_EPSILON); the unit roundoff u = 2^-53 is the relative error of one correctly rounded
// operation (half an ulp; Shewchuk's "epsilon"). "k ulps of m" in core always means
// k * kMachineEpsilon * |m|: an absolute bound, k spacings of doubles at the magnitude m.
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
