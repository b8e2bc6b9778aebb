// SSV overlap tests and the rectangle-rectangle distance (core/bounding/swept_sphere_overlap.h).
// Oracle, sharing no code with core/: the core distance minimized in long double by nested
// ternary search over one core's parameters (the distance from a point of an affine family to a
// convex set is convex in the parameters, so ternary search converges to the minimum), the
// inner distance from a point to the other core computed directly (clamped projection).
#include <doctest/doctest.h>

#include <limits>

#include "core/bounding/swept_sphere_overlap.h"
#include "verification/bounding_volume_oracle.h"

using namespace cdlab;
using bvoracle::LD;
using bvoracle::V;

namespace {

template <class F>
LD minimize01(F f, int iterations) {
    LD lo = -1, hi = 1;  // parameters in [-1, 1]
    for (int i = 0; i < iterations; ++i) {
        const LD m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) <= f(m2)) hi = m2;
        else lo = m1;
    }
    return std::min({f(lo), f(hi), f(LD(-1)), f(LD(1))});
}

// Long double rectangle: center, unit axes u, v (from the stored axes), half lengths.
struct LRect {
    V c, u, v;
    LD a, b;
    explicit LRect(const Rss& r)
        : c(r.center), u(Vec3(r.axes.col(0))), v(Vec3(r.axes.col(1))), a(r.halfLengths.x()), b(r.halfLengths.y()) {}
    V at(LD s, LD t) const { return c + u * (a * s) + v * (b * t); }
};

// Distance from p to the solid rectangle r by nested ternary search (independent of the
// clamped-projection formula in core/).
LD pointRectDistance(const V& p, const LRect& r) {
    return minimize01([&](LD s) { return minimize01([&](LD t) { return bvoracle::norm(p - r.at(s, t)); }, 60); }, 60);
}

// Rectangle-rectangle distance: minimize over A's parameters the distance from A's point to B,
// the latter by the clamped projection in long double (exact for orthonormal axes).
LD rectRectDistance(const Rss& ra, const Rss& rb) {
    const LRect a(ra), b(rb);
    auto toB = [&](const V& p) {
        const V d = p - b.c;
        const LD s = std::clamp(bvoracle::dot(d, b.u), -b.a, b.a), t = std::clamp(bvoracle::dot(d, b.v), -b.b, b.b);
        return bvoracle::norm(p - (b.c + b.u * s + b.v * t));
    };
    return minimize01([&](LD s) { return minimize01([&](LD t) { return toB(a.at(s, t)); }, 70); }, 70);
}

LD segSegDistance(const Capsule& a, const Capsule& b) {
    const V a0(a.a), a1(a.b), b0(b.a), b1(b.b);
    return minimize01([&](LD s) { return bvoracle::distPointSegment(a0 + (a1 - a0) * ((s + 1) / 2), b0, b1); }, 120);
}

Rss randomRss(std::mt19937& rng, double scale, const Vec3& offset) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Rss r;
    r.center = offset + scale * Vec3(u(rng), u(rng), u(rng)) * 2.0;
    r.axes = bvoracle::randomRotation(rng).toRotationMatrix();
    r.halfLengths = scale * Vec2(u(rng), u(rng));
    r.radius = scale * 0.2 * u(rng);
    return r;
}

}  // namespace

TEST_SUITE("swept_sphere_overlap") {
    TEST_CASE("rectangle-rectangle distance equals the long double minimization") {
        std::mt19937 rng(60);
        int touching = 0;
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4}) {
                for (int rep = 0; rep < 40; ++rep) {
                    const Rss a = randomRss(rng, scale, Vec3::Constant(offset));
                    const Rss b = randomRss(rng, scale, Vec3::Constant(offset));
                    const RectangleDistanceResult d = distanceRectangleRectangle(a, b);
                    const LD truth = rectRectDistance(a, b);
                    // Ternary search converges to ~1e-12 of the scale (70 steps of 2/3 on [-1, 1]
                    // leave 1e-12 in the parameter); at offset 1e4 the stored corners carry
                    // 1e-12 absolute rounding.
                    CHECK(std::abs(LD(d.distance) - truth) <= 1e-9L * scale + 1e-11L);
                    // The witnesses lie on their rectangles and realize the distance.
                    CHECK(std::abs((d.pointOnA - d.pointOnB).norm() - d.distance) <= 1e-12 * (scale + offset));
                    CHECK(pointRectDistance(V(d.pointOnA), LRect(a)) <= 1e-9L * scale + 1e-11L);
                    CHECK(pointRectDistance(V(d.pointOnB), LRect(b)) <= 1e-9L * scale + 1e-11L);
                    touching += d.distance == 0.0;
                }
            }
        }
        CHECK(touching > 10);  // the crossing branch was exercised
    }

    TEST_CASE("parallel and coplanar rectangles") {
        Rss a, b;
        a.halfLengths = Vec2(2, 1);
        b = a;
        b.center = Vec3(1, 0.5, 3);  // parallel, overlapping footprints: distance = plane gap
        CHECK(distanceRectangleRectangle(a, b).distance == doctest::Approx(3.0));
        b.center = Vec3(5, 0, 0);  // coplanar, side by side: gap 1
        CHECK(distanceRectangleRectangle(a, b).distance == doctest::Approx(1.0));
        b.center = Vec3(0.5, 0.2, 0);  // coplanar, overlapping
        CHECK(distanceRectangleRectangle(a, b).distance == 0.0);
        b.halfLengths = Vec2(0, 0);  // a point inside a
        CHECK(distanceRectangleRectangle(a, b).distance == 0.0);
        b.center = Vec3(0.5, 0.2, 2);  // a point above a
        CHECK(distanceRectangleRectangle(a, b).distance == doctest::Approx(2.0));
        // Crossing at right angles: an edge pierces.
        b.center = Vec3(0, 0, 0);
        b.halfLengths = Vec2(1, 1);
        b.axes = Eigen::AngleAxisd(0.5 * 3.14159265358979, Vec3::UnitX()).toRotationMatrix();
        const RectangleDistanceResult d = distanceRectangleRectangle(a, b);
        CHECK(d.distance == 0.0);
        CHECK(
            ((d.features == RectangleFeaturePair::EdgeCrossesA) || (d.features == RectangleFeaturePair::EdgeCrossesB)));
    }

    TEST_CASE("RSS, LSS, PSS overlap agree with the long double core distance") {
        std::mt19937 rng(61);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int hits = 0, misses = 0;
        for (int rep = 0; rep < 200; ++rep) {
            const double scale = std::pow(10.0, std::uniform_int_distribution<int>(-3, 3)(rng));
            const Vec3 offset = Vec3::Constant(rep % 2 ? 1e4 : 0.0);
            const Rss a = randomRss(rng, scale, offset), b = randomRss(rng, scale, offset);
            const SweptSphereOverlapResult r = testRssRss(a, b);
            const LD gap = rectRectDistance(a, b) - LD(a.radius) - LD(b.radius);
            const LD band = 1e-9L * scale + 1e-11L;  // oracle accuracy (see above)
            if (gap > band) CHECK_FALSE(r.hit);
            if (gap < -band) CHECK(r.hit);
            CHECK(std::abs(LD(r.separation) - gap) <= band);
            (r.hit ? hits : misses)++;

            const Capsule ca{offset + scale * Vec3(u(rng), u(rng), u(rng)),
                             offset + scale * Vec3(u(rng), u(rng), u(rng)), 0.2 * scale * u(rng)};
            const Capsule cb{offset + scale * Vec3(u(rng), u(rng), u(rng)),
                             offset + scale * Vec3(u(rng), u(rng), u(rng)), 0.2 * scale * u(rng)};
            const SweptSphereOverlapResult l = testLssLss(ca, cb);
            const LD lgap = segSegDistance(ca, cb) - LD(ca.radius) - LD(cb.radius);
            if (lgap > band) CHECK_FALSE(l.hit);
            if (lgap < -band) CHECK(l.hit);
            CHECK(std::abs(LD(l.separation) - lgap) <= band);

            const Sphere sa{ca.a, ca.radius}, sb{cb.a, cb.radius};
            const LD sgap = bvoracle::norm(V(sa.center) - V(sb.center)) - LD(sa.radius) - LD(sb.radius);
            const SweptSphereOverlapResult s = testPssPss(sa, sb);
            if (sgap > band) CHECK_FALSE(s.hit);
            if (sgap < -band) CHECK(s.hit);
        }
        CHECK(hits > 20);
        CHECK(misses > 20);
    }

    TEST_CASE("touching counts as a hit, invalid input gives no hit and NaN") {
        const Capsule a{Vec3(0, 0, 0), Vec3(1, 0, 0), 0.5};
        const Capsule b{Vec3(0, 1, 0), Vec3(1, 1, 0), 0.5};
        CHECK(testLssLss(a, b).hit);
        CHECK(testLssLss(a, b).separation == 0.0);
        CHECK(testPssPss(Sphere{Vec3::Zero(), 1.0}, Sphere{Vec3(2, 0, 0), 1.0}).hit);
        Rss ra, rb;
        ra.radius = rb.radius = 0.5;
        rb.center = Vec3(0, 0, 1);
        CHECK(testRssRss(ra, rb).hit);
        CHECK_FALSE(testLssLss(a, Capsule{Vec3(kNaN, 0, 0), Vec3::Zero(), 1.0}).hit);
        CHECK(std::isnan(testLssLss(a, Capsule{Vec3(kNaN, 0, 0), Vec3::Zero(), 1.0}).separation));
        CHECK_FALSE(testLssLss(a, Capsule{Vec3::Zero(), Vec3::Zero(), -1.0}).hit);
        Rss bad = ra;
        bad.center = Vec3(kNaN, 0, 0);
        CHECK_FALSE(testRssRss(ra, bad).hit);
        bad = ra;
        bad.radius = -1.0;
        CHECK_FALSE(testRssRss(ra, bad).hit);
        CHECK_FALSE(testPssPss(Sphere{Vec3::Zero(), -1.0}, Sphere{Vec3::Zero(), 1.0}).hit);
        CHECK(std::isnan(distanceRectangleRectangle(
                             ra, bad.radius < 0 ? Rss{Vec3::Constant(kNaN), Mat3::Identity(), Vec2::Zero(), 0} : ra)
                             .distance));
    }

}  // TEST_SUITE
