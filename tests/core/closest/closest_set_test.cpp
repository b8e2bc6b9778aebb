// closestSetOfPolytopes against sets written down by hand: two axis-aligned boxes apart along x
// (the overlap rectangle of their facing faces, by interval arithmetic), a box turned 45° about z
// facing a box (the edge's overlap with the face's z range), boxes apart along a diagonal (one
// corner pair: the fallback point).
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

#include "core/closest/closest_set.h"

using namespace cdlab;

namespace closest_set_test {

std::vector<Vec3> corners(const Vec3& c, const Vec3& h, const Quat& q = Quat::Identity()) {
    std::vector<Vec3> out;
    for (int k = 0; k < 8; ++k) out.push_back(c + q * Vec3(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()));
    return out;
}

}  // namespace closest_set_test

TEST_CASE("closest set: facing faces of boxes give their overlap rectangle") {
    using namespace closest_set_test;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        const Vec3 ca(u(rng), u(rng), u(rng)), ha(pos(rng), pos(rng), pos(rng));
        const Vec3 hb(pos(rng), pos(rng), pos(rng));
        const double gap = pos(rng);
        const Vec3 cb(ca.x() + ha.x() + gap + hb.x(), ca.y() + 0.8 * u(rng), ca.z() + 0.8 * u(rng));
        const std::vector<Vec3> a = corners(ca, ha), b = corners(cb, hb);
        const double y0 = std::max(ca.y() - ha.y(), cb.y() - hb.y()), y1 = std::min(ca.y() + ha.y(), cb.y() + hb.y());
        const double z0 = std::max(ca.z() - ha.z(), cb.z() - hb.z()), z1 = std::min(ca.z() + ha.z(), cb.z() + hb.z());
        if (!(y1 - y0 > 1e-3 && z1 - z0 > 1e-3)) continue;  // the faces must overlap in an area
        const ClosestSet s = closestSetOfPolytopes(a, b, Vec3::UnitX(), gap, 1e-9, Vec3::Zero());
        REQUIRE(s.onA.size() == 4);
        Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
        for (const Vec3& p : s.onA) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        CHECK(lo.x() == doctest::Approx(ca.x() + ha.x()));
        CHECK(hi.x() == doctest::Approx(ca.x() + ha.x()));
        CHECK(lo.y() == doctest::Approx(y0));
        CHECK(hi.y() == doctest::Approx(y1));
        CHECK(lo.z() == doctest::Approx(z0));
        CHECK(hi.z() == doctest::Approx(z1));
        CHECK((s.offset - Vec3(gap, 0, 0)).norm() <= 1e-12);
    }
}

TEST_CASE("closest set: an edge facing a face gives the edge's part over the face, skew features one point") {
    using namespace closest_set_test;
    // A turned 45° about z: its +x extreme is the vertical edge x = √2, y = 0, z in [-1, 1].
    const Quat turn(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()));
    const std::vector<Vec3> a = corners(Vec3::Zero(), Vec3(1, 1, 1), turn);
    const std::vector<Vec3> b = corners(Vec3(std::sqrt(2.0) + 0.5 + 0.5, 0.1, 0.6), Vec3(0.5, 0.5, 0.5));
    const ClosestSet s = closestSetOfPolytopes(a, b, Vec3::UnitX(), 0.5, 1e-9, Vec3::Zero());
    REQUIRE(s.onA.size() == 2);
    const double z0 = std::min(s.onA[0].z(), s.onA[1].z()), z1 = std::max(s.onA[0].z(), s.onA[1].z());
    CHECK(z0 == doctest::Approx(0.1));  // B's face spans z in [0.1, 1.1], A's edge [-1, 1]
    CHECK(z1 == doctest::Approx(1.0));
    for (const Vec3& p : s.onA) CHECK(std::abs(p.y()) <= 1e-12);
    // Both turned 45° about different axes: two skew edges, one pair (the fallback).
    const Quat other(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()));
    const std::vector<Vec3> c = corners(Vec3(2 * std::sqrt(2.0) + 0.3, 0, 0), Vec3(1, 1, 1), other);
    const Vec3 fallback(std::sqrt(2.0), 0, 0);
    const ClosestSet t = closestSetOfPolytopes(a, c, Vec3::UnitX(), 0.3, 1e-9, fallback);
    REQUIRE(t.onA.size() == 1);
    CHECK((t.onA[0] - fallback).norm() <= 1e-9);
}
