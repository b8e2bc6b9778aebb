// core/query/pair.h against closed forms evaluated in long double, independent of GJK and EPA:
// sphere, capsule and box pairs (centre distances, segment–segment critical points, the clamped
// point of a box), a plane's and a ray's closed forms, the touching rule at its boundary, the
// statuses of the failures, and the agreement of penetrationWithMargins (typed shapes) with
// pairQuery: one implementation (core/gjk_epa/margins.h marginPairOnCores) answers both.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/margins.h"
#include "core/query/pair.h"
#include "core/query/touch.h"
#include "tests/random_vectors.h"

using namespace cdlab;

namespace {

using LD = long double;

LD exactNorm(const Vec3& a, const Vec3& b) {
    const LD x = LD(a.x()) - b.x(), y = LD(a.y()) - b.y(), z = LD(a.z()) - b.z();
    return std::sqrt(x * x + y * y + z * z);
}

}  // namespace

TEST_CASE("pair query: two spheres, every field against the centre distance") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-3, 3), r(0.05, 1.5);
    for (int i = 0; i < 400; ++i) {
        const Vec3 ca(u(rng), u(rng), u(rng)), cb(u(rng), u(rng), u(rng));
        const double ra = r(rng), rb = r(rng);
        const LD d = exactNorm(ca, cb);
        if (d < 1e-6) continue;
        const PairResult p = pairQuery(QueryShape::sphere(ca, ra), QueryShape::sphere(cb, rb));
        REQUIRE(p.status == PairStatus::Ok);
        REQUIRE(p.hasWitness);
        const LD gap = d - ra - rb;
        CHECK(p.intersect == (gap <= 0));
        const Vec3 n((LD(cb.x()) - ca.x()) / d, (LD(cb.y()) - ca.y()) / d, (LD(cb.z()) - ca.z()) / d);
        CHECK((p.normal - n).norm() < 1e-12);
        if (p.intersect) CHECK(std::abs(p.depth + double(gap)) < 1e-12);
        else CHECK(std::abs(p.distance - double(gap)) < 1e-12);
        // The witnesses are on the spheres, along the normal: pointA − pointB = ∓gap · n.
        CHECK(std::abs(double(exactNorm(p.pointA, ca)) - ra) < 1e-12);
        CHECK(std::abs(double(exactNorm(p.pointB, cb)) - rb) < 1e-12);
    }
}

TEST_CASE("pair query: a box and a point, the clamped point of Arvo's test") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-4, 4);
    const Vec3 lo(-1, -0.5, -2), hi(1.5, 0.5, 0.25);
    for (int i = 0; i < 300; ++i) {
        const Vec3 p(u(rng), u(rng), u(rng));
        const Vec3 q = p.cwiseMax(lo).cwiseMin(hi);
        const LD d = exactNorm(p, q);
        if (d < 1e-9) continue;  // inside: the depth case below
        PairOptions o;
        o.depth = false;
        const PairResult r = pairQuery(QueryShape::aabb(lo, hi), QueryShape::point(p), o);
        REQUIRE(r.status == PairStatus::Ok);
        CHECK_FALSE(r.intersect);
        CHECK(std::abs(r.distance - double(d)) < 1e-13);
        CHECK((r.pointA - q).norm() < 1e-12);
        CHECK((r.pointB - p).norm() == 0.0);
    }
    // A point inside: the depth is the distance to the nearest face.
    const PairResult in = pairQuery(QueryShape::aabb(lo, hi), QueryShape::point(Vec3(1.25, 0, -1)));
    CHECK(in.intersect);
    CHECK(std::abs(in.depth - 0.25) < 1e-15);
    CHECK((in.normal - Vec3::UnitX()).norm() < 1e-15);
}

TEST_CASE("pair query: the touching rule") {
    // Two unit boxes at x = 1e9, 5e-5 apart: W ≈ 2, the gap is 1e11 times the tolerance.
    const QueryShape a = QueryShape::aabb(Vec3(1e9, 0, 0), Vec3(1e9 + 1, 1, 1));
    const QueryShape b = QueryShape::aabb(Vec3(1e9 + 1 + 5e-5, 0, 0), Vec3(1e9 + 2, 1, 1));
    const PairResult far = pairQuery(a, b);
    CHECK_FALSE(far.intersect);
    const double gap = (1e9 + 1 + 5e-5) - (1e9 + 1);  // exact (Sterbenz): 5e-5 to the spacing 1.2e-7 at 1e9
    CHECK(std::abs(far.distance - gap) <= 1e-13 * 2);
    // Spheres whose gap is 0.5 and 2 tolerances: touching, then separated.
    const double tol = kTouchRelative * (2.0 + 1.0 + 1.0);  // W = 2 (centres 2 apart), radii 1 + 1
    for (const double k : {0.5, 2.0}) {
        const QueryShape s = QueryShape::sphere(Vec3::Zero(), 1.0), t = QueryShape::sphere(Vec3(2 + k * tol, 0, 0), 1.0);
        CHECK(touchTolerance(s, t) == doctest::Approx(tol).epsilon(1e-3));
        const PairResult p = pairQuery(s, t);
        CHECK(p.intersect == (k < 1));
        if (p.intersect) CHECK(p.depth == 0.0);
    }
}

TEST_CASE("pair query: planes and rays in closed form") {
    const QueryShape ground = QueryShape::plane(Vec3(0, 2, 0), 2.0);  // y = 1, rescaled: the same plane
    CHECK(ground.normal.cwiseAbs().maxCoeff() >= 0.5);
    CHECK(ground.normal.cwiseAbs().maxCoeff() < 1.0);
    const PairResult sphere = pairQuery(ground, QueryShape::sphere(Vec3(3, 1.25, 0), 0.5));
    CHECK(sphere.intersect);
    CHECK(sphere.depth == 0.25);
    CHECK(sphere.normal == Vec3::UnitY());
    const PairResult ray = pairQuery(QueryShape::ray(Vec3(0, 3, 0), Vec3(1, 0, 0)), ground);
    CHECK_FALSE(ray.intersect);
    CHECK(ray.distance == 2.0);
    const PairResult crossing = pairQuery(QueryShape::ray(Vec3(0, 3, 0), Vec3(0, -1, 0)), ground);
    CHECK(crossing.intersect);
    // Two rays: skew lines 1 apart whose feet are at s, t > 0.
    const PairResult rays = pairQuery(QueryShape::ray(Vec3(-1, 0, 0), Vec3(1, 0, 0)), QueryShape::ray(Vec3(0, -1, 1), Vec3(0, 1, 0)));
    CHECK_FALSE(rays.intersect);
    CHECK(std::abs(rays.distance - 1.0) < 1e-15);
    CHECK((rays.pointA - Vec3::Zero()).norm() < 1e-15);
    CHECK((rays.pointB - Vec3(0, 0, 1)).norm() < 1e-15);
}

TEST_CASE("pair query: failures are statuses, not answers") {
    const QueryShape tilted = QueryShape::plane(Vec3(1, 1, 0), 0.0), flat = QueryShape::plane(Vec3(0, 1, 0), 0.0);
    CHECK(pairQuery(tilted, flat).status == PairStatus::UnboundedPenetration);
    PairOptions noDepth;
    noDepth.depth = false;
    const PairResult crossing = pairQuery(tilted, flat, noDepth);
    CHECK(crossing.status == PairStatus::Ok);
    CHECK(crossing.intersect);
    // Two points 3.4e308 apart: the distance overflows double precision.
    const PairResult huge = pairQuery(QueryShape::point(Vec3(1.7e308, 0, 0)), QueryShape::point(Vec3(-1.7e308, 0, 0)));
    CHECK(huge.status != PairStatus::Ok);
    CHECK(std::string(describe(PairStatus::Overflow)).find("overflows") != std::string::npos);
}

TEST_CASE("pair query: a cylinder's polished distance and a capsule's") {
    // A sphere above a cylinder's rim, along the rim's outward diagonal: distance |c − rim| − r.
    const QueryShape cyl = QueryShape::cylinder(Vec3::Zero(), 1.0, 1.0);
    const Vec3 c(1 + 2 / std::sqrt(2.0), 1 + 2 / std::sqrt(2.0), 0);
    const PairResult p = pairQuery(cyl, QueryShape::sphere(c, 0.5));
    REQUIRE(p.status == PairStatus::Ok);
    CHECK_FALSE(p.intersect);
    CHECK(std::abs(p.distance - (double(exactNorm(c, Vec3(1, 1, 0))) - 0.5)) < 1e-12);
    CHECK((p.pointA - Vec3(1, 1, 0)).norm() < 1e-9);
    // Two crossing capsules: depth r_a + r_b − 0 along the common perpendicular.
    const PairResult x =
        pairQuery(QueryShape::capsule(Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.25), QueryShape::capsule(Vec3(0, -1, 0.1), Vec3(0, 1, 0.1), 0.25));
    CHECK(x.intersect);
    CHECK(std::abs(x.depth - 0.4) < 1e-14);
    CHECK((x.normal - Vec3::UnitZ()).norm() < 1e-14);
}

TEST_CASE("pair query: typed shapes through penetrationWithMargins give pairQuery's answer, bit for bit") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1), r(0.1, 0.8);
    for (int i = 0; i < 200; ++i) {
        const Vec3 a0(u(rng), u(rng), u(rng)), a1(u(rng), u(rng), u(rng)), b0(u(rng), u(rng), u(rng)), b1(u(rng), u(rng), u(rng));
        const double ra = r(rng), rb = r(rng);
        const EpaResult typed = penetrationWithMargins(CapsuleShape{a0, a1, ra}, CapsuleShape{b0, b1, rb});
        const PairResult query = pairQuery(QueryShape::capsule(a0, a1, ra), QueryShape::capsule(b0, b1, rb));
        REQUIRE(query.status == PairStatus::Ok);
        CHECK((typed.status != EpaStatus::Separated) == query.intersect);
        // Same decision; the same numbers up to the query's power-of-two scaling (exact) and its
        // move of a far pair (none here: the pair straddles the origin).
        if (query.intersect) CHECK(std::abs(typed.depth - query.depth) <= 1e-15 * (1 + query.depth));
        CHECK((typed.normal - query.normal).norm() <= 1e-15);
    }
}
