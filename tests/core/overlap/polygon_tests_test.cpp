// Convex polygon tests (core/overlap/polygon_tests.h). Oracles: exact integer arithmetic (__int128) on
// integer coordinates, with a different formulation (fan triangles for containment, vertex /
// edge features for overlap), and dense sampling for clipping.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/overlap/polygon_tests.h"
#include "verification/intersection_oracles.h"

using cdlab::Vec2;
using cdlab::Vec3;

namespace {

using I = __int128;
struct P {
    long long x, y;
};
I cross(P o, P a, P b) { return I(a.x - o.x) * (b.y - o.y) - I(a.y - o.y) * (b.x - o.x); }

// Andrew's monotone chain (counterclockwise, collinear points dropped).
std::vector<P> hull(std::vector<P> pts) {
    std::sort(pts.begin(), pts.end(), [](P a, P b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    pts.erase(std::unique(pts.begin(), pts.end(), [](P a, P b) { return a.x == b.x && a.y == b.y; }), pts.end());
    if (pts.size() < 3) return pts;
    std::vector<P> h(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
        h[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
        h[k++] = pts[i - 1];
    }
    h.resize(k - 1);
    return h;
}

// Closed triangle containment by exact signs.
bool inTriangle(P a, P b, P c, P p) {
    const I d1 = cross(a, b, p), d2 = cross(b, c, p), d3 = cross(c, a, p);
    const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
    return !(neg && pos);
}
// Oracle containment for a ccw hull with >= 3 vertices: some fan triangle holds p.
bool inHull(const std::vector<P>& h, P p) {
    for (std::size_t i = 1; i + 1 < h.size(); ++i)
        if (inTriangle(h[0], h[i], h[i + 1], p)) return true;
    return false;
}
bool onSeg(P a, P b, P p) {
    return cross(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}
bool segsMeet(P a, P b, P c, P d) {
    const I o1 = cross(a, b, c), o2 = cross(a, b, d), o3 = cross(c, d, a), o4 = cross(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
    return onSeg(a, b, c) || onSeg(a, b, d) || onSeg(c, d, a) || onSeg(c, d, b);
}
bool hullsMeet(const std::vector<P>& a, const std::vector<P>& b) {
    for (P p : a)
        if (inHull(b, p)) return true;
    for (P p : b)
        if (inHull(a, p)) return true;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (segsMeet(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    return false;
}

std::vector<P> randomHull(oracle::Rng& rng, int range, long long cx, long long cy) {
    std::vector<P> pts;
    const int n = rng.integer(3, 9);
    for (int i = 0; i < n; ++i) pts.push_back({cx + rng.integer(-range, range), cy + rng.integer(-range, range)});
    return hull(pts);
}

std::vector<Vec2> toVec(const std::vector<P>& h, double offset, bool reverse, std::size_t rotate) {
    std::vector<Vec2> v;
    for (P p : h) v.push_back(Vec2(double(p.x) + offset, double(p.y) + offset));
    if (reverse) std::reverse(v.begin(), v.end());
    std::rotate(v.begin(), v.begin() + rotate % v.size(), v.end());
    return v;
}

}  // namespace

TEST_SUITE("polygon_tests") {
    TEST_CASE("pointInConvexPolygon2d matches the exact fan oracle (both windings, all starts, offsets)") {
        oracle::Rng rng(3);
        int inside = 0, boundary = 0, total = 0;
        for (double offset : {0.0, 1e4, 1e6}) {
            for (int n = 0; n < 400; ++n) {
                const std::vector<P> h = randomHull(rng, 20, 0, 0);
                if (h.size() < 3) continue;
                for (int q = 0; q < 40; ++q) {
                    const P p{rng.integer(-22, 22), rng.integer(-22, 22)};
                    const bool expected = inHull(h, p);
                    const Vec2 pv(double(p.x) + offset, double(p.y) + offset);
                    for (bool rev : {false, true}) {
                        const auto poly = toVec(h, offset, rev, q);
                        REQUIRE(cdlab::pointInConvexPolygon2d(poly, pv) == expected);
                    }
                    inside += expected;
                    for (std::size_t i = 0; i < h.size(); ++i) boundary += onSeg(h[i], h[(i + 1) % h.size()], p);
                    ++total;
                }
            }
        }
        CHECK(inside > total / 10);
        CHECK(boundary > 100);  // touching cases exercised
    }

    TEST_CASE("pointInConvexPolygon2d degenerate polygons") {
        const std::vector<Vec2> seg = {Vec2(0, 0), Vec2(2, 2), Vec2(1, 1)};
        CHECK(cdlab::pointInConvexPolygon2d(seg, Vec2(0.5, 0.5)));
        CHECK(cdlab::pointInConvexPolygon2d(seg, Vec2(2, 2)));
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(seg, Vec2(2.5, 2.5)));
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(seg, Vec2(0.5, 0.6)));
        const std::vector<Vec2> pt = {Vec2(1, 1)};
        CHECK(cdlab::pointInConvexPolygon2d(pt, Vec2(1, 1)));
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(pt, Vec2(1, 1.0000001)));
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(std::vector<Vec2>{}, Vec2(0, 0)));
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const std::vector<Vec2> tri = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(tri, Vec2(nan, 0)));
        // Collinear consecutive vertices are allowed.
        const std::vector<Vec2> sq = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)};
        CHECK(cdlab::pointInConvexPolygon2d(sq, Vec2(1, 0)));
        CHECK_FALSE(cdlab::pointInConvexPolygon2d(sq, Vec2(1, -1e-300)));
    }

    TEST_CASE("intersectConvexPolygons2d matches the exact feature oracle") {
        oracle::Rng rng(5);
        int hits = 0, total = 0;
        for (double offset : {0.0, 1e4, 1e6}) {
            for (int n = 0; n < 1500; ++n) {
                const std::vector<P> a = randomHull(rng, 8, 0, 0);
                const std::vector<P> b = randomHull(rng, 8, rng.integer(-16, 16), rng.integer(-16, 16));
                const bool expected = hullsMeet(a, b);
                for (int variant = 0; variant < 4; ++variant) {
                    const auto pa = toVec(a, offset, variant & 1, n);
                    const auto pb = toVec(b, offset, variant & 2, n + 1);
                    REQUIRE(cdlab::intersectConvexPolygons2d(pa, pb).hit == expected);
                    REQUIRE(cdlab::intersectConvexPolygons2d(pb, pa).hit == expected);
                }
                hits += expected;
                ++total;
            }
        }
        CHECK(hits > total / 5);
        CHECK(hits < total * 4 / 5);
    }

    TEST_CASE("intersectConvexPolygons2d reports the separating edge and handles touching") {
        const std::vector<Vec2> a = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
        const std::vector<Vec2> touch = {Vec2(1, 0.5), Vec2(2, 0), Vec2(2, 1)};  // vertex on edge
        CHECK(cdlab::intersectConvexPolygons2d(a, touch).hit);
        const std::vector<Vec2> apart = {Vec2(1 + 1e-15, 0.5), Vec2(2, 0), Vec2(2, 1)};
        const auto r = cdlab::intersectConvexPolygons2d(a, apart);
        CHECK_FALSE(r.hit);
        CHECK(r.separatingPolygon == 0);
        CHECK(r.separatingEdge == 1);  // edge (1,0)-(1,1)
        // Segment (2 vertices) and point polygons.
        const std::vector<Vec2> seg = {Vec2(-1, 2), Vec2(2, -1)};
        CHECK(cdlab::intersectConvexPolygons2d(a, seg).hit);
        const std::vector<Vec2> seg2 = {Vec2(-1, 2.0000001), Vec2(2, -0.9999999)};
        CHECK(cdlab::intersectConvexPolygons2d(a, seg2).hit);
        const std::vector<Vec2> corner = {Vec2(1, 1), Vec2(3, 3)};
        CHECK(cdlab::intersectConvexPolygons2d(a, corner).hit);
        const std::vector<Vec2> missCorner = {Vec2(1 + 1e-15, 1), Vec2(3, 3)};
        CHECK_FALSE(cdlab::intersectConvexPolygons2d(a, missCorner).hit);
        CHECK_FALSE(cdlab::intersectConvexPolygons2d(a, std::vector<Vec2>{}).hit);
    }

    TEST_CASE("clipLineToConvexPolygon2d agrees with dense sampling") {
        oracle::Rng rng(9);
        for (int n = 0; n < 300; ++n) {
            std::vector<P> h = randomHull(rng, 10, 0, 0);
            if (h.size() < 3) continue;
            const auto poly = toVec(h, 0.0, n % 2, n);
            const Vec2 p(rng.uniform(-15, 15), rng.uniform(-15, 15));
            const Vec2 d(rng.uniform(-30, 30), rng.uniform(-30, 30));
            const auto clip = cdlab::clipLineToConvexPolygon2d(poly, p, d, 0.0, 1.0);
            // Oracle: sample s in [0, 1]; first and last inside sample.
            double first = -1, last = -1;
            const int N = 20000;
            for (int i = 0; i <= N; ++i) {
                const double s = double(i) / N;
                const Vec2 x = p + s * d;
                bool in = true;
                for (std::size_t k = 0; k < h.size(); ++k) {
                    const P a = h[k], b = h[(k + 1) % h.size()];
                    if ((b.x - a.x) * (x.y() - a.y) - (b.y - a.y) * (x.x() - a.x) < 0) in = false;
                }
                if (in) {
                    if (first < 0) first = s;
                    last = s;
                }
            }
            if (first < 0) {
                // Either a miss or an interval shorter than the sampling step.
                if (clip.hit) CHECK(clip.tExit - clip.tEnter < 2.0 / N);
                continue;
            }
            REQUIRE(clip.hit);
            CHECK(std::abs(clip.tEnter - first) <= 1.0 / N + 1e-12);
            CHECK(std::abs(clip.tExit - last) <= 1.0 / N + 1e-12);
        }
    }

    TEST_CASE("3D polygons: point in polygon and coplanar overlap in rotated planes") {
        oracle::Rng rng(13);
        for (double offset : {0.0, 1e4}) {
            for (int n = 0; n < 300; ++n) {
                const cdlab::Mat3 R = rng.rotation().toRotationMatrix();
                const Vec3 o = rng.vec(-1, 1) + Vec3::Constant(offset);
                auto lift = [&](const Vec2& v) { return Vec3(o + R * Vec3(v.x(), v.y(), 0.0)); };
                const std::vector<P> a = randomHull(rng, 8, 0, 0);
                const std::vector<P> b = randomHull(rng, 8, rng.integer(-16, 16), rng.integer(-16, 16));
                if (a.size() < 3 || b.size() < 3) continue;
                std::vector<Vec3> a3, b3;
                for (P p : a) a3.push_back(lift(Vec2(double(p.x), double(p.y))));
                for (P p : b) b3.push_back(lift(Vec2(double(p.x), double(p.y))));
                // Oracle robust to the rounding of the rotation: the 2D answer must not change when b
                // is moved by a quarter unit (integer inputs: exact answers have margin 0 or >= ...).
                // Shrinking/growing b about its centroid by 2% classifies clear cases.
                auto scaled = [&](double f) {
                    double cx = 0, cy = 0;
                    for (P p : b) {
                        cx += double(p.x);
                        cy += double(p.y);
                    }
                    cx /= double(b.size());
                    cy /= double(b.size());
                    std::vector<Vec2> out;
                    for (P p : b) out.push_back(Vec2(cx + f * (double(p.x) - cx), cy + f * (double(p.y) - cy)));
                    return out;
                };
                std::vector<Vec2> a2;
                for (P p : a) a2.push_back(Vec2(double(p.x), double(p.y)));
                const bool shrunkHit = cdlab::intersectConvexPolygons2d(a2, scaled(0.98)).hit;
                const bool grownHit = cdlab::intersectConvexPolygons2d(a2, scaled(1.02)).hit;
                const double tol = 1e-9 * (1.0 + offset);
                if (shrunkHit) CHECK(cdlab::intersectCoplanarConvexPolygons3d(a3, b3, tol).hit);
                if (!grownHit) CHECK_FALSE(cdlab::intersectCoplanarConvexPolygons3d(a3, b3, tol).hit);
                // Lifted off the plane by far more than the tolerance: never.
                std::vector<Vec3> off = b3;
                for (Vec3& v : off) v += R.col(2) * 1e-3;
                CHECK_FALSE(cdlab::intersectCoplanarConvexPolygons3d(a3, off, tol).hit);
                // Point containment: centroid of a inside, a point outside the bounding circle out.
                Vec3 centroid = Vec3::Zero();
                for (const Vec3& v : a3) centroid += v / double(a3.size());
                CHECK(cdlab::pointInConvexPolygon3d(a3, centroid, tol));
                CHECK_FALSE(cdlab::pointInConvexPolygon3d(a3, lift(Vec2(40, 0)), tol));
                CHECK_FALSE(cdlab::pointInConvexPolygon3d(a3, centroid + R.col(2) * 1e-3, tol));
            }
        }
        // Degenerate 3D polygons: a segment.
        const std::vector<Vec3> seg = {Vec3(0, 0, 0), Vec3(2, 2, 2)};
        CHECK(cdlab::pointInConvexPolygon3d(seg, Vec3(1, 1, 1)));
        CHECK_FALSE(cdlab::pointInConvexPolygon3d(seg, Vec3(1, 1, 1.5)));
        CHECK_FALSE(cdlab::pointInConvexPolygon3d(seg, Vec3(3, 3, 3)));
    }
}
