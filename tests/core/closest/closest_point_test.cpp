// Closest point on segments and triangles: against long double brute force, dense sampling,
// exact integer cases, all vertex orderings, ties, degenerate triangles, large offsets, and an
// exact (BigInt) oracle for the region choice near boundaries.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include "core/closest/closest_point.h"
#include "verification/closest_oracle.h"
#include "tests/core/closest/closest_test_support.h"

using namespace cdlab;
using R = TriangleRegion;

namespace {

// Region names as std::string for doctest messages.
using cdlab::test::N;

// Vertex set (indices into a, b, c) of a triangle region.
std::set<int> featureOf(R r) {
    switch (r) {
        case R::A: return {0};
        case R::B: return {1};
        case R::C: return {2};
        case R::AB: return {0, 1};
        case R::BC: return {1, 2};
        case R::CA: return {0, 2};
        case R::ABC: return {0, 1, 2};
    }
    return {};
}

using cdlab::test::randomVec;

// The barycentric weights are consistent with the point and vanish off the named feature.
void checkWeights(const ClosestPointOnTriangleResult& r, const Triangle& t, double tolerance) {
    const std::set<int> f = featureOf(r.region);
    for (int i = 0; i < 3; ++i) {
        CHECK(r.barycentric[i] >= 0.0);
        if (!f.count(i)) CHECK(r.barycentric[i] == 0.0);
        if (f.size() == 1 && f.count(i)) CHECK(r.barycentric[i] == 1.0);
    }
    CHECK(std::abs(r.barycentric.sum() - 1.0) < 1e-12);
    const Vec3 fromWeights = r.barycentric.x() * t.a + r.barycentric.y() * t.b + r.barycentric.z() * t.c;
    CHECK((fromWeights - r.point).norm() <= tolerance);
}

}  // namespace

TEST_SUITE("closest_point") {
    TEST_CASE("nameOf gives the exact region names") {
        CHECK(std::string(nameOf(R::A)) == "A");
        CHECK(std::string(nameOf(R::B)) == "B");
        CHECK(std::string(nameOf(R::C)) == "C");
        CHECK(std::string(nameOf(R::AB)) == "AB");
        CHECK(std::string(nameOf(R::BC)) == "BC");
        CHECK(std::string(nameOf(R::CA)) == "CA");
        CHECK(std::string(nameOf(R::ABC)) == "ABC");
        CHECK(std::string(nameOf(SegmentRegion::AB)) == "AB");
        const char* tet[] = {"A",  "B",  "C",   "D",   "AB",  "AC",  "AD",  "BC",
                             "BD", "CD", "ABC", "ABD", "ACD", "BCD", "ABCD"};
        for (int i = 0; i < 15; ++i) CHECK(std::string(nameOf(static_cast<TetrahedronRegion>(i))) == tet[i]);
    }

    TEST_CASE("point-segment: regions, endpoints exactly, zero length") {
        const Segment s{Vec3(0, 0, 0), Vec3(4, 0, 0)};
        auto r = closestPointOnSegment(Vec3(-1, 2, 0), s);
        CHECK(N(r.region) == N(SegmentRegion::A));
        CHECK(r.t == 0.0);
        CHECK(r.point == s.a);
        r = closestPointOnSegment(Vec3(0, 2, 0), s);  // on the boundary plane: endpoint wins
        CHECK(N(r.region) == N(SegmentRegion::A));
        r = closestPointOnSegment(Vec3(4, -3, 1), s);
        CHECK(N(r.region) == N(SegmentRegion::B));
        CHECK(r.point == s.b);
        CHECK(r.distanceSquared == 10.0);
        r = closestPointOnSegment(Vec3(3, 1, 1), s);
        CHECK(N(r.region) == N(SegmentRegion::AB));
        CHECK(r.t == 0.75);
        CHECK(r.point == Vec3(3, 0, 0));
        CHECK(r.distanceSquared == 2.0);
        r = closestPointOnSegment(Vec3(1, 1, 1), Segment{Vec3(2, 2, 2), Vec3(2, 2, 2)});
        CHECK(N(r.region) == N(SegmentRegion::A));
        CHECK(r.distanceSquared == 3.0);
        r = closestPointOnSegment(Vec3(NAN, 0, 0), s);
        CHECK(std::isnan(r.distanceSquared));
    }

    TEST_CASE("point-segment: random queries against long double") {
        std::mt19937_64 rng(1);
        for (int i = 0; i < 2000; ++i) {
            const double offset = (i % 3 == 0) ? 1e6 : 0.0;
            const Segment s{randomVec(rng, 2) + Vec3::Constant(offset), randomVec(rng, 2) + Vec3::Constant(offset)};
            const Vec3 p = randomVec(rng, 3) + Vec3::Constant(offset);
            const auto r = closestPointOnSegment(p, s);
            const long double truth = oracle::segmentDistance2(oracle::L(p), oracle::L(s.a), oracle::L(s.b));
            CHECK(std::abs(static_cast<long double>(r.distanceSquared) - truth) <= 1e-9L * (1 + offset * 1e-3));
            CHECK(r.t >= 0.0);
            CHECK(r.t <= 1.0);
        }
    }

    TEST_CASE("segment-segment: crossing, parallel, degenerate, against brute force") {
        // Crossing segments (skew by 1 in z): closest pair at the crossing.
        auto r = closestPointsSegmentSegment({Vec3(-1, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, -1, 1), Vec3(0, 1, 1)});
        CHECK(r.s == 0.5);
        CHECK(r.t == 0.5);
        CHECK(r.distanceSquared == 1.0);
        CHECK_FALSE(r.parallel);
        // Parallel, overlapping: distance 2, any pair in the overlap.
        r = closestPointsSegmentSegment({Vec3(0, 0, 0), Vec3(4, 0, 0)}, {Vec3(2, 2, 0), Vec3(6, 2, 0)});
        CHECK(r.parallel);
        CHECK(r.distanceSquared == doctest::Approx(4.0));
        CHECK(r.pointOnFirst.x() >= 2.0 - 1e-12);
        // Parallel, disjoint along the line: endpoint pair.
        r = closestPointsSegmentSegment({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(3, 1, 0), Vec3(5, 1, 0)});
        CHECK(r.distanceSquared == doctest::Approx(5.0));
        CHECK(r.pointOnFirst == Vec3(1, 0, 0));
        CHECK(r.pointOnSecond == Vec3(3, 1, 0));
        // Both points; one point.
        r = closestPointsSegmentSegment({Vec3(1, 1, 1), Vec3(1, 1, 1)}, {Vec3(1, 1, 3), Vec3(1, 1, 3)});
        CHECK(r.degenerate);
        CHECK(r.distanceSquared == 4.0);
        r = closestPointsSegmentSegment({Vec3(1, 1, 1), Vec3(1, 1, 1)}, {Vec3(0, 0, 0), Vec3(4, 0, 0)});
        CHECK(r.s == 0.0);
        CHECK(r.t == 0.25);
        CHECK(r.distanceSquared == 2.0);

        // Random (including near-parallel): distance vs dense brute force over both parameters,
        // refined in long double: the returned pair is feasible and no sampled pair beats it.
        std::mt19937_64 rng(2);
        for (int i = 0; i < 300; ++i) {
            Segment s1{randomVec(rng, 1), randomVec(rng, 1)};
            Segment s2{randomVec(rng, 1), randomVec(rng, 1)};
            if (i % 4 == 0) s2 = {s1.a + Vec3(0.1, 0.3, 0.2), s1.b + Vec3(0.1, 0.3, 0.2) + 1e-9 * randomVec(rng, 1)};
            const auto q = closestPointsSegmentSegment(s1, s2);
            REQUIRE(q.s >= 0.0);
            REQUIRE(q.s <= 1.0);
            REQUIRE(q.t >= 0.0);
            REQUIRE(q.t <= 1.0);
            // Oracle: min over the first parameter on a fine grid of the exact point-segment distance.
            long double best = 1e300L;
            const int n = 2000;
            for (int k = 0; k <= n; ++k) {
                const long double s = static_cast<long double>(k) / n;
                const oracle::LVec p = oracle::L(s1.a) + s * (oracle::L(s1.b) - oracle::L(s1.a));
                best = std::min(best, oracle::segmentDistance2(p, oracle::L(s2.a), oracle::L(s2.b)));
            }
            // The grid min over-estimates the true min by at most the grid step times the slope.
            const long double step = (oracle::L(s1.b) - oracle::L(s1.a)).norm() / n;
            CHECK(std::sqrt(static_cast<long double>(q.distanceSquared)) <= std::sqrt(best) + 1e-12L);
            CHECK(std::sqrt(static_cast<long double>(q.distanceSquared)) >= std::sqrt(best) - step - 1e-12L);
        }
    }

    TEST_CASE("segment-segment: huge and tiny scales give the unit-scale parameters") {
        // s and t do not depend on scale. Squared lengths overflow above ~1e154 (half-size 1e78
        // boxes' edge contacts were NaN) and underflow below ~1e-154 (segments taken for points):
        // the scaled copies by powers of two must give the unit answer exactly, and points on the
        // segments; 1e300 apart the differences themselves overflow.
        std::mt19937_64 rng(3);
        for (int i = 0; i < 500; ++i) {
            const Segment s1{randomVec(rng, 1), randomVec(rng, 1)}, s2{randomVec(rng, 1), randomVec(rng, 1)};
            const auto unit = closestPointsSegmentSegment(s1, s2);
            for (const double scale : {0x1p+260, 0x1p+1000, 0x1p-600, 0x1p-1000}) {
                const auto q = closestPointsSegmentSegment({scale * s1.a, scale * s1.b}, {scale * s2.a, scale * s2.b});
                CHECK(q.s == unit.s);
                CHECK(q.t == unit.t);
                CHECK(q.parallel == unit.parallel);
                CHECK(q.pointOnFirst.allFinite());
                CHECK((q.pointOnFirst - scale * unit.pointOnFirst).norm() <= 1e-15 * scale);
            }
        }
    }

    TEST_CASE("segment-segment: subnormal coordinates give the unit-scale parameters") {
        // Integer coordinates times 2^-1074 (the subnormal grid: every such difference is exact).
        // The largest difference lies below 2^-1023, so its scale to [1, 2) is no double: the
        // scaling takes two exact products. The scaled differences equal the integer ones scaled
        // the same way, so s and t must be the integer segments' bit for bit.
        std::mt19937_64 rng(11);
        std::uniform_int_distribution<int> coordinate(-20, 20);
        const auto integerVec = [&] { return Vec3(coordinate(rng), coordinate(rng), coordinate(rng)); };
        for (int i = 0; i < 500; ++i) {
            const Segment s1{integerVec(), integerVec()}, s2{integerVec(), integerVec()};
            const auto unit = closestPointsSegmentSegment(s1, s2);
            for (const double scale : {0x1p-1074, 0x1p-1064}) {
                const auto q = closestPointsSegmentSegment({scale * s1.a, scale * s1.b}, {scale * s2.a, scale * s2.b});
                CHECK(q.s == unit.s);
                CHECK(q.t == unit.t);
                CHECK(q.parallel == unit.parallel);
                CHECK(q.degenerate == unit.degenerate);
            }
        }
    }

    TEST_CASE("triangle: integer cases with the region known by construction") {
        const Triangle t{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
        struct Case {
            Vec3 p;
            R region;
            Vec3 point;
        };
        const Case cases[] = {
            {Vec3(-1, -1, 3), R::A, Vec3(0, 0, 0)}, {Vec3(5, -1, 2), R::B, Vec3(4, 0, 0)},
            {Vec3(-1, 6, 0), R::C, Vec3(0, 4, 0)},  {Vec3(2, -3, 1), R::AB, Vec3(2, 0, 0)},
            {Vec3(3, 3, 5), R::BC, Vec3(2, 2, 0)},  {Vec3(-2, 1, -1), R::CA, Vec3(0, 1, 0)},
            {Vec3(1, 1, 7), R::ABC, Vec3(1, 1, 0)}, {Vec3(1, 2, -3), R::ABC, Vec3(1, 2, 0)},
        };
        for (const Case& c : cases) {
            ClosestPointTrace trace;
            const auto r = closestPointOnTriangle(c.p, t, &trace);
            CHECK(N(r.region) == N(c.region));
            CHECK(r.point == c.point);
            CHECK(r.distanceSquared == (c.p - c.point).squaredNorm());
            CHECK(r.status == SimplexStatus::Regular);
            checkWeights(r, t, 1e-14);
            // Trace: Ericson's order, every test but the last rejected, the last accepted, result copied.
            REQUIRE(!trace.tests.empty());
            CHECK(N(trace.tests.back().candidate) == N(c.region));
            CHECK(trace.tests.back().accepted);
            for (size_t k = 0; k + 1 < trace.tests.size(); ++k) CHECK_FALSE(trace.tests[k].accepted);
            CHECK(N(trace.result.region) == N(r.region));
        }
        // Ericson's order is A, B, AB, C, CA, BC, ABC.
        ClosestPointTrace trace;
        closestPointOnTriangle(Vec3(1, 1, 7), t, &trace);
        const R order[] = {R::A, R::B, R::AB, R::C, R::CA, R::BC, R::ABC};
        REQUIRE(trace.tests.size() == 7);
        for (int k = 0; k < 7; ++k) CHECK(N(trace.tests[k].candidate) == N(order[k]));
        CHECK(std::string(trace.tests[0].terms[0].name) == "d1");
        CHECK(trace.tests[0].terms[0].value == 4.0);  // (b-a).(p-a) = (4,0,0).(1,1,7)
        CHECK(trace.tests[0].terms[0].sign == 1);
        CHECK(trace.tests[0].termCount == 1);  // d1 > 0: the && short-circuits
    }

    TEST_CASE("triangle: points exactly on region boundaries follow the tie convention") {
        const Triangle t{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
        // A | AB boundary (d1 == 0, outside AB): vertex wins.
        CHECK(N(closestPointOnTriangle(Vec3(0, -3, 1), t).region) == N(R::A));
        // A | CA boundary (d2 == 0): vertex wins.
        CHECK(N(closestPointOnTriangle(Vec3(-2, 0, -1), t).region) == N(R::A));
        // B | BC boundary ((c-b).(p-b) == 0, outside BC): vertex wins.
        CHECK(N(closestPointOnTriangle(Vec3(5, 1, 2), t).region) == N(R::B));
        // C | BC and C | CA boundaries.
        CHECK(N(closestPointOnTriangle(Vec3(1, 5, 0), t).region) == N(R::C));
        CHECK(N(closestPointOnTriangle(Vec3(-1, 4, 3), t).region) == N(R::C));
        // AB | ABC (vc == 0 with the projection on the edge): edge wins, above and in the plane.
        CHECK(N(closestPointOnTriangle(Vec3(2, 0, 5), t).region) == N(R::AB));
        CHECK(N(closestPointOnTriangle(Vec3(2, 0, 0), t).region) == N(R::AB));
        CHECK(N(closestPointOnTriangle(Vec3(2, 2, -1), t).region) == N(R::BC));
        CHECK(N(closestPointOnTriangle(Vec3(0, 3, 4), t).region) == N(R::CA));
        // On a vertex, in the plane: vertex.
        CHECK(N(closestPointOnTriangle(Vec3(4, 0, 0), t).region) == N(R::B));
        // Inside, in the plane: face, distance 0.
        const auto r = closestPointOnTriangle(Vec3(1, 1, 0), t);
        CHECK(N(r.region) == N(R::ABC));
        CHECK(r.distanceSquared == 0.0);
    }

    TEST_CASE("triangle: random queries vs long double brute force, all 6 vertex orderings") {
        std::mt19937_64 rng(3);
        const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        const double offsets[] = {0.0, 1e4, 1e6};
        for (double offset : offsets) {
            for (int i = 0; i < 1500; ++i) {
                const Vec3 shift = Vec3(offset, -0.5 * offset, 0.25 * offset);
                const double scale = std::pow(10.0, (i % 7) - 3);  // 1e-3 .. 1e3
                Vec3 v[3] = {scale * randomVec(rng, 1) + shift, scale * randomVec(rng, 1) + shift,
                             scale * randomVec(rng, 1) + shift};
                // Points on boundaries too: every 5th query is an exact vertex or edge midpoint lifted.
                Vec3 p = scale * randomVec(rng, 2) + shift;
                if (i % 5 == 1) p = v[i % 3];
                const long double truth = oracle::triangleDistance2(p, v[0], v[1], v[2]);
                std::set<int> firstFeature;
                Vec3 firstPoint = Vec3::Zero();
                for (int k = 0; k < 6; ++k) {
                    const Triangle t{v[perms[k][0]], v[perms[k][1]], v[perms[k][2]]};
                    const auto r = closestPointOnTriangle(p, t);
                    REQUIRE(r.status == SimplexStatus::Regular);
                    // Distance: the point's rounding is ~u |coordinates|, so the tolerance scales
                    // with the offset, and with the distance itself.
                    const long double d = std::sqrt(static_cast<long double>(r.distanceSquared));
                    const long double tol = 1e-14L * (offset + 10 * scale) + 1e-12L * d;
                    CHECK(std::abs(d - std::sqrt(truth)) <= tol);
                    checkWeights(r, t, 1e-13 * (offset + 10 * scale));
                    // The region, mapped back to the original vertices, is the same for every ordering.
                    std::set<int> feature;
                    for (int local : featureOf(r.region)) feature.insert(perms[k][local]);
                    if (k == 0) {
                        firstFeature = feature;
                        firstPoint = r.point;
                    } else {
                        CHECK(feature == firstFeature);
                        CHECK((r.point - firstPoint).norm() <= 1e-14 * (offset + 10 * scale) + 1e-12 * double(d));
                    }
                }
            }
        }
    }

    TEST_CASE("triangle: dense barycentric sampling bounds the distance") {
        std::mt19937_64 rng(4);
        const int n = 120;
        for (int i = 0; i < 60; ++i) {
            const Triangle t{randomVec(rng, 1), randomVec(rng, 1), randomVec(rng, 1)};
            const Vec3 p = randomVec(rng, 1.5);
            double gridMin = 1e300;
            for (int u = 0; u <= n; ++u) {
                for (int v = 0; u + v <= n; ++v) {
                    const double bu = double(u) / n, bv = double(v) / n, bw = 1.0 - bu - bv;
                    gridMin = std::min(gridMin, (bu * t.a + bv * t.b + bw * t.c - p).norm());
                }
            }
            // Every triangle point is within one grid cell (diameter <= longest edge / n) of a sample.
            const double cell = std::max({(t.a - t.b).norm(), (t.b - t.c).norm(), (t.c - t.a).norm()}) / n;
            const double d = std::sqrt(closestPointOnTriangle(p, t).distanceSquared);
            CHECK(d <= gridMin + 1e-12);
            CHECK(d >= gridMin - cell - 1e-12);
        }
    }

    TEST_CASE("triangle: degenerate inputs give the closest point of the point set, never NaN") {
        // Collinear, c in the middle of ab.
        const Triangle line{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0)};
        auto r = closestPointOnTriangle(Vec3(1, 1, 0), line);
        CHECK(r.status == SimplexStatus::Degenerate);
        CHECK(N(r.region) == N(R::C));  // projects exactly onto c
        CHECK(r.point == Vec3(1, 0, 0));
        r = closestPointOnTriangle(Vec3(0.5, 1, 0), line);
        CHECK(N(r.region) == N(R::AB));  // the spanning edge
        CHECK(r.point == Vec3(0.5, 0, 0));
        CHECK(r.barycentric == Vec3(0.75, 0.25, 0));
        CHECK(N(closestPointOnTriangle(Vec3(-1, 0, 3), line).region) == N(R::A));
        CHECK(N(closestPointOnTriangle(Vec3(3, 1, 0), line).region) == N(R::B));
        // Collinear, a in the middle.
        const Triangle line2{Vec3(1, 1, 1), Vec3(3, 3, 3), Vec3(-1, -1, -1)};
        r = closestPointOnTriangle(Vec3(2, 2, 5), line2);
        CHECK(N(r.region) == N(R::B));  // projects onto b = (3,3,3) exactly
        r = closestPointOnTriangle(Vec3(2, 2, 2.5), line2);
        CHECK(N(r.region) == N(R::BC));  // inside AB too, but BC is the spanning edge
        r = closestPointOnTriangle(Vec3(-5, -5, -5), line2);
        CHECK(N(r.region) == N(R::C));
        CHECK(r.point == Vec3(-1, -1, -1));
        r = closestPointOnTriangle(Vec3(0, 0, 0), line2);
        CHECK(N(r.region) == N(R::BC));
        CHECK(r.distanceSquared == doctest::Approx(0.0));
        // Two equal vertices.
        const Triangle twin{Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(3, 1, 1)};
        r = closestPointOnTriangle(Vec3(2, 5, 1), twin);
        CHECK(r.point == Vec3(2, 1, 1));
        CHECK(N(r.region) == N(R::BC));
        r = closestPointOnTriangle(Vec3(0, 0, 0), twin);
        CHECK(N(r.region) == N(R::A));  // the first of the equal vertices
        // All three equal.
        const Triangle dot{Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)};
        r = closestPointOnTriangle(Vec3(0, 0, 0), dot);
        CHECK(N(r.region) == N(R::A));
        CHECK(r.point == Vec3(1, 2, 3));
        CHECK(r.distanceSquared == 14.0);
        // Random collinear triangles (dyadic, so exactly collinear) vs long double: distances match,
        // region names a feature holding the point.
        std::mt19937_64 rng(5);
        std::uniform_int_distribution<int> k(-8, 8);
        for (int i = 0; i < 500; ++i) {
            const Vec3 base = (8 * randomVec(rng, 10)).array().round() / 8,
                       dir(k(rng) / 8.0, k(rng) / 8.0, k(rng) / 8.0);
            const Triangle t{base + k(rng) * dir, base + k(rng) * dir, base + k(rng) * dir};
            const Vec3 p = randomVec(rng, 10);
            r = closestPointOnTriangle(p, t);
            REQUIRE(r.point.allFinite());
            CHECK(r.status == SimplexStatus::Degenerate);
            CHECK(std::abs(std::sqrt(r.distanceSquared) -
                           std::sqrt(double(oracle::triangleDistance2(p, t.a, t.b, t.c)))) < 1e-11);
            checkWeights(r, t, 1e-12);
        }
        // Non-finite input.
        r = closestPointOnTriangle(Vec3(0, 0, 0), Triangle{Vec3(NAN, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
        CHECK(r.status == SimplexStatus::NonFinite);
        CHECK(std::isnan(r.distanceSquared));
        r = closestPointOnTriangle(Vec3(INFINITY, 0, 0), line);
        CHECK(r.status == SimplexStatus::NonFinite);
    }

    TEST_CASE("triangle: near-boundary points, exact region vs BigInt oracle (naive double fails)") {
        // Points one ulp off an exact region boundary, on triangles at offsets 1 .. 1e6. The truth is
        // Ericson's decision evaluated in exact integer arithmetic on the same doubles.
        std::mt19937_64 rng(6);
        std::uniform_int_distribution<int> small(-6, 6);
        int naiveWrong = 0, fallbacks = 0, total = 0;
        const double offsets[] = {1.0, 1e3, 1e6};
        for (double offset : offsets) {
            for (int i = 0; i < 700; ++i) {
                const Vec3 o = Vec3(offset, 0.75 * offset, -0.5 * offset);
                const Vec3 a = o + Vec3(small(rng), small(rng), small(rng)) / 4.0;
                const Vec3 b = o + Vec3(small(rng), small(rng), small(rng)) / 4.0;
                const Vec3 c = o + Vec3(small(rng), small(rng), small(rng)) / 4.0;
                const Vec3 n = (b - a).cross(c - a);  // exact: small dyadic integers
                if (n == Vec3::Zero()) continue;
                // An exact boundary point: on an edge or at a vertex, lifted along the normal and
                // pushed out along an edge normal or edge direction by a dyadic amount.
                const Vec3 verts[3] = {a, b, c};
                const int e = i % 3;
                const Vec3 x = verts[e], y = verts[(e + 1) % 3];
                const double s = double(small(rng) + 6) / 12.0;  // in [0, 1]
                Vec3 p = x + (y - x) * std::ldexp(std::round(std::ldexp(s, 4)), -4) + n * (small(rng) / 8.0);
                if (i % 2) p += (y - x).cross(n) * (small(rng) / 16.0);  // off the edge, in-plane normal direction
                // One ulp in a random coordinate and direction.
                const int axis = i % 3;
                // (From 0 that is one subnormal ulp, 2^-1074: the predicates are exact there too.)
                const double toward = (i / 3) % 2 ? INFINITY : -INFINITY;
                p[axis] = std::nextafter(p[axis], toward);
                const R truth = oracle::exactEricsonRegion(p, a, b, c);
                ClosestPointTrace trace;
                const auto r = closestPointOnTriangle(p, Triangle{a, b, c}, &trace);
                CHECK(N(r.region) == N(truth));
                ++total;
                if (oracle::naiveEricsonRegion(p, a, b, c) != truth) ++naiveWrong;
                for (const auto& test : trace.tests) {
                    for (int k = 0; k < test.termCount; ++k) fallbacks += test.terms[k].exactFallback;
                }
            }
        }
        MESSAGE("near-boundary queries: " << total << ", naive double region wrong: " << naiveWrong
                                          << ", exact fallbacks: " << fallbacks);
        CHECK(naiveWrong > 0);  // the test has teeth: plain double does get these wrong
    }

    TEST_CASE("triangle: a hand-built case where the naive d1 rounds to the wrong sign") {
        // ab = (1,1,1), p - a = (2^60, 1, -2^60): d1 = 1 exactly, but 2^60 + 1 rounds to 2^60 in
        // double and the naive sum is 0, so naive Ericson answers A (d1 <= 0 && d2 <= 0).
        const Vec3 a(0, 0, 0), b(1, 1, 1), c(-1, 0, -1);  // d2 = -2^60 + 2^60 = 0 exactly
        const Vec3 p(0x1p60, 1.0, -0x1p60);
        REQUIRE(N(oracle::naiveEricsonRegion(p, a, b, c)) == N(R::A));
        const R truth = oracle::exactEricsonRegion(p, a, b, c);
        CHECK(N(truth) != N(R::A));
        ClosestPointTrace trace;
        const auto r = closestPointOnTriangle(p, Triangle{a, b, c}, &trace);
        CHECK(N(r.region) == N(truth));
        REQUIRE(!trace.tests.empty());
        CHECK(trace.tests[0].terms[0].value == 0.0);  // what the naive code saw
        CHECK(trace.tests[0].terms[0].sign == 1);     // the exact sign
        CHECK(trace.tests[0].terms[0].exactFallback);
    }

}  // TEST_SUITE
