// Voronoi-region geometry for drawing: the in-plane polygons tile the rectangle and every point
// of a region's polygon has its closest triangle point on that region's feature (long double
// brute force); boundary planes separate the regions they name; tetrahedron half-space regions
// tile space and agree with an exact BigInt region oracle.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/closest/voronoi_regions.h"
#include "verification/closest_oracle.h"
#include "tests/core/closest/closest_test_support.h"

using namespace cdlab;
using R = TriangleRegion;

namespace {

using cdlab::test::N;

double polygonArea(const std::vector<Vec3>& poly, const Vec3& normal, const Vec3& origin = Vec3::Zero()) {
    Vec3 sum = Vec3::Zero();
    for (size_t i = 0; i < poly.size(); ++i) sum += (poly[i] - origin).cross(poly[(i + 1) % poly.size()] - origin);
    return 0.5 * sum.dot(normal);  // > 0 for counterclockwise about normal
}

// Long double distance from p to the closure of a triangle feature.
long double featureDistance2(const Vec3& p, const Triangle& t, R r) {
    using oracle::L;
    switch (r) {
        case R::A: return (L(p) - L(t.a)).squaredNorm();
        case R::B: return (L(p) - L(t.b)).squaredNorm();
        case R::C: return (L(p) - L(t.c)).squaredNorm();
        case R::AB: return oracle::segmentDistance2(L(p), L(t.a), L(t.b));
        case R::BC: return oracle::segmentDistance2(L(p), L(t.b), L(t.c));
        case R::CA: return oracle::segmentDistance2(L(p), L(t.c), L(t.a));
        case R::ABC: return oracle::triangleDistance2(p, t.a, t.b, t.c);
    }
    return 0;
}

using cdlab::test::randomVec;

}  // namespace

TEST_SUITE("voronoi_regions") {
    TEST_CASE("clipConvexPolygon: a unit square cut along its diagonal") {
        const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
        const auto half = clipConvexPolygon(square, {Vec3(0, 0, 0), Vec3(-1, 1, 0)});  // keep y <= x
        CHECK(half.size() == 3);
        CHECK(polygonArea(half, Vec3::UnitZ()) == doctest::Approx(0.5));
        CHECK(clipConvexPolygon(square, {Vec3(0, 0, 5), Vec3(0, 0, 1)}).size() == 4);  // all kept
        CHECK(clipConvexPolygon(square, {Vec3(0, 0, -5), Vec3(0, 0, 1)}).empty());     // all cut
    }

    TEST_CASE("triangle: 7 in-plane regions tile the rectangle, each holds its feature's points") {
        std::mt19937_64 rng(21);
        for (int trial = 0; trial < 40; ++trial) {
            const Vec3 offset = (trial % 4 == 3) ? Vec3(1e4, -1e4, 2e4) : Vec3::Zero();
            const Triangle t{randomVec(rng, 1) + offset, randomVec(rng, 1) + offset, randomVec(rng, 1) + offset};
            const auto d = triangleVoronoiRegions({t, 0.75, 0.5});
            REQUIRE(d.valid);
            CHECK(std::abs(d.normal.norm() - 1.0) < 1e-12);
            CHECK(std::abs(d.normal.dot(t.b - t.a)) < 1e-9);
            const double rectArea = polygonArea({d.rectangle.begin(), d.rectangle.end()}, d.normal, t.a);
            CHECK(rectArea > 0.0);
            double total = 0.0;
            for (int k = 0; k < 7; ++k) {
                const auto& poly = d.regions[k];
                CHECK(static_cast<int>(poly.region) == k);
                const double area = polygonArea(poly.vertices, d.normal, t.a);
                CHECK(area >= -1e-9);  // counterclockwise (or empty)
                total += area;
                for (const Vec3& x : poly.vertices) CHECK(std::abs(d.normal.dot(x - t.a)) < 1e-9 * (1 + offset.norm()));
                // Random points of the polygon (convex combinations of its vertices): the closest
                // point of the triangle lies on this polygon's feature (brute force, long double).
                if (poly.vertices.size() < 3) continue;
                for (int s = 0; s < 20; ++s) {
                    std::uniform_real_distribution<double> w(0.0, 1.0);
                    Vec3 p = Vec3::Zero();
                    double sum = 0.0;
                    for (const Vec3& x : poly.vertices) {
                        const double wi = w(rng);
                        p += wi * (x - t.a);
                        sum += wi;
                    }
                    p = t.a + p / sum + (s % 2 ? 0.3 : -0.2) * d.normal;  // off the plane too: same region
                    const long double truth = oracle::triangleDistance2(p, t.a, t.b, t.c);
                    const long double mine = featureDistance2(p, t, poly.region);
                    CHECK(std::sqrt(mine) - std::sqrt(truth) <= 1e-9L * (1 + offset.norm()));
                }
            }
            CHECK(total == doctest::Approx(rectArea).epsilon(1e-9));
        }
        // Collinear: nothing to draw.
        CHECK_FALSE(triangleVoronoiRegions({Triangle{Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)}, 1.0, 1.0}).valid);
        CHECK_FALSE(triangleVoronoiRegions({Triangle{Vec3(0, 0, 0), Vec3(NAN, 1, 1), Vec3(2, 0, 2)}, 1.0, 1.0}).valid);
    }

    TEST_CASE("triangle: the 9 boundary planes separate the two regions they name") {
        const Triangle t{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(1, 3, 0)};
        const auto d = triangleVoronoiRegions({t, 2.0, 1.5});
        REQUIRE(d.valid);
        for (const auto& b : d.boundaries) {
            CHECK(std::abs(b.normal.norm() - 1.0) < 1e-12);
            for (const Vec3& x : b.quad) CHECK(std::abs(b.normal.dot(x - b.point)) < 1e-12);
            CHECK(std::abs(b.quad[2].z() - 1.5) < 1e-12);  // extruded by +-height along the normal (z)
            // Just in front of / behind the middle of the boundary quad: the brute-force closest
            // point lies on the `front` / `behind` feature.
            const Vec3 mid = 0.25 * (b.quad[0] + b.quad[1] + b.quad[2] + b.quad[3]);
            for (int side : {-1, 1}) {
                const Vec3 p = mid + side * 1e-3 * b.normal;
                const R expected = side > 0 ? b.front : b.behind;
                const long double truth = oracle::triangleDistance2(p, t.a, t.b, t.c);
                CHECK(std::sqrt(featureDistance2(p, t, expected)) - std::sqrt(truth) <= 1e-12L);
                // ... and strictly not on the other side's feature when that one is a vertex.
                const R other = side > 0 ? b.behind : b.front;
                if (other == R::A || other == R::B || other == R::C) {
                    // (second order: sqrt(D^2 + 1e-6) - D with D ~ 1..3)
                    CHECK(std::sqrt(featureDistance2(p, t, other)) - std::sqrt(truth) > 1e-8L);
                }
            }
        }
        CHECK(N(d.boundaries[0].behind) == "A");
        CHECK(N(d.boundaries[0].front) == "AB");
        CHECK(N(d.boundaries[8].behind) == "ABC");
        CHECK(N(d.boundaries[8].front) == "CA");
    }

    TEST_CASE("tetrahedron: half-space regions tile space and match the exact oracle") {
        std::mt19937_64 rng(22);
        for (int trial = 0; trial < 20; ++trial) {
            const std::array<Vec3, 4> v = {randomVec(rng, 1), randomVec(rng, 1), randomVec(rng, 1), randomVec(rng, 1)};
            const auto d = tetrahedronVoronoiRegions({Tetrahedron{v[0], v[1], v[2], v[3]}, 1.0});
            REQUIRE(d.valid);
            for (int s = 0; s < 300; ++s) {
                const Vec3 p = randomVec(rng, 2.5);
                int containing = 0, which = -1;
                for (int k = 0; k < 15; ++k) {
                    bool in = true;
                    for (const HalfSpace& h : d.regions[k].halfSpaces) in = in && h.normal.dot(p - h.point) <= 1e-12;
                    if (in) {
                        ++containing;
                        which = k;
                    }
                }
                CHECK(containing == 1);  // generic points: exactly one region (they tile space)
                if (containing == 1) {
                    CHECK(N(static_cast<TetrahedronRegion>(which)) == N(oracle::exactTetrahedronRegion(p, v)));
                }
            }
            // Faces: on their plane, inside the box, and inside the region's other half-spaces.
            for (const auto& r : d.regions) {
                REQUIRE(r.faces.size() == r.halfSpaces.size());
                for (size_t i = 0; i < r.faces.size(); ++i) {
                    for (const Vec3& x : r.faces[i]) {
                        CHECK(std::abs(r.halfSpaces[i].normal.dot(x - r.halfSpaces[i].point)) < 1e-9);
                        CHECK(d.box.exteriorDistance(x) < 1e-9);
                        for (const HalfSpace& h : r.halfSpaces) CHECK(h.normal.dot(x - h.point) <= 1e-9);
                    }
                }
            }
        }
        CHECK_FALSE(
            tetrahedronVoronoiRegions({Tetrahedron{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}, 1.0})
                .valid);
    }

}  // TEST_SUITE
