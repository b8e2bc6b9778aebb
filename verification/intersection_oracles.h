// Test-only oracles for the primitive intersection tests (core/intersect_*.h, sat_tests.h,
// triangle_triangle.h, moving_point.h). Deliberately shares no code with core/: long double
// arithmetic, different formulations (distance minimization, feature enumeration) and exact
// integer arithmetic (__int128) on integer-valued inputs.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "core/base/types.h"

namespace oracle {

using LD = long double;
struct V3 {
    LD x = 0, y = 0, z = 0;
    V3() = default;
    V3(LD a, LD b, LD c) : x(a), y(b), z(c) {}
    explicit V3(const cdlab::Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
    V3 operator+(const V3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    V3 operator-(const V3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    V3 operator*(LD s) const { return {x * s, y * s, z * s}; }
    LD operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
inline LD dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(const V3& a, const V3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline LD norm(const V3& a) { return std::sqrt(dot(a, a)); }

/// Distance from p to segment ab (long double, projection clamped).
inline LD distPointSegment(const V3& p, const V3& a, const V3& b) {
    const V3 ab = b - a;
    const LD l2 = dot(ab, ab);
    LD t = l2 > 0 ? dot(p - a, ab) / l2 : 0;
    t = std::clamp<LD>(t, 0, 1);
    return norm(p - (a + ab * t));
}

/// Distance from p to the solid triangle abc: plane distance when the projection has
/// non-negative area coordinates, otherwise the nearest edge.
inline LD distPointTriangle(const V3& p, const V3& a, const V3& b, const V3& c) {
    const V3 n = cross(b - a, c - a);
    const LD n2 = dot(n, n);
    LD best = std::min({distPointSegment(p, a, b), distPointSegment(p, b, c), distPointSegment(p, c, a)});
    if (n2 > 0) {
        const LD h = dot(p - a, n) / n2;
        const V3 q = p - n * h;
        const LD wa = dot(cross(b - q, c - q), n), wb = dot(cross(c - q, a - q), n), wc = dot(cross(a - q, b - q), n);
        if (wa >= 0 && wb >= 0 && wc >= 0) best = std::min(best, std::abs(h) * std::sqrt(n2));
    }
    return best;
}

/// Distance from p to an axis-aligned box [lo, hi] (sum of squared per-axis excess).
inline LD distPointBox(const V3& p, const V3& lo, const V3& hi) {
    LD s = 0;
    for (int i = 0; i < 3; ++i) {
        const LD e = std::max<LD>({lo[i] - p[i], p[i] - hi[i], LD(0)});
        s += e * e;
    }
    return std::sqrt(s);
}

/// Minimum over s in [0, 1] of a convex function f(s), by ternary search.
template <class F>
LD minimizeConvex(F f, int iterations = 100) {
    LD lo = 0, hi = 1;
    for (int i = 0; i < iterations; ++i) {
        const LD m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) <= f(m2)) hi = m2;
        else lo = m1;
    }
    return std::min({f(lo), f(hi), f(0), f(1)});
}

/// First parameter s in [0, sMax] where inside(s) holds, by dense sampling then bisection;
/// returns -1 when no sample is inside.
template <class F>
LD firstInside(F inside, LD sMax, int samples = 4000) {
    if (inside(LD(0))) return 0;
    for (int i = 1; i <= samples; ++i) {
        const LD s = sMax * i / samples;
        if (inside(s)) {
            LD lo = sMax * (i - 1) / samples, hi = s;
            for (int k = 0; k < 80; ++k) {
                const LD m = (lo + hi) / 2;
                if (inside(m)) hi = m;
                else lo = m;
            }
            return hi;
        }
    }
    return -1;
}

/// The 6 vertex orderings of a triangle.
inline std::array<cdlab::Triangle, 6> orderings(const cdlab::Triangle& t) {
    return {cdlab::Triangle{t.a, t.b, t.c}, cdlab::Triangle{t.b, t.c, t.a}, cdlab::Triangle{t.c, t.a, t.b},
            cdlab::Triangle{t.a, t.c, t.b}, cdlab::Triangle{t.c, t.b, t.a}, cdlab::Triangle{t.b, t.a, t.c}};
}

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(unsigned seed) : gen(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(gen); }
    cdlab::Vec3 vec(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
    cdlab::Vec3 unit() {
        cdlab::Vec3 v;
        do v = vec(-1, 1);
        while (v.squaredNorm() > 1 || v.squaredNorm() < 1e-4);
        return v.normalized();
    }
    cdlab::Quat rotation() {
        cdlab::Quat q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        return q.normalized();
    }
};

}  // namespace oracle
