// refineDirection (core/gjk_epa/direction_refinement.h) against closed forms: it reaches the minimum
// of g(m) = h_A(m) + h_B(−m) on a smooth patch (a point in a sphere), on a ridge (a point inside a
// cylinder, nearest its side: the support jumps between the two rims across the ridge) and at a
// rim (a point beside a cylinder's cap edge); and it leaves an exact face normal exactly as it is.
#include <doctest/doctest.h>

#include <cmath>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/direction_refinement.h"

using namespace cdlab;

namespace {

struct Point {
    Vec3 p;
    Vec3 support(const Vec3&) const { return p; }
};

// m turned away from `exact` by `angle` toward an arbitrary tangent.
Vec3 turned(const Vec3& exact, double angle) {
    const Vec3 t = (exact.unitOrthogonal() + 0.3 * exact.cross(exact.unitOrthogonal())).normalized();
    return (std::cos(angle) * exact + std::sin(angle) * t).normalized();
}

}  // namespace

TEST_CASE("refineDirection: smooth patch, ridge and rim reach the closed form") {
    SUBCASE("a point inside a sphere: depth r − |p − c| along (c − p)/|c − p|") {
        const Point a{Vec3(0.1, 0.2, -0.3)};
        const SphereShape b{1.0};  // centre at the origin
        const Vec3 exact = Vec3(-0.1, -0.2, 0.3).normalized();
        const DirectionRefinement r = refineDirection(a, b, turned(exact, 1e-4), 1.0);
        CHECK(r.steps > 0);
        CHECK(r.value == doctest::Approx(1.0 - std::sqrt(0.14)).epsilon(1e-15));
        CHECK((r.direction - exact).norm() < 1e-14);
    }
    SUBCASE("a point inside a cylinder, nearest its side: the ridge between the rims") {
        const Point a{Vec3(0.3, 0.2, 0.4)};
        const CylinderShape b{1.0, 1.0};  // half height 1, radius 1, axis y
        const Vec3 exact(-0.6, 0.0, -0.8);  // pushes b away from the point, radially
        const DirectionRefinement r = refineDirection(a, b, turned(exact, 1e-4), 1.0);
        CHECK(r.value == doctest::Approx(0.5).epsilon(1e-15));
        CHECK((r.direction - exact).norm() < 1e-14);
    }
    SUBCASE("a point beside a cylinder's top rim: separated, g = −distance") {
        const Point a{Vec3(2.0, 2.0, 1.0)};
        const CylinderShape b{1.0, 1.0};
        // Nearest point of b: the rim point (2, 0, 1)/√5 at y = 1.
        const Vec3 rim = Vec3(2.0, 0.0, 1.0) / std::sqrt(5.0) + Vec3(0, 1, 0);
        const Vec3 exact = (rim - a.p).normalized();  // from a toward b
        const DirectionRefinement r = refineDirection(a, b, turned(exact, 1e-3), 1.0);
        CHECK(-r.value == doctest::Approx((rim - a.p).norm()).epsilon(1e-15));
        CHECK((r.direction - exact).norm() < 1e-13);
    }
}

TEST_CASE("refineDirection: an exact face normal is a kink, left unchanged") {
    const Point a{Vec3(0.25, 0.5, -0.125)};
    const BoxShape b{Vec3(1.0, 1.0, 1.0)};
    // The point is nearest b's +y face: depth 0.5 along −y (b pushed down, away from it).
    const DirectionRefinement r = refineDirection(a, b, Vec3(0, -1, 0), 1.0);
    CHECK(r.steps == 0);
    CHECK(r.direction == Vec3(0, -1, 0));
    CHECK(r.value == 0.5);
    // Started off the face normal, it returns to it.
    const DirectionRefinement back = refineDirection(a, b, turned(Vec3(0, -1, 0), 1e-5), 1.0);
    CHECK(back.value == doctest::Approx(0.5).epsilon(1e-15));
    CHECK((back.direction - Vec3(0, -1, 0)).norm() < 1e-14);
}
