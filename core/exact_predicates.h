// Exact signs of small polynomials in double inputs: a floating-point filter with a rigorous
// running error bound, backed by exact floating-point expansion arithmetic when the filter
// cannot certify the sign.
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
// upper bound on its absolute error) and, only if |value| <= error, again with `Expansion`
// (exact). Both evaluations run the same expression, so the filter can never disagree with the
// exact path about *which* polynomial is being signed.
//
// Assumptions (Shewchuk's): IEEE-754 binary64, round-to-nearest-even, no FMA contraction
// (-ffp-contract=off), no overflow or underflow inside the expansion arithmetic. For the degree
// <= 4 predicates of closest_point.h the last one holds when every input coordinate is zero or
// has magnitude in [2^-200, 2^240] (about [6e-61, 1.7e72]): every exact term is then a multiple
// of 2^-4*(200+52) > 2^-1022 and below 2^996, where Dekker's split still works.
// Non-finite inputs do not crash or loop; their sign is meaningless.
#pragma once

#include <cmath>
#include <vector>

#include "core/types.h"

namespace cdlab::exact {

/// Error-free sum: sum + error == a + b exactly, sum = fl(a + b) (Knuth; Shewchuk Thm. 7).
inline void twoSum(double a, double b, double& sum, double& error) {
    sum = a + b;
    const double bVirtual = sum - a;
    const double aVirtual = sum - bVirtual;
    error = (a - aVirtual) + (b - bVirtual);
}

/// Error-free product: product + error == a * b exactly, product = fl(a * b)
/// (Dekker's split; Shewchuk Thm. 18). Requires |a|, |b| < 2^996 and no underflow.
void twoProduct(double a, double b, double& product, double& error);

/// Exact real number as a floating-point expansion: the sum of its components, which are
/// nonoverlapping, sorted by increasing magnitude and never zero (the empty expansion is 0).
/// Heap-allocated (std::vector): it is only built on the rare uncertain path of a predicate.
class Expansion {
public:
    Expansion() = default;
    explicit Expansion(double x) {
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
inline constexpr double kRounding = 0x1p-52;
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

/// Exact sign of `expression`, a generic callable `(auto zero) -> T` evaluated with T = Bounded
/// and, if the filter is inconclusive, with T = Expansion. *usedExact (if given) tells which.
template <class Expression>
int filteredSign(const Expression& expression, bool* usedExact = nullptr) {
    const Bounded approx = expression(Bounded{});
    const int s = certainSign(approx);
    if (usedExact) *usedExact = (s == 0);
    if (s != 0) return s;
    return expression(Expansion{}).sign();
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
