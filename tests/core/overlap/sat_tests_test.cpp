// Box SAT tests (core/overlap/sat_tests.h). Oracles, sharing no code with the SAT:
//  - segment / triangle vs box: minimum long double distance from the segment (ternary search)
//    or the triangle (nested ternary search) to the box, which is convex in the parameters.
//    Clear miss: distance > 1e-6; clear hit: distance 0 to the box shrunk by 1e-6.
//  - OBB-OBB: feature enumeration in long double (a vertex of one inside the other, or an edge of
//    one crossing a face of the other), run on boxes scaled by (1 - 1e-6) for clear hits and
//    (1 + 1e-6) for clear misses.
#include <doctest/doctest.h>

#include <limits>

#include "core/overlap/sat_tests.h"
#include "verification/intersection_oracles.h"

using namespace cdlab;
using oracle::LD;
using oracle::V3;

namespace {

LD segmentBoxDistance(const V3& p, const V3& q, const V3& lo, const V3& hi) {
    return oracle::minimizeConvex([&](LD s) { return oracle::distPointBox(p + (q - p) * s, lo, hi); });
}

LD triangleBoxDistance(const V3& a, const V3& b, const V3& c, const V3& lo, const V3& hi) {
    return oracle::minimizeConvex(
        [&](LD u) {
            return oracle::minimizeConvex(
                [&](LD v) { return oracle::distPointBox(a + (b - a) * u + (c - a) * ((1 - u) * v), lo, hi); }, 40);
        },
        40);
}

// Box given as center, half extents and axes (long double).
struct LBox {
    V3 c, e;
    V3 u[3];
    V3 local(const V3& p) const {
        const V3 d = p - c;
        return {oracle::dot(d, u[0]), oracle::dot(d, u[1]), oracle::dot(d, u[2])};
    }
    bool contains(const V3& p) const {
        const V3 l = local(p);
        return std::abs(l.x) <= e.x && std::abs(l.y) <= e.y && std::abs(l.z) <= e.z;
    }
    V3 vertex(int i) const {
        return c + u[0] * (i & 1 ? e.x : -e.x) + u[1] * (i & 2 ? e.y : -e.y) + u[2] * (i & 4 ? e.z : -e.z);
    }
};

LBox toL(const Obb& b, LD scale) {
    LBox l;
    l.c = V3(b.center);
    l.e = V3(b.halfExtents) * scale;
    for (int i = 0; i < 3; ++i) l.u[i] = V3(b.axes.col(i));
    return l;
}

// Edge pq of one box crosses a face of box b (in b's frame: plane x_i = +-e_i).
bool edgeCrossesFace(const V3& p, const V3& q, const LBox& b) {
    const V3 lp = b.local(p), lq = b.local(q);
    for (int i = 0; i < 3; ++i) {
        for (LD side : {LD(-1), LD(1)}) {
            const LD plane = side * b.e[i];
            const LD dp = lp[i] - plane, dq = lq[i] - plane;
            if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) continue;
            const LD s = dp / (dp - dq);
            const V3 x = lp + (lq - lp) * s;
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            if (std::abs(x[j]) <= b.e[j] && std::abs(x[k]) <= b.e[k]) return true;
        }
    }
    return false;
}

bool boxesMeet(const LBox& a, const LBox& b) {
    static constexpr int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                          {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (int i = 0; i < 8; ++i)
        if (b.contains(a.vertex(i)) || a.contains(b.vertex(i))) return true;
    for (const auto& e : kEdges)
        if (edgeCrossesFace(a.vertex(e[0]), a.vertex(e[1]), b) || edgeCrossesFace(b.vertex(e[0]), b.vertex(e[1]), a))
            return true;
    return false;
}

}  // namespace

TEST_SUITE("sat_tests") {
    TEST_CASE("segment-AABB and segment-OBB against the distance oracle") {
        oracle::Rng rng(1);
        int hits = 0, misses = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 1500; ++n) {
                const Vec3 c = rng.vec(-1, 1) + Vec3::Constant(offset), e = rng.vec(0.05, 1.5);
                Segment seg{rng.vec(-3, 3) + Vec3::Constant(offset), rng.vec(-3, 3) + Vec3::Constant(offset)};
                if (n % 7 == 0) seg.b[n % 3] = seg.a[n % 3];  // parallel to a box face
                if (n % 11 == 0) seg.b = seg.a;               // a point
                const V3 lo(c - e), hi(c + e), p(seg.a), q(seg.b), eps(1e-6, 1e-6, 1e-6);
                const bool clearMiss = segmentBoxDistance(p, q, lo, hi) > 1e-6;
                const bool clearHit = segmentBoxDistance(p, q, lo + eps, hi - eps) == 0;
                if (!clearMiss && !clearHit) continue;
                REQUIRE(testSegmentAabb(seg, Aabb{c - e, c + e}).hit == clearHit);
                // The same configuration rotated: segment-OBB.
                const Mat3 R = rng.rotation().toRotationMatrix();
                const Segment rs{c + R * (seg.a - c), c + R * (seg.b - c)};
                CHECK(testSegmentObb(rs, Obb{c, e, R}).hit == clearHit);
                hits += clearHit;
                misses += clearMiss;
            }
        }
        CHECK(hits > 300);
        CHECK(misses > 300);
        // Touching a face / an edge / a corner; parallel; degenerate.
        const Aabb box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        CHECK(testSegmentAabb({Vec3(1, 0.5, 0.5), Vec3(2, 0.5, 0.5)}, box).hit);
        CHECK(testSegmentAabb({Vec3(2, 1, 0.5), Vec3(0, -1, 0.5)}, box).hit);  // touches edge (1,0,z)
        CHECK_FALSE(testSegmentAabb({Vec3(2, 0.999, 0.5), Vec3(0, -1.001, 0.5)}, box).hit);
        CHECK(testSegmentAabb({Vec3(1, 1, 1), Vec3(2, 3, 4)}, box).hit);
        CHECK(testSegmentAabb({Vec3(-1, 1, 0.5), Vec3(2, 1, 0.5)}, box).hit);  // along the top face
        CHECK_FALSE(testSegmentAabb({Vec3(-1, 1.001, 0.5), Vec3(2, 1.001, 0.5)}, box).hit);
        CHECK(testSegmentAabb({Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5)}, box).hit);
        CHECK_FALSE(testSegmentAabb({Vec3(0.5, 0.5, std::nan("")), Vec3(0.5, 0.5, 0.5)}, box).hit);
        CHECK_FALSE(
            testSegmentAabb({Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5)}, Aabb{Vec3(1, 0, 0), Vec3(0, 1, 1)}).hit);
        SatTrace trace;
        const SatResult r = testSegmentAabb({Vec3(2, 2, 0.5), Vec3(3, 0.5, 0.5)}, box, &trace);
        CHECK_FALSE(r.hit);
        CHECK(trace.steps.back().separating);
        CHECK(r.separatingAxis.kind == trace.steps.back().kind);
    }

    TEST_CASE("triangle-AABB against the nested distance oracle, every vertex order") {
        oracle::Rng rng(2);
        int hits = 0, misses = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 250; ++n) {
                const Vec3 c = rng.vec(-1, 1) + Vec3::Constant(offset), e = rng.vec(0.05, 1.2);
                const Vec3 center = rng.vec(-2, 2) + Vec3::Constant(offset);
                Triangle tri{center + rng.vec(-1.5, 1.5), center + rng.vec(-1.5, 1.5), center + rng.vec(-1.5, 1.5)};
                if (n % 9 == 0) tri.c = tri.a + 2.0 * (tri.b - tri.a);  // zero area (sliver, rounded)
                if (n % 13 == 0) tri.b[0] = tri.a[0];                   // an edge parallel to a face
                const V3 lo(c - e), hi(c + e), eps(1e-6, 1e-6, 1e-6);
                const V3 a(tri.a), b(tri.b), cc(tri.c);
                const bool clearMiss = triangleBoxDistance(a, b, cc, lo, hi) > 1e-6;
                const bool clearHit = !clearMiss && triangleBoxDistance(a, b, cc, lo + eps, hi - eps) == 0;
                if (!clearMiss && !clearHit) continue;
                for (const Triangle& perm : oracle::orderings(tri))
                    REQUIRE(testTriangleAabb(perm, Aabb{c - e, c + e}).hit == clearHit);
                hits += clearHit;
                misses += clearMiss;
            }
        }
        CHECK(hits > 40);
        CHECK(misses > 40);
        // Touching cases with exact coordinates.
        const Aabb box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        CHECK(testTriangleAabb({Vec3(1, 0.5, 0.5), Vec3(2, 0, 0), Vec3(2, 1, 1)}, box).hit);  // vertex on face
        CHECK(testTriangleAabb({Vec3(2, 2, 0.5), Vec3(1, 2, 0.5), Vec3(2, 1, 0.5)},
                               Aabb{Vec3(0, 0, 0), Vec3(1.5, 1.5, 1)})
                  .hit);  // edge through corner region
        CHECK_FALSE(testTriangleAabb({Vec3(2, 2, 0.5), Vec3(1, 2, 0.5), Vec3(2, 1, 0.5)},
                                     Aabb{Vec3(0, 0, 0), Vec3(1.49, 1.49, 1)})
                        .hit);
        CHECK(testTriangleAabb({Vec3(-1, -1, 1), Vec3(3, -1, 1), Vec3(-1, 3, 1)}, box).hit);  // lies on the top face
        CHECK_FALSE(testTriangleAabb({Vec3(-1, -1, 1.0001), Vec3(3, -1, 1.0001), Vec3(-1, 3, 1.0001)}, box).hit);
        // Large triangle cutting through the box: only its plane touches it (normal axis).
        CHECK(testTriangleAabb({Vec3(-10, -10, 3), Vec3(10, -10, -3), Vec3(0, 10, 0)}, box).hit);
        SatTrace trace;
        const SatResult sep = testTriangleAabb({Vec3(-10, -10, 12), Vec3(10, -10, 6), Vec3(0, 10, 9)}, box, &trace);
        CHECK_FALSE(sep.hit);
        CHECK(sep.separatingAxis.separating);
        CHECK(trace.steps.back().separating);
        trace.steps.clear();
        CHECK(testTriangleAabb({Vec3(-10, -10, 3), Vec3(10, -10, -3), Vec3(0, 10, 0)}, box, &trace).hit);
        CHECK(trace.steps.size() == 13);
        CHECK(trace.steps.back().kind == SatAxisKind::Normal);
        CHECK_FALSE(testTriangleAabb({Vec3(std::nan(""), 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, box).hit);
    }

    TEST_CASE("OBB-OBB against the feature oracle") {
        oracle::Rng rng(3);
        int hits = 0, misses = 0;
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 1500; ++n) {
                const Vec3 s = Vec3::Constant(offset);
                Obb a = Obb::fromRotation(rng.vec(-1, 1) + s, rng.vec(0.05, 1.2), rng.rotation());
                Obb b = Obb::fromRotation(rng.vec(-1.5, 1.5) + s, rng.vec(0.05, 1.2), rng.rotation());
                if (n % 4 == 0) b.axes = a.axes;  // all edges parallel
                if (n % 4 == 1) {                 // one pair of parallel edges
                    const Eigen::AngleAxisd spin(rng.uniform(0, 6.28), a.axes.col(2));
                    b.axes = spin.toRotationMatrix() * a.axes;
                }
                const bool clearHit = boxesMeet(toL(a, 1 - 1e-6), toL(b, 1 - 1e-6));
                const bool clearMiss = !boxesMeet(toL(a, 1 + 1e-6), toL(b, 1 + 1e-6));
                if (!clearHit && !clearMiss) continue;
                REQUIRE(testObbObb(a, b).hit == clearHit);
                REQUIRE(testObbObb(b, a).hit == clearHit);
                hits += clearHit;
                misses += clearMiss;
            }
        }
        CHECK(hits > 300);
        CHECK(misses > 300);
    }

    TEST_CASE("OBB-OBB exact touching, parallel edges and traces") {
        const Vec3 o(1e4, -1e4, 1e4);
        const Obb a{o, Vec3(1, 1, 1), Mat3::Identity()};
        // Face contact, edge contact (rotated 45 degrees about z: touches with an edge), separated.
        CHECK(testObbObb(a, Obb{o + Vec3(2, 0.5, 0), Vec3(1, 1, 1), Mat3::Identity()}).hit);
        CHECK_FALSE(testObbObb(a, Obb{o + Vec3(2.001, 0.5, 0), Vec3(1, 1, 1), Mat3::Identity()}).hit);
        const Mat3 rz = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).toRotationMatrix();
        CHECK(testObbObb(a, Obb{o + Vec3(1 + std::sqrt(2.0) - 1e-9, 0, 0), Vec3(1, 1, 1), rz}).hit);
        CHECK_FALSE(testObbObb(a, Obb{o + Vec3(1 + std::sqrt(2.0) + 1e-6, 0, 0), Vec3(1, 1, 1), rz}).hit);
        // Edge-edge: b rotated 45 degrees about x and about z, offset along the diagonal: the
        // separating axis is a cross product.
        const Mat3 rx = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix();
        const Obb b{o + Vec3(2.5, 2.5, 0), Vec3(1, 1, 1), rx * rz};
        SatTrace trace;
        const SatResult r = testObbObb(a, b, &trace);
        CHECK(trace.steps.back().separating == !r.hit);
        // Parallel edges (identical axes) far apart along a face axis at a large offset: no
        // spurious result from the zero cross products.
        for (double gap : {0.5, 1e-6}) {
            const Obb c{o + Vec3(0, 2 + gap, 0), Vec3(1, 1, 1), Mat3::Identity()};
            CHECK_FALSE(testObbObb(a, c).hit);
        }
        CHECK(testObbObb(a, a).hit);
        CHECK_FALSE(testObbObb(a, Obb{o, Vec3(-1, 1, 1), Mat3::Identity()}).hit);
        CHECK_FALSE(testObbObb(a, Obb{Vec3(std::nan(""), 0, 0), Vec3(1, 1, 1), Mat3::Identity()}).hit);
        CHECK(testAabbAabb({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 1, 1), Vec3(2, 2, 2)}).hit);
        CHECK_FALSE(
            testAabbAabb({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 1, std::nextafter(1.0, 2.0)), Vec3(2, 2, 2)}).hit);
    }
}
