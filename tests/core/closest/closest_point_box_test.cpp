// Closest point on a box with its Voronoi region (core/closest/closest_point_box.h). Oracles: the
// distance against the brute-force minimum over a dense grid of the box's surface (0 inside), and
// the region against the feature holding the closest point (which of its box-frame coordinates sit
// at ±e).
#include <doctest/doctest.h>

#include <random>

#include "core/closest/closest_point_box.h"

using namespace cdlab;

TEST_CASE("closest point on a rotated box: the region's feature holds the point, the distance is the least") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    int byDimension[4] = {0, 0, 0, 0};
    for (int round = 0; round < 400; ++round) {
        const Obb box = Obb::fromRotation(Vec3(u(rng), u(rng), u(rng)), Vec3(0.5 + 0.4 * u(rng), 0.5 + 0.4 * u(rng), 0.5 + 0.4 * u(rng)),
                                          Quat(u(rng), u(rng), u(rng), u(rng)).normalized());
        const double reach = round % 2 ? 2.5 : 1.0;  // half the points near the box: the inside is met too
        const Vec3 p(reach * u(rng), reach * u(rng), reach * u(rng));
        const BoxRegionResult r = closestPointOnBox(p, box);
        REQUIRE(r.valid);
        ++byDimension[r.dimension];
        // The point is in the box, on the region's feature: at ±e exactly on the outside axes.
        const Vec3 local = box.axes.transpose() * (r.point - box.center);
        for (int i = 0; i < 3; ++i) {
            CHECK(std::abs(local[i]) <= box.halfExtents[i] * (1 + 1e-12) + 1e-12);
            if (r.tests[std::size_t(i)].side != 0)
                CHECK(std::abs(std::abs(local[i]) - box.halfExtents[i]) <= 1e-12);
        }
        CHECK(int(r.corners.size()) == (r.dimension == 3 ? 0 : 1 << r.dimension));
        // The distance is the least over a dense sample of the box (grid over the solid's surface).
        double best = INFINITY;
        const int n = 24;
        for (int a = 0; a <= n; ++a)
            for (int b = 0; b <= n; ++b)
                for (int face = 0; face < 6; ++face) {
                    Vec3 q;
                    const int axis = face / 2;
                    q[axis] = face % 2 ? box.halfExtents[axis] : -box.halfExtents[axis];
                    q[(axis + 1) % 3] = (2.0 * a / n - 1) * box.halfExtents[(axis + 1) % 3];
                    q[(axis + 2) % 3] = (2.0 * b / n - 1) * box.halfExtents[(axis + 2) % 3];
                    best = std::min(best, (box.center + box.axes * q - p).norm());
                }
        if (r.dimension == 3) CHECK(r.distance == 0);
        else {
            CHECK(r.distance <= best + 1e-12);
            CHECK(r.distance >= best - 0.1);  // the grid's spacing bounds how far above the least it can sit
            CHECK((p - r.point).norm() == doctest::Approx(r.distance));
        }
    }
    for (int d = 0; d < 4; ++d) CHECK(byDimension[d] > 10);  // vertex, edge, face and inside regions all met
}

TEST_CASE("box regions: names, ties on the slab boundary, bad input") {
    const Obb box{Vec3::Zero(), Vec3(1, 2, 3), Mat3::Identity()};
    CHECK(regionName(closestPointOnBox(Vec3(2, 3, 4), box)) == "vertex +x+y+z");
    CHECK(closestPointOnBox(Vec3(2, 3, 4), box).corners == std::vector<int>{7});
    CHECK(regionName(closestPointOnBox(Vec3(-2, 0, 4), box)) == "edge −x+z");
    CHECK(regionName(closestPointOnBox(Vec3(0, -5, 0), box)) == "face −y");
    CHECK(closestPointOnBox(Vec3(0, -5, 0), box).distance == 3);
    CHECK(regionName(closestPointOnBox(Vec3(0.5, 0, 0), box)) == "inside");
    CHECK(regionName(closestPointOnBox(Vec3(1, 2, 5), box)) == "face +z");  // on the slab boundary: the face wins
    CHECK_FALSE(closestPointOnBox(Vec3(NAN, 0, 0), box).valid);
    CHECK_FALSE(closestPointOnBox(Vec3::Zero(), Obb{Vec3::Zero(), Vec3(-1, 1, 1), Mat3::Identity()}).valid);
}
