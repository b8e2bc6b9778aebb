// Support mappings. Oracles: dense samples of each shape (the support value must reach the sampled
// maximum of d · x) plus an analytic membership test (the support point must belong to the shape,
// so its value cannot exceed the true maximum); brute-force vertex maxima for polytopes.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "core/geometry/polyhedron.h"
#include "core/geometry/polyhedron_presets.h"
#include "core/geometry/shapes.h"

using namespace cdlab;
using presets::SplitMix64;

static_assert(SupportMapping<PointShape>);
static_assert(SupportMapping<SegmentShape>);
static_assert(SupportMapping<TriangleShape>);
static_assert(SupportMapping<SphereShape>);
static_assert(SupportMapping<BoxShape>);
static_assert(SupportMapping<CapsuleShape>);
static_assert(SupportMapping<CylinderShape>);
static_assert(SupportMapping<ConeShape>);
static_assert(SupportMapping<PolytopeShape>);
static_assert(SupportMapping<Transformed<BoxShape>>);
static_assert(SupportMapping<MinkowskiSum<SphereShape, TriangleShape>>);
static_assert(SupportMapping<RoundedShape<Transformed<PolytopeShape>>>);

namespace {

std::vector<Vec3> directions(int n, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> d;
    for (int i = 0; i < n; ++i) d.push_back(rng.onUnitSphere() * std::pow(10.0, rng.uniform(-3, 3)));
    for (int i = 0; i < 3; ++i)
        for (double s : {-1.0, 1.0}) {
            Vec3 a = Vec3::Zero();
            a[i] = s;
            d.push_back(a);  // axis directions: tie cases for boxes, cylinders, polytopes
        }
    d.push_back(Vec3(1, 1, 0));
    d.push_back(Vec3(0, -1, 1));
    return d;
}

// Checks support(d) against samples: value >= max sample value - tol, point is in the shape.
template <class S>
void checkAgainstSamples(const S& shape, const std::vector<Vec3>& samples,
                         const std::function<bool(const Vec3&)>& contains, double tol) {
    for (const Vec3& d : directions(300, 17)) {
        const Vec3 s = shape.support(d);
        REQUIRE(s.allFinite());
        double best = -std::numeric_limits<double>::infinity();
        for (const Vec3& x : samples) best = std::max(best, d.dot(x));
        CHECK(d.dot(s) >= best - tol * d.norm());
        CHECK(contains(s));
    }
}

std::vector<Vec3> ballSamples(int n, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> s;
    for (int i = 0; i < n; ++i) s.push_back(rng.onUnitSphere());
    return s;
}

double segmentDistance(const Vec3& x, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (x - a - t * ab).norm();
}

}  // namespace

TEST_SUITE("shapes") {
    TEST_CASE("primitive supports vs dense samples and membership") {
        const double tolSample = 2e-3;  // sampling density: a few thousand points per surface
        {
            const PointShape p{Vec3(1, -2, 3)};
            checkAgainstSamples(
                p, {p.point}, [&](const Vec3& x) { return x == p.point; }, 0.0);
        }
        {
            const SegmentShape s{Vec3(1, 2, 3), Vec3(-2, 0.5, 1)};
            std::vector<Vec3> smp;
            for (int i = 0; i <= 100; ++i) smp.push_back(s.a + (s.b - s.a) * (i / 100.0));
            checkAgainstSamples(
                s, smp, [&](const Vec3& x) { return x == s.a || x == s.b; }, 0.0);
        }
        {
            const TriangleShape t{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 1)};
            checkAgainstSamples(
                t, {t.a, t.b, t.c}, [&](const Vec3& x) { return x == t.a || x == t.b || x == t.c; }, 0.0);
        }
        {
            const SphereShape s{1.5};
            std::vector<Vec3> smp = ballSamples(20000, 3);
            for (Vec3& x : smp) x *= s.radius;
            checkAgainstSamples(
                s, smp, [&](const Vec3& x) { return x.norm() <= s.radius * (1 + 1e-14); }, tolSample);
        }
        {
            const BoxShape b{Vec3(0.5, 1.0, 2.0)};
            std::vector<Vec3> smp;
            for (int i = 0; i < 8; ++i)
                smp.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 1.0 : -1.0, (i & 4) ? 2.0 : -2.0);
            checkAgainstSamples(
                b, smp, [&](const Vec3& x) { return (x.cwiseAbs() - b.halfExtents).maxCoeff() <= 0; }, 0.0);
        }
        {
            const CapsuleShape c{Vec3(0, -1, 0.5), Vec3(1, 1, 0), 0.3};
            std::vector<Vec3> smp;
            for (const Vec3& u : ballSamples(20000, 4)) {
                smp.push_back(c.a + c.radius * u);
                smp.push_back(c.b + c.radius * u);
            }
            checkAgainstSamples(
                c, smp, [&](const Vec3& x) { return segmentDistance(x, c.a, c.b) <= c.radius * (1 + 1e-12); },
                tolSample);
            const CapsuleShape y = CapsuleShape::alongY(2.0, 0.5);
            CHECK(y.support(Vec3(0, 1, 0)).isApprox(Vec3(0, 2.5, 0)));
        }
        {
            const CylinderShape c{0.75, 1.25};
            std::vector<Vec3> smp;
            for (int i = 0; i < 4000; ++i) {
                const double a = 2 * std::numbers::pi * i / 4000;
                for (double y : {-c.halfHeight, c.halfHeight})
                    smp.emplace_back(c.radius * std::cos(a), y, c.radius * std::sin(a));
            }
            checkAgainstSamples(
                c, smp,
                [&](const Vec3& x) {
                    return std::abs(x.y()) <= c.halfHeight && std::hypot(x.x(), x.z()) <= c.radius * (1 + 1e-14);
                },
                tolSample);
        }
        {
            const ConeShape c{1.0, 0.6};
            std::vector<Vec3> smp{Vec3(0, c.halfHeight, 0)};
            for (int i = 0; i < 4000; ++i) {
                const double a = 2 * std::numbers::pi * i / 4000;
                smp.emplace_back(c.radius * std::cos(a), -c.halfHeight, c.radius * std::sin(a));
            }
            checkAgainstSamples(
                c, smp,
                [&](const Vec3& x) {
                    const double t = (c.halfHeight - x.y()) / (2 * c.halfHeight);  // 0 at apex, 1 at base
                    return t >= -1e-15 && t <= 1 + 1e-15 &&
                           std::hypot(x.x(), x.z()) <= c.radius * t * (1 + 1e-12) + 1e-15;
                },
                tolSample);
        }
    }

    TEST_CASE("zero, tiny, huge and NaN directions give finite points") {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const Vec3 dirs[] = {Vec3::Zero(), Vec3(1e-310, 0, 0), Vec3(0, -1e300, 1e300), Vec3(nan, 0, 1),
                             Vec3(std::numeric_limits<double>::infinity(), 0, 0)};
        const PolytopeShape poly(presets::randomHull(200, 5));
        for (const Vec3& d : dirs) {
            CHECK(SphereShape{2.0}.support(d).allFinite());
            CHECK(BoxShape{}.support(d).allFinite());
            CHECK(CapsuleShape{}.support(d).allFinite());
            CHECK(CylinderShape{}.support(d).allFinite());
            CHECK(ConeShape{}.support(d).allFinite());
            CHECK(poly.support(d).allFinite());
            CHECK(RoundedShape<BoxShape>{BoxShape{}, 0.1}.support(d).allFinite());
        }
        CHECK(SphereShape{2.0}.support(Vec3(1e-310, 0, 0)).isApprox(Vec3(2, 0, 0)));
        CHECK(SphereShape{2.0}.support(Vec3(0, -1e300, 0)).isApprox(Vec3(0, -2, 0)));
        CHECK(poly.supportIndex(Vec3::Zero()) == 0);
        CHECK(poly.supportIndexLoop(Vec3::Zero()) == 0);
    }

    TEST_CASE("polytope: loop and hill climbing equal the brute-force maximum over vertices") {
        for (int n : {8, 20, 100, 2000}) {
            for (auto kind : {presets::RandomHullKind::OnSphere, presets::RandomHullKind::InBall}) {
                const ConvexPolyhedron hull = presets::randomHull(n, 1000 + n, kind, 2.0);
                const PolytopeShape shape(hull);
                REQUIRE(shape.vertexCount() == hull.vertexCount());
                CAPTURE(n);
                SplitMix64 rng(n);
                for (const Vec3& d : directions(400, 99)) {
                    int brute = 0;
                    for (int i = 1; i < hull.vertexCount(); ++i)
                        if (d.dot(hull.position(i)) > d.dot(hull.position(brute))) brute = i;
                    CHECK(shape.supportIndexLoop(d) == brute);
                    CHECK(shape.supportIndex(d) == brute);
                    const int climbed = shape.supportIndexClimb(d, -1);
                    CHECK(d.dot(shape.vertex(climbed)) == d.dot(hull.position(brute)));
                    // Warm start from a random vertex reaches the same maximum.
                    const int start = static_cast<int>(rng.next() % static_cast<std::uint64_t>(shape.vertexCount()));
                    CHECK(d.dot(shape.vertex(shape.supportIndex(d, start))) == d.dot(hull.position(brute)));
                }
            }
        }
    }

    TEST_CASE("polytope ties: boxes, prisms and geodesic spheres along axes") {
        // Plateaus: a box face along an axis (4 equal vertices), a 40-gon cap (40 equal vertices) and a
        // 200-gon cap (larger than the plateau buffer: falls back to the loop).
        const ConvexPolyhedron meshes[] = {presets::box(Vec3(1, 2, 3)), presets::prism(40, 1.0, 1.0),
                                           presets::prism(200, 1.0, 1.0), presets::geodesicSphere(3)};
        for (const ConvexPolyhedron& m : meshes) {
            const PolytopeShape shape(m);
            for (const Vec3& d : directions(200, 5)) {
                const int loop = shape.supportIndexLoop(d);
                for (int start = 0; start < shape.vertexCount(); start += 7) {
                    const int climb = shape.supportIndexClimb(d, start);
                    CHECK(d.dot(shape.vertex(climb)) == d.dot(shape.vertex(loop)));
                    CHECK(climb == loop);  // the plateau's lowest index = the loop's first maximum
                }
            }
        }
    }

    TEST_CASE("polytope without adjacency and empty polytope") {
        const PolytopeShape pts(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
        CHECK(!pts.hasAdjacency());
        CHECK(pts.supportIndex(Vec3(1, 0, 0)) == 1);  // first of the duplicated maxima
        CHECK(pts.supportIndex(Vec3(1, 0, 0), 3) == 1);
        const PolytopeShape empty;
        CHECK(empty.supportIndex(Vec3(1, 0, 0)) == -1);
        CHECK(empty.support(Vec3(1, 0, 0)) == Vec3::Zero());
        const PolytopeShape flat(presets::regularPolygon(6, 1.0));  // a flat hexagon
        CHECK(flat.support(Vec3(1, 0, 0)).isApprox(Vec3(1, 0, 0)));
    }

    TEST_CASE("Transformed: support equals transformed samples, at offsets up to 1e6") {
        const BoxShape box{Vec3(0.5, 1.0, 0.25)};
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i)
            corners.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 1.0 : -1.0, (i & 4) ? 0.25 : -0.25);
        for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(1e4, 2e4, -3e4), Vec3(1e6, -1e6, 1e6)}) {
            Transform T;
            T.position = offset;
            T.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
            const Transformed<BoxShape> shape{box, T};
            for (const Vec3& d : directions(200, 8)) {
                double best = -1e300;
                for (const Vec3& c : corners) best = std::max(best, d.dot(T.apply(c)));
                const Vec3 s = shape.support(d);
                // Both sides are computed at |x| ~ |offset|: allow a few ulps of that magnitude.
                CHECK(std::abs(d.dot(s) - best) <= 1e-15 * d.norm() * (offset.norm() + 2) * 8);
                CHECK((T.applyInverse(s).cwiseAbs() - box.halfExtents).maxCoeff() <=
                      1e-9 * (offset.norm() + 1) * 1e-6 + 1e-9);
            }
            const ShapeBounds b = supportBounds(shape);
            for (const Vec3& c : corners) {
                CHECK((T.apply(c) - b.min).minCoeff() >= -1e-9);
                CHECK((b.max - T.apply(c)).minCoeff() >= -1e-9);
            }
            CHECK(shape.boundingRadius() >= (T.apply(corners[7])).norm() - 1e-6);
        }
    }

    TEST_CASE("MinkowskiSum and RoundedShape: values add, cores and margins reproduce support") {
        const TriangleShape tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        const SphereShape ball{0.25};
        const MinkowskiSum<TriangleShape, SphereShape> sum{tri, ball};
        const RoundedShape<TriangleShape> rounded{tri, 0.25};
        Transform T;
        T.position = Vec3(3, -1, 2);
        T.rotation = Quat(Eigen::AngleAxisd(1.1, Vec3(0, 1, 1).normalized()));
        const RoundedShape<Transformed<PolytopeShape>> roundedPoly{{PolytopeShape(presets::randomHull(100, 3)), T},
                                                                   0.5};
        // Samples of the rounded triangle: vertices plus sphere samples.
        std::vector<Vec3> smp;
        for (const Vec3& u : ballSamples(5000, 6))
            for (const Vec3& v : {tri.a, tri.b, tri.c}) smp.push_back(v + 0.25 * u);
        for (const Vec3& d : directions(200, 12)) {
            double best = -1e300;
            for (const Vec3& x : smp) best = std::max(best, d.dot(x));
            CHECK(d.dot(sum.support(d)) >= best - 2e-3 * d.norm());
            CHECK(d.dot(sum.support(d)) == doctest::Approx(d.dot(tri.support(d)) + 0.25 * d.norm()));
            CHECK(sum.support(d).isApprox(rounded.support(d)));
            const Vec3 u = d.normalized();
            CHECK((sum.supportCore(d) + sum.margin() * u).isApprox(sum.support(d)));
            CHECK((roundedPoly.supportCore(d) + roundedPoly.margin() * u).isApprox(roundedPoly.support(d)));
            CHECK((coreSupport(ball, d)).norm() == 0.0);
            CHECK((CapsuleShape{}.supportCore(d) + 0.5 * u).isApprox(CapsuleShape{}.support(d)));
        }
        CHECK(rounded.margin() == 0.25);
        CHECK(sum.margin() == 0.25);
        CHECK(marginOf(RoundedShape<SphereShape>{SphereShape{1.0}, 0.5}) == 1.5);
        CHECK(&rounded.core() == &rounded.inner);
    }

    TEST_CASE("bounding radius contains the support in every direction") {
        const PolytopeShape poly(presets::randomHull(300, 8, presets::RandomHullKind::InBall, 2.0));
        for (const Vec3& d : directions(300, 21)) {
            CHECK(SphereShape{1.5}.support(d).norm() <= SphereShape{1.5}.boundingRadius() + 1e-12);
            CHECK(BoxShape{Vec3(1, 2, 3)}.support(d).norm() <= BoxShape{Vec3(1, 2, 3)}.boundingRadius() + 1e-12);
            CHECK(CapsuleShape{}.support(d).norm() <= CapsuleShape{}.boundingRadius() + 1e-12);
            CHECK(CylinderShape{}.support(d).norm() <= CylinderShape{}.boundingRadius() + 1e-12);
            CHECK(ConeShape{}.support(d).norm() <= ConeShape{}.boundingRadius() + 1e-12);
            CHECK(poly.support(d).norm() <= poly.boundingRadius() + 1e-12);
        }
    }

}  // TEST_SUITE
