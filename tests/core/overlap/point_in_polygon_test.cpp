// Point in polygon three ways (core/overlap/point_in_polygon.h). Oracle: the winding number by
// quadrant counting (Hormann & Agathos 2001's idea, the signed quarter turns of p -> v_i) in exact
// integer arithmetic on integer coordinates — no angles and no ray; it shares no code with the
// tests under test. Crossing parity equals winding parity for every polygon, self-intersecting ones
// included; the edge-side test's "inside" holds only in the kernel, so it implies the oracle's.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/overlap/point_in_polygon.h"
#include "core/overlap/polygon_tests.h"

using cdlab::Vec2;

namespace {

using I = __int128;
struct IntPoint {
    long long x, y;
};

int quadrant(long long x, long long y) {
    if (x > 0 && y >= 0) return 0;
    if (x <= 0 && y > 0) return 1;
    if (x < 0 && y <= 0) return 2;
    return 3;
}

struct Oracle {
    bool onBoundary = false;
    int winding = 0;
};

Oracle windingOracle(const std::vector<IntPoint>& poly, IntPoint p) {
    Oracle o;
    int quarterTurns = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const IntPoint a = poly[i], b = poly[(i + 1) % poly.size()];
        const long long ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y;
        const I cross = I(ax) * by - I(ay) * bx;
        if (cross == 0 && std::min(ax, bx) <= 0 && std::max(ax, bx) >= 0 && std::min(ay, by) <= 0 &&
            std::max(ay, by) >= 0) {
            o.onBoundary = true;
            return o;
        }
        int d = quadrant(bx, by) - quadrant(ax, ay);
        if (d == 3) d = -1;
        if (d == -3) d = 1;
        if (d == 2 || d == -2) d = cross > 0 ? 2 : -2;  // half a turn, its sense from the exact cross product
        quarterTurns += d;
    }
    o.winding = quarterTurns / 4;
    return o;
}

std::vector<Vec2> toVec(const std::vector<IntPoint>& poly) {
    std::vector<Vec2> v;
    for (IntPoint q : poly) v.emplace_back(double(q.x), double(q.y));
    return v;
}

// A random polygon: star-shaped around 0 when `simple`, else vertices anywhere (self-intersecting).
std::vector<IntPoint> randomPolygon(std::mt19937_64& rng, bool simple) {
    std::uniform_int_distribution<int> count(3, 12);
    std::uniform_int_distribution<long long> coord(-20, 20);
    const int n = count(rng);
    std::vector<IntPoint> poly;
    if (!simple) {
        for (int i = 0; i < n; ++i) poly.push_back({coord(rng), coord(rng)});
        return poly;
    }
    std::uniform_real_distribution<double> radius(3.0, 20.0);
    for (int i = 0; i < n; ++i) {
        const double angle = 2 * M_PI * (i + 0.5) / n;
        const double r = radius(rng);
        poly.push_back({std::llround(r * std::cos(angle)), std::llround(r * std::sin(angle))});
    }
    return poly;
}

}  // namespace

TEST_CASE("crossing number, angle summation and edge sides agree with the exact winding number") {
    std::mt19937_64 rng(20261127);
    std::uniform_int_distribution<long long> coord(-22, 22);
    int inside = 0, boundary = 0, multiWound = 0, kernelPoints = 0, convexChecked = 0;
    for (int round = 0; round < 3000; ++round) {
        const std::vector<IntPoint> poly = randomPolygon(rng, round % 3 != 0);
        const std::vector<Vec2> v = toVec(poly);
        for (int k = 0; k < 20; ++k) {
            const IntPoint p{coord(rng), coord(rng)};
            const Vec2 q(double(p.x), double(p.y));
            const Oracle o = windingOracle(poly, p);
            const auto crossing = cdlab::crossingNumber(v, q);
            const auto angles = cdlab::angleSummation(v, q);
            const auto sides = cdlab::sameSideOfEveryEdge(v, q);
            CHECK(crossing.onBoundary == o.onBoundary);
            CHECK(angles.onBoundary == o.onBoundary);
            if (o.onBoundary) {
                ++boundary;
                CHECK(crossing.inside);
                CHECK(angles.inside);
                continue;
            }
            CHECK(angles.winding == o.winding);
            CHECK(crossing.inside == (o.winding % 2 != 0));
            CHECK(crossing.crossingEdges.size() % 2 == std::size_t(std::abs(o.winding) % 2));
            inside += o.winding != 0;
            multiWound += std::abs(o.winding) > 1;
            if (sides.inside) {  // the kernel of the polygon: inside by every rule
                ++kernelPoints;
                CHECK(o.winding != 0);
            }
            if (round % 3 != 0 && sides.orientation != 0) {
                // On a convex polygon the edge-side test is the convex test of polygon_tests.h.
                bool convex = true;
                for (std::size_t i = 0; i < v.size() && convex; ++i) {
                    const Vec2 e0 = v[(i + 1) % v.size()] - v[i], e1 = v[(i + 2) % v.size()] - v[(i + 1) % v.size()];
                    convex = (e0.x() * e1.y() - e0.y() * e1.x()) * sides.orientation >= 0;
                }
                if (convex) {
                    ++convexChecked;
                    CHECK(sides.inside == cdlab::pointInConvexPolygon2d(v, q));
                    CHECK(sides.inside == (o.winding != 0));
                }
            }
        }
    }
    // The cases were all met.
    CHECK(inside > 1000);
    CHECK(boundary > 50);
    CHECK(multiWound > 20);
    CHECK(kernelPoints > 500);
    CHECK(convexChecked > 200);
}

TEST_CASE("a pentagram's centre: winding 2 (nonzero rule: inside), 2 crossings (even-odd: outside)") {
    std::vector<Vec2> star;
    for (int i = 0; i < 5; ++i) {
        const double a = M_PI / 2 + 2 * M_PI * (2 * i) / 5;  // every second corner of a pentagon
        star.emplace_back(std::cos(a), std::sin(a));
    }
    const Vec2 centre(0.0, 0.05);
    const auto angles = cdlab::angleSummation(star, centre);
    const auto crossing = cdlab::crossingNumber(star, centre);
    CHECK(angles.winding == 2);
    CHECK(angles.inside);
    CHECK(crossing.crossingEdges.size() == 2);
    CHECK_FALSE(crossing.inside);
    // The inner pentagon is on the inner side of all five edge lines: the edge-side test says inside too.
    CHECK(cdlab::sameSideOfEveryEdge(star, centre).inside);
    CHECK_FALSE(cdlab::sameSideOfEveryEdge(star, Vec2(0, 0.9)).inside);  // in a spike: outside one edge line
}

TEST_CASE("a ray through a vertex counts it once for a crossing, not at all for a touch") {
    // Diamond with vertices on p's horizontal line: the ray passes through the right vertex (a crossing
    // of the boundary) — counted once; a point level with a spike's tip sees a touch — not counted.
    const std::vector<Vec2> diamond = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    CHECK(cdlab::crossingNumber(diamond, Vec2(0, 0)).crossingEdges.size() == 1);
    CHECK(cdlab::crossingNumber(diamond, Vec2(-2, 0)).crossingEdges.size() == 2);  // enters and leaves through vertices
    const std::vector<Vec2> spike = {{0, 0}, {4, 0}, {4, 1}, {3, 3}, {2, 1}, {0, 1}};
    CHECK(cdlab::crossingNumber(spike, Vec2(1, 3)).crossingEdges.empty());  // level with the tip (3, 3): a touch
    CHECK_FALSE(cdlab::crossingNumber(spike, Vec2(1, 3)).inside);
}

TEST_CASE("a polygon far from the origin keeps its orientation (the area is taken about a corner)") {
    const std::vector<Vec2> tri = {{1e8, 1e8}, {1e8 + 1, 1e8}, {1e8, 1e8 + 1}};
    const auto r = cdlab::sameSideOfEveryEdge(tri, Vec2(1e8 + 0.25, 1e8 + 0.25));
    CHECK(r.orientation == 1);
    CHECK(r.inside);
    CHECK(cdlab::crossingNumber(tri, Vec2(1e8 + 0.25, 1e8 + 0.25)).inside);
    CHECK(cdlab::angleSummation(tri, Vec2(1e8 + 0.25, 1e8 + 0.25)).winding == 1);
}

TEST_CASE("degenerate polygons and points") {
    const std::vector<Vec2> two = {{0, 0}, {1, 0}};
    CHECK_FALSE(cdlab::crossingNumber(two, Vec2(0.5, 0)).inside);
    CHECK_FALSE(cdlab::angleSummation(two, Vec2(0.5, 0)).inside);
    const std::vector<Vec2> flat = {{0, 0}, {1, 0}, {2, 0}};
    CHECK(cdlab::sameSideOfEveryEdge(flat, Vec2(0.5, 0)).orientation == 0);
    CHECK_FALSE(cdlab::sameSideOfEveryEdge(flat, Vec2(0.5, 1)).inside);
    const std::vector<Vec2> tri = {{0, 0}, {1, 0}, {0, 1}};
    CHECK_FALSE(cdlab::crossingNumber(tri, Vec2(NAN, 0)).inside);
    CHECK(cdlab::sameSideOfEveryEdge(tri, Vec2(0.5, 0)).onBoundary);
    CHECK(cdlab::crossingNumber(tri, Vec2(0.5, 0.5)).onBoundary);
}
