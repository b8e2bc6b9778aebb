// Exact signs of small polynomials in double inputs: a floating-point filter with a rigorous
// running error bound, backed by exact arithmetic when the filter cannot certify the sign.
//
// Source: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", Discrete & Computational Geometry 18 (1997): two-sum (Thm. 7),
// two-product with Dekker's split (Thm. 18), fast expansion sum with zero elimination
// (Thm. 13), scale expansion (Thm. 19), compress (§2.8).
//
// How a predicate is written: once, as a generic lambda over the number type,
//   auto d1 = [&](auto zero) { using T = decltype(zero); return dotOfDifferences<T>(a, b, a, p); };
//   int s = filteredSign(d1);
// The lambda is evaluated first with `Bounded` (plain double arithmetic that also carries an
// upper bound on its absolute error) and, only if |value| <= error, exactly (exactSign): with
// `Expansion` when `ExponentBounds` shows that no expansion component or intermediate can
// underflow or overflow, otherwise with `BigDyadic` (core/base/big_dyadic.h: integers of any length
// times a power of two, no exponent limit). All evaluations run the same expression, so they can
// never disagree about *which* polynomial is being signed.
//
// Exact for EVERY finite double input: any mix of magnitudes, subnormals included.
//  - The filter stays valid under underflow (kUnderflow below) and overflow (an infinite or NaN
//    value or bound is never certain).
//  - Expansions follow Shewchuk's assumptions (IEEE-754 binary64, round-to-nearest-even, no FMA
//    contraction: -ffp-contract=off, no overflow or underflow); ExponentBounds checks the last two
//    per expression. For the degree <= 4 predicates below that holds whenever every input
//    coordinate is zero or has magnitude in [2^-200, 2^241) (about [6e-61, 3.5e72]), so inputs
//    there take exactly the path they always took.
//  - Otherwise (e.g. 0.2 next to 1e85, both scaled by 2^-283: a degree-4 product is then about
//    2^-1136, below the smallest subnormal, and twoProduct returns 0 + 0 for a nonzero product,
//    a zero sign) BigDyadic decides: about 1-6 us more for the two mixed-magnitude closest-point reproducers
//    (tests/core/closest/closest_mixed_magnitude_test.cpp), about 40 us for a whole closest-point query whose
//    coordinates spread over the entire range.
// Non-finite inputs do not crash or loop; their sign is meaningless.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "core/base/big_dyadic.h"
#include "core/base/double_double.h"
#include "core/base/tolerances.h"
#include "core/base/types.h"

namespace cdlab::exact {

// The error-free transformations (sum + error == a + b, product + error == a * b exactly;
// twoProduct requires |a|, |b| < 2^996 and no underflow) are double_double.h's.
using dd::twoProduct;
using dd::twoSum;

/// Exact real number as a floating-point expansion: the sum of its components, which are
/// nonoverlapping, sorted by increasing magnitude and never zero (the empty expansion is 0).
/// Heap-allocated (std::vector): it is only built on the rare uncertain path of a predicate.
class Expansion {
public:
    Expansion() = default;
    // (Forced inline: GCC 12 stopped inlining it once exactSign gained its BigDyadic branch, and
    // the out-of-line call cost ~2% on the exact path.)
    [[gnu::always_inline]] explicit Expansion(double x) {
        if (x != 0.0) components_.push_back(x);
    }

    /// -1, 0 or +1: the sign of the exact value (the sign of the largest component).
    int sign() const;
    /// Approximation of the value (sum of components, largest last; error < 1 ulp after compress).
    double estimate() const;
    const std::vector<double>& components() const { return components_; }

    friend Expansion operator+(const Expansion& e, const Expansion& f);
    friend Expansion operator-(const Expansion& e, const Expansion& f);
    friend Expansion operator*(const Expansion& e, const Expansion& f);
    Expansion operator-() const;

private:
    /// Rewrites the expansion with as few components as possible (Shewchuk §2.8 compress).
    void compress();
    /// e * b for one double b (Shewchuk scale_expansion_zeroelim).
    static Expansion scale(const Expansion& e, double b);

    std::vector<double> components_;
};

/// A double computed in plain floating-point arithmetic together with a rigorous upper bound
/// on its absolute distance to the exact value of the same expression on the same inputs
/// (running error analysis). Bounded(x) is exact (error 0).
struct Bounded {
    double value = 0.0;
    double error = 0.0;
    Bounded() = default;
    explicit Bounded(double x) : value(x) {}
    Bounded(double v, double e) : value(v), error(e) {}
};

namespace detail {
// Relative rounding error of one operation, taken as 2u = 2^-52 instead of u = 2^-53 so the
// bound survives the roundings of its own computation; the final product with kInflate
// (1 + 2^-48) covers the few roundings in summing the error terms. Both are deliberately
// generous: a looser bound only sends a few more near-zero cases to the exact path.
inline constexpr double kRounding = kMachineEpsilon;
inline constexpr double kInflate = 1.0 + 0x1p-48;
// Absolute error allowance for products that underflow: each of the (at most five) products in
// operator* loses at most half the smallest subnormal 2^-1075 when it underflows.
inline constexpr double kUnderflow = 0x1p-1072;
}  // namespace detail

inline Bounded operator+(const Bounded& x, const Bounded& y) {
    const double v = x.value + y.value;
    return {v, (x.error + y.error + std::abs(v) * detail::kRounding) * detail::kInflate};
}
inline Bounded operator-(const Bounded& x, const Bounded& y) {
    const double v = x.value - y.value;
    return {v, (x.error + y.error + std::abs(v) * detail::kRounding) * detail::kInflate};
}
inline Bounded operator*(const Bounded& x, const Bounded& y) {
    // x*y - X*Y = x*(y-Y) + y*(x-X) - (x-X)*(y-Y), plus the rounding of the product itself.
    const double v = x.value * y.value;
    const double e = std::abs(x.value) * y.error + std::abs(y.value) * x.error + x.error * y.error +
                     std::abs(v) * detail::kRounding + detail::kUnderflow;
    return {v, e * detail::kInflate};
}

/// Certified sign of a Bounded value: +1 / -1 when the error bound excludes zero, 0 when it
/// does not (uncertain, NOT "zero").
inline int certainSign(const Bounded& x) {
    if (x.value > x.error) return 1;
    if (-x.value > x.error) return -1;
    return 0;
}

/// Bookkeeping of binary exponents instead of a value: evaluating an expression with this type
/// tells whether evaluating it with Expansion is exact. Each input must be zero or of magnitude
/// in [2^-200, 2^241) (else the expression is not `safe`); every input then gets the same
/// bounds (|x| < 2^241, x a multiple of 2^-252), so the check costs a few integer operations
/// and depends only on the expression's shape. Per node of the expression:
///   high:  the sum of the absolute values of its monomials (its "permanent") is < 2^high;
///          every expansion component and every intermediate of twoSum / twoProduct / split is
///          bounded by that sum (up to a factor 1 + 2^-40), hence below 2^high;
///   grain: its exact value, and every component and intermediate, is an integer multiple of
///          2^grain (rounding a multiple of 2^g gives a multiple of 2^g, Dekker's split pieces
///          are multiples of their input's grain, products multiply grains);
///   safe:  every input in range, and every node so far with high <= kMaxHigh (Dekker's split
///          multiplies by 2^27 + 1, which must not overflow: < 2^996.9; 6 bits of margin) and
///          grain >= -1074. A multiple of 2^-1074 below 2^-1022 is a subnormal, represented
///          exactly, so with every intermediate such a multiple IEEE arithmetic rounds exactly
///          as with an unbounded exponent, the model in which Shewchuk's theorems hold.
/// The predicates below (degree <= 4, at most 3-term sums) reach high <= 973 and grain >= -1008.
struct ExponentBounds {
    static constexpr int kMaxHigh = 990;
    static constexpr int kMinGrain = -1074;
    int high = 241;    // |input| < 2^241
    int grain = -252;  // |input| >= 2^-200 has its lowest bit at 2^-252 or above
    bool safe = true;

    /// x == 0 or 2^-200 <= |x| < 2^241, tested on the bit pattern: with the sign bit shifted
    /// out, the pattern is 0 or has a biased exponent in [1023 - 200, 1023 + 240], i.e. lies in
    /// [823 << 53, 1264 << 53); one wrapping subtraction tests both ends.
    static bool inRange(double x) {
        constexpr std::uint64_t kLow = std::uint64_t{1023 - 200} << 53, kWidth = std::uint64_t{200 + 240 + 1} << 53;
        const std::uint64_t pattern = std::bit_cast<std::uint64_t>(x) << 1;
        return (pattern - kLow < kWidth) | (pattern == 0);
    }

    ExponentBounds() = default;
    explicit ExponentBounds(double x) : safe(inRange(x)) {}
    ExponentBounds(int highBound, int grainBound, bool safeSoFar)
        : high(highBound), grain(grainBound), safe(safeSoFar && highBound <= kMaxHigh && grainBound >= kMinGrain) {}
};

inline ExponentBounds operator+(const ExponentBounds& x, const ExponentBounds& y) {
    return {std::max(x.high, y.high) + 1, std::min(x.grain, y.grain), x.safe && y.safe};
}
inline ExponentBounds operator-(const ExponentBounds& x, const ExponentBounds& y) { return x + y; }
inline ExponentBounds operator*(const ExponentBounds& x, const ExponentBounds& y) {
    return {x.high + y.high, x.grain + y.grain, x.safe && y.safe};
}

/// Sign of `expression` evaluated with T = BigDyadic (kept out of line so that the callers on the
/// common paths stay small).
template <class Expression>
[[gnu::noinline, gnu::cold]] int bigDyadicSign(const Expression& expression) {
    return expression(BigDyadic{}).sign();
}

/// Exact sign of `expression`, a generic callable `(auto zero) -> T`: with T = Expansion where
/// ExponentBounds shows that to be exact, else with T = BigDyadic. For any finite inputs.
template <class Expression>
int exactSign(const Expression& expression) {
    if (expression(ExponentBounds{}).safe) return expression(Expansion{}).sign();
    return bigDyadicSign(expression);
}

/// True when every coordinate of every point is in ExponentBounds' input range (0 or magnitude in
/// [2^-200, 2^241)); false for NaN and infinities. The predicates of this file (degree <= 4, at
/// most 3-term sums: high <= 973, grain >= -1008) are then all expansion-safe, so a caller that
/// checked its inputs once can skip the per-expression bookkeeping (exactSign(expression, true)).
/// Tested as: no magnitude m with 0 < m < 2^-200 (min(2^-200 - m, m) > 0), and the sum of all
/// magnitudes below 2^241 (a floating-point sum of nonnegative terms is at least its largest
/// term; NaN and infinity propagate). Slightly stricter than per coordinate, and branch-free:
/// it runs on every closest-point query, at about the cost of checking the inputs are finite.
inline bool inExpansionRange(std::initializer_list<const Vec3*> points) {
    Eigen::Array3d sum = Eigen::Array3d::Zero(), tiny = Eigen::Array3d::Zero();
    for (const Vec3* point : points) {
        const Eigen::Array3d magnitude = point->array().abs();
        sum += magnitude;
        tiny = tiny.max((0x1p-200 - magnitude).min(magnitude));
    }
    const bool belowTop = sum.sum() < 0x1p241, noneTiny = !(tiny.maxCoeff() > 0.0);
    return belowTop && noneTiny;
}

/// exactSign for one of this file's predicates, when the caller knows whether all the points it
/// reads are in range; if they are not, the per-expression bookkeeping decides (the expression
/// may read only in-range ones).
template <class Expression>
int exactSign(const Expression& expression, bool inputsInRange) {
    if (inputsInRange) return expression(Expansion{}).sign();
    return exactSign(expression);
}

/// Exact sign of `expression` evaluated with T = Bounded and, if the filter is inconclusive,
/// exactly (exactSign). *usedExact (if given) tells whether exact arithmetic decided.
template <class Expression>
int filteredSign(const Expression& expression, bool* usedExact = nullptr) {
    const Bounded approx = expression(Bounded{});
    const int s = certainSign(approx);
    if (usedExact) *usedExact = (s == 0);
    if (s != 0) return s;
    return exactSign(expression);
}

/// (b - a) · (d - c) in number type T (Bounded, Expansion or double).
template <class T>
T dotOfDifferences(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    T sum = (T(b.x()) - T(a.x())) * (T(d.x()) - T(c.x()));
    sum = sum + (T(b.y()) - T(a.y())) * (T(d.y()) - T(c.y()));
    sum = sum + (T(b.z()) - T(a.z())) * (T(d.z()) - T(c.z()));
    return sum;
}

/// Component i of (b - a) × (c - a) in number type T.
template <class T>
T crossComponent(const Vec3& a, const Vec3& b, const Vec3& c, int i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    return (T(b[j]) - T(a[j])) * (T(c[k]) - T(a[k])) - (T(b[k]) - T(a[k])) * (T(c[j]) - T(a[j]));
}

/// (b - a) · ((c - a) × (d - a)): six times the signed volume of tetrahedron abcd, in type T.
template <class T>
T orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    T sum = (T(b[0]) - T(a[0])) * crossComponent<T>(a, c, d, 0);
    sum = sum + (T(b[1]) - T(a[1])) * crossComponent<T>(a, c, d, 1);
    sum = sum + (T(b[2]) - T(a[2])) * crossComponent<T>(a, c, d, 2);
    return sum;
}

/// Ericson's vc for triangle (a, b, c) and point p, in type T:
///   vc = d1*d4 - d3*d2 = ((b-a)·(p-a)) ((c-a)·(p-b)) - ((b-a)·(p-b)) ((c-a)·(p-a))
///      = ((b-a)×(c-a)) · ((p-a)×(p-b))            (Lagrange's identity)
/// vc <= 0 iff p is on the far side of edge ab from c, measured in the plane of the triangle
/// (vc = |b-a|^2 (c-a)·x with x the component of p-a orthogonal to ab).
template <class T>
T edgeSide(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
    return dotOfDifferences<T>(a, b, a, p) * dotOfDifferences<T>(a, c, b, p) -
           dotOfDifferences<T>(a, b, b, p) * dotOfDifferences<T>(a, c, a, p);
}

/// Exact sign of (b - a) · (d - c).
int dotSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, bool* usedExact = nullptr);
/// Exact sign of orient3d(a, b, c, d) = (b-a)·((c-a)×(d-a)); 0 iff the four points are coplanar.
int orient3dSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, bool* usedExact = nullptr);
/// Exact sign of edgeSide(a, b, c, p) (Ericson's vc; see above).
int edgeSideSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, bool* usedExact = nullptr);
/// Exact test: a, b, c collinear (including repeated points), i.e. (b-a)×(c-a) == 0 exactly.
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace cdlab::exact
