// castRayRoundedHull against independent oracles (verification/cast_oracle.h: Cyrus–Beck on
// brute-force facets, first roots of convex distance functions, all in long double) and on the
// degenerate cases by hand: grazing rays, rays along faces and through edges and vertices, gaps.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/cast/ray_cast.h"
#include "verification/cast_oracle.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/random_vectors.h"

using namespace cdlab;
namespace co = cdlab::demos::cast_oracle;

namespace {

// The hit normal is a normal of S at the hit point: a supporting plane of the core there, offset by
// the radius (every core point v has n·(v − (point − r n)) <= 0), facing the ray.
void checkSupportingNormal(const ConvexCastHit& h, const Ray& ray, const std::vector<Vec3>& core, double r,
                           double scale) {
    CHECK(std::abs(h.normal.norm() - 1) < 1e-12);
    const Vec3 base = h.point - r * h.normal;
    for (const Vec3& v : core) CHECK(h.normal.dot(v - base) <= 1e-10 * scale);
    CHECK(h.normal.dot(ray.direction) <= 1e-12 * ray.direction.norm());
}

using cdlab::test::randomVec;

}  // namespace

TEST_CASE("ray cast: random polytopes agree with Cyrus-Beck on brute-force facets (long double)") {
    std::mt19937_64 rng(2026);
    int hits = 0, misses = 0, insides = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        const int n = 4 + trial % 9;
        const std::vector<Vec3> p = test::randomPolytope(rng, n, 1.0, randomVec(rng, 0.5));
        const Vec3 origin = trial % 10 == 0 ? randomVec(rng, 0.5) : randomVec(rng, 3.0);  // some start inside
        const Ray ray{origin, Vec3(randomVec(rng, 1.2) - origin) * (0.25 + trial % 4)};
        if (ray.direction.isZero()) continue;
        const co::PolytopeCast want = co::castRayPolytope(ray.origin, ray.direction, p);
        if (!want.valid) continue;
        const ConvexCastHit got = castRayRoundedHull(ray, p, 0.0, {});
        const double scale = 3.0 * ray.direction.norm();
        CAPTURE(trial);
        if (want.inside) {
            CHECK(got.inside);
            ++insides;
        } else if (want.hit && want.margin > 1e-9) {
            REQUIRE(got.hit);
            CHECK_FALSE(got.inside);
            CHECK(std::abs(got.t - double(want.tEnter)) <= 1e-9 * got.t + 1e-12 * scale);
            CHECK((got.point - ray.at(got.t)).norm() <= 1e-15 * scale);
            checkSupportingNormal(got, ray, p, 0.0, 3.0);
            ++hits;
        } else if (!want.hit && want.margin < -1e-9) {
            CHECK_FALSE(got.hit);
            ++misses;
        }
    }
    CHECK(hits > 150);  // the loop tests all three answers, not one
    CHECK(misses > 300);
    CHECK(insides > 20);
}

TEST_CASE("ray cast: spheres, capsules and rounded boxes agree with the first root of the distance") {
    std::mt19937_64 rng(7);
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        const int kind = trial % 3;  // sphere, capsule, rounded box
        std::vector<Vec3> core;
        const Vec3 c = randomVec(rng, 0.5);
        std::uniform_real_distribution<double> radius(0.05, 0.8);
        const double r = radius(rng);
        co::LVec lo, hi;
        if (kind == 0) core = {c};
        if (kind == 1) core = {c, c + randomVec(rng, 1.0)};
        if (kind == 2) {
            const Vec3 h = randomVec(rng, 0.6).cwiseAbs();
            for (int i = 0; i < 8; ++i)
                core.push_back(c + Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
            lo = co::toL(Vec3(c - h));
            hi = co::toL(Vec3(c + h));
        }
        const Vec3 origin = randomVec(rng, 3.0);
        const Ray ray{origin, Vec3(randomVec(rng, 1.2) - origin)};  // aimed near the shape: hits and misses
        const auto dist = [&](long double t) {
            const co::LVec x = co::toL(ray.origin) + t * co::toL(ray.direction);
            long double d = 0;
            if (kind == 0) d = (x - co::toL(core[0])).norm();
            if (kind == 1) d = co::pointSegmentDistance(x, co::toL(core[0]), co::toL(core[1]));
            if (kind == 2) d = co::pointBoxDistance(x, lo, hi);
            return d - (long double)r;
        };
        const long double tMax = 20.0L / ray.direction.norm();
        const co::ConvexMinimum m = co::minimumOfConvex(dist, tMax);
        const ConvexCastHit got = castRayRoundedHull(ray, core, r, {});
        CAPTURE(trial);
        CAPTURE(kind);
        if (dist(0) < -1e-9) {
            CHECK(got.inside);
        } else if (dist(0) > 1e-9 && m.value < -1e-6) {
            REQUIRE(got.hit);
            const long double want = co::firstRootOfConvex(dist, tMax);
            CHECK(std::abs(got.t - double(want)) <= 1e-9 * got.t + 1e-12 * 3.0 / ray.direction.norm());
            checkSupportingNormal(got, ray, core, r, 3.0);
            ++hits;
        } else if (m.value > 1e-9) {
            CHECK_FALSE(got.hit);
            ++misses;
        }
    }
    CHECK(hits > 300);
    CHECK(misses > 300);
}

TEST_CASE("ray cast: grazing rays hit, rays through a gap miss") {
    std::vector<Vec3> box;
    for (int i = 0; i < 8; ++i) box.push_back(Vec3(i & 1 ? 0.7 : 0.1, i & 2 ? 0.7 : 0.1, i & 4 ? 0.7 : 0.1));
    SUBCASE("tangent to a sphere") {
        const ConvexCastHit h = castRayRoundedHull(Ray{Vec3(-2, 1, 0), Vec3(1, 0, 0)}, std::vector<Vec3>{Vec3::Zero()}, 1.0);
        REQUIRE(h.hit);
        CHECK(h.t == doctest::Approx(2.0).epsilon(1e-12));
        CHECK(h.normal.isApprox(Vec3(0, 1, 0), 1e-6));
        const ConvexCastHit tangent = castRayRoundedHull(Ray{Vec3(-2, 0.3, 0), Vec3(1, 0, 0)},
                                                         std::vector<Vec3>{Vec3::Zero()}, 0.3);
        REQUIRE(tangent.hit);  // 0.3 is not a double: the discriminant rounds either way
        CHECK(std::abs(tangent.t - 2.0) < 1e-6);
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-2, 1 + 1e-9, 0), Vec3(1, 0, 0)}, std::vector<Vec3>{Vec3::Zero()}, 1.0).hit);
    }
    SUBCASE("along a face, into the next one") {
        const ConvexCastHit h = castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.7), Vec3(1, 0, 0)}, box);
        REQUIRE(h.hit);
        CHECK(h.t == doctest::Approx(1.1).epsilon(1e-12));
        CHECK(h.normal.isApprox(Vec3(-1, 0, 0), 1e-12));  // the face it runs into, not the one it slides on
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.7 + 1e-9), Vec3(1, 0, 0)}, box).hit);
    }
    SUBCASE("through an edge and through a vertex") {
        const ConvexCastHit e = castRayRoundedHull(Ray{Vec3(-0.9, -0.9, 0.4), Vec3(1, 1, 0)}, box);
        REQUIRE(e.hit);
        CHECK(e.t == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(e.normal.x() <= 1e-15);
        CHECK(e.normal.y() <= 1e-15);
        // Over the top edge x = z = 0.7 at 45°: touches it, and misses it by 1e-9 higher.
        const ConvexCastHit graze = castRayRoundedHull(Ray{Vec3(0, 0.4, 1.4), Vec3(1, 0, -1)}, box);
        REQUIRE(graze.hit);
        CHECK(graze.t == doctest::Approx(0.7).epsilon(1e-12));
        CHECK(graze.normal.x() >= -1e-15);
        CHECK(graze.normal.z() >= -1e-15);
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(0, 0.4, 1.4 + 1e-9), Vec3(1, 0, -1)}, box).hit);
        const ConvexCastHit v = castRayRoundedHull(Ray{Vec3(-0.9, -0.9, -0.9), Vec3(2, 2, 2)}, box);
        REQUIRE(v.hit);
        CHECK(v.t == doctest::Approx(0.5).epsilon(1e-12));
    }
    SUBCASE("segment and point cores") {
        const std::vector<Vec3> seg = {Vec3(0, 0, 0), Vec3(2, 0, 0)};
        const ConvexCastHit across = castRayRoundedHull(Ray{Vec3(0.5, -1, 0), Vec3(0, 4, 0)}, seg);
        REQUIRE(across.hit);
        CHECK(across.t == doctest::Approx(0.25).epsilon(1e-12));
        CHECK(across.normal.isApprox(Vec3(0, -1, 0), 1e-12));
        const ConvexCastHit along = castRayRoundedHull(Ray{Vec3(5, 0, 0), Vec3(-1, 0, 0)}, seg);
        REQUIRE(along.hit);
        CHECK(along.t == doctest::Approx(3.0).epsilon(1e-12));  // the near end, not GJK's common point
        CHECK(along.normal.isApprox(Vec3(1, 0, 0), 1e-12));
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(0.5, -1, 1e-9), Vec3(0, 4, 0)}, seg).hit);
        const ConvexCastHit point = castRayRoundedHull(Ray{Vec3(1, 1, 1), Vec3(-1, -1, -1)}, std::vector<Vec3>{Vec3::Zero()});
        REQUIRE(point.hit);
        CHECK(point.t == doctest::Approx(1.0).epsilon(1e-12));
    }
    SUBCASE("flat cores: two-sided, coplanar rays, rounded") {
        const std::vector<Vec3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        const ConvexCastHit below = castRayRoundedHull(Ray{Vec3(0.2, 0.2, -2), Vec3(0, 0, 1)}, tri);
        REQUIRE(below.hit);
        CHECK(below.t == doctest::Approx(2.0).epsilon(1e-12));
        CHECK(below.normal.isApprox(Vec3(0, 0, -1), 1e-12));
        const ConvexCastHit inPlane = castRayRoundedHull(Ray{Vec3(-1, 0.25, 0), Vec3(1, 0, 0)}, tri);
        REQUIRE(inPlane.hit);
        CHECK(inPlane.t == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(castRayRoundedHull(Ray{Vec3(0.2, 0.2, 0), Vec3(0, 0, 1)}, tri).inside);
        const ConvexCastHit rounded = castRayRoundedHull(Ray{Vec3(0.2, 0.2, -2), Vec3(0, 0, 1)}, tri, 0.5);
        REQUIRE(rounded.hit);
        CHECK(rounded.t == doctest::Approx(1.5).epsilon(1e-12));
        CHECK(rounded.normal.isApprox(Vec3(0, 0, -1), 1e-12));
    }
    SUBCASE("max t at the hit, and just before it") {
        ConvexCastOptions o;
        o.maxT = 1.1;
        CHECK(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.4), Vec3(1, 0, 0)}, box, 0.0, o).hit);
        o.maxT = 1.0999999;
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.4), Vec3(1, 0, 0)}, box, 0.0, o).hit);
    }
    SUBCASE("degenerate input gives no hit") {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.4), Vec3::Zero()}, box).hit);
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(nan, 0.4, 0.4), Vec3(1, 0, 0)}, box).hit);
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.4), Vec3(1, 0, 0)}, box, -1.0).hit);
        CHECK_FALSE(castRayRoundedHull(Ray{Vec3(-1, 0.4, 0.4), Vec3(1, 0, 0)}, std::vector<Vec3>{}).hit);
    }
}
