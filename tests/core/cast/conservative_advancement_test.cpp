// Conservative advancement (core/cast/conservative_advancement.h). Oracle: the exact first contact of
// two convex polygons (as prisms much thicker than they are wide, so the 3D distance is the polygons'
// distance) found by dense sampling of the pose over t and bisection, the distance of two disjoint
// convex polygons being the least vertex-edge distance both ways and overlap decided by their edge
// normals (2D SAT), in long double (verification/polygon_oracle.h): no GJK in the oracle. Checks:
// the advancement never passes the first contact, stops within its tolerance of touching, and says
// "no contact" only when there is none.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/cast/conservative_advancement.h"
#include "core/cast/time_of_impact.h"
#include "verification/polygon_oracle.h"

using namespace cdlab;

namespace {

using oracle::P2;
using oracle::polygonDistance;

constexpr double kHalfThickness = 50.0;  // z extent of the prisms: never the closest direction

std::vector<Vec3> prism(const std::vector<Vec2>& polygon) {
    std::vector<Vec3> v;
    for (const Vec2& p : polygon)
        for (double z : {-kHalfThickness, kHalfThickness}) v.emplace_back(p.x(), p.y(), z);
    return v;
}

std::vector<P2> placed(const std::vector<Vec2>& body, const Transform& pose) {
    std::vector<Vec3> out;
    for (const Vec2& p : body) out.push_back(pose.apply(Vec3(p.x(), p.y(), 0)));
    return oracle::polygon2(out);
}

std::vector<Vec2> regularPolygon(int n, double radius, double phase) {
    std::vector<Vec2> v;
    for (int i = 0; i < n; ++i) {
        const double a = phase + 2 * M_PI * i / n;
        v.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    return v;
}

}  // namespace

TEST_CASE("conservative advancement never passes the first contact and stops within its tolerance") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> sides(3, 8);
    int contacts = 0, misses = 0, turning = 0;
    for (int round = 0; round < 300; ++round) {
        const std::vector<Vec2> a2 = regularPolygon(sides(rng), 1.0 + 0.5 * u(rng), u(rng));
        const std::vector<Vec2> b2 = regularPolygon(sides(rng), 0.6 + 0.3 * u(rng), u(rng));
        Transform start;
        start.position = Vec3(3.5 + u(rng), 1.5 * u(rng), 0);
        RigidMotion motion;
        motion.linear = Vec3(-4.5 + u(rng), 1.5 * u(rng), 0);
        motion.angular = Vec3(0, 0, round % 4 == 0 ? 0.0 : 3.0 * u(rng));
        turning += motion.angular.z() != 0;
        AdvancementOptions options;
        options.tolerance = 1e-7;
        options.maxSteps = 100000;
        const AdvancementResult r = conservativeAdvancement(prism(a2), prism(b2), start, motion, options);
        // The oracle's first contact: the first sample with distance 0, refined by bisection.
        const auto A = placed(a2, Transform{});
        auto distanceAt = [&](double t) { return polygonDistance(A, placed(b2, poseAt(start, motion, t))); };
        REQUIRE(distanceAt(0) > 1e-3);  // the rounds start apart
        double firstContact = -1;
        const int samples = 4000;
        for (int k = 1; k <= samples; ++k) {
            const double t = double(k) / samples;
            if (distanceAt(t) == 0) {
                double lo = double(k - 1) / samples, hi = t;
                for (int it = 0; it < 60; ++it) {
                    const double mid = 0.5 * (lo + hi);
                    (distanceAt(mid) == 0 ? hi : lo) = mid;
                }
                firstContact = hi;
                break;
            }
        }
        if (r.outcome == AdvancementResult::Outcome::Contact) {
            ++contacts;
            CHECK(double(distanceAt(r.t)) <= 1e-7 + 1e-12);
            CHECK(double(distanceAt(r.t)) >= 0);
            // Conservative: the contact found is never after the first contact.
            if (firstContact >= 0) CHECK(r.t <= firstContact + 1e-12);
            CHECK(std::abs(r.distance - double(distanceAt(r.t))) <= 1e-9);
        } else {
            REQUIRE(r.outcome == AdvancementResult::Outcome::NoContact);  // never the step budget here
            ++misses;
            // Apart the whole time (a graze shorter than a sample could hide; none in these rounds).
            CHECK(firstContact < 0);
        }
    }
    CHECK(contacts > 100);
    CHECK(misses > 20);
    CHECK(turning > 150);
}

TEST_CASE("without a turn, advancement agrees with the exact translational time of impact") {
    const std::vector<Vec3> a = prism(regularPolygon(5, 1.0, 0.3));
    const std::vector<Vec3> body = prism(regularPolygon(4, 0.5, 0.1));
    Transform start;
    start.position = Vec3(4, 0.4, 0);
    RigidMotion motion;
    motion.linear = Vec3(-5, -0.2, 0);
    AdvancementOptions options;
    options.tolerance = 1e-9;
    const AdvancementResult r = conservativeAdvancement(a, body, start, motion, options);
    REQUIRE(r.outcome == AdvancementResult::Outcome::Contact);
    std::vector<Vec3> b;
    for (const Vec3& p : body) b.push_back(start.apply(p));
    const TimeOfImpactResult exact = translationalTimeOfImpact(a, 0, Vec3::Zero(), b, 0, motion.linear);
    REQUIRE(exact.hit);
    CHECK(r.t <= exact.t + 1e-12);
    CHECK(r.t >= exact.t - 1e-9 / 5.0 - 1e-12);  // within tolerance / speed
    CHECK(r.steps <= 3);  // a face-on approach along a fixed normal closes in one step (plus the check)
}

TEST_CASE("advancement: touching at the start, no motion, bad input") {
    const std::vector<Vec3> a = prism(regularPolygon(4, 1.0, 0.0));
    Transform start;
    start.position = Vec3(0.5, 0, 0);
    CHECK(conservativeAdvancement(a, a, start, RigidMotion{}).outcome == AdvancementResult::Outcome::InitiallyTouching);
    start.position = Vec3(5, 0, 0);
    CHECK(conservativeAdvancement(a, a, start, RigidMotion{}).outcome == AdvancementResult::Outcome::NoContact);
    CHECK(conservativeAdvancement({}, a, start, RigidMotion{}).outcome == AdvancementResult::Outcome::InvalidInput);
    RigidMotion bad;
    bad.angular = Vec3(0, 0, NAN);
    CHECK(conservativeAdvancement(a, a, start, bad).outcome == AdvancementResult::Outcome::InvalidInput);
    // A spin alone that sweeps a corner into A: contact, reached in finitely many steps.
    RigidMotion spin;
    spin.angular = Vec3(0, 0, 2.0);
    const std::vector<Vec3> bar = prism({{-1.6, -0.1}, {1.6, -0.1}, {1.6, 0.1}, {-1.6, 0.1}});
    start.position = Vec3(0, 1.6, 0);  // the bar above A, turning about its centre: its ends swing down
    const std::vector<Vec3> small = prism(regularPolygon(4, 0.5, M_PI / 4));
    const AdvancementResult r = conservativeAdvancement(small, bar, start, spin);
    CHECK(r.outcome == AdvancementResult::Outcome::Contact);
    CHECK(r.steps < 100);
}
