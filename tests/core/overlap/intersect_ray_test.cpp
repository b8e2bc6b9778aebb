// Ray / segment tests (core/overlap/intersect_ray.h). Oracles: long double distance functions with
// dense sampling + bisection along the ray for t, the long double closest approach for the
// boolean (clear cases only), hand-built exact cases for touching, parallel and -0.
#include <doctest/doctest.h>

#include <limits>

#include "core/overlap/intersect_ray.h"
#include "verification/intersection_oracles.h"

using namespace cdlab;
using oracle::LD;
using oracle::V3;

TEST_SUITE("intersect_ray") {
    TEST_CASE("ray-sphere and segment-sphere against sampling + bisection") {
        oracle::Rng rng(1);
        int hits = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 400; ++n) {
                const Vec3 shift = Vec3::Constant(offset);
                const Sphere s{rng.vec(-1, 1) + shift, rng.uniform(0.2, 2.0)};
                const Vec3 origin = rng.vec(-5, 5) + shift;
                // Aim near the sphere so that about half the rays hit.
                const Vec3 aim = s.center + rng.vec(-1.5, 1.5) * s.radius;
                const Ray ray{origin, (aim - origin).normalized() * rng.uniform(0.1, 3.0)};
                const V3 o(ray.origin), d(ray.direction), c(s.center);
                auto inside = [&](LD t) { return oracle::norm(o + d * t - c) <= LD(s.radius); };
                // Closest approach of the ray (long double).
                const LD tc = std::max<LD>(0, oracle::dot(c - o, d) / oracle::dot(d, d));
                const LD dmin = oracle::norm(o + d * tc - c);
                const RayHit hit = intersectRaySphere(ray, s);
                if (std::abs(dmin - s.radius) < 1e-6) continue;  // grazing: exact cases below
                REQUIRE(hit.hit == (dmin < s.radius));
                if (!hit.hit) continue;
                ++hits;
                const LD t = oracle::firstInside(inside, tc + 1, 2000);
                CHECK(std::abs(hit.t - double(t)) < 1e-7 * (1 + offset));
                CHECK((hit.point - ray.at(hit.t)).norm() < 1e-9 * (1 + offset));
                // Segment a -> b = the ray's first 2 units.
                const Segment seg{ray.origin, ray.at(2.0)};
                const RayHit sh = intersectSegmentSphere(seg, s);
                if (std::abs(t - 2) > 1e-6) {
                    REQUIRE(sh.hit == (t <= 2));
                    if (sh.hit) CHECK(std::abs(sh.t - double(t) / 2) < 1e-7 * (1 + offset));
                }
            }
        }
        CHECK(hits > 100);
    }

    TEST_CASE("ray-sphere exact cases: inside, tangent, zero radius, degenerate") {
        const Sphere s{Vec3(0, 0, 0), 1.0};
        CHECK(intersectRaySphere({Vec3(0, 0, 0), Vec3(1, 0, 0)}, s).t == 0.0);  // inside: t = 0
        CHECK(intersectRaySphere({Vec3(1, 0, 0), Vec3(1, 0, 0)}, s).hit);       // on surface, leaving
        const RayHit tangent = intersectRaySphere({Vec3(-5, 1, 0), Vec3(1, 0, 0)}, s);
        CHECK(tangent.hit);
        CHECK(tangent.t == doctest::Approx(5.0));
        CHECK_FALSE(intersectRaySphere({Vec3(-5, 1.0000001, 0), Vec3(1, 0, 0)}, s).hit);
        CHECK_FALSE(intersectRaySphere({Vec3(5, 0, 0), Vec3(1, 0, 0)}, s).hit);                   // behind
        CHECK(intersectRaySphere({Vec3(-5, 0, 0), Vec3(2, 0, 0)}, s).t == doctest::Approx(2.0));  // non-unit
        CHECK(intersectRaySphere({Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Sphere{Vec3(0, 0, 0), 0.0}).hit);
        CHECK_FALSE(intersectRaySphere({Vec3(-5, 0, 0), Vec3(0, 0, 0)}, s).hit);  // zero direction
        CHECK_FALSE(intersectRaySphere({Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Sphere{Vec3(0, 0, 0), -1.0}).hit);
        CHECK_FALSE(intersectRaySphere({Vec3(kNaN, 0, 0), Vec3(1, 0, 0)}, s).hit);
        CHECK_FALSE(intersectRaySphere({Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Sphere{Vec3(0, 0, 0), kNaN}).hit);
        // Degenerate segment = point.
        CHECK(intersectSegmentSphere({Vec3(0.5, 0, 0), Vec3(0.5, 0, 0)}, s).hit);
        CHECK_FALSE(intersectSegmentSphere({Vec3(1.5, 0, 0), Vec3(1.5, 0, 0)}, s).hit);
        CHECK_FALSE(intersectSegmentSphere({Vec3(-5, 0, 0), Vec3(-1.0000001, 0, 0)}, s).hit);
        CHECK(intersectSegmentSphere({Vec3(-5, 0, 0), Vec3(-1, 0, 0)}, s).t == 1.0);
    }

    TEST_CASE("ray-sphere quadratic trace: the line's two crossings and the outcome") {
        oracle::Rng rng(11);
        int both = 0;
        for (int n = 0; n < 500; ++n) {
            const Sphere s{rng.vec(-1, 1), rng.uniform(0.2, 2.0)};
            const Vec3 origin = rng.vec(-5, 5);
            const Ray ray{origin, (s.center + rng.vec(-1.5, 1.5) * s.radius - origin) * rng.uniform(0.1, 3.0)};
            SphereQuadraticTrace q;
            const RayHit hit = intersectRaySphere(ray, s, &q);
            // Oracle: the line's crossings in long double from the closest approach (a different formula).
            const V3 o(ray.origin), d(ray.direction), c(s.center);
            const LD tc = oracle::dot(c - o, d) / oracle::dot(d, d);
            const LD dmin = oracle::norm(o + d * tc - c);
            if (std::abs(dmin - s.radius) < 1e-6) continue;
            REQUIRE(q.rootsValid == (dmin < s.radius));
            if (q.rootsValid) {
                ++both;
                const LD half = std::sqrt(LD(s.radius) * s.radius - dmin * dmin) / oracle::norm(d);
                CHECK(std::abs(q.t0 - double(tc - half)) < 1e-9 * (1 + std::abs(double(tc))));
                CHECK(std::abs(q.t1 - double(tc + half)) < 1e-9 * (1 + std::abs(double(tc))));
            }
            // The outcome names why: inside (t0 <= 0 <= t1), behind, miss or hit at t0.
            using O = SphereQuadraticTrace::Outcome;
            if (q.outcome == O::Hit) CHECK((hit.hit && hit.t == doctest::Approx(q.t0)));
            if (q.outcome == O::StartsInside) CHECK((hit.hit && hit.t == 0.0 && q.t0 <= 1e-12 && q.t1 >= -1e-12));
            if (q.outcome == O::PointsAway || q.outcome == O::NoRealRoot) CHECK_FALSE(hit.hit);
            if (q.outcome == O::PointsAway && q.rootsValid) CHECK(q.t1 < 0);
        }
        CHECK(both > 100);
        SphereQuadraticTrace q;
        CHECK_FALSE(intersectSegmentSphere({Vec3(-5, 0, 0), Vec3(-2, 0, 0)}, Sphere{Vec3(0, 0, 0), 1.0}, &q).hit);
        CHECK(q.outcome == SphereQuadraticTrace::Outcome::BeyondEnd);
        CHECK(q.t0 == doctest::Approx(4.0 / 3.0));
        CHECK_FALSE(intersectSegmentSphere({Vec3(5, 0, 0), Vec3(5, 0, 0)}, Sphere{Vec3(0, 0, 0), 1.0}, &q).hit);
        CHECK(q.outcome == SphereQuadraticTrace::Outcome::PointOutside);
        CHECK_FALSE(intersectRaySphere({Vec3(5, 0, 0), Vec3(0, 0, 0)}, Sphere{Vec3(0, 0, 0), 1.0}, &q).hit);
        CHECK(q.outcome == SphereQuadraticTrace::Outcome::Invalid);
    }

    TEST_CASE("ray-AABB slabs against sampling, including rays starting inside") {
        oracle::Rng rng(2);
        int hits = 0, insideStarts = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 500; ++n) {
                const Vec3 c = rng.vec(-1, 1) + Vec3::Constant(offset), e = rng.vec(0.1, 2);
                const Aabb box{c - e, c + e};
                const Vec3 origin = rng.vec(-4, 4) + Vec3::Constant(offset);
                Ray ray{origin, (c + rng.vec(-2, 2) - origin).normalized()};
                if (n % 5 == 0) ray.direction[n % 3] = (n % 2) ? 0.0 : -0.0;  // parallel to a slab
                const V3 lo(box.min), hi(box.max), o(ray.origin), d(ray.direction);
                auto inside = [&](LD t) { return oracle::distPointBox(o + d * t, lo, hi) == 0; };
                // Clear classification: the ray's min distance to the box (convex in t), and to the
                // box shrunk by 1e-6.
                auto minDist = [&](const V3& l, const V3& h) {
                    return oracle::minimizeConvex([&](LD s) { return oracle::distPointBox(o + d * (s * 20), l, h); });
                };
                const V3 eps(1e-6, 1e-6, 1e-6);
                const bool clearMiss = minDist(lo, hi) > 1e-6;
                const bool clearHit = minDist(lo + eps, hi - eps) == 0;
                if (!clearMiss && !clearHit) continue;
                const RayBoxHit hit = intersectRayAabb(ray, box);
                REQUIRE(hit.hit == clearHit);
                if (!hit.hit) continue;
                ++hits;
                insideStarts += hit.enterAxis < 0;
                const LD t = oracle::firstInside(inside, 20, 4000);
                CHECK(std::abs(hit.tEnter - double(t)) < 1e-6 * (1 + offset));
                CHECK(hit.tExit >= hit.tEnter);
                CHECK(oracle::distPointBox(V3(ray.at(hit.tExit)), lo, hi) < 1e-9 * (1 + offset));
                CHECK((hit.point.array() >= box.min.array()).all());
                CHECK((hit.point.array() <= box.max.array()).all());
            }
        }
        CHECK(hits > 100);
        CHECK(insideStarts > 10);
    }

    TEST_CASE("ray-AABB: +0 / -0 components, boundary starts, edges and corners") {
        const Aabb box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        for (double z : {0.0, -0.0}) {
            // Origin on the slab plane x = 0 with direction.x = +-0: inside the closed slab.
            const RayBoxHit h = intersectRayAabb({Vec3(0, 0.5, -1), Vec3(z, 0, 1)}, box);
            CHECK(h.hit);
            CHECK(h.tEnter == 1.0);
            CHECK(h.enterAxis == 2);
            CHECK(std::isfinite(h.tExit));
            CHECK(intersectRayAabb({Vec3(1, 1, -1), Vec3(z, z, 1)}, box).hit);  // along an edge
            CHECK_FALSE(intersectRayAabb({Vec3(1 + 1e-16 * 2, 0.5, -1), Vec3(z, 0, 1)}, box).hit);
            CHECK_FALSE(intersectRayAabb({Vec3(-1e-300, 0.5, -1), Vec3(z, 0, 1)}, box).hit);
        }
        // Start on the boundary, pointing out: t = 0.
        const RayBoxHit out = intersectRayAabb({Vec3(1, 0.5, 0.5), Vec3(1, 0, 0)}, box);
        CHECK(out.hit);
        CHECK(out.tEnter == 0.0);
        CHECK(out.tExit == 0.0);
        // Through a corner only.
        CHECK(intersectRayAabb({Vec3(-1, -1, -1), Vec3(1, 1, 1)}, box).tEnter == 1.0);
        CHECK(intersectRayAabb({Vec3(2, 0.5, 1), Vec3(-1, 0, -1)}, box).hit);  // grazes edge x=1,z=0
        CHECK_FALSE(intersectRayAabb({Vec3(2, 0.5, 1 - 1e-7), Vec3(-1, 0, -1)}, box).hit);
        // Degenerate: zero direction, NaN, empty box, flat box.
        CHECK_FALSE(intersectRayAabb({Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0)}, box).hit);
        CHECK_FALSE(intersectRayAabb({Vec3(0.5, 0.5, kNaN), Vec3(1, 0, 0)}, box).hit);
        CHECK_FALSE(intersectRayAabb({Vec3(-1, 0.5, 0.5), Vec3(kNaN, 0, 0)}, box).hit);
        CHECK_FALSE(intersectRayAabb({Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)}, Aabb{Vec3(1, 0, 0), Vec3(0, 1, 1)}).hit);
        CHECK(intersectRayAabb({Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)}, Aabb{Vec3(0, 0, 0), Vec3(0, 1, 1)}).hit);
        // Segment version and the trace.
        SlabTrace trace;
        CHECK_FALSE(intersectSegmentAabb({Vec3(-2, 0.5, 0.5), Vec3(-0.5, 0.5, 0.5)}, box, &trace).hit);
        REQUIRE(trace.steps.size() == 1);
        CHECK(trace.steps[0].rejected);
        CHECK(intersectSegmentAabb({Vec3(-2, 0.5, 0.5), Vec3(0, 0.5, 0.5)}, box).tEnter == 1.0);
        CHECK(intersectSegmentAabb({Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5)}, box).hit);
    }

    TEST_CASE("ray-plane and segment-plane") {
        const Plane p{Vec3(0, 0, 2), 2.0};  // z = 1, non-unit normal
        const RayHit h = intersectRayPlane({Vec3(0, 0, 5), Vec3(0, 0, -2)}, p);
        CHECK(h.hit);
        CHECK(h.t == 2.0);
        CHECK(h.point.z() == 1.0);
        CHECK_FALSE(intersectRayPlane({Vec3(0, 0, 5), Vec3(0, 0, 1)}, p).hit);
        CHECK(intersectRayPlane({Vec3(0, 0, 1), Vec3(1, 0, 0)}, p).hit);          // in the plane
        CHECK_FALSE(intersectRayPlane({Vec3(0, 0, 1.5), Vec3(1, 0, 0)}, p).hit);  // parallel
        CHECK_FALSE(intersectRayPlane({Vec3(0, 0, 5), Vec3(0, 0, -1)}, Plane{Vec3::Zero(), 0}).hit);
        CHECK(intersectSegmentPlane({Vec3(0, 0, 0), Vec3(0, 0, 1)}, p).t == 1.0);
        CHECK_FALSE(intersectSegmentPlane({Vec3(0, 0, 0), Vec3(0, 0, 0.999)}, p).hit);
        CHECK(intersectSegmentPlane({Vec3(3, 3, 1), Vec3(3, 3, 1)}, p).hit);
        CHECK_FALSE(intersectSegmentPlane({Vec3(0, 0, kNaN), Vec3(0, 0, 1)}, p).hit);
    }

    TEST_CASE("ray-triangle and segment-triangle against a long double oracle, every vertex order") {
        oracle::Rng rng(4);
        int hits = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 600; ++n) {
                const Vec3 shift = Vec3::Constant(offset);
                const Triangle tri{rng.vec(-1, 1) + shift, rng.vec(-1, 1) + shift, rng.vec(-1, 1) + shift};
                const Vec3 origin = rng.vec(-3, 3) + shift;
                const Vec3 aim = (tri.a + tri.b + tri.c) / 3.0 + rng.vec(-0.7, 0.7);
                const Ray ray{origin, (aim - origin).normalized()};
                // Oracle: plane crossing and signed area coordinates in long double.
                const V3 a(tri.a), b(tri.b), c(tri.c), o(ray.origin), d(ray.direction);
                const V3 nrm = oracle::cross(b - a, c - a);
                const LD dn = oracle::dot(d, nrm);
                if (std::abs(dn) < 1e-6) continue;
                const LD t = oracle::dot(a - o, nrm) / dn;
                const V3 x = o + d * t;
                const LD area = oracle::dot(nrm, nrm);
                const LD wa = oracle::dot(oracle::cross(b - x, c - x), nrm) / area;
                const LD wb = oracle::dot(oracle::cross(c - x, a - x), nrm) / area;
                const LD wc = 1 - wa - wb;
                const LD margin = std::min({wa, wb, wc, t});
                if (std::abs(margin) < 1e-7) continue;
                const bool expected = margin > 0;
                for (const Triangle& perm : oracle::orderings(tri)) {
                    const RayTriangleHit h = intersectRayTriangle(ray, perm);
                    REQUIRE(h.hit == expected);
                    if (!expected) continue;
                    CHECK(std::abs(h.t - double(t)) < 1e-9 * (1 + offset));
                    const Vec3 rebuilt =
                        h.barycentric.x() * perm.a + h.barycentric.y() * perm.b + h.barycentric.z() * perm.c;
                    CHECK((rebuilt - h.point).norm() < 1e-8 * (1 + offset));
                    // Single-sided: only front faces (d . n < 0 for this ordering).
                    const bool front = ((perm.b - perm.a).cross(perm.c - perm.a)).dot(ray.direction) < 0;
                    CHECK(intersectRayTriangle(ray, perm, {false}).hit == front);
                    CHECK(h.backFace == !front);
                    // Segment through the same points.
                    const Segment seg{ray.origin, ray.at(double(t) * 2)};
                    const RayTriangleHit sh = intersectSegmentTriangle(seg, perm);
                    REQUIRE(sh.hit);
                    CHECK(std::abs(sh.t - 0.5) < 1e-9 * (1 + offset));
                    CHECK_FALSE(intersectSegmentTriangle({ray.origin, ray.at(double(t) * 0.99)}, perm).hit);
                }
                hits += expected;
            }
        }
        CHECK(hits > 100);
    }

    TEST_CASE("ray-triangle is watertight: rays through a shared edge hit at least one triangle") {
        // Guard for the exact decision: with floating-point edge tests, rays crossing a planar
        // quad near its shared diagonal can miss both triangles. (The quad must be planar: over a
        // fold, a ray passing just outside the crease legitimately misses both.)
        oracle::Rng rng(6);
        for (double offset : {0.0, 1e4, 1e6}) {
            const Vec3 s = Vec3::Constant(offset);
            const Vec3 p0 = Vec3(0, 0, 0) + s, p1 = Vec3(1, 0.1, 0) + s, p2 = Vec3(1.1, 1, 0) + s,
                       p3 = Vec3(0, 1.05, 0) + s;
            const Triangle t1{p0, p1, p2}, t2{p0, p2, p3};
            int both = 0;
            for (int n = 0; n < 20000; ++n) {
                const double u = rng.uniform(0, 1);
                const Vec3 target = p0 + u * (p2 - p0);  // on the diagonal (rounded)
                const Vec3 origin = target + rng.unit() * 3.0;
                const Ray ray{origin, target - origin};
                const bool h1 = intersectRayTriangle(ray, t1).hit, h2 = intersectRayTriangle(ray, t2).hit;
                REQUIRE((h1 || h2));
                both += h1 && h2;
                const Segment seg{origin, origin + 2.0 * (target - origin)};
                REQUIRE((intersectSegmentTriangle(seg, t1).hit || intersectSegmentTriangle(seg, t2).hit));
            }
            // Through the shared vertex p0 exactly: both triangles.
            CHECK(intersectRayTriangle({p0 + Vec3(0.25, -0.125, 1), Vec3(-0.25, 0.125, -1)}, t1).hit);
            CHECK(intersectRayTriangle({p0 + Vec3(0.25, -0.125, 1), Vec3(-0.25, 0.125, -1)}, t2).hit);
            CHECK(both >= 0);
        }
    }

    TEST_CASE("ray-triangle touching, coplanar and degenerate cases") {
        const Triangle tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        // Through a vertex and an edge exactly.
        CHECK(intersectRayTriangle({Vec3(0, 0, 1), Vec3(0, 0, -1)}, tri).hit);
        CHECK(intersectRayTriangle({Vec3(0.5, 0.5, 1), Vec3(0, 0, -1)}, tri).hit);
        CHECK_FALSE(intersectRayTriangle({Vec3(0.5, 0.5 + 0x1p-53, 1), Vec3(0, 0, -1)}, tri).hit);
        // Origin on the triangle: t = 0.
        const RayTriangleHit on = intersectRayTriangle({Vec3(0.25, 0.25, 0), Vec3(0, 0, 1)}, tri);
        CHECK(on.hit);
        CHECK(on.t == 0.0);
        // Coplanar ray: hits where it enters the triangle in the plane.
        const RayTriangleHit cop = intersectRayTriangle({Vec3(-1, 0.25, 0), Vec3(1, 0, 0)}, tri);
        CHECK(cop.hit);
        CHECK(cop.coplanar);
        CHECK(cop.t == doctest::Approx(1.0));
        CHECK_FALSE(intersectRayTriangle({Vec3(-1, 0.25, 0), Vec3(-1, 0, 0)}, tri).hit);
        CHECK_FALSE(intersectRayTriangle({Vec3(-1, 0.25, 0), Vec3(1, 0, 0)}, tri, {false}).hit);
        CHECK_FALSE(intersectRayTriangle({Vec3(-1, 0.25, 1e-300), Vec3(1, 0, 0)}, tri).hit);
        // Coplanar segment: exact decision, first contact.
        const RayTriangleHit cs = intersectSegmentTriangle({Vec3(-1, 0.25, 0), Vec3(1, 0.25, 0)}, tri);
        CHECK(cs.hit);
        CHECK(cs.t == doctest::Approx(0.5));
        CHECK(intersectSegmentTriangle({Vec3(1, 1, 0), Vec3(0, 2, 0)},
                                       Triangle{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)})
                  .hit);
        CHECK_FALSE(intersectSegmentTriangle({Vec3(1, 1 + 0x1p-52, 0), Vec3(0, 2 + 0x1p-51, 0)},
                                             Triangle{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)})
                        .hit);
        // Segment ending exactly on the face.
        CHECK(intersectSegmentTriangle({Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0)}, tri).t == 1.0);
        // Degenerate: zero-area triangle, zero direction, NaN.
        const Triangle flat{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)};
        CHECK_FALSE(intersectRayTriangle({Vec3(1, 1, 1), Vec3(0, 0, -1)}, flat).hit);
        CHECK_FALSE(intersectSegmentTriangle({Vec3(1, 1, 1), Vec3(1, 1, -1)}, flat).hit);
        CHECK_FALSE(intersectRayTriangle({Vec3(0.2, 0.2, 1), Vec3(0, 0, 0)}, tri).hit);
        CHECK_FALSE(intersectRayTriangle({Vec3(0.2, 0.2, 1), Vec3(0, 0, kNaN)}, tri).hit);
        CHECK_FALSE(intersectSegmentTriangle({Vec3(0.2, 0.2, kNaN), Vec3(0.2, 0.2, -1)}, tri).hit);
        CHECK(intersectSegmentTriangle({Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 0)}, tri).hit);  // point on it
    }
}
