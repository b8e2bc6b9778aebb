// Moving point time of impact (core/overlap/moving_point.h). Oracle: long double point-in-shape tests,
// the path's minimum distance by ternary search (clear hit / miss), the first time inside by
// dense sampling + bisection; exact hand-built cases for r = 0 and grazing contacts.
#include <doctest/doctest.h>

#include <limits>

#include "core/overlap/moving_point.h"
#include "verification/intersection_oracles.h"

using namespace cdlab;
using oracle::LD;
using oracle::V3;

TEST_SUITE("moving_point") {
    TEST_CASE("moving point vs sphere and capsule: time of impact against sampling") {
        oracle::Rng rng(1);
        int sphereHits = 0, capsuleHits = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 600; ++n) {
                const Vec3 s = Vec3::Constant(offset);
                const Capsule cap{rng.vec(-1, 1) + s, rng.vec(-1, 1) + s, rng.uniform(0.05, 0.8)};
                MovingPoint m{Vec3::Zero(), Vec3::Zero(), rng.uniform(-1, 0.5), 0.0};
                m.tEnd = m.tBegin + rng.uniform(0.5, 2.0);
                // Start at `start` at tBegin, heading for a point near the capsule (about half hit).
                const Vec3 start = rng.vec(-3, 3) + s, aim = cap.a + rng.vec(-1.2, 1.2);
                m.velocity = (aim - start) * rng.uniform(0.5, 2.0) / (m.tEnd - m.tBegin);
                if (n % 10 == 0) m.velocity = (cap.b - cap.a) * rng.uniform(-1, 1);  // parallel to the axis
                m.position = start - m.tBegin * m.velocity;
                const V3 p0(m.at(m.tBegin)), p1(m.at(m.tEnd)), a(cap.a), b(cap.b);
                const LD span = LD(m.tEnd) - LD(m.tBegin);
                auto pos = [&](LD u) { return p0 + (p1 - p0) * u; };  // u in [0, 1]
                auto toi = [&](auto dist, LD r) -> LD {               // -1: clear miss, -2: unclear
                    const LD dmin = oracle::minimizeConvex([&](LD u) { return dist(pos(u)); });
                    if (std::abs(dmin - r) < 1e-7) return -2;
                    if (dmin > r) return -1;
                    return oracle::firstInside([&](LD u) { return dist(pos(u)) <= r; }, 1, 4000);
                };
                // Capsule.
                const LD tc = toi([&](const V3& x) { return oracle::distPointSegment(x, a, b); }, cap.radius);
                if (tc != -2) {
                    const MovingPointHit h = intersectMovingPointCapsule(m, cap);
                    REQUIRE(h.hit == (tc >= 0));
                    if (h.hit) {
                        ++capsuleHits;
                        CHECK(std::abs(h.t - double(LD(m.tBegin) + tc * span)) < 1e-7 * (1 + offset));
                        CHECK(std::abs(double(oracle::distPointSegment(V3(h.point), a, b)) - cap.radius) <
                              (tc == 0 ? cap.radius + 1e-9 : 1e-7 * (1 + offset)));
                    }
                }
                // Sphere at cap.a.
                const Sphere sph{cap.a, cap.radius};
                const LD ts = toi([&](const V3& x) { return oracle::norm(x - a); }, sph.radius);
                if (ts != -2) {
                    const MovingPointHit h = intersectMovingPointSphere(m, sph);
                    REQUIRE(h.hit == (ts >= 0));
                    if (h.hit) {
                        ++sphereHits;
                        CHECK(std::abs(h.t - double(LD(m.tBegin) + ts * span)) < 1e-7 * (1 + offset));
                        if (ts > 0) CHECK(h.normal.norm() == doctest::Approx(1.0));
                    }
                }
            }
        }
        CHECK(sphereHits > 100);
        CHECK(capsuleHits > 150);
    }

    TEST_CASE("moving point vs triangle against the long double plane crossing, every vertex order") {
        oracle::Rng rng(2);
        int hits = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 800; ++n) {
                const Vec3 s = Vec3::Constant(offset);
                const Triangle tri{rng.vec(-1, 1) + s, rng.vec(-1, 1) + s, rng.vec(-1, 1) + s};
                const Vec3 start = rng.vec(-2, 2) + s, aim = (tri.a + tri.b + tri.c) / 3.0 + rng.vec(-0.7, 0.7);
                const MovingPoint m{start, (aim - start) * rng.uniform(0.5, 2.0), 0.0, 1.0};
                const V3 a(tri.a), b(tri.b), c(tri.c), p0(m.at(0.0)), p1(m.at(1.0));
                const V3 nrm = oracle::cross(b - a, c - a);
                const LD d0 = oracle::dot(p0 - a, nrm), d1 = oracle::dot(p1 - a, nrm);
                const LD nn = oracle::norm(nrm);
                if (std::abs(d0 - d1) < 1e-6 * nn) continue;
                const LD u = d0 / (d0 - d1);
                const V3 x = p0 + (p1 - p0) * u;
                const LD wa = oracle::dot(oracle::cross(b - x, c - x), nrm) / (nn * nn);
                const LD wb = oracle::dot(oracle::cross(c - x, a - x), nrm) / (nn * nn);
                const LD margin = std::min({wa, wb, 1 - wa - wb, u, 1 - u});
                if (std::abs(margin) < 1e-7) continue;
                for (const Triangle& perm : oracle::orderings(tri)) {
                    const MovingPointHit h = intersectMovingPointTriangle(m, perm);
                    REQUIRE(h.hit == (margin > 0));
                    if (!h.hit) continue;
                    CHECK(std::abs(h.t - double(u)) < 1e-9 * (1 + offset));
                    // The normal faces the start point.
                    CHECK(h.normal.dot(m.at(0.0) - perm.a) > 0);
                }
                hits += margin > 0;
            }
        }
        CHECK(hits > 100);
    }

    TEST_CASE("exact and degenerate cases") {
        // Capsule radius 0: only an exact crossing of the segment counts.
        const Capsule seg{Vec3(0, -1, 0), Vec3(0, 1, 0), 0.0};
        const MovingPointHit cross = intersectMovingPointCapsule({Vec3(-1, 0.5, 0), Vec3(2, 0, 0), 0.0, 1.0}, seg);
        CHECK(cross.hit);
        CHECK(cross.t == doctest::Approx(0.5));
        CHECK(cross.point.isApprox(Vec3(0, 0.5, 0)));
        CHECK_FALSE(intersectMovingPointCapsule({Vec3(-1, 0.5, 0x1p-60), Vec3(2, 0, 0), 0.0, 1.0}, seg).hit);
        CHECK(intersectMovingPointCapsule({Vec3(-1, 1, 0), Vec3(2, 0, 0), 0.0, 1.0}, seg).hit);  // through the end
        CHECK_FALSE(intersectMovingPointCapsule({Vec3(-1, 1 + 0x1p-52, 0), Vec3(2, 0, 0), 0.0, 1.0}, seg).hit);
        // Collinear motion along the segment: first contact at its near end.
        const MovingPointHit along = intersectMovingPointCapsule({Vec3(0, -3, 0), Vec3(0, 4, 0), 0.0, 1.0}, seg);
        CHECK(along.hit);
        CHECK(along.t == doctest::Approx(0.5));
        // Radius 0 and zero length: a point.
        CHECK(intersectMovingPointCapsule({Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.0, 2.0},
                                          Capsule{Vec3(0, 0, 0), Vec3(0, 0, 0), 0.0})
                  .t == doctest::Approx(1.0));
        // Grazing the cylinder side exactly (touching counts).
        const Capsule cap{Vec3(0, -1, 0), Vec3(0, 1, 0), 1.0};
        const MovingPointHit graze = intersectMovingPointCapsule({Vec3(-2, 0, 1), Vec3(1, 0, 0), 0.0, 5.0}, cap);
        CHECK(graze.hit);
        CHECK(graze.t == doctest::Approx(2.0));
        CHECK(graze.normal.isApprox(Vec3(0, 0, 1)));
        // Through the end sphere, starting inside, out of the time range.
        CHECK(intersectMovingPointCapsule({Vec3(0, 5, 0), Vec3(0, -1, 0), 0.0, 10.0}, cap).t == doctest::Approx(3.0));
        CHECK(intersectMovingPointCapsule({Vec3(0, 0, 0), Vec3(0, -1, 0), 0.0, 10.0}, cap).t == 0.0);
        CHECK(intersectMovingPointCapsule({Vec3(0, 5, 0), Vec3(0, -1, 0), 1.0, 10.0}, cap).t == doctest::Approx(3.0));
        CHECK(intersectMovingPointCapsule({Vec3(0, 0, 0), Vec3(0, -1, 0), 2.0, 10.0}, cap).t ==
              2.0);  // inside at tBegin
        CHECK_FALSE(intersectMovingPointCapsule({Vec3(0, 5, 0), Vec3(0, -1, 0), 0.0, 2.9}, cap).hit);
        // Sphere: zero velocity, inside and outside; tBegin > tEnd; NaN; negative radius.
        const Sphere sph{Vec3(0, 0, 0), 1.0};
        CHECK(intersectMovingPointSphere({Vec3(0.5, 0, 0), Vec3(0, 0, 0), 0.0, 1.0}, sph).hit);
        CHECK_FALSE(intersectMovingPointSphere({Vec3(1.5, 0, 0), Vec3(0, 0, 0), 0.0, 1.0}, sph).hit);
        CHECK_FALSE(intersectMovingPointSphere({Vec3(-5, 0, 0), Vec3(10, 0, 0), 1.0, 0.0}, sph).hit);
        CHECK_FALSE(intersectMovingPointSphere({Vec3(-5, 0, 0), Vec3(std::nan(""), 0, 0), 0.0, 1.0}, sph).hit);
        CHECK_FALSE(
            intersectMovingPointSphere({Vec3(-5, 0, 0), Vec3(10, 0, 0), 0.0, 1.0}, Sphere{Vec3(0, 0, 0), -1.0}).hit);
        CHECK_FALSE(intersectMovingPointCapsule({Vec3(-5, 0, 0), Vec3(10, 0, 0), 0.0, 1.0},
                                                Capsule{Vec3(0, 0, 0), Vec3(0, 1, 0), -1.0})
                        .hit);
        CHECK(intersectMovingPointSphere({Vec3(-5, 0, 0), Vec3(10, 0, 0), 0.0, 1.0}, Sphere{Vec3(0, 0, 0), 0.0}).t ==
              doctest::Approx(0.5));
        // Triangle: moving within its plane, touching an edge at t = 1, degenerate triangle.
        const Triangle tri{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
        const MovingPointHit inPlane = intersectMovingPointTriangle({Vec3(-1, 0.5, 0), Vec3(1, 0, 0), 0.0, 3.0}, tri);
        CHECK(inPlane.hit);
        CHECK(inPlane.t == doctest::Approx(1.0));
        CHECK(intersectMovingPointTriangle({Vec3(1, 1, 1), Vec3(0, 0, -1), 0.0, 1.0}, tri).t == 1.0);
        CHECK_FALSE(intersectMovingPointTriangle({Vec3(1, 1 + 0x1p-52, 1), Vec3(0, 0, -1), 0.0, 1.0}, tri).hit);
        CHECK_FALSE(intersectMovingPointTriangle({Vec3(1, 1, 1), Vec3(0, 0, -1), 0.0, 1.0},
                                                 Triangle{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)})
                        .hit);
    }
}
