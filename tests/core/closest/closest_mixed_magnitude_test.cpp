// Exact regions and closest points for EVERY finite double input (hostile input, "closest_point_triangle
// with mixed magnitudes"): coordinates from 2^-1074 (subnormal) to 2^1023 mixed within one query,
// exact boundary cases scaled by wildly different powers of two. Truth: the independent BigInt
// oracle (verification/closest_oracle.h), never the code under test.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/base/big_dyadic.h"
#include "core/base/exact_predicates.h"
#include "core/closest/closest_point.h"
#include "verification/closest_oracle.h"
#include "tests/core/closest/closest_test_support.h"

using namespace cdlab;
using oracle::BigInt;
using oracle::BigVec;
using R = TriangleRegion;
using T = TetrahedronRegion;

namespace {

using cdlab::test::N;

BigInt pow2(int k) { return BigInt::fromParts(1, k, false); }
BigInt absolute(const BigInt& x) { return x.sign < 0 ? -x : x; }
bool lessEqual(const BigInt& x, const BigInt& y) { return (y - x).sign >= 0; }

// ---------------------------------------------------------------------------------------------
// Inputs over the whole double range.

// A random double: binary exponent uniform in [-1022, 1023], 1 in 8 subnormal, 1 in 3 with a
// 4-bit significand (so that sums and products cancel exactly more often), random sign.
double anyDouble(std::mt19937_64& rng) {
    std::uint64_t significand = rng() & ((std::uint64_t{1} << 52) - 1);
    if (rng() % 3 == 0) significand &= ~((std::uint64_t{1} << 48) - 1);
    std::uint64_t bits;
    if (rng() % 8 == 0) {
        bits = (significand >> (rng() % 52)) | 1u;  // subnormal: biased exponent 0
    } else {
        bits = (std::uint64_t(1 + rng() % 2046) << 52) | significand;
    }
    if (rng() & 1) bits |= std::uint64_t{1} << 63;
    return std::bit_cast<double>(bits);
}

// A point whose coordinates are random doubles, zeros, or coordinates already used in the query
// (equal coordinates give exactly zero differences: ties).
Vec3 mixedPoint(std::mt19937_64& rng, std::vector<double>& used) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
        const int kind = int(rng() % 20);
        if (kind < 3) v[i] = 0.0;
        else if (kind < 8 && !used.empty()) v[i] = used[rng() % used.size()];
        else v[i] = anyDouble(rng);
        used.push_back(v[i]);
    }
    return v;
}

// Small integers (many exact ties: points on region boundaries), each axis then scaled by its own
// power of two from the whole range: a query mixing 2^-1074 with 2^1021, still with exact ties.
struct AxisScaledGrid {
    std::array<int, 3> exponent;
    explicit AxisScaledGrid(std::mt19937_64& rng) {
        std::uniform_int_distribution<int> k(-1074, 1021);
        for (int& e : exponent) e = k(rng);
    }
    Vec3 point(std::mt19937_64& rng) const {
        std::uniform_int_distribution<int> small(-3, 3);  // |3 * 2^1021| < 2^1023: exact
        return Vec3(std::ldexp(small(rng), exponent[0]), std::ldexp(small(rng), exponent[1]),
                    std::ldexp(small(rng), exponent[2]));
    }
};

bool collinearTruth(const Vec3& a, const Vec3& b, const Vec3& c) {
    const int K = oracle::commonShift({a, b, c});
    const BigVec A = oracle::toBig(a, K);
    const BigVec n = oracle::cross(oracle::sub(oracle::toBig(b, K), A), oracle::sub(oracle::toBig(c, K), A));
    return n.v[0].sign == 0 && n.v[1].sign == 0 && n.v[2].sign == 0;
}

int volumeSignTruth(const std::array<Vec3, 4>& v) {
    const int K = oracle::commonShift({v[0], v[1], v[2], v[3]});
    const BigVec A = oracle::toBig(v[0], K);
    return oracle::dotv(oracle::sub(oracle::toBig(v[1], K), A),
                        oracle::cross(oracle::sub(oracle::toBig(v[2], K), A), oracle::sub(oracle::toBig(v[3], K), A)))
        .sign;
}

// ---------------------------------------------------------------------------------------------
// The documented accuracy outside the plain range: q within one ulp, a relative 2^-52, of the
// exact rational numerator / (denominator 2^t), plus 2^-1074 absolute (subnormal), t >= 0:
//   |Q den 2^(t+1074) - num 2^(Kq+1074)| <= |num| 2^(Kq+1022) + den 2^(t+Kq),   q = Q / 2^Kq.
bool withinRounding(double q, BigInt numerator, BigInt denominator, int t) {
    if (!std::isfinite(q)) return false;  // (the oracle's scaling would not terminate on inf / NaN)
    if (denominator.sign < 0) {
        numerator = -numerator;
        denominator = -denominator;
    }
    const int Kq = oracle::commonShift({Vec3(q, 0, 0)});
    const BigInt Q = oracle::toBig(q, Kq);
    const BigInt error = absolute(Q * denominator * pow2(t + 1074) - numerator * pow2(Kq + 1074));
    return lessEqual(error, absolute(numerator) * pow2(Kq + 1022) + denominator * pow2(t + Kq));
}

// Checks the point and weights of an edge xy result against the exact projection:
// point_i = (X_i UU + U_i UW) / UU, weight of y = UW / UU, of x = (UU - UW) / UU (NaN: not given).
void checkEdgePoint(const Vec3& p, const Vec3& x, const Vec3& y, const Vec3& point, double weightX, double weightY) {
    REQUIRE(point.allFinite());  // (the oracle's scaling would not terminate on inf / NaN)
    const int K = oracle::commonShift({p, x, y});
    const BigVec X = oracle::toBig(x, K), U = oracle::sub(oracle::toBig(y, K), X),
                 W = oracle::sub(oracle::toBig(p, K), X);
    const BigInt uu = oracle::dotv(U, U), uw = oracle::dotv(U, W);
    for (int i = 0; i < 3; ++i) CHECK(withinRounding(point[i], X.v[i] * uu + U.v[i] * uw, uu, K));
    CHECK(withinRounding(weightY, uw, uu, 0));
    if (!std::isnan(weightX)) CHECK(withinRounding(weightX, uu - uw, uu, 0));
}

// Face xyz: point_i = (P_i NN - n_i (n.W)) / NN, weights n.((Y-P)x(Z-P)) / NN etc.
void checkFacePoint(const Vec3& p, const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& point,
                    const Vec3& weights) {
    REQUIRE(point.allFinite());
    const int K = oracle::commonShift({p, x, y, z});
    const BigVec P = oracle::toBig(p, K), X = oracle::toBig(x, K), Y = oracle::toBig(y, K), Z = oracle::toBig(z, K);
    const BigVec n = oracle::cross(oracle::sub(Y, X), oracle::sub(Z, X));
    const BigInt nn = oracle::dotv(n, n), height = oracle::dotv(n, oracle::sub(P, X));
    for (int i = 0; i < 3; ++i) CHECK(withinRounding(point[i], P.v[i] * nn - n.v[i] * height, nn, K));
    const BigVec px = oracle::sub(X, P), py = oracle::sub(Y, P), pz = oracle::sub(Z, P);
    CHECK(withinRounding(weights[0], oracle::dotv(n, oracle::cross(py, pz)), nn, 0));
    CHECK(withinRounding(weights[1], oracle::dotv(n, oracle::cross(pz, px)), nn, 0));
    CHECK(withinRounding(weights[2], oracle::dotv(n, oracle::cross(px, py)), nn, 0));
}

// Point and weights of a triangle result outside the plain range, by region.
void checkTrianglePoint(const Vec3& p, const Triangle& t, const ClosestPointOnTriangleResult& r) {
    const Vec3 v[3] = {t.a, t.b, t.c};
    switch (r.region) {
        case R::A:
        case R::B:
        case R::C: {
            const int i = static_cast<int>(r.region);
            CHECK(r.point == v[i]);
            CHECK(r.barycentric == Vec3::Unit(i));
            break;
        }
        case R::AB: checkEdgePoint(p, t.a, t.b, r.point, r.barycentric[0], r.barycentric[1]); break;
        case R::BC: checkEdgePoint(p, t.b, t.c, r.point, r.barycentric[1], r.barycentric[2]); break;
        case R::CA: checkEdgePoint(p, t.c, t.a, r.point, r.barycentric[2], r.barycentric[0]); break;
        case R::ABC: checkFacePoint(p, t.a, t.b, t.c, r.point, r.barycentric); break;
    }
}

using cdlab::test::make;

// Vertices of a tetrahedron region's feature, in the order of closest_point.h's enum.
std::vector<int> tetFeature(T r) {
    static const std::vector<std::vector<int>> kFeatures = {{0},       {1},       {2},       {3},       {0, 1},
                                                            {0, 2},    {0, 3},    {1, 2},    {1, 3},    {2, 3},
                                                            {0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}, {}};
    return kFeatures[static_cast<std::size_t>(r)];
}

void checkTetrahedronPoint(const Vec3& p, const std::array<Vec3, 4>& v, const ClosestPointOnTetrahedronResult& r) {
    const std::vector<int> f = tetFeature(r.region);
    for (int i = 0; i < 4; ++i) {
        if (r.region != T::ABCD && std::find(f.begin(), f.end(), i) == f.end()) CHECK(r.barycentric[i] == 0.0);
    }
    if (f.size() == 1) {
        CHECK(r.point == v[f[0]]);
        CHECK(r.barycentric[f[0]] == 1.0);
    } else if (f.size() == 2) {
        checkEdgePoint(p, v[f[0]], v[f[1]], r.point, r.barycentric[f[0]], r.barycentric[f[1]]);
    } else if (f.size() == 3) {
        checkFacePoint(p, v[f[0]], v[f[1]], v[f[2]], r.point,
                       Vec3(r.barycentric[f[0]], r.barycentric[f[1]], r.barycentric[f[2]]));
    } else {  // inside: p itself, weights orient(.. p ..) / orient(a, b, c, d)
        CHECK(r.point == p);
        const int K = oracle::commonShift({p, v[0], v[1], v[2], v[3]});
        BigVec V[4];
        for (int i = 0; i < 4; ++i) V[i] = oracle::toBig(v[i], K);
        auto orient = [](const BigVec& a, const BigVec& b, const BigVec& c, const BigVec& d) {
            return oracle::dotv(oracle::sub(b, a), oracle::cross(oracle::sub(c, a), oracle::sub(d, a)));
        };
        const BigInt volume = orient(V[0], V[1], V[2], V[3]);
        for (int i = 0; i < 4; ++i) {
            BigVec U[4] = {V[0], V[1], V[2], V[3]};
            U[i] = oracle::toBig(p, K);
            CHECK(withinRounding(r.barycentric[i], orient(U[0], U[1], U[2], U[3]), volume, 0));
        }
    }
}

// value * 2^K as an integer (K large enough).
BigInt scaledValue(const exact::BigDyadic& x, int K) {
    BigInt sum;
    for (std::size_t i = 0; i < x.limbs().size(); ++i)
        sum = sum + BigInt::fromParts(x.limbs()[i], 32 * int(i) + x.exponent() + K, x.sign() < 0);
    return sum;
}

}  // namespace

TEST_SUITE("closest_mixed_magnitude") {
    TEST_CASE("regression: the two mixed-magnitude closest_point_triangle queries") {
        // printf '%s\n' '{"id":1,"op":"closest_point_triangle","point":[0.2,0.2,1e85],
        //   "triangle":[[0,0,0],[1,0,0],[0,1,0]]}' | cdlab query   -> region AB (exact: ABC)
        // '{"op":"closest_point_triangle","point":[0.5,-1e-80,0],"triangle":[[0,0,0],[1,0,0],[0,1,1e200]]}'
        //   -> region A at distance 0.5 (exact: AB, point (0.5, 0, 0), distance 1e-80).
        // cdlab query scales each query by 2^-e (largest coordinate in [0.5, 1)); that put 0.2 at
        // 0.2 * 2^-283 (and 1 at 2^-665 in the second query), and the degree-4 vc = d1 d4 - d3 d2
        // (~2^-1136), resp. the degree-2 d1 = (b-a).(p-a) (~2^-1331), fell below the smallest
        // subnormal: twoProduct returned 0 + 0, the exact sign came out 0, and the ties rule
        // accepted AB (vc <= 0), resp. A (d1 <= 0). Checked both as given and as the query scaled them.
        struct Case {
            Vec3 p;
            Triangle t;
            R region;
            Vec3 point;
        };
        const Case cases[] = {
            {Vec3(0.2, 0.2, 1e85), Triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, R::ABC, Vec3(0.2, 0.2, 0)},
            {Vec3(0.5, -1e-80, 0), Triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1e200)}, R::AB, Vec3(0.5, 0, 0)},
        };
        for (const Case& c : cases) {
            for (int e : {0, -283, -665}) {
                auto scaled = [e](const Vec3& v) {
                    return Vec3(std::ldexp(v.x(), e), std::ldexp(v.y(), e), std::ldexp(v.z(), e));
                };
                const Vec3 p = scaled(c.p);
                const Triangle t{scaled(c.t.a), scaled(c.t.b), scaled(c.t.c)};
                REQUIRE(N(oracle::exactEricsonRegion(p, t.a, t.b, t.c)) == N(c.region));
                const auto r = closestPointOnTriangle(p, t);
                CHECK(N(r.region) == N(c.region));
                CHECK(r.point == scaled(c.point));
                CHECK(r.status == SimplexStatus::Regular);
                checkTrianglePoint(p, t, r);
            }
        }
        // The unscaled second query: distance 1e-80 (squared, to rounding).
        const auto r = closestPointOnTriangle(cases[1].p, cases[1].t);
        CHECK(r.distanceSquared == doctest::Approx(1e-160).epsilon(1e-15));
    }

    TEST_CASE("outside the plain range, a closest point that is a double comes out exactly") {
        // Before: cdlab query scaled [1e-300, 1e-300, 5] over the triangle [[0,0,0],[1e300,0,0],
        // [0,1e300,0]] by 2^-997, which flushed 1e-300 to 0 (region A); core itself answers exactly.
        const auto r = closestPointOnTriangle(Vec3(1e-300, 1e-300, 5),
                                              Triangle{Vec3(0, 0, 0), Vec3(1e300, 0, 0), Vec3(0, 1e300, 0)});
        CHECK(N(r.region) == N(R::ABC));
        CHECK(r.point == Vec3(1e-300, 1e-300, 0));
        // Points above a triangle in the plane z = 0 at any scale, at any height: the projection
        // (x, y, 0) is a double, so exactly that.
        std::mt19937_64 rng(230);
        std::uniform_int_distribution<int> k(-1000, 1000);
        std::uniform_real_distribution<double> unit(0.0, 0.5);
        for (int i = 0; i < 2000; ++i) {
            const double size = std::ldexp(1.0, k(rng));
            const Triangle t{Vec3(0, 0, 0), Vec3(size, 0, 0), Vec3(0, size, 0)};
            const double x = std::ldexp(unit(rng), k(rng) % 40) * size, y = unit(rng) * size;
            if (!(x > 0.0 && x + y < size)) continue;
            const Vec3 p(x, y, anyDouble(rng));
            const auto q = closestPointOnTriangle(p, t);
            CHECK(N(q.region) == N(R::ABC));
            CHECK(q.point == Vec3(x, y, 0));
        }
    }

    TEST_CASE("BigDyadic: exact sums and products over the whole exponent range, subnormals included") {
        std::mt19937_64 rng(221);
        for (int i = 0; i < 600; ++i) {
            double x[8];
            for (double& v : x) v = anyDouble(rng);
            if (i % 4 == 0) x[1] = x[0];  // exact cancellation
            using D = exact::BigDyadic;
            const D value = (D(x[0]) - D(x[1])) * (D(x[2]) + D(x[3])) * (D(x[4]) - D(x[5])) * (D(x[6]) - D(x[7])) -
                            D(x[0]) * D(x[2]) * D(x[4]) * D(x[6]);
            const int K = oracle::commonShift({Vec3(x[0], x[1], x[2]), Vec3(x[3], x[4], x[5]), Vec3(x[6], x[7], 0)});
            BigInt b[8];
            for (int k = 0; k < 8; ++k) b[k] = oracle::toBig(x[k], K);
            const BigInt truth =
                (b[0] - b[1]) * (b[2] + b[3]) * (b[4] - b[5]) * (b[6] - b[7]) - b[0] * b[2] * b[4] * b[6];
            CHECK(value.sign() == truth.sign);
            // Limbs drop whole zero limbs only: the exponent is at most 31 below the lowest set bit.
            CHECK((scaledValue(value, 4 * K + 32) - truth * pow2(32)).sign == 0);
            if (value.sign() != 0) {
                CHECK(value.limbs().front() != 0);
                CHECK(value.limbs().back() != 0);
            }
            CHECK((value - value).sign() == 0);
            CHECK((value - value).limbs().empty());
        }
        CHECK(exact::BigDyadic(std::numeric_limits<double>::denorm_min()).exponent() == -1074);
        CHECK(exact::BigDyadic(-std::numeric_limits<double>::max()).sign() == -1);
        CHECK(exact::BigDyadic(std::numeric_limits<double>::infinity()).sign() == 0);  // documented: 0
    }

    TEST_CASE("BigDyadic quotient: within one ulp, exact when the quotient is a double") {
        std::mt19937_64 rng(222);
        int subnormal = 0;
        for (int i = 0; i < 3000; ++i) {
            const double n[3] = {anyDouble(rng), anyDouble(rng), anyDouble(rng)};
            const double d[2] = {anyDouble(rng), anyDouble(rng)};
            using D = exact::BigDyadic;
            const D numerator = D(n[0]) * D(n[1]) + D(n[2]), denominator = D(d[0]) * D(d[1]);
            const double q = exact::quotient(numerator, denominator);
            const int K = oracle::commonShift({Vec3(n[0], n[1], n[2]), Vec3(d[0], d[1], 0)});
            const BigInt num = oracle::toBig(n[0], K) * oracle::toBig(n[1], K) + oracle::toBig(n[2], K) * pow2(K);
            const BigInt den = oracle::toBig(d[0], K) * oracle::toBig(d[1], K);
            if (std::isinf(q)) {  // then the exact quotient is at least 2^1023 (near or past the largest double)
                CHECK(lessEqual(den * pow2(1023), absolute(num)));
                continue;
            }
            CHECK(withinRounding(q, num, den, 0));
            CHECK(!(q == 0.0 && std::signbit(q)));
            subnormal += q != 0.0 && std::abs(q) < std::numeric_limits<double>::min();
        }
        CHECK(subnormal > 10);
        // An exactly representable quotient comes out exactly, subnormal or not: (x * D) / D.
        for (int i = 0; i < 3000; ++i) {
            const double x = anyDouble(rng), d[3] = {anyDouble(rng), anyDouble(rng), anyDouble(rng)};
            using D = exact::BigDyadic;
            const D denominator = D(d[0]) * D(d[1]) + D(d[2]);
            if (denominator.sign() == 0) continue;
            CHECK(exact::quotient(D(x) * denominator, denominator) == x);
        }
        CHECK(exact::quotient(exact::BigDyadic(), exact::BigDyadic(-3.0)) == 0.0);
        CHECK(!std::signbit(exact::quotient(exact::BigDyadic(), exact::BigDyadic(-3.0))));
    }

    TEST_CASE("ExponentBounds and inExpansionRange: the documented range keeps the expansion path") {
        using exact::ExponentBounds;
        const double below = std::nextafter(0x1p-200, 0.0), top = std::nextafter(0x1p241, 0.0);
        CHECK(ExponentBounds::inRange(0.0));
        CHECK(ExponentBounds::inRange(-0.0));
        CHECK(ExponentBounds::inRange(0x1p-200));
        CHECK(ExponentBounds::inRange(-top));
        CHECK_FALSE(ExponentBounds::inRange(below));
        CHECK_FALSE(ExponentBounds::inRange(0x1p241));
        CHECK_FALSE(ExponentBounds::inRange(std::numeric_limits<double>::denorm_min()));
        CHECK_FALSE(ExponentBounds::inRange(std::numeric_limits<double>::infinity()));
        CHECK_FALSE(ExponentBounds::inRange(std::numeric_limits<double>::quiet_NaN()));
        // Every predicate shape of exact_predicates.h is expansion-safe on the range's extremes.
        const Vec3 a(top, -0x1p-200, 0), b(-top, 0x1p-200, top), c(0x1p-200, -top, -0x1p-200), d(top, top, -top);
        CHECK(exact::dotOfDifferences<ExponentBounds>(a, b, c, d).safe);
        CHECK(exact::orient3d<ExponentBounds>(a, b, c, d).safe);
        CHECK(exact::edgeSide<ExponentBounds>(a, b, c, d).safe);
        CHECK(exact::crossComponent<ExponentBounds>(a, b, c, 0).safe);
        CHECK(exact::edgeSide<ExponentBounds>(a, b, c, d).high <= 973);
        CHECK(exact::edgeSide<ExponentBounds>(a, b, c, d).grain >= -1008);
        // One coordinate out of range: not safe.
        CHECK_FALSE(exact::edgeSide<ExponentBounds>(a, b, c, Vec3(1, 1, below)).safe);
        CHECK_FALSE(exact::dotOfDifferences<ExponentBounds>(a, b, c, Vec3(0x1p241, 0, 0)).safe);
        // inExpansionRange: implies every coordinate is in range (its sum test is stricter: the
        // extremes above fail it); NaN and infinity fail.
        CHECK_FALSE(exact::inExpansionRange({&a, &b, &c}));
        const Vec3 small(0x1p-200, -0x1p238, 0), one(1, -1, 0.5);
        CHECK(exact::inExpansionRange({&small, &one}));
        const Vec3 nan(0, std::numeric_limits<double>::quiet_NaN(), 0),
            inf(0, 0, -std::numeric_limits<double>::infinity());
        const Vec3 subnormal(1, std::numeric_limits<double>::denorm_min(), 1);
        CHECK_FALSE(exact::inExpansionRange({&one, &nan}));
        CHECK_FALSE(exact::inExpansionRange({&inf, &one}));
        CHECK_FALSE(exact::inExpansionRange({&one, &subnormal}));
        std::mt19937_64 rng(223);
        for (int i = 0; i < 20000; ++i) {
            std::vector<double> used;
            const Vec3 p = mixedPoint(rng, used), q = mixedPoint(rng, used);
            const bool each = ExponentBounds::inRange(p.x()) && ExponentBounds::inRange(p.y()) &&
                              ExponentBounds::inRange(p.z()) && ExponentBounds::inRange(q.x()) &&
                              ExponentBounds::inRange(q.y()) && ExponentBounds::inRange(q.z());
            if (exact::inExpansionRange({&p, &q})) CHECK(each);
            if (each && p.cwiseAbs().sum() + q.cwiseAbs().sum() < 0x1p240) CHECK(exact::inExpansionRange({&p, &q}));
        }
    }

    TEST_CASE("Bounded: the error bound holds across the whole exponent range") {
        std::mt19937_64 rng(224);
        int certified = 0;
        for (int i = 0; i < 3000; ++i) {
            std::vector<double> used;
            const Vec3 a = mixedPoint(rng, used), b = mixedPoint(rng, used), c = mixedPoint(rng, used),
                       d = mixedPoint(rng, used);
            const exact::Bounded approx = exact::edgeSide<exact::Bounded>(a, b, c, d);
            const int K = oracle::commonShift({a, b, c, d});
            const BigVec A = oracle::toBig(a, K), B = oracle::toBig(b, K), C = oracle::toBig(c, K),
                         D = oracle::toBig(d, K);
            const BigInt truth = oracle::dotv(oracle::cross(oracle::sub(B, A), oracle::sub(C, A)),
                                              oracle::cross(oracle::sub(D, A), oracle::sub(D, B)));
            if (!std::isfinite(approx.value) || !std::isfinite(approx.error)) {
                CHECK(exact::certainSign(approx) == 0);  // overflow is never "certain"
                continue;
            }
            // |value - truth| <= error at the common scale 2^S.
            const int S = std::max(4 * K, oracle::commonShift({Vec3(approx.value, approx.error, 0)}));
            const BigInt diff = oracle::toBig(approx.value, S) - truth * pow2(S - 4 * K);
            CHECK(lessEqual(absolute(diff), oracle::toBig(approx.error, S)));
            if (exact::certainSign(approx) != 0) {
                ++certified;
                CHECK(exact::certainSign(approx) == truth.sign);
            }
        }
        CHECK(certified > 150);  // the filter still decides many mixed-magnitude cases
    }

    TEST_CASE("predicates: exact signs for mixed magnitudes and axis-scaled exact ties") {
        std::mt19937_64 rng(225);
        int viaBigDyadic = 0, zeros = 0;
        for (int i = 0; i < 2000; ++i) {
            Vec3 a, b, c, d;
            if (i % 2 == 0) {
                std::vector<double> used;
                a = mixedPoint(rng, used), b = mixedPoint(rng, used), c = mixedPoint(rng, used),
                d = mixedPoint(rng, used);
            } else {
                const AxisScaledGrid grid(rng);
                a = grid.point(rng), b = grid.point(rng), c = grid.point(rng), d = grid.point(rng);
            }
            const int K = oracle::commonShift({a, b, c, d});
            const BigVec A = oracle::toBig(a, K), B = oracle::toBig(b, K), C = oracle::toBig(c, K),
                         D = oracle::toBig(d, K);
            const BigInt dot = oracle::dot(A, B, C, D);
            const BigInt volume = oracle::dotv(oracle::sub(B, A), oracle::cross(oracle::sub(C, A), oracle::sub(D, A)));
            const BigInt side = oracle::dotv(oracle::cross(oracle::sub(B, A), oracle::sub(C, A)),
                                             oracle::cross(oracle::sub(D, A), oracle::sub(D, B)));
            bool used = false;
            CHECK(exact::dotSign(a, b, c, d) == dot.sign);
            CHECK(exact::orient3dSign(a, b, c, d, &used) == volume.sign);
            CHECK(exact::edgeSideSign(a, b, c, d) == side.sign);
            CHECK(exact::collinear(a, b, c) == collinearTruth(a, b, c));
            // The generic entry point (per-expression bookkeeping) agrees.
            CHECK(exact::filteredSign([&](auto zero) { return exact::edgeSide<decltype(zero)>(a, b, c, d); }) ==
                  side.sign);
            viaBigDyadic += used && !exact::orient3d<exact::ExponentBounds>(a, b, c, d).safe;
            zeros += side.sign == 0;
        }
        MESSAGE("orient3d decided by BigDyadic: " << viaBigDyadic << ", edgeSide exactly 0: " << zeros);
        CHECK(viaBigDyadic > 100);
        CHECK(zeros > 25);
    }

    TEST_CASE("triangle: exact region, and the point to rounding, for any finite input") {
        std::mt19937_64 rng(226);
        int regions[7] = {}, degenerate = 0, outOfRange = 0;
        for (int i = 0; i < 3000; ++i) {
            Vec3 p;
            Triangle t;
            const int kind = i % 4;
            if (kind == 0) {  // random over the whole range
                std::vector<double> used;
                t = {mixedPoint(rng, used), mixedPoint(rng, used), mixedPoint(rng, used)};
                p = mixedPoint(rng, used);
            } else if (kind == 1) {  // exact ties, each axis at its own scale
                const AxisScaledGrid grid(rng);
                t = {grid.point(rng), grid.point(rng), grid.point(rng)};
                p = grid.point(rng);
            } else if (kind == 2) {  // a small triangle and a far point, or the reverse (the reproducers' shapes)
                const AxisScaledGrid grid(rng), far(rng);
                t = {grid.point(rng), grid.point(rng), grid.point(rng)};
                p = far.point(rng);
                if (rng() % 2) std::swap(t.c, p);
            } else {  // one vertex huge or tiny, the rest at 1, the point near an edge
                std::uniform_int_distribution<int> small(-4, 4);
                std::uniform_int_distribution<int> k(-1074, 1020);
                t = {Vec3(0, 0, 0), Vec3(small(rng), 1, 0),
                     Vec3(std::ldexp(1, k(rng)), small(rng), std::ldexp(-3, k(rng)))};
                p = Vec3(std::ldexp(small(rng), -2), std::ldexp(small(rng), k(rng)), std::ldexp(small(rng), k(rng)));
            }
            const auto r = closestPointOnTriangle(p, t);
            if (collinearTruth(t.a, t.b, t.c)) {
                CHECK(r.status == SimplexStatus::Degenerate);
                ++degenerate;
                continue;
            }
            REQUIRE(r.status == SimplexStatus::Regular);
            const R truth = oracle::exactEricsonRegion(p, t.a, t.b, t.c);
            CHECK(N(r.region) == N(truth));
            ++regions[static_cast<int>(truth)];
            if (!exact::inExpansionRange({&p, &t.a, &t.b, &t.c})) {
                ++outOfRange;
                checkTrianglePoint(p, t, r);
            }
        }
        MESSAGE("regions A B C AB BC CA ABC: "
                << regions[0] << " " << regions[1] << " " << regions[2] << " " << regions[3] << " " << regions[4] << " "
                << regions[5] << " " << regions[6] << "; degenerate " << degenerate << "; out of range " << outOfRange);
        for (int count : regions) CHECK(count > 20);
        CHECK(degenerate > 10);
        CHECK(outOfRange > 1500);
    }

    TEST_CASE("triangle: uniform power-of-two scaling over the whole range keeps the region") {
        // Region choice is scale-invariant; 2^k * small integers are exact for k in [-1074, 1019].
        std::mt19937_64 rng(227);
        std::uniform_int_distribution<int> small(-6, 6), k(-1074, 1019);
        for (int i = 0; i < 2000; ++i) {
            const Vec3 a(small(rng), small(rng), small(rng)), b(small(rng), small(rng), small(rng)),
                c(small(rng), small(rng), small(rng)), p(small(rng), small(rng), small(rng));
            if (collinearTruth(a, b, c)) continue;
            const R unscaled = closestPointOnTriangle(p, Triangle{a, b, c}).region;
            const int e = k(rng);
            auto s = [e](const Vec3& v) {
                return Vec3(std::ldexp(v.x(), e), std::ldexp(v.y(), e), std::ldexp(v.z(), e));
            };
            const auto r = closestPointOnTriangle(s(p), Triangle{s(a), s(b), s(c)});
            CHECK(N(r.region) == N(unscaled));
            CHECK(N(r.region) == N(oracle::exactEricsonRegion(s(p), s(a), s(b), s(c))));
        }
    }

    TEST_CASE("segment: exact region, and the point to rounding, for any finite input") {
        std::mt19937_64 rng(228);
        int regions[3] = {};
        for (int i = 0; i < 2000; ++i) {
            Vec3 p, a, b;
            if (i % 2) {
                std::vector<double> used;
                a = mixedPoint(rng, used), b = mixedPoint(rng, used), p = mixedPoint(rng, used);
            } else {
                const AxisScaledGrid grid(rng);
                a = grid.point(rng), b = grid.point(rng), p = grid.point(rng);
            }
            const int K = oracle::commonShift({p, a, b});
            const BigVec P = oracle::toBig(p, K), A = oracle::toBig(a, K), B = oracle::toBig(b, K);
            const SegmentRegion truth = oracle::dot(A, B, A, P).sign <= 0   ? SegmentRegion::A
                                        : oracle::dot(B, A, B, P).sign <= 0 ? SegmentRegion::B
                                                                            : SegmentRegion::AB;
            const auto r = closestPointOnSegment(p, Segment{a, b});
            CHECK(N(r.region) == N(truth));
            ++regions[static_cast<int>(truth)];
            if (truth == SegmentRegion::AB && !exact::inExpansionRange({&p, &a, &b}))
                checkEdgePoint(p, a, b, r.point, std::numeric_limits<double>::quiet_NaN(), r.t);
        }
        for (int count : regions) CHECK(count > 100);
    }

    TEST_CASE("tetrahedron: exact region, and the point to rounding, for any finite input") {
        std::mt19937_64 rng(229);
        int regionsSeen[15] = {}, flat = 0;
        for (int i = 0; i < 1500; ++i) {
            std::array<Vec3, 4> v;
            Vec3 p;
            if (i % 3 == 0) {
                std::vector<double> used;
                for (Vec3& x : v) x = mixedPoint(rng, used);
                p = mixedPoint(rng, used);
            } else {
                const AxisScaledGrid grid(rng);
                for (Vec3& x : v) x = grid.point(rng);
                p = grid.point(rng);
                if (i % 3 == 2) p = AxisScaledGrid(rng).point(rng);  // the point at other scales
            }
            const auto r = closestPointOnTetrahedron(p, make(v));
            if (volumeSignTruth(v) == 0) {
                CHECK(r.status == SimplexStatus::Degenerate);
                ++flat;
                continue;
            }
            REQUIRE(r.status == SimplexStatus::Regular);
            const T truth = oracle::exactTetrahedronRegion(p, v);
            CHECK(N(r.region) == N(truth));
            ++regionsSeen[static_cast<int>(truth)];
            if (!exact::inExpansionRange({&p, &v[0], &v[1], &v[2], &v[3]})) checkTetrahedronPoint(p, v, r);
        }
        int distinct = 0;
        for (int count : regionsSeen) distinct += count > 0;
        MESSAGE("tetrahedron regions seen: " << distinct << ", flat: " << flat);
        CHECK(distinct == 15);
        CHECK(flat > 10);
    }

}  // TEST_SUITE
