// The expanding polygon (core/gjk_epa/epa_2d.h) on planar shapes: the depth, the normal (A toward
// B) and the witnesses (pointA - pointB = depth * normal) of two overlapping squares do not depend
// on the order of GJK's start simplex, and touching squares report Touching with depth 0.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa_2d.h"

using namespace cdlab;

namespace {

/// An axis-aligned rectangle in z = 0 about `center`: in-plane directions only, as a 2D scene's box.
struct PlanarRectangle {
    Vec3 halfExtents;
    Vec3 center;
    Vec3 support(const Vec3& d) const {
        Vec3 inPlane = d;
        inPlane.z() = 0.0;
        return BoxShape{halfExtents}.support(inPlane) + center;
    }
};

}  // namespace

TEST_CASE("2D EPA: square overlap in every vertex order of the start triangle") {
    // Unit squares overlapping by 0.25 along x: depth 0.25, normal +x (A toward B).
    const PlanarRectangle a{Vec3(0.5, 0.5, 0), Vec3::Zero()};
    PlanarRectangle b{Vec3(0.5, 0.5, 0), Vec3(0.75, 0.1, 0)};
    const GjkResult g = gjkDistance(a, b);
    REQUIRE(g.intersect());
    REQUIRE(g.simplex.count >= 1);
    const GjkSimplex s = g.simplex;
    std::vector<int> order(s.count);
    std::iota(order.begin(), order.end(), 0);
    do {
        GjkSimplex p = s;
        for (int i = 0; i < s.count; ++i) p.vertex[i] = s.vertex[order[i]];
        Epa2dTrace trace;
        const Epa2dResult r = epaPenetration2d(a, b, p, EpaOptions{}, &trace);
        CHECK(r.status == EpaStatus::Penetrating);
        CHECK(r.depth == doctest::Approx(0.25).epsilon(1e-12));
        CHECK((r.normal - Vec3::UnitX()).norm() < 1e-12);
        CHECK((r.pointA - r.pointB - r.depth * r.normal).norm() < 1e-12);
    } while (std::next_permutation(order.begin(), order.end()));
    // Touching squares: depth 0 with the contact normal.
    b.center = Vec3(1.0, 0.1, 0);
    const GjkResult gt = gjkDistance(a, b);
    REQUIRE(gt.intersect());
    const Epa2dResult rt = epaPenetration2d(a, b, gt.simplex, EpaOptions{});
    CHECK(rt.status == EpaStatus::Touching);
    CHECK(rt.depth == 0.0);
    CHECK(std::abs(rt.normal.x()) == doctest::Approx(1.0));
}
