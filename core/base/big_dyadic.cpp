// Exact dyadic arithmetic: see core/base/big_dyadic.h.
#include "core/base/big_dyadic.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>

namespace cdlab::exact {

namespace {

using Limbs = std::vector<std::uint32_t>;
constexpr int kLimbBits = 32;

// a * 2^bits (bits >= 0).
Limbs shiftedLeft(const Limbs& a, int bits) {
    const std::size_t wholeLimbs = static_cast<std::size_t>(bits / kLimbBits);
    const int partBits = bits % kLimbBits;
    Limbs r(wholeLimbs, 0u);
    r.reserve(wholeLimbs + a.size() + 1);
    if (partBits == 0) {
        r.insert(r.end(), a.begin(), a.end());
        return r;
    }
    std::uint32_t carry = 0;
    for (std::uint32_t limb : a) {
        r.push_back((limb << partBits) | carry);
        carry = limb >> (kLimbBits - partBits);
    }
    if (carry != 0) r.push_back(carry);
    return r;
}

// Sign of a - b for magnitudes without leading zero limbs.
int compareMagnitudes(const Limbs& a, const Limbs& b) {
    if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
    for (std::size_t i = a.size(); i-- > 0;) {
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    }
    return 0;
}

Limbs addMagnitudes(const Limbs& a, const Limbs& b) {
    const Limbs& longer = a.size() >= b.size() ? a : b;
    const Limbs& shorter = a.size() >= b.size() ? b : a;
    Limbs r;
    r.reserve(longer.size() + 1);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < longer.size(); ++i) {
        const std::uint64_t sum = carry + longer[i] + (i < shorter.size() ? shorter[i] : 0u);
        r.push_back(static_cast<std::uint32_t>(sum));
        carry = sum >> kLimbBits;
    }
    if (carry != 0) r.push_back(static_cast<std::uint32_t>(carry));
    return r;
}

// a - b for a >= b.
Limbs subtractMagnitudes(const Limbs& a, const Limbs& b) {
    Limbs r;
    r.reserve(a.size());
    std::uint32_t borrow = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const std::uint64_t subtrahend = std::uint64_t{i < b.size() ? b[i] : 0u} + borrow;
        borrow = a[i] < subtrahend ? 1u : 0u;
        r.push_back(static_cast<std::uint32_t>((std::uint64_t{borrow} << kLimbBits) + a[i] - subtrahend));
    }
    return r;
}

Limbs multiplyMagnitudes(const Limbs& a, const Limbs& b) {
    Limbs r(a.size() + b.size(), 0u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::uint64_t carry = 0;
        for (std::size_t j = 0; j < b.size(); ++j) {
            // <= (2^32-1)^2 + 2 (2^32-1) = 2^64 - 1: no overflow.
            const std::uint64_t t = std::uint64_t{a[i]} * b[j] + r[i + j] + carry;
            r[i + j] = static_cast<std::uint32_t>(t);
            carry = t >> kLimbBits;
        }
        r[i + b.size()] = static_cast<std::uint32_t>(carry);
    }
    return r;
}

// |x| = leading * 2^exponent with leading in [2^63, 2^64), truncated (relative error < 2^-63).
std::uint64_t leading64(const BigDyadic& x, int& exponent) {
    const Limbs& limbs = x.limbs();
    const std::size_t n = limbs.size();
    // The top three limbs (missing ones are zero) as t2:t1:t0, a 96-bit number whose top limb is
    // nonzero; shifting it up by the leading zeros of t2 and keeping 64 bits keeps the top ones.
    const std::uint32_t t2 = limbs[n - 1];
    const std::uint32_t t1 = n >= 2 ? limbs[n - 2] : 0u;
    const std::uint32_t t0 = n >= 3 ? limbs[n - 3] : 0u;
    const int zeros = std::countl_zero(t2);
    std::uint64_t leading = (std::uint64_t{t2} << kLimbBits) | t1;
    if (zeros > 0) leading = (leading << zeros) | (t0 >> (kLimbBits - zeros));
    exponent = x.exponent() + kLimbBits * (static_cast<int>(n) - 3) + kLimbBits - zeros;
    return leading;
}

// floor(high * 2^64 / divisor) for high < divisor and divisor >= 2^63 (so the quotient is in
// [2^63, 2^64)): restoring binary long division, one quotient bit per step.
std::uint64_t shiftedQuotient(std::uint64_t high, std::uint64_t divisor) {
    std::uint64_t remainder = high, quotient = 0;
    for (int bit = 0; bit < 64; ++bit) {
        const bool overflow = (remainder >> 63) != 0;  // 2 * remainder >= 2^64 > divisor
        remainder <<= 1;
        quotient <<= 1;
        if (overflow || remainder >= divisor) {
            remainder -= divisor;  // modulo 2^64: the true difference is below divisor
            quotient |= 1;
        }
    }
    return quotient;
}

}  // namespace

BigDyadic::BigDyadic(double x) {
    if (!std::isfinite(x) || x == 0.0) return;
    // IEEE-754 binary64: |x| = significand * 2^(biased - 1075), with the implicit leading bit for
    // normal numbers; subnormals (biased == 0) have exponent -1074 and no implicit bit.
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
    if (biased != 0) significand |= std::uint64_t{1} << 52;
    sign_ = (bits >> 63) != 0 ? -1 : 1;
    exponent_ = std::max(biased, 1) - 1075;
    limbs_ = {static_cast<std::uint32_t>(significand), static_cast<std::uint32_t>(significand >> kLimbBits)};
    normalize();
}

void BigDyadic::normalize() {
    while (!limbs_.empty() && limbs_.back() == 0) limbs_.pop_back();
    if (limbs_.empty()) {
        sign_ = 0;
        exponent_ = 0;
        return;
    }
    const auto firstNonzero = std::find_if(limbs_.begin(), limbs_.end(), [](std::uint32_t l) { return l != 0; });
    exponent_ += kLimbBits * static_cast<int>(firstNonzero - limbs_.begin());
    limbs_.erase(limbs_.begin(), firstNonzero);
}

BigDyadic operator+(const BigDyadic& x, const BigDyadic& y) {
    if (x.sign_ == 0) return y;
    if (y.sign_ == 0) return x;
    // Align both on the smaller exponent; then it is integer arithmetic.
    BigDyadic r;
    r.exponent_ = std::min(x.exponent_, y.exponent_);
    const Limbs a = shiftedLeft(x.limbs_, x.exponent_ - r.exponent_);
    const Limbs b = shiftedLeft(y.limbs_, y.exponent_ - r.exponent_);
    if (x.sign_ == y.sign_) {
        r.sign_ = x.sign_;
        r.limbs_ = addMagnitudes(a, b);
    } else {
        const int order = compareMagnitudes(a, b);
        if (order == 0) return BigDyadic{};
        r.sign_ = order > 0 ? x.sign_ : y.sign_;
        r.limbs_ = order > 0 ? subtractMagnitudes(a, b) : subtractMagnitudes(b, a);
    }
    r.normalize();
    return r;
}

BigDyadic BigDyadic::operator-() const {
    BigDyadic r = *this;
    r.sign_ = -r.sign_;
    return r;
}

BigDyadic operator-(const BigDyadic& x, const BigDyadic& y) { return x + (-y); }

BigDyadic operator*(const BigDyadic& x, const BigDyadic& y) {
    BigDyadic r;
    if (x.sign_ == 0 || y.sign_ == 0) return r;
    r.sign_ = x.sign_ * y.sign_;
    r.exponent_ = x.exponent_ + y.exponent_;
    r.limbs_ = multiplyMagnitudes(x.limbs_, y.limbs_);
    r.normalize();
    return r;
}

double quotient(const BigDyadic& numerator, const BigDyadic& denominator) {
    if (numerator.sign() == 0 || denominator.sign() == 0) return 0.0;
    int numeratorExponent = 0, denominatorExponent = 0;
    std::uint64_t n = leading64(numerator, numeratorExponent);
    const std::uint64_t d = leading64(denominator, denominatorExponent);
    // 64 quotient bits of n / d: floor(n 2^64 / d) needs n < d; else halve n (its lowest bit
    // goes, a relative 2^-64).
    int exponent = numeratorExponent - denominatorExponent - 64;
    if (n >= d) {
        n >>= 1;
        ++exponent;
    }
    // Three truncations (n, d, the division) of relative size below 2^-63 each, then one
    // rounding to 53 bits: the result is within half an ulp plus 3 * 2^-63 of the exact quotient,
    // and exact where the exact quotient is a double.
    const double magnitude = std::ldexp(static_cast<double>(shiftedQuotient(n, d)), exponent);
    // (A quotient below half the smallest subnormal is +0, never -0.)
    return numerator.sign() * denominator.sign() < 0 && magnitude != 0.0 ? -magnitude : magnitude;
}

}  // namespace cdlab::exact
