// Ray / segment quadratics far from the origin (issue 41): intersectRaySphere and the moving point
// against a capsule's cylinder side, against the exact closed forms of far_quadratic_oracle.h
// (integer inputs, __int128 and long double). Before the fix b² − a c lost r² to the rounding of
// |m|²: a unit sphere at 1e9 was hit at its centre.
#include <doctest/doctest.h>

#include "core/overlap/intersect_ray.h"
#include "core/overlap/moving_point.h"
#include "tests/core/overlap/far_quadratic_oracle.h"

using namespace cdlab;
using faroracle::LD;

TEST_SUITE("intersect_ray_far") {
    TEST_CASE("a unit sphere at 1e9 and 4e18: the entry, not the centre") {
        const RayHit h = intersectRaySphere(Ray{Vec3::Zero(), Vec3::UnitX()}, Sphere{Vec3(1e9, 0, 0), 1.0});
        REQUIRE(h.hit);
        CHECK(h.t == 999999999.0);
        // (1e9 − sqrt(1 − 0.25)) / 2e9 along a segment, the centre 0.5 off the line.
        const RayHit s = intersectSegmentSphere(Segment{Vec3::Zero(), Vec3(2e9, 0, 0)}, Sphere{Vec3(1e9, 0.5, 0), 1.0});
        REQUIRE(s.hit);
        CHECK(s.t == double((1e9L - std::sqrt(0.75L)) / 2e9L));
        const RayHit far = intersectRaySphere(Ray{Vec3(0, 0, 0), Vec3(1, 0, 0)}, Sphere{Vec3(4e18, 0, 0), 1.0});
        REQUIRE(far.hit);
        CHECK(far.t == double(4e18L - 1));
    }

    TEST_CASE("random far rays against unit spheres: within a few roundings of the exact entry") {
        std::mt19937_64 rng(41);
        int hits = 0;
        for (double distance : {1e9, 4e18}) {
            for (int i = 0; i < 400; ++i) {
                const faroracle::FarCase f = faroracle::farCase(rng, distance, 1);
                const double r = 1.0;
                LD t0, t1;
                const bool exact = faroracle::sphere(f.origin, f.direction, f.center, r, t0, t1);
                const RayHit h = intersectRaySphere(Ray{f.origin, f.direction}, Sphere{f.center, r});
                const LD halfChord = exact ? (t1 - t0) * LD(f.direction.norm()) / 2 : 0;
                if (!exact || halfChord < r / 4) continue;  // misses and grazes: conditioning, not this fix
                CAPTURE(i);
                CAPTURE(distance);
                REQUIRE(h.hit);
                ++hits;
                CHECK(faroracle::ulpsOf(h.t, t0, LD(distance) / LD(f.direction.norm())) <= 8);
            }
        }
        CHECK(hits > 100);
    }

    TEST_CASE("a moving point against a far capsule's side: the exact entry") {
        std::mt19937_64 rng(42);
        std::uniform_int_distribution<int> dir(-1000, 1000);
        int hits = 0;
        for (int i = 0; i < 400; ++i) {
            const faroracle::FarCase f = faroracle::farCase(rng, 1e9, 1);
            const Vec3 g(dir(rng), dir(rng), dir(rng));  // the axis, through the far centre
            // Across the path (over 30 degrees from it): the side, not an end sphere, is met first.
            if (g.norm() < 100 || g.cross(f.direction).norm() < 0.5 * g.norm() * f.direction.norm()) continue;
            const Capsule c{f.center - 4 * g, f.center + 4 * g, 1.0};
            // The path from the origin to twice the centre: t on the segment is the ray's t / 2.
            const MovingPoint m{f.origin, 2 * f.center - f.origin};
            LD t0, t1;
            if (!faroracle::cylinder(f.origin, 2 * f.center - f.origin, c.a, c.b, c.radius, t0, t1)) continue;
            const LD chord = (t1 - t0) * LD((2 * f.center - f.origin).norm());
            if (chord < 0.5) continue;  // grazing
            const MovingPointHit h = intersectMovingPointCapsule(m, c);
            CAPTURE(i);
            REQUIRE(h.hit);
            ++hits;
            CHECK(faroracle::ulpsOf(h.t, t0, 1.0L) <= 8);
        }
        CHECK(hits > 100);
    }
}
