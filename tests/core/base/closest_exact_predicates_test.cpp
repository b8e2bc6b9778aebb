// The exact-arithmetic kit behind the closest-point region choice, checked against BigInt
// (arbitrary-precision integers on the exactly scaled doubles): error-free transformations,
// expansion sums/products (value and nonoverlapping invariant), the running error bound of
// Bounded, and the filtered predicates on near-degenerate inputs.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/exact_predicates.h"
#include "verification/closest_oracle.h"
#include "tests/random_vectors.h"

using namespace cdlab;
using oracle::BigInt;

namespace {

BigInt pow2(int k) { return BigInt::fromParts(1, k, false); }

// Binary exponent of the lowest / highest set bit of a nonzero double.
int lowBit(double x) {
    int e;
    const double f = std::frexp(std::abs(x), &e);
    uint64_t m = static_cast<uint64_t>(std::ldexp(f, 53));
    int k = e - 53;
    while ((m & 1u) == 0) {
        m >>= 1;
        ++k;
    }
    return k;
}
int highBit(double x) {
    int e;
    std::frexp(std::abs(x), &e);
    return e - 1;
}

// Sum of the components as a BigInt at scale 2^K (K large enough for every component).
BigInt expansionValue(const exact::Expansion& e, int K) {
    BigInt sum;
    for (double c : e.components()) sum = sum + oracle::toBig(c, K);
    return sum;
}
int shiftFor(double x) {
    if (x == 0.0) return 0;
    int e;
    std::frexp(x, &e);
    return 53 - e;
}

void checkInvariant(const exact::Expansion& e) {
    const auto& c = e.components();
    for (size_t i = 0; i < c.size(); ++i) {
        CHECK(c[i] != 0.0);
        // Nonoverlapping, increasing magnitude: every bit of c[i] lies below c[i+1]'s lowest bit.
        if (i + 1 < c.size()) CHECK(highBit(c[i]) < lowBit(c[i + 1]));
    }
}

using cdlab::test::randomVec;

}  // namespace

TEST_SUITE("closest_exact_predicates") {
    TEST_CASE("twoSum and twoProduct are error-free") {
        std::mt19937_64 rng(31);
        std::uniform_real_distribution<double> u(-1, 1);
        std::uniform_int_distribution<int> ex(-60, 60);
        for (int i = 0; i < 5000; ++i) {
            const double a = std::ldexp(u(rng), ex(rng)), b = std::ldexp(u(rng), ex(rng));
            double s, e, p, f;
            exact::twoSum(a, b, s, e);
            exact::twoProduct(a, b, p, f);
            const int K = 300;
            CHECK(s == a + b);
            CHECK(p == a * b);
            const BigInt lhs = oracle::toBig(s, K) + oracle::toBig(e, K);
            const BigInt rhs = oracle::toBig(a, K) + oracle::toBig(b, K);
            CHECK((lhs - rhs).sign == 0);
            const BigInt prod = oracle::toBig(a, K) * oracle::toBig(b, K);
            const BigInt mine = (oracle::toBig(p, 2 * K) + oracle::toBig(f, 2 * K));
            CHECK((prod - mine).sign == 0);
        }
    }

    TEST_CASE("expansion arithmetic: exact values of degree-4 polynomials, invariant kept") {
        std::mt19937_64 rng(32);
        std::uniform_real_distribution<double> u(-1, 1);
        std::uniform_int_distribution<int> ex(-40, 40);
        for (int i = 0; i < 400; ++i) {
            double x[8];
            for (double& v : x) v = std::ldexp(u(rng), ex(rng));
            using E = exact::Expansion;
            const E value = (E(x[0]) - E(x[1])) * (E(x[2]) + E(x[3])) * (E(x[4]) - E(x[5])) * (E(x[6]) - E(x[7])) -
                            E(x[0]) * E(x[2]) * E(x[4]) * E(x[6]);
            checkInvariant(value);
            const int K = 200;
            BigInt b[8];
            for (int k = 0; k < 8; ++k) b[k] = oracle::toBig(x[k], K);
            const BigInt truth =
                (b[0] - b[1]) * (b[2] + b[3]) * (b[4] - b[5]) * (b[6] - b[7]) - b[0] * b[2] * b[4] * b[6];
            CHECK(value.sign() == truth.sign);
            CHECK((expansionValue(value, 4 * K) - truth).sign == 0);
            // Exact cancellation gives exactly zero.
            CHECK((value - value).sign() == 0);
            CHECK((value - value).components().empty());
        }
    }

    TEST_CASE("Bounded: the running error bound contains the exact value") {
        std::mt19937_64 rng(33);
        int tight = 0;
        for (int i = 0; i < 3000; ++i) {
            // Near-orthogonal dot products of differences: heavy cancellation.
            const Vec3 a = randomVec(rng, 1) * 1e3, b = randomVec(rng, 1) * 1e3, c = randomVec(rng, 1);
            const Vec3 dir = (b - a);
            Vec3 d = c + dir.unitOrthogonal() * 7.0 + dir * (i % 2 ? 1e-14 : 0.0);
            const exact::Bounded approx = exact::dotOfDifferences<exact::Bounded>(a, b, c, d);
            CHECK(approx.value == (b - a).x() * (d - c).x() + (b - a).y() * (d - c).y() + (b - a).z() * (d - c).z());
            const int K = oracle::commonShift({a, b, c, d});
            const BigInt truth =
                oracle::dot(oracle::toBig(a, K), oracle::toBig(b, K), oracle::toBig(c, K), oracle::toBig(d, K));
            // |value - truth| <= error, compared at a common scale 2^S.
            const int S = std::max({2 * K, shiftFor(approx.value), shiftFor(approx.error)});
            const BigInt scaledTruth = truth * pow2(S - 2 * K);
            const BigInt diff = oracle::toBig(approx.value, S) - scaledTruth;
            const BigInt err = oracle::toBig(approx.error, S);
            BigInt absDiff = diff;
            if (absDiff.sign < 0) absDiff = -absDiff;
            CHECK((err - absDiff).sign >= 0);
            tight += exact::certainSign(approx) == 0;
            // The filtered sign is the exact sign.
            CHECK(exact::dotSign(a, b, c, d) == truth.sign);
        }
        CHECK(tight > 100);  // near-zero cases reached the exact path
    }

    TEST_CASE("filtered predicates: orient3d, edgeSide and collinearity on near-degenerate inputs") {
        std::mt19937_64 rng(34);
        std::uniform_int_distribution<int> small(-8, 8);
        int fallbacks = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 o = Vec3(1e5, -3e4, 7e3) * (i % 3);
            const Vec3 a = o + Vec3(small(rng), small(rng), small(rng)) / 8.0;
            const Vec3 b = o + Vec3(small(rng), small(rng), small(rng)) / 8.0;
            const Vec3 c = o + Vec3(small(rng), small(rng), small(rng)) / 8.0;
            // d coplanar with abc (dyadic combination), then one ulp off.
            Vec3 d = a + (b - a) * (small(rng) / 4.0) + (c - a) * (small(rng) / 4.0);
            // (One ulp off 0 is subnormal, 2^-1074: exact too, through the BigDyadic fallback.)
            d[i % 3] = std::nextafter(d[i % 3], i % 2 ? INFINITY : -INFINITY);
            const int K = oracle::commonShift({a, b, c, d});
            const auto A = oracle::toBig(a, K), B = oracle::toBig(b, K), C = oracle::toBig(c, K),
                       D = oracle::toBig(d, K);
            const BigInt vol = oracle::dotv(oracle::sub(B, A), oracle::cross(oracle::sub(C, A), oracle::sub(D, A)));
            bool used = false;
            CHECK(exact::orient3dSign(a, b, c, d, &used) == vol.sign);
            fallbacks += used;
            // edgeSide = ((b-a)x(c-a)).((p-a)x(p-b)) with p = d.
            const BigInt side = oracle::dotv(oracle::cross(oracle::sub(B, A), oracle::sub(C, A)),
                                             oracle::cross(oracle::sub(D, A), oracle::sub(D, B)));
            CHECK(exact::edgeSideSign(a, b, c, d) == side.sign);
            // Collinearity: a, b and a dyadic point of line ab, then one ulp off.
            Vec3 e = a + (b - a) * (small(rng) / 8.0);
            const bool onLine = i % 2 == 0;
            if (!onLine) e[(i / 2) % 3] = std::nextafter(e[(i / 2) % 3], INFINITY);
            const auto E = oracle::toBig(e, oracle::commonShift({a, b, e}));
            const auto n = oracle::cross(oracle::sub(oracle::toBig(b, oracle::commonShift({a, b, e})),
                                                     oracle::toBig(a, oracle::commonShift({a, b, e}))),
                                         oracle::sub(E, oracle::toBig(a, oracle::commonShift({a, b, e}))));
            const bool truthCollinear = n.v[0].sign == 0 && n.v[1].sign == 0 && n.v[2].sign == 0;
            CHECK(exact::collinear(a, b, e) == truthCollinear);
        }
        CHECK(fallbacks > 100);
    }

}  // TEST_SUITE
