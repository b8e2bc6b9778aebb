// Sphere tests (core/overlap/intersect_sphere.h). Oracles: long double distances (per-axis excess for
// boxes; plane-or-nearest-edge for triangles), clear cases only; exact touching by hand.
#include <doctest/doctest.h>

#include <limits>

#include "core/overlap/intersect_sphere.h"
#include "verification/intersection_oracles.h"

using namespace cdlab;
using oracle::LD;
using oracle::V3;

TEST_SUITE("intersect_sphere") {
    TEST_CASE("sphere-sphere against long double distance, exact touching") {
        oracle::Rng rng(1);
        for (double offset : {0.0, 1e4, 1e6}) {
            for (int n = 0; n < 2000; ++n) {
                const Sphere a{rng.vec(-2, 2) + Vec3::Constant(offset), rng.uniform(0, 1.5)};
                const Sphere b{rng.vec(-2, 2) + Vec3::Constant(offset), rng.uniform(0, 1.5)};
                const LD dist = oracle::norm(V3(b.center) - V3(a.center));
                const LD gap = dist - LD(a.radius) - LD(b.radius);
                if (std::abs(gap) < 1e-9 * (1 + offset)) continue;
                const SphereSphereResult r = intersectSphereSphere(a, b);
                REQUIRE(r.hit == (gap < 0));
                CHECK(std::abs(r.depth + double(gap)) < 1e-9 * (1 + offset));
                CHECK(r.normal.norm() == doctest::Approx(1.0));
                CHECK(intersectSphereSphere(b, a).hit == r.hit);
            }
        }
        CHECK(intersectSphereSphere({Vec3(0, 0, 0), 1}, {Vec3(3, 0, 0), 2}).hit);  // touching
        CHECK_FALSE(intersectSphereSphere({Vec3(0, 0, 0), 1}, {Vec3(3, 0, 0), 2.0 - 0x1p-51})
                        .hit);  // a sum exactly representable below 3
        const SphereSphereResult same = intersectSphereSphere({Vec3(1, 1, 1), 1}, {Vec3(1, 1, 1), 0});
        CHECK(same.hit);
        CHECK(same.normal == Vec3::UnitX());
        CHECK(intersectSphereSphere({Vec3(0, 0, 0), 0}, {Vec3(0, 0, 0), 0}).hit);  // two equal points
        CHECK_FALSE(intersectSphereSphere({Vec3(0, 0, 0), -1}, {Vec3(0, 0, 0), 2}).hit);
        CHECK_FALSE(intersectSphereSphere({Vec3(std::nan(""), 0, 0), 1}, {Vec3(0, 0, 0), 2}).hit);
    }

    TEST_CASE("sphere-AABB and sphere-OBB against long double box distance") {
        oracle::Rng rng(2);
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 2000; ++n) {
                const Vec3 c = rng.vec(-1, 1) + Vec3::Constant(offset), e = rng.vec(0, 1.5);
                const Aabb box{c - e, c + e};
                const Sphere s{rng.vec(-3, 3) + Vec3::Constant(offset), rng.uniform(0, 1.5)};
                const LD d = oracle::distPointBox(V3(s.center), V3(box.min), V3(box.max));
                if (std::abs(d - s.radius) < 1e-9 * (1 + offset)) continue;
                const SphereShapeResult r = intersectSphereAabb(s, box);
                REQUIRE(r.hit == (d < s.radius));
                CHECK(std::abs(std::sqrt(r.distanceSquared) - double(d)) < 1e-9 * (1 + offset));
                // The same box as an OBB rotated by R, the sphere center moved with it.
                const Mat3 R = rng.rotation().toRotationMatrix();
                const Obb obb{c, e, R};
                const Sphere moved{c + R * (s.center - c), s.radius};
                if (std::abs(d - s.radius) > 1e-7 * (1 + offset)) CHECK(intersectSphereObb(moved, obb).hit == r.hit);
            }
        }
        const Aabb unit{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        CHECK(intersectSphereAabb({Vec3(2, 0.5, 0.5), 1.0}, unit).hit);  // touching a face
        CHECK(intersectSphereAabb({Vec3(2, 1, 1), 1.0}, unit).hit);      // touching an edge
        CHECK_FALSE(intersectSphereAabb({Vec3(2, 1, 1), std::nextafter(1.0, 0.0)}, unit).hit);
        CHECK(intersectSphereAabb({Vec3(0.5, 0.5, 0.5), 0.0}, unit).hit);  // point inside
        CHECK_FALSE(intersectSphereAabb({Vec3(0, 0, 0), 1.0}, Aabb{Vec3(1, 0, 0), Vec3(0, 1, 1)}).hit);
        CHECK_FALSE(intersectSphereObb({Vec3(0, 0, 0), 1.0}, Obb{Vec3(0, 0, 0), Vec3(-1, 1, 1), Mat3::Identity()}).hit);
    }

    TEST_CASE("sphere-triangle against plane-or-edge distance, every vertex order") {
        oracle::Rng rng(3);
        int hits = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 1500; ++n) {
                const Vec3 shift = Vec3::Constant(offset);
                const Triangle tri{rng.vec(-1, 1) + shift, rng.vec(-1, 1) + shift, rng.vec(-1, 1) + shift};
                const Sphere s{rng.vec(-1.5, 1.5) + shift, rng.uniform(0, 1)};
                const LD d = oracle::distPointTriangle(V3(s.center), V3(tri.a), V3(tri.b), V3(tri.c));
                if (std::abs(d - s.radius) < 1e-8 * (1 + offset)) continue;
                for (const Triangle& perm : oracle::orderings(tri)) {
                    const SphereShapeResult r = intersectSphereTriangle(s, perm);
                    REQUIRE(r.hit == (d < s.radius));
                    CHECK(std::abs(std::sqrt(r.distanceSquared) - double(d)) < 1e-8 * (1 + offset));
                }
                hits += d < s.radius;
            }
        }
        CHECK(hits > 300);
        // Touching at a vertex, an edge and the face; degenerate triangles.
        const Triangle tri{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
        CHECK(intersectSphereTriangle({Vec3(0.5, 0.5, 1), 1.0}, tri).hit);
        CHECK_FALSE(intersectSphereTriangle({Vec3(0.5, 0.5, 1), std::nextafter(1.0, 0.0)}, tri).hit);
        CHECK(intersectSphereTriangle({Vec3(-1, -1, 0), std::sqrt(2.0)}, tri).hit);
        CHECK(intersectSphereTriangle({Vec3(1, -1, 0), 1.0}, tri).hit);
        const Triangle line{Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)};
        CHECK(intersectSphereTriangle({Vec3(1, 1, 1.5), 0.5}, line).hit);
        CHECK_FALSE(intersectSphereTriangle({Vec3(3, 3, 3), 1.0}, line).hit);
        const Triangle point{Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
        CHECK(intersectSphereTriangle({Vec3(1, 1, 2), 1.0}, point).hit);
        CHECK_FALSE(
            intersectSphereTriangle({Vec3(1, 1, 2), 1.0}, Triangle{Vec3(std::nan(""), 0, 0), tri.b, tri.c}).hit);
    }
}
