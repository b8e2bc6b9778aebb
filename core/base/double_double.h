// Error-free transformations and double-double arithmetic.
//
// TwoSum (Knuth, TAOCP vol. 2 §4.2.2, Thm. B) and TwoProduct with Dekker's splitting
// (Dekker 1971; Shewchuk 1997, Thms. 17-18) give a + b and a * b exactly as an unevaluated sum
// hi + lo of two doubles. DoubleDouble carries about 106 significant bits (Hida, Li, Bailey,
// "Library for Double-Double and Quad-Double Arithmetic", 2000, §2: the "sloppy" add and the
// product with relative error <= 4 u² are enough here). The split needs |a| < 2^996; callers
// scale their inputs by a power of two first.
#pragma once

namespace cdlab::dd {

/// s + e == a + b exactly (no precondition on the magnitudes).
inline void twoSum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bv = s - a;
    const double av = s - bv;
    e = (a - av) + (b - bv);
}

/// s + e == a + b exactly, valid when |a| >= |b| or a == 0.
inline void fastTwoSum(double a, double b, double& s, double& e) {
    s = a + b;
    e = b - (s - a);
}

/// p + e == a * b exactly (Dekker's product; no fma needed, so the result does not depend on
/// -ffp-contract or on the CPU having an fma unit).
inline void twoProduct(double a, double b, double& p, double& e) {
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1: halves of at most 26 bits each
    p = a * b;
    double c = kSplitter * a;
    const double aHi = c - (c - a), aLo = a - aHi;
    c = kSplitter * b;
    const double bHi = c - (c - b), bLo = b - bHi;
    e = ((aHi * bHi - p) + aHi * bLo + aLo * bHi) + aLo * bLo;
}

/// An unevaluated sum hi + lo with |lo| <= ulp(hi) / 2.
struct DoubleDouble {
    double hi = 0.0;
    double lo = 0.0;

    DoubleDouble() = default;
    DoubleDouble(double x) : hi(x), lo(0.0) {}  // NOLINT: implicit on purpose (mixed arithmetic)
    DoubleDouble(double h, double l) : hi(h), lo(l) {}

    double value() const { return hi + lo; }
};

/// a - b of two doubles, exact.
inline DoubleDouble exactDifference(double a, double b) {
    DoubleDouble r;
    twoSum(a, -b, r.hi, r.lo);
    return r;
}

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
    double s, e;
    twoSum(a.hi, b.hi, s, e);
    e += a.lo + b.lo;
    DoubleDouble r;
    fastTwoSum(s, e, r.hi, r.lo);
    return r;
}

inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }
inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }

inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
    double p, e;
    twoProduct(a.hi, b.hi, p, e);
    e += a.hi * b.lo + a.lo * b.hi;
    DoubleDouble r;
    fastTwoSum(p, e, r.hi, r.lo);
    return r;
}

/// A 3-vector of double-doubles (plain array: Eigen is not needed for a dozen operations).
struct Vec3DD {
    DoubleDouble x, y, z;
};

inline Vec3DD operator-(const Vec3DD& a, const Vec3DD& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3DD operator*(const DoubleDouble& s, const Vec3DD& a) { return {s * a.x, s * a.y, s * a.z}; }
inline DoubleDouble dot(const Vec3DD& a, const Vec3DD& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3DD cross(const Vec3DD& a, const Vec3DD& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace cdlab::dd
