// Exact orientation predicates (core/base/orient.h) against exact integer arithmetic: inputs are
// integers times 2^-8 plus a large dyadic offset, so every coordinate is exact and the
// determinant can be evaluated exactly with __int128 on the integer parts.
#include <doctest/doctest.h>

#include <limits>

#include "core/base/orient.h"
#include "verification/intersection_oracles.h"

using cdlab::Vec2;
using cdlab::Vec3;

namespace {

using I = __int128;
struct IV {
    I x, y, z;
};
constexpr double kUnit = 1.0 / 256.0;

int sign(I v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

I det3(IV a, IV b, IV c) {
    return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
}
IV sub(IV a, IV b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

Vec3 toVec(IV p, double offset) {
    return Vec3(double(p.x) * kUnit + offset, double(p.y) * kUnit + offset, double(p.z) * kUnit + offset);
}

}  // namespace

TEST_SUITE("orient") {
    TEST_CASE("orient3d matches exact integer determinants on near-coplanar points") {
        oracle::Rng rng(7);
        int zeros = 0, checked = 0;
        for (double offset : {0.0, 1e4, 1e6}) {
            for (int n = 0; n < 20000; ++n) {
                auto rnd = [&] {
                    return IV{rng.integer(-1 << 20, 1 << 20), rng.integer(-1 << 20, 1 << 20),
                              rng.integer(-1 << 20, 1 << 20)};
                };
                const IV a = rnd(), b = rnd(), c = rnd();
                // d exactly coplanar with a, b, c (integer combination), then nudged by -1, 0 or +1
                // unit on one axis: decided by the exact fallback, not the filter.
                const int i = rng.integer(-3, 3), j = rng.integer(-3, 3);
                IV d{a.x + i * (b.x - a.x) + j * (c.x - a.x), a.y + i * (b.y - a.y) + j * (c.y - a.y),
                     a.z + i * (b.z - a.z) + j * (c.z - a.z)};
                if (n % 3 == 1) d.x += rng.integer(-1, 1);
                if (n % 3 == 2) d = rnd();
                // Keep the offset representation exact: |coordinate| * 2^-8 + 1e6 needs < 53 bits.
                const I expected = det3(sub(b, a), sub(c, a), sub(d, a));
                const int got = cdlab::orient3d(toVec(a, offset), toVec(b, offset), toVec(c, offset), toVec(d, offset));
                REQUIRE(got == sign(expected));
                zeros += expected == 0;
                ++checked;
            }
        }
        CHECK(zeros > 1000);  // the degenerate branch was exercised
        CHECK(checked == 60000);
    }

    TEST_CASE("orient2d matches exact integer determinants on near-collinear points") {
        oracle::Rng rng(11);
        for (double offset : {0.0, 1e4, 1e6}) {
            for (int n = 0; n < 20000; ++n) {
                const I ax = rng.integer(-1 << 20, 1 << 20), ay = rng.integer(-1 << 20, 1 << 20);
                const I bx = rng.integer(-1 << 20, 1 << 20), by = rng.integer(-1 << 20, 1 << 20);
                const int k = rng.integer(-4, 4);
                I cx = ax + k * (bx - ax), cy = ay + k * (by - ay);
                if (n % 2) cy += rng.integer(-1, 1);
                const I expected = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
                auto v = [&](I x, I y) { return Vec2(double(x) * kUnit + offset, double(y) * kUnit + offset); };
                REQUIRE(cdlab::orient2d(v(ax, ay), v(bx, by), v(cx, cy)) == sign(expected));
            }
        }
    }

    TEST_CASE("orient3d sign conventions, permutations and tiny perturbations") {
        const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
        CHECK(cdlab::orient3d(a, b, c, Vec3(0, 0, 1)) == 1);
        CHECK(cdlab::orient3d(a, c, b, Vec3(0, 0, 1)) == -1);
        CHECK(cdlab::orient3d(a, b, c, Vec3(0.3, 0.3, 0)) == 0);
        // A perturbation far below the filter's resolution at a large offset.
        const Vec3 o(1e6, 1e6, 1e6);
        const double tiny = std::nextafter(1e6, 2e6) - 1e6;
        CHECK(cdlab::orient3d(a + o, b + o, c + o, Vec3(0.25, 0.25, 0) + o) == 0);
        CHECK(cdlab::orient3d(a + o, b + o, c + o, Vec3(0.25, 0.25, tiny) + o) == 1);
        CHECK(cdlab::orient3d(a + o, b + o, c + o, Vec3(0.25, 0.25, -tiny) + o) == -1);
        CHECK(cdlab::orient2d(Vec2(0, 0), Vec2(1, 1), Vec2(0.5, 0.5 + 0x1p-53)) == 1);
        CHECK(cdlab::orient2d(Vec2(0, 0), Vec2(1, 1), Vec2(0.5, 0.5 - 0x1p-53)) == -1);
        // signDet3 with a plain row equals the triple product sign.
        CHECK(cdlab::signDet3(Vec3(0, 0, 1), Vec3::Zero(), b, a, c, a) == 1);
        // Non-finite input: 0, no crash.
        const double nan = std::numeric_limits<double>::quiet_NaN();
        CHECK(cdlab::orient3d(a, b, c, Vec3(nan, 0, 0)) == 0);
        CHECK(cdlab::orient2d(Vec2(nan, 0), Vec2(1, 0), Vec2(0, 1)) == 0);
    }

    // Coordinates near the double limit: the filter's products overflow (inf, or inf - inf = NaN),
    // which is no answer for finite inputs (not "coplanar": the exact stage decides). Scaling by a power of two
    // keeps every sign, so the small points' signs are the oracle.
    TEST_CASE("orient3d and orient2d keep their exact sign when the filter overflows") {
        const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), up(0.25, 0.25, 0x1p-40), flat(0.25, 0.25, 0);
        for (const double scale : {0x1p500, 0x1p900, 0x1p1000}) {
            CHECK(cdlab::orient3d(scale * a, scale * b, scale * c, scale * up) == 1);
            CHECK(cdlab::orient3d(scale * a, scale * c, scale * b, scale * up) == -1);
            CHECK(cdlab::orient3d(scale * a, scale * b, scale * c, scale * flat) == 0);
            CHECK(cdlab::orient2d(Vec2(0, 0), scale * Vec2(1, 1), scale * Vec2(0.5, 0.5 + 0x1p-40)) == 1);
        }
        // Differences that overflow: -1e308 and +1e308 (the exact evaluation takes them as they are).
        const Vec3 far(-1e308, 0, 0);
        CHECK(cdlab::orient3d(far, Vec3(1e308, 0, 0), Vec3(0, 1e308, 0), Vec3(0, 0, 1e308)) == 1);
    }

    TEST_CASE("projectionAxis detects exactly collinear triangles") {
        CHECK(cdlab::projectionAxis({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)}) == -1);
        CHECK(cdlab::projectionAxis({Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}) == -1);
        CHECK(cdlab::projectionAxis({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}) == 2);
        CHECK(cdlab::projectionAxis({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2 + 0x1p-51)}) >= 0);
    }
}
