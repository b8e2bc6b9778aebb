// core/query's casts, mass properties and feature walks against closed forms: a ray into a sphere
// (the quadratic's smaller root), two spheres closing head-on (gap / closing speed), a box's volume
// and inertia (m (b² + c²) / 12), and V-Clip / Lin–Canny on two boxes (the gap between faces).
#include <doctest/doctest.h>

#include <cmath>

#include "core/query/cast.h"
#include "core/query/feature_walk.h"
#include "core/query/mass.h"
#include "core/query/touch.h"

using namespace cdlab;

TEST_CASE("query casts: a ray into a sphere and two spheres closing head-on") {
    const RayCastQueryResult r = rayCastQuery(Vec3(-5, 0.6, 0), Vec3(2, 0, 0), QueryShape::sphere(Vec3::Zero(), 1.0), 100.0);
    REQUIRE(r.status == PairStatus::Ok);
    CHECK(r.hit);
    CHECK_FALSE(r.inside);
    // x = −sqrt(1 − 0.36) = −0.8 at t = (5 − 0.8) / 2.
    CHECK(std::abs(r.t - 2.1) < 1e-14);
    CHECK((r.point - Vec3(-0.8, 0.6, 0)).norm() < 1e-14);
    CHECK((r.normal - Vec3(-0.8, 0.6, 0)).norm() < 1e-14);
    const RayCastQueryResult miss = rayCastQuery(Vec3(-5, 1.5, 0), Vec3(1, 0, 0), QueryShape::sphere(Vec3::Zero(), 1.0), 100.0);
    CHECK_FALSE(miss.hit);
    const RayCastQueryResult inside = rayCastQuery(Vec3(0.1, 0, 0), Vec3(1, 0, 0), QueryShape::sphere(Vec3::Zero(), 1.0), 1.0);
    CHECK(inside.inside);
    CHECK(inside.point == Vec3(0.1, 0, 0));

    // Centres 10 apart, radii 1 + 1.5, closing at 10 per unit time: contact at t = 0.75.
    const ImpactQueryResult t = timeOfImpactQuery(QueryShape::sphere(Vec3::Zero(), 1.0), Vec3(4, 0, 0),
                                                  QueryShape::sphere(Vec3(10, 0, 0), 1.5), Vec3(-6, 0, 0));
    REQUIRE(t.status == PairStatus::Ok);
    CHECK(t.result.hit);
    CHECK(std::abs(t.result.t - 0.75) < 1e-12);
    CHECK((t.result.normal - Vec3::UnitX()).norm() < 1e-12);
    CHECK((t.result.pointA - Vec3(4, 0, 0)).norm() < 1e-9);
    // The work limit is checked before the cast: a tiny limit refuses two boxes (8 × 8 points).
    ImpactQueryOptions tight;
    tight.maxDifferencePoints = 63;
    const ImpactQueryResult refused = timeOfImpactQuery(QueryShape::aabb(Vec3::Zero(), Vec3::Ones()), Vec3(1, 0, 0),
                                                        QueryShape::aabb(Vec3(3, 0, 0), Vec3(4, 1, 1)), Vec3::Zero(), tight);
    CHECK(refused.status == PairStatus::WorkLimit);
    CHECK(refused.hullA * refused.hullB == 64);
}

TEST_CASE("query mass properties: a box, a sphere and the refusals") {
    const MassQueryResult box = massPropertiesQuery(QueryShape::aabb(Vec3(1, 2, 3), Vec3(3, 3, 7)), 2.0);
    REQUIRE(box.status == MassQueryResult::Status::Ok);
    const double a = 2, b = 1, c = 4, m = 2.0 * a * b * c;
    CHECK(std::abs(box.volume - a * b * c) < 1e-13);
    CHECK(std::abs(box.mass - m) < 1e-13);
    CHECK((box.centerOfMass - Vec3(2, 2.5, 5)).norm() < 1e-13);
    CHECK(std::abs(box.inertia(0, 0) - m * (b * b + c * c) / 12) < 1e-12);
    CHECK(std::abs(box.inertia(1, 1) - m * (a * a + c * c) / 12) < 1e-12);
    CHECK(std::abs(box.inertia(2, 2) - m * (a * a + b * b) / 12) < 1e-12);
    CHECK(std::abs(box.inertia(0, 1)) < 1e-12);
    const MassQueryResult sphere = massPropertiesQuery(QueryShape::sphere(Vec3(1, 0, 0), 2.0), 1.0);
    CHECK(std::abs(sphere.volume - 4.0 / 3.0 * M_PI * 8) < 1e-12);
    CHECK(massPropertiesQuery(QueryShape::sphere(Vec3::Zero(), 0.0), 1.0).status == MassQueryResult::Status::NoVolume);
    CHECK(massPropertiesQuery(QueryShape::segment(Vec3::Zero(), Vec3::Ones()), 1.0).status ==
          MassQueryResult::Status::UnsupportedKind);
    const MassQueryResult tiny = massPropertiesQuery(QueryShape::aabb(Vec3::Zero(), Vec3::Constant(1e-100)), 1.0);
    CHECK(tiny.status == MassQueryResult::Status::OutOfRange);
}

TEST_CASE("query feature walks: V-Clip and Lin–Canny find the gap between two boxes") {
    const QueryShape a = QueryShape::aabb(Vec3::Zero(), Vec3::Ones()), b = QueryShape::aabb(Vec3(1.25, 0.5, 0.5), Vec3(2, 2, 2));
    const int k = normalisingExponent(a, b);
    const WalkBody wa = walkBodyOf(a, k), wb = walkBodyOf(b, k);
    REQUIRE(wa.status == WalkBody::Status::Ok);
    REQUIRE(wb.status == WalkBody::Status::Ok);
    for (const bool linCanny : {false, true}) {
        const WalkPairResult r = walkPair(wa, wb, k, std::ldexp(touchTolerance(a, b), k), linCanny);
        REQUIRE(r.status == PairStatus::Ok);
        CHECK_FALSE(r.intersect);
        CHECK(std::abs(r.distance - 0.25) < 1e-15);
        CHECK(std::abs(r.pointA.x() - 1.0) < 1e-15);
        CHECK(std::abs(r.pointB.x() - 1.25) < 1e-15);
    }
    CHECK(walkBodyOf(QueryShape::sphere(Vec3::Zero(), 1), 0).status == WalkBody::Status::NotPolyhedron);
    CHECK(walkBodyOf(QueryShape::polytope({Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3(1, 1, 0)}), 0).status ==
          WalkBody::Status::DegenerateHull);
}
