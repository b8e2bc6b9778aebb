// Independent oracles for the closest-point tests (never the code under test):
//  - BigInt: arbitrary-precision integers (base 2^32) to evaluate predicates exactly on doubles,
//    which are dyadic rationals: every coordinate is scaled by a common 2^K to an integer.
//  - long double brute force for distances (64-bit mantissa vs 53 in double).
//  - a naive plain-double Ericson ClosestPtPointTriangle, the baseline that exactness beats.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/base/types.h"
#include "core/closest/closest_point.h"

namespace oracle {

using cdlab::Vec3;

// ---------------------------------------------------------------------------------------------
// BigInt: sign-magnitude, little-endian base 2^32 limbs.
struct BigInt {
    int sign = 0;  // -1, 0, +1
    std::vector<uint32_t> mag;

    static BigInt fromParts(uint64_t m, int shift, bool negative) {  // +-m * 2^shift, shift >= 0
        BigInt r;
        if (m == 0) return r;
        r.sign = negative ? -1 : 1;
        const int words = shift / 32, bits = shift % 32;
        r.mag.assign(static_cast<size_t>(words), 0u);
        unsigned __int128 v = static_cast<unsigned __int128>(m) << bits;
        while (v != 0) {
            r.mag.push_back(static_cast<uint32_t>(v));
            v >>= 32;
        }
        return r;
    }
    static int cmpMag(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
        if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
        for (size_t i = a.size(); i-- > 0;) {
            if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
        }
        return 0;
    }
    static void trim(std::vector<uint32_t>& a) {
        while (!a.empty() && a.back() == 0) a.pop_back();
    }
    static std::vector<uint32_t> addMag(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
        std::vector<uint32_t> r(std::max(a.size(), b.size()) + 1, 0);
        uint64_t carry = 0;
        for (size_t i = 0; i < r.size(); ++i) {
            uint64_t s = carry + (i < a.size() ? a[i] : 0) + (i < b.size() ? b[i] : 0);
            r[i] = static_cast<uint32_t>(s);
            carry = s >> 32;
        }
        trim(r);
        return r;
    }
    static std::vector<uint32_t> subMag(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {  // |a| >= |b|
        std::vector<uint32_t> r(a.size(), 0);
        int64_t borrow = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            int64_t s = static_cast<int64_t>(a[i]) - borrow - (i < b.size() ? b[i] : 0);
            borrow = s < 0;
            r[i] = static_cast<uint32_t>(s + (borrow ? (int64_t(1) << 32) : 0));
        }
        trim(r);
        return r;
    }
    friend BigInt operator+(const BigInt& x, const BigInt& y) {
        if (x.sign == 0) return y;
        if (y.sign == 0) return x;
        BigInt r;
        if (x.sign == y.sign) {
            r.sign = x.sign;
            r.mag = addMag(x.mag, y.mag);
            return r;
        }
        const int c = cmpMag(x.mag, y.mag);
        if (c == 0) return r;
        r.sign = c > 0 ? x.sign : y.sign;
        r.mag = c > 0 ? subMag(x.mag, y.mag) : subMag(y.mag, x.mag);
        return r;
    }
    BigInt operator-() const {
        BigInt r = *this;
        r.sign = -r.sign;
        return r;
    }
    friend BigInt operator-(const BigInt& x, const BigInt& y) { return x + (-y); }
    friend BigInt operator*(const BigInt& x, const BigInt& y) {
        BigInt r;
        if (x.sign == 0 || y.sign == 0) return r;
        r.sign = x.sign * y.sign;
        r.mag.assign(x.mag.size() + y.mag.size(), 0);
        for (size_t i = 0; i < x.mag.size(); ++i) {
            uint64_t carry = 0;
            for (size_t j = 0; j < y.mag.size(); ++j) {
                uint64_t t = static_cast<uint64_t>(x.mag[i]) * y.mag[j] + r.mag[i + j] + carry;
                r.mag[i + j] = static_cast<uint32_t>(t);
                carry = t >> 32;
            }
            size_t k = i + y.mag.size();
            while (carry) {
                uint64_t t = static_cast<uint64_t>(r.mag[k]) + carry;
                r.mag[k++] = static_cast<uint32_t>(t);
                carry = t >> 32;
            }
        }
        trim(r.mag);
        return r;
    }
};

// Exact scaling of doubles to integers: x * 2^K with K = the common shift that makes every
// coordinate of the query an integer.
inline int exponentNeeded(double x) {  // smallest K with x * 2^K integer
    if (x == 0.0) return -100000;
    int e;
    const double f = std::frexp(std::abs(x), &e);  // x = f 2^e, f in [0.5, 1)
    uint64_t m = static_cast<uint64_t>(std::ldexp(f, 53));
    int k = 53 - e;
    while ((m & 1u) == 0) {
        m >>= 1;
        --k;
    }
    return k;
}
inline BigInt toBig(double x, int K) {
    if (x == 0.0) return BigInt{};
    int e;
    const double f = std::frexp(std::abs(x), &e);
    const uint64_t m = static_cast<uint64_t>(std::ldexp(f, 53));  // |x| = m 2^(e-53)
    return BigInt::fromParts(m, e - 53 + K, x < 0);               // requires e - 53 + K >= 0 (K from exponentNeeded)
}
struct BigVec {
    BigInt v[3];
};
inline int commonShift(std::initializer_list<Vec3> points) {
    int K = 0;
    for (const Vec3& p : points) {
        for (int i = 0; i < 3; ++i) K = std::max(K, exponentNeeded(p[i]));
    }
    // Make the shift >= the binary exponent gap of every value (toBig needs e - 53 + K >= 0).
    for (const Vec3& p : points) {
        for (int i = 0; i < 3; ++i) {
            if (p[i] == 0.0) continue;
            int e;
            std::frexp(p[i], &e);
            K = std::max(K, 53 - e);
        }
    }
    return K;
}
inline BigVec toBig(const Vec3& p, int K) { return {{toBig(p[0], K), toBig(p[1], K), toBig(p[2], K)}}; }
inline BigInt dot(const BigVec& a, const BigVec& b, const BigVec& c, const BigVec& d) {  // (b-a).(d-c)
    BigInt s;
    for (int i = 0; i < 3; ++i) s = s + (b.v[i] - a.v[i]) * (d.v[i] - c.v[i]);
    return s;
}
inline BigVec sub(const BigVec& a, const BigVec& b) { return {{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]}}; }
inline BigVec cross(const BigVec& a, const BigVec& b) {
    return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}
inline BigInt dotv(const BigVec& a, const BigVec& b) { return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2]; }

/// Exact Ericson region (ClosestPtPointTriangle's decisions in exact integer arithmetic).
/// Only for non-collinear triangles.
inline cdlab::TriangleRegion exactEricsonRegion(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    using R = cdlab::TriangleRegion;
    const int K = commonShift({p, a, b, c});
    const BigVec P = toBig(p, K), A = toBig(a, K), B = toBig(b, K), C = toBig(c, K);
    const BigInt d1 = dot(A, B, A, P), d2 = dot(A, C, A, P);
    if (d1.sign <= 0 && d2.sign <= 0) return R::A;
    const BigInt d3 = dot(A, B, B, P), d4 = dot(A, C, B, P);
    if (d3.sign >= 0 && (d4 - d3).sign <= 0) return R::B;
    const BigInt vc = d1 * d4 - d3 * d2;
    if (vc.sign <= 0 && d1.sign >= 0 && d3.sign <= 0) return R::AB;
    const BigInt d5 = dot(A, B, C, P), d6 = dot(A, C, C, P);
    if (d6.sign >= 0 && (d5 - d6).sign <= 0) return R::C;
    const BigInt vb = d5 * d2 - d1 * d6;
    if (vb.sign <= 0 && d2.sign >= 0 && d6.sign <= 0) return R::CA;
    const BigInt va = d3 * d6 - d5 * d4;
    if (va.sign <= 0 && (d4 - d3).sign >= 0 && (d5 - d6).sign >= 0) return R::BC;
    return R::ABC;
}

/// Naive plain-double Ericson (the book's code, region only): the baseline.
inline cdlab::TriangleRegion naiveEricsonRegion(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    using R = cdlab::TriangleRegion;
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return R::A;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return R::B;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return R::AB;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return R::C;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return R::CA;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return R::BC;
    return R::ABC;
}

/// Exact region of a non-flat tetrahedron: closed-region tests by increasing dimension
/// (vertex, edge, face, inside), exact integer arithmetic. Independent of the cdlab code path:
/// uses the cross-product forms (normal cones written with face normals) instead of dot-product
/// differences.
inline cdlab::TetrahedronRegion exactTetrahedronRegion(const Vec3& p, const std::array<Vec3, 4>& v) {
    const int K = commonShift({p, v[0], v[1], v[2], v[3]});
    const BigVec P = toBig(p, K);
    BigVec V[4];
    for (int i = 0; i < 4; ++i) V[i] = toBig(v[i], K);
    auto sgn = [](const BigInt& x) { return x.sign; };
    // vertices
    for (int x = 0; x < 4; ++x) {
        bool in = true;
        for (int y = 0; y < 4 && in; ++y) {
            if (y != x) in = sgn(dot(V[x], P, V[x], V[y])) <= 0;
        }
        if (in) return static_cast<cdlab::TetrahedronRegion>(x);
    }
    // edges: perpendicular part of p-x: xp*|e|^2 - e (e.xp); test . (z - x) <= 0 for both others
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (int e = 0; e < 6; ++e) {
        const int x = kEdges[e][0], y = kEdges[e][1];
        const BigVec E = sub(V[y], V[x]), XP = sub(P, V[x]);
        if (sgn(dotv(E, XP)) < 0 || sgn(dot(V[y], P, V[y], V[x])) < 0) continue;
        const BigInt ee = dotv(E, E), ep = dotv(E, XP);
        bool in = true;
        for (int k = 2; k < 4 && in; ++k) {
            const BigVec Z = sub(V[kEdges[e][k]], V[x]);
            in = sgn(dotv(XP, Z) * ee - ep * dotv(E, Z)) <= 0;
        }
        if (in) return static_cast<cdlab::TetrahedronRegion>(4 + e);
    }
    // faces: p on the outer side (or on) the plane, and the projection inside the closed face:
    // (n x (y - x)) . (p - x) >= 0 style tests with the face normal n oriented consistently.
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    for (int f = 0; f < 4; ++f) {
        const int i = kFaces[f][0], j = kFaces[f][1], k = kFaces[f][2], w = kFaces[f][3];
        const BigVec n = cross(sub(V[j], V[i]), sub(V[k], V[i]));
        const int sideW = sgn(dotv(n, sub(V[w], V[i])));
        if (sgn(dotv(n, sub(P, V[i]))) * sideW > 0) continue;
        // inside the closed face in projection: n . ((q - p) x (r - p)) >= 0 for each edge qr in ijk order
        const int idx[3] = {i, j, k};
        bool in = true;
        for (int m = 0; m < 3 && in; ++m) {
            const BigVec& Q = V[idx[m]];
            const BigVec& R = V[idx[(m + 1) % 3]];
            in = sgn(dotv(n, cross(sub(Q, P), sub(R, P)))) >= 0;
        }
        if (in) return static_cast<cdlab::TetrahedronRegion>(10 + f);
    }
    return cdlab::TetrahedronRegion::ABCD;
}

// ---------------------------------------------------------------------------------------------
// long double brute force.
using LVec = Eigen::Matrix<long double, 3, 1>;
inline LVec L(const Vec3& v) { return v.cast<long double>(); }

inline long double segmentDistance2(const LVec& p, const LVec& a, const LVec& b) {
    const LVec ab = b - a;
    const long double len2 = ab.squaredNorm();
    long double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0;
    t = std::clamp(t, 0.0L, 1.0L);
    return (p - (a + t * ab)).squaredNorm();
}

/// Distance^2 from p to the solid triangle: min over the three edges and, when p projects
/// inside, the plane distance.
inline long double triangleDistance2(const Vec3& pd, const Vec3& ad, const Vec3& bd, const Vec3& cd) {
    const LVec p = L(pd), a = L(ad), b = L(bd), c = L(cd);
    long double best = std::min({segmentDistance2(p, a, b), segmentDistance2(p, b, c), segmentDistance2(p, c, a)});
    const LVec n = (b - a).cross(c - a);
    const long double n2 = n.squaredNorm();
    if (n2 > 0) {
        const long double u = n.dot((b - p).cross(c - p)), v = n.dot((c - p).cross(a - p)),
                          w = n.dot((a - p).cross(b - p));
        if (u >= 0 && v >= 0 && w >= 0) {
            const long double h = n.dot(p - a);
            best = std::min(best, h * h / n2);
        }
    }
    return best;
}

/// Distance^2 from p to the solid tetrahedron: 0 inside, else min over the four faces.
inline long double tetrahedronDistance2(const Vec3& p, const std::array<Vec3, 4>& v) {
    const LVec P = L(p);
    LVec V[4];
    for (int i = 0; i < 4; ++i) V[i] = L(v[i]);
    const long double vol = (V[1] - V[0]).dot((V[2] - V[0]).cross(V[3] - V[0]));
    if (vol != 0) {
        bool inside = true;
        static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
        for (const auto& f : kFaces) {
            const LVec n = (V[f[1]] - V[f[0]]).cross(V[f[2]] - V[f[0]]);
            const long double sp = n.dot(P - V[f[0]]), sw = n.dot(V[f[3]] - V[f[0]]);
            if (sp * sw < 0) inside = false;
        }
        if (inside) return 0;
    }
    return std::min({triangleDistance2(p, v[0], v[1], v[2]), triangleDistance2(p, v[0], v[1], v[3]),
                     triangleDistance2(p, v[0], v[2], v[3]), triangleDistance2(p, v[1], v[2], v[3])});
}

}  // namespace oracle
