// Triangle-triangle (core/overlap/triangle_triangle.h). Oracle: long double edge-triangle crossings
// with explicit margins (clear cases only), plus distances of the reported segment's end points
// to both triangles; exact hand-built touching cases (dyadic coordinates) with one-ulp
// perturbations, under all 36 vertex orderings and both argument orders.
#include <doctest/doctest.h>

#include <limits>

#include "core/overlap/triangle_triangle.h"
#include "verification/intersection_oracles.h"

using namespace cdlab;
using oracle::LD;
using oracle::V3;

namespace {

// Edge pq against triangle abc in long double: +1 clear crossing, -1 clear miss, 0 unclear.
int edgeCrossing(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c, LD margin) {
    const V3 n = oracle::cross(b - a, c - a);
    const LD nn = oracle::norm(n);
    const LD dp = oracle::dot(p - a, n) / nn, dq = oracle::dot(q - a, n) / nn;
    if ((dp > margin && dq > margin) || (dp < -margin && dq < -margin)) return -1;
    if (std::abs(dp) <= margin && std::abs(dq) <= margin) return 0;  // nearly coplanar edge
    if (std::abs(dp) <= margin || std::abs(dq) <= margin) return 0;
    const V3 x = p + (q - p) * (dp / (dp - dq));
    const LD area = nn * nn;
    const LD wa = oracle::dot(oracle::cross(b - x, c - x), n) / area;
    const LD wb = oracle::dot(oracle::cross(c - x, a - x), n) / area;
    const LD wc = 1 - wa - wb;
    const LD m = std::min({wa, wb, wc});
    if (m > margin) return 1;
    if (m < -margin) return -1;
    return 0;
}

// +1 clear hit, -1 clear miss, 0 unclear.
int oracleTriTri(const Triangle& s, const Triangle& t) {
    const V3 A[3] = {V3(s.a), V3(s.b), V3(s.c)}, B[3] = {V3(t.a), V3(t.b), V3(t.c)};
    bool unclear = false;
    for (int i = 0; i < 3; ++i) {
        const int r1 = edgeCrossing(A[i], A[(i + 1) % 3], B[0], B[1], B[2], 1e-7);
        const int r2 = edgeCrossing(B[i], B[(i + 1) % 3], A[0], A[1], A[2], 1e-7);
        if (r1 == 1 || r2 == 1) return 1;
        unclear |= r1 == 0 || r2 == 0;
    }
    return unclear ? 0 : -1;
}

void checkAllOrders(const Triangle& s, const Triangle& t, bool expected) {
    INFO("t = ", t.a.transpose(), " / ", t.b.transpose(), " / ", t.c.transpose());
    for (const Triangle& ps : oracle::orderings(s))
        for (const Triangle& pt : oracle::orderings(t)) {
            REQUIRE(intersectTriangleTriangle(ps, pt).hit == expected);
            REQUIRE(intersectTriangleTriangle(pt, ps).hit == expected);
        }
}

}  // namespace

TEST_SUITE("triangle_triangle") {
    TEST_CASE("random triangles against the long double crossing oracle, segment lies on both") {
        oracle::Rng rng(1);
        int hits = 0, misses = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 3000; ++n) {
                const Vec3 sft = Vec3::Constant(offset);
                const Vec3 c1 = rng.vec(-0.5, 0.5) + sft, c2 = rng.vec(-0.5, 0.5) + sft;
                const Triangle s{c1 + rng.vec(-1, 1), c1 + rng.vec(-1, 1), c1 + rng.vec(-1, 1)};
                const Triangle t{c2 + rng.vec(-1, 1), c2 + rng.vec(-1, 1), c2 + rng.vec(-1, 1)};
                const int expected = oracleTriTri(s, t);
                if (expected == 0) continue;
                const TriangleTriangleResult r = intersectTriangleTriangle(s, t);
                REQUIRE(r.hit == (expected > 0));
                REQUIRE(intersectTriangleTriangle(t, s).hit == r.hit);
                if (!r.hit) {
                    ++misses;
                    continue;
                }
                ++hits;
                REQUIRE(r.hasSegment);
                for (const Vec3& x : {r.segmentStart, r.segmentEnd, Vec3(0.5 * (r.segmentStart + r.segmentEnd))}) {
                    CHECK(oracle::distPointTriangle(V3(x), V3(s.a), V3(s.b), V3(s.c)) < 1e-9 * (1 + offset));
                    CHECK(oracle::distPointTriangle(V3(x), V3(t.a), V3(t.b), V3(t.c)) < 1e-9 * (1 + offset));
                }
            }
        }
        CHECK(hits > 300);
        CHECK(misses > 300);
    }

    TEST_CASE("exact touching cases and one-ulp misses, all vertex orders, offsets") {
        for (double off : {0.0, 1e4, 1e6}) {
            const Vec3 o = Vec3::Constant(off);
            const Triangle base{Vec3(0, 0, 0) + o, Vec3(4, 0, 0) + o, Vec3(0, 4, 0) + o};
            // About one ulp at this offset (at 0: 2^-50, two ulps of the coordinates in [2, 4)).
            const double up = off == 0.0 ? 0x1p-50 : std::nextafter(off, 2 * off) - off;
            // Vertex touching the face from above.
            checkAllOrders(base, {Vec3(1, 1, 0) + o, Vec3(1, 2, 3) + o, Vec3(2, 1, 3) + o}, true);
            checkAllOrders(base, {Vec3(1, 1, up) + o, Vec3(1, 2, 3) + o, Vec3(2, 1, 3) + o}, false);
            // Edge crossing an edge (x = 2 crossing the hypotenuse x + y = 4 at (2, 2, 0)).
            checkAllOrders(base, {Vec3(2, 2, 0) + o, Vec3(3, 3, 2) + o, Vec3(1, 1, 2) + o}, true);
            checkAllOrders(base, {Vec3(2, 2, up) + o, Vec3(3, 3, 2) + o, Vec3(1, 1, 2) + o}, false);
            // Vertex on vertex.
            checkAllOrders(base, {Vec3(4, 0, 0) + o, Vec3(5, 1, 1) + o, Vec3(5, -1, 1) + o}, true);
            // Piercing.
            checkAllOrders(base, {Vec3(1, 1, -1) + o, Vec3(1, 1, 1) + o, Vec3(2, 5, 0) + o}, true);
            // Coplanar: overlapping, sharing an edge, touching at a vertex, apart.
            checkAllOrders(base, {Vec3(1, 1, 0) + o, Vec3(5, 1, 0) + o, Vec3(1, 5, 0) + o}, true);
            checkAllOrders(base, {Vec3(4, 0, 0) + o, Vec3(0, 4, 0) + o, Vec3(4, 4, 0) + o}, true);
            checkAllOrders(base, {Vec3(2, 2, 0) + o, Vec3(4, 2, 0) + o, Vec3(2, 4, 0) + o}, true);
            checkAllOrders(base, {Vec3(2, 2 + 2 * up, 0) + o, Vec3(4, 2, 0) + o, Vec3(2, 4, 0) + o}, false);
            checkAllOrders(base, {Vec3(2, 2 - 2 * up, 0) + o, Vec3(4, 2, 0) + o, Vec3(2, 4, 0) + o}, true);
            checkAllOrders(base, {Vec3(2 + 1e-9, 2 + 1e-9, 0) + o, Vec3(4, 4, 0) + o, Vec3(2, 5, 0) + o}, false);
            checkAllOrders(base, {Vec3(1, 1, 0) + o, Vec3(2, 1, 0) + o, Vec3(1, 2, 0) + o}, true);  // contained
        }
        // The reported segment for a clean crossing.
        const Triangle s{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
        const TriangleTriangleResult r = intersectTriangleTriangle(s, {Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, 3, 0)});
        REQUIRE(r.hasSegment);
        const Vec3 lo = r.segmentStart.cwiseMin(r.segmentEnd), hi = r.segmentStart.cwiseMax(r.segmentEnd);
        CHECK((lo - Vec3(1, 1, 0)).norm() < 1e-12);
        CHECK((hi - Vec3(1, 3, 0)).norm() < 1e-12);
        // Coplanar hit: no segment.
        const TriangleTriangleResult c = intersectTriangleTriangle(s, {Vec3(1, 1, 0), Vec3(5, 1, 0), Vec3(1, 5, 0)});
        CHECK(c.coplanar);
        CHECK_FALSE(c.hasSegment);
        // Touching at one point: start == end.
        const TriangleTriangleResult p = intersectTriangleTriangle(s, {Vec3(1, 1, 0), Vec3(1, 2, 3), Vec3(2, 1, 3)});
        CHECK((p.segmentStart - Vec3(1, 1, 0)).norm() < 1e-15);
        CHECK((p.segmentEnd - Vec3(1, 1, 0)).norm() < 1e-15);
    }

    TEST_CASE("parallel planes and degenerate input") {
        const Triangle s{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
        CHECK_FALSE(intersectTriangleTriangle(s, {Vec3(0, 0, 1e-300), Vec3(4, 0, 1e-300), Vec3(0, 4, 1e-300)}).hit);
        // Zero-area triangles give no hit (documented), even when they cross.
        CHECK_FALSE(intersectTriangleTriangle(s, {Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, 1, 2)}).hit);
        CHECK_FALSE(intersectTriangleTriangle(s, {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}).hit);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        CHECK_FALSE(intersectTriangleTriangle(s, {Vec3(nan, 1, -1), Vec3(1, 1, 1), Vec3(2, 1, 2)}).hit);
        CHECK_FALSE(intersectTriangleTriangle(s, {Vec3(INFINITY, 1, -1), Vec3(1, 1, 1), Vec3(2, 1, 2)}).hit);
    }
}
