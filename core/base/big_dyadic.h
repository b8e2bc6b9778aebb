// Exact arithmetic on dyadic rationals m * 2^e, m an integer of any length and e an int: the
// fallback of the exact predicates (core/base/exact_predicates.h) and of the closest points
// (core/closest/closest_point.cpp) for inputs where floating-point expansions could underflow or
// overflow. Every finite double is such a number (subnormals included), and sums, differences
// and products are exact with no exponent limit: 2^-1074 and 2^1023 meet without loss.
//
// Representation: sign and magnitude, the magnitude in base 2^32 limbs (least significant
// first) times a power of two; whole zero limbs at either end are dropped. Schoolbook
// multiplication (Knuth, TAOCP vol. 2, §4.3.1, Algorithms A, S, M). The numbers stay small in
// practice: a degree-4 polynomial in doubles spanning the whole exponent range needs about
// 4 * 2100 bits (~260 limbs). Allocates (std::vector): for rare paths, not inner loops.
#pragma once

#include <cstdint>
#include <vector>

namespace cdlab::exact {

class BigDyadic {
public:
    BigDyadic() = default;  ///< 0
    /// x exactly. A non-finite x gives 0 (callers reject NaN and infinities before asking).
    explicit BigDyadic(double x);

    /// -1, 0 or +1.
    int sign() const { return sign_; }
    /// |value| = sum over i of limbs()[i] * 2^(32 i), times 2^exponent(). Both end limbs are
    /// nonzero; 0 has no limbs.
    const std::vector<std::uint32_t>& limbs() const { return limbs_; }
    int exponent() const { return exponent_; }

    friend BigDyadic operator+(const BigDyadic& x, const BigDyadic& y);
    friend BigDyadic operator-(const BigDyadic& x, const BigDyadic& y);
    friend BigDyadic operator*(const BigDyadic& x, const BigDyadic& y);
    BigDyadic operator-() const;

private:
    /// Drops zero limbs at both ends (the low ones into the exponent); sets 0 canonically.
    void normalize();

    int sign_ = 0;
    int exponent_ = 0;
    std::vector<std::uint32_t> limbs_;
};

/// numerator / denominator as a double, denominator != 0: within half an ulp plus a relative
/// 3 * 2^-63 of the exact quotient (64-bit leading parts, a 64-bit integer quotient, one
/// rounding), so within one ulp, and exact where the exact quotient is a double; where the
/// quotient is subnormal, at most 2^-1075 more; +-inf beyond the double range. Never -0.
double quotient(const BigDyadic& numerator, const BigDyadic& denominator);

}  // namespace cdlab::exact
