// Oracle for the ray / segment quadratics far from the origin (issue 41): the first parameter at
// which o + t d meets a sphere or a cylinder side, for inputs whose coordinates are integers
// (|x| < 2^62, as doubles exactly). Offsets, cross and dot products are exact in __int128; only the
// final squares, square root and quotient are rounded, in long double (64-bit significand), so
// the answer is the exact root to ~1e-19 relative. Shares no code with core: closed forms only.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "core/base/types.h"

namespace faroracle {

using I = __int128;
using LD = long double;
struct IV {
    I x, y, z;
};

inline I toInt(double v) { return I(std::int64_t(v)); }  // v is an integer below 2^63
inline IV toInt(const cdlab::Vec3& v) { return {toInt(v.x()), toInt(v.y()), toInt(v.z())}; }
inline IV sub(const IV& a, const IV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline IV cross(const IV& a, const IV& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline I dot(const IV& a, const IV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LD norm2(const IV& a) { return LD(a.x) * LD(a.x) + LD(a.y) * LD(a.y) + LD(a.z) * LD(a.z); }

/// The roots t0 <= t1 of |p + t q|² = R², p and q exact: false when the line
/// misses (disc < 0) or q = 0. disc = |q|² R² − |p × q|² (Lagrange), exact up to its last rounding.
inline bool roots(const IV& p, const IV& q, LD R2, LD& t0, LD& t1) {
    const LD qq = norm2(q);
    if (!(qq > 0)) return false;
    const LD disc = qq * R2 - norm2(cross(p, q));
    if (disc < 0) return false;
    const LD b = LD(dot(p, q)), s = std::sqrt(disc);
    t0 = (-b - s) / qq;
    t1 = (-b + s) / qq;
    return true;
}

/// The line o + t d against the sphere |x − c| = r: its entry and exit parameters.
inline bool sphere(const cdlab::Vec3& o, const cdlab::Vec3& d, const cdlab::Vec3& c, double r, LD& t0, LD& t1) {
    return roots(sub(toInt(o), toInt(c)), toInt(d), LD(r) * LD(r), t0, t1);
}

/// The line o + t d against the infinite cylinder of radius r about the line through a and b:
/// with L = b − a, |L × (o − a) + t L × d|² = |L|² r².
inline bool cylinder(const cdlab::Vec3& o, const cdlab::Vec3& d, const cdlab::Vec3& a, const cdlab::Vec3& b, double r,
                     LD& t0, LD& t1) {
    const IV L = sub(toInt(b), toInt(a));
    return roots(cross(L, sub(toInt(o), toInt(a))), cross(L, toInt(d)), norm2(L) * LD(r) * LD(r), t0, t1);
}

/// |computed − exact| in units of the rounding of `scale` (2^-52 scale): the error budget of a
/// root whose inputs are ~scale / |d| away.
inline double ulpsOf(double computed, LD exact, LD scale) {
    return double(std::abs(LD(computed) - exact) / (scale * 0x1p-52L));
}

/// A far case: direction d (small integers), the centre λ d + q with λ a multiple of 2^10 (so
/// λ d is a double), origin −q' small: the line passes within |q + q'|⊥ of the centre.
struct FarCase {
    cdlab::Vec3 origin, direction, center;
};
inline FarCase farCase(std::mt19937_64& rng, double distance, int spread) {
    std::uniform_int_distribution<int> small(-spread, spread), dir(-1000, 1000);
    FarCase f;
    do f.direction = cdlab::Vec3(dir(rng), dir(rng), dir(rng));
    while (f.direction.norm() < 100);
    const double lambda = std::ldexp(std::floor(std::ldexp(distance / f.direction.norm(), -10)), 10);
    f.center = lambda * f.direction;  // λ d_i: at most 53 significant bits, exact
    f.origin = cdlab::Vec3(small(rng), small(rng), small(rng));
    return f;
}

}  // namespace faroracle
