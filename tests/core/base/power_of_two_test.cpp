// PowerOfTwo (core/base/power_of_two.h) against std::ldexp, bit for bit: random doubles over the
// whole range (normal and subnormal, both signs) and every k it accepts, and the special values.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "core/base/power_of_two.h"

using cdlab::PowerOfTwo;

namespace {

bool sameBits(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

TEST_SUITE("power_of_two") {
    TEST_CASE("random finite doubles times 2^k for every k accepted: rounded as std::ldexp rounds them") {
        std::mt19937_64 rng(20261128);
        std::uniform_int_distribution<int> anyK(-1074, 2046);
        int mismatches = 0;
        for (int i = 0; i < 300000; ++i) {
            double x;
            do x = std::bit_cast<double>(rng());  // every exponent, subnormals included
            while (!std::isfinite(x));
            const int k = anyK(rng);
            mismatches += !sameBits(PowerOfTwo(k)(x), std::ldexp(x, k));
        }
        CHECK(mismatches == 0);
    }

    TEST_CASE("the scalings of edge_pair_distance: down to a largest coordinate below 1 and back, at every exponent") {
        std::mt19937_64 rng(7);
        for (int e = -1073; e <= 1024; ++e) {
            for (int j = 0; j < 20; ++j) {
                const double x = std::bit_cast<double>(rng());
                if (!std::isfinite(x)) continue;
                CHECK(sameBits(PowerOfTwo(-e)(x), std::ldexp(x, -e)));
                CHECK(sameBits(PowerOfTwo(e)(x), std::ldexp(x, e)));
            }
        }
    }

    TEST_CASE("special values: zeros, the extremes, infinities, NaN") {
        constexpr double inf = std::numeric_limits<double>::infinity();
        const double values[] = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                                 std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                                 -std::numeric_limits<double>::max(), 0.75, 3.5, inf, -inf,
                                 std::numeric_limits<double>::quiet_NaN()};
        for (double x : values)
            for (int k : {-1074, -1073, -1024, -1023, -1022, -1, 0, 1, 1023, 1024, 1074, 2046})
                CHECK(sameBits(PowerOfTwo(k)(x), std::ldexp(x, k)));
    }
}  // TEST_SUITE
