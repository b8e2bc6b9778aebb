// The primitives demo draws its figures from the traces checked here: every committed scene of
// golden/primitives is run numerically (RunContext{} without GL) and its numbers are recomputed
// here another way — the quadratic's roots from the closest approach, the slab intervals from the
// box's planes, the SAT intervals by projecting every corner, the point-in-polygon verdicts by an
// exact quarter-turn winding count — and the reader's errors name the JSON path.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app/catalog/catalog.h"
#include "verification/polygon_oracle.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

Json sceneJson(const std::string& name) {
    return readJsonFile(std::string(CDLAB_SOURCE_DIR) + "/golden/primitives/" + name + ".json");
}

Json runScene(const std::string& name) {
    return loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/primitives/" + name + ".json")->run(RunContext{}).trace;
}

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

std::string errorOf(const std::string& text) { return test::sceneTextError(text); }

Mat3 rotation(const Json& q) {
    return Quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>()).normalized().toRotationMatrix();
}

}  // namespace

TEST_SUITE("primitives_demo") {
    TEST_CASE("ray and segment vs sphere: the roots are the line's crossings, the outcome names the answer") {
        for (const char* name : {"ray_sphere", "segment_sphere_short"}) {
            const Json s = sceneJson(name), t = runScene(name);
            const Vec3 c = vec(s["shape"]["sphere"]["center"]);
            const double r = s["shape"]["sphere"]["radius"];
            Vec3 o, d;
            if (s.contains("ray")) {
                o = vec(s["ray"]["origin"]);
                d = vec(s["ray"]["direction"]);
            } else {
                o = vec(s["segment"][0]);
                d = vec(s["segment"][1]) - o;
            }
            // Closest approach of the line, then half the chord: t = tc ± sqrt(r² − dist²) / |d|.
            const double tc = (c - o).dot(d) / d.squaredNorm();
            const double dist = (o + tc * d - c).norm();
            REQUIRE(dist < r);
            const double half = std::sqrt(r * r - dist * dist) / d.norm();
            const Json& q = t["quadratic"];
            CHECK(q["roots"][0].get<double>() == doctest::Approx(tc - half).epsilon(1e-12));
            CHECK(q["roots"][1].get<double>() == doctest::Approx(tc + half).epsilon(1e-12));
            const bool reaches = tc - half >= 0 && (s.contains("ray") || tc - half <= 1);
            CHECK(t["hit"].get<bool>() == reaches);
            CHECK(q["outcome"] == (reaches ? "hit" : "beyond the end"));
            if (reaches) CHECK(t["t"].get<double>() == doctest::Approx(tc - half).epsilon(1e-12));
        }
    }

    TEST_CASE("ray vs AABB: each slab's interval is where the ray is between the slab's two planes") {
        for (const char* name : {"ray_aabb", "ray_aabb_miss"}) {
            const Json s = sceneJson(name), t = runScene(name);
            const Vec3 o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
            const Vec3 lo = vec(s["shape"]["aabb"]["min"]), hi = vec(s["shape"]["aabb"]["max"]);
            double enter = 0, exit = INFINITY;
            for (const Json& slab : t["slabs"]) {
                const int i = slab["axis"];
                const double a = (lo[i] - o[i]) / d[i], b = (hi[i] - o[i]) / d[i];
                CHECK(std::min(a, b) == doctest::Approx(std::min(slab["t_near"].get<double>(), slab["t_far"].get<double>())));
                CHECK(std::max(a, b) == doctest::Approx(std::max(slab["t_near"].get<double>(), slab["t_far"].get<double>())));
                enter = std::max(enter, std::min(a, b));
                exit = std::min(exit, std::max(a, b));
            }
            CHECK(t["hit"].get<bool>() == (enter <= exit));
            if (enter <= exit) {
                CHECK(t["t"].get<double>() == doctest::Approx(enter));
                CHECK(t["t_exit"].get<double>() == doctest::Approx(exit));
                // The entry point lies on the box's surface.
                const Vec3 p = o + enter * d;
                CHECK(((p - lo).cwiseMin(hi - p)).cwiseAbs().minCoeff() < 1e-12);
            }
        }
    }

    TEST_CASE("segment vs OBB: the slabs are the box's own, in its frame") {
        const Json s = sceneJson("segment_obb"), t = runScene("segment_obb");
        const Json& b = s["shape"]["obb"];
        const Mat3 R = rotation(b["rotation"]);
        const Vec3 c = vec(b["center"]), e = vec(b["half_extents"]);
        const Vec3 p = vec(s["segment"][0]), q = vec(s["segment"][1]);
        const Vec3 u0 = R.transpose() * (p - c), du = R.transpose() * (q - p);
        double enter = 0, exit = 1;
        for (const Json& slab : t["slabs"]) {
            const int i = slab["axis"];
            const double lo = std::min((-e[i] - u0[i]) / du[i], (e[i] - u0[i]) / du[i]),
                         hi = std::max((-e[i] - u0[i]) / du[i], (e[i] - u0[i]) / du[i]);
            CHECK(std::min(slab["t_near"].get<double>(), slab["t_far"].get<double>()) == doctest::Approx(lo).epsilon(1e-12));
            CHECK(std::max(slab["t_near"].get<double>(), slab["t_far"].get<double>()) == doctest::Approx(hi).epsilon(1e-12));
            enter = std::max(enter, lo);
            exit = std::min(exit, hi);
        }
        REQUIRE(t["hit"].get<bool>() == (enter <= exit));
        CHECK(t["t"].get<double>() == doctest::Approx(enter).epsilon(1e-12));
        CHECK(t["t_exit"].get<double>() == doctest::Approx(exit).epsilon(1e-12));
    }

    TEST_CASE("ray vs triangle: the weights rebuild the hit point") {
        const Json s = sceneJson("ray_triangle"), t = runScene("ray_triangle");
        REQUIRE(t["hit"].get<bool>());
        const Json& tri = s["shape"]["triangle"];
        const Vec3 w = vec(t["barycentric"]);
        const Vec3 p = w.x() * vec(tri[0]) + w.y() * vec(tri[1]) + w.z() * vec(tri[2]);
        CHECK((p - vec(t["point"])).norm() < 1e-12);
        CHECK(w.minCoeff() >= 0);
        CHECK(w.sum() == doctest::Approx(1.0));
        CHECK((vec(s["ray"]["origin"]) + t["t"].get<double>() * vec(s["ray"]["direction"]) - p).norm() < 1e-12);
    }

    TEST_CASE("ray vs sphere: a ray that starts inside hits at 0, a tangent ray has one double root") {
        {
            const Json s = sceneJson("ray_sphere_inside"), t = runScene("ray_sphere_inside");
            const Vec3 c = vec(s["shape"]["sphere"]["center"]), o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
            const double r = s["shape"]["sphere"]["radius"];
            REQUIRE((o - c).norm() < r);
            // The chord through o: one crossing behind it, one ahead; the ray is in the sphere at t = 0.
            const double tc = (c - o).dot(d) / d.squaredNorm(), dist = (o + tc * d - c).norm();
            const double half = std::sqrt(r * r - dist * dist) / d.norm();
            CHECK(t["quadratic"]["roots"][0].get<double>() == doctest::Approx(tc - half).epsilon(1e-12));
            CHECK(t["quadratic"]["roots"][1].get<double>() == doctest::Approx(tc + half).epsilon(1e-12));
            CHECK(tc - half < 0);
            CHECK(tc + half > 0);
            CHECK(t["hit"].get<bool>());
            CHECK(t["t"].get<double>() == 0);
            CHECK(t["quadratic"]["c"].get<double>() == doctest::Approx((o - c).squaredNorm() - r * r).epsilon(1e-12));
        }
        {
            const Json s = sceneJson("ray_sphere_tangent"), t = runScene("ray_sphere_tangent");
            const Vec3 c = vec(s["shape"]["sphere"]["center"]), o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
            const double r = s["shape"]["sphere"]["radius"];
            // The line's closest approach to the centre is exactly r away: one root, where it touches.
            const double tc = (c - o).dot(d) / d.squaredNorm();
            CHECK((o + tc * d - c).norm() == doctest::Approx(r).epsilon(1e-15));
            CHECK(t["quadratic"]["discriminant"].get<double>() == 0);
            CHECK(t["quadratic"]["roots"][0].get<double>() == doctest::Approx(tc).epsilon(1e-15));
            CHECK(t["quadratic"]["roots"][1].get<double>() == doctest::Approx(tc).epsilon(1e-15));
            CHECK(t["hit"].get<bool>());
            CHECK((vec(t["point"]) - c).norm() == doctest::Approx(r).epsilon(1e-15));
        }
    }

    TEST_CASE("ray vs AABB: a ray parallel to a slab is inside it for every t or never") {
        const Json s = sceneJson("ray_aabb_parallel"), t = runScene("ray_aabb_parallel");
        const Vec3 o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
        const Vec3 lo = vec(s["shape"]["aabb"]["min"]), hi = vec(s["shape"]["aabb"]["max"]);
        double enter = 0, exit = INFINITY;
        int parallel = 0;
        for (const Json& slab : t["slabs"]) {
            const int i = slab["axis"];
            CHECK(slab["parallel"].get<bool>() == (d[i] == 0));
            if (d[i] == 0) {
                ++parallel;
                CHECK(slab["rejected"].get<bool>() == !(lo[i] <= o[i] && o[i] <= hi[i]));
                continue;
            }
            const double a = (lo[i] - o[i]) / d[i], b = (hi[i] - o[i]) / d[i];
            CHECK(std::min(a, b) == doctest::Approx(slab["t_near"].get<double>()));
            CHECK(std::max(a, b) == doctest::Approx(slab["t_far"].get<double>()));
            enter = std::max(enter, std::min(a, b));
            exit = std::min(exit, std::max(a, b));
        }
        CHECK(parallel == 1);
        REQUIRE(t["hit"].get<bool>() == (enter <= exit));
        CHECK(t["t"].get<double>() == doctest::Approx(enter));
        CHECK(t["t_exit"].get<double>() == doctest::Approx(exit));
    }

    TEST_CASE("ray vs triangle: a miss by a negative weight at the plane point") {
        const Json s = sceneJson("ray_triangle_miss"), t = runScene("ray_triangle_miss");
        const Json& tri = s["shape"]["triangle"];
        const Vec3 a = vec(tri[0]), b = vec(tri[1]), c = vec(tri[2]);
        const Vec3 o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
        // o + t·d = a + u·(b − a) + v·(c − a), solved by Cramer's rule: weights (1 − u − v, u, v).
        Mat3 m;
        m.col(0) = b - a;
        m.col(1) = c - a;
        m.col(2) = -d;
        const double det = m.determinant();
        REQUIRE(det != 0);
        Vec3 x;
        for (int k = 0; k < 3; ++k) {
            Mat3 mk = m;
            mk.col(k) = o - a;
            x[k] = mk.determinant() / det;
        }
        const Vec3 w(1 - x[0] - x[1], x[0], x[1]);
        CHECK_FALSE(t["hit"].get<bool>());
        const Json& crossing = t["plane_crossing"];
        CHECK(crossing["t"].get<double>() == doctest::Approx(x[2]).epsilon(1e-12));
        for (int k = 0; k < 3; ++k) CHECK(crossing["weights"][k].get<double>() == doctest::Approx(w[k]).epsilon(1e-12));
        CHECK(w.minCoeff() < 0);  // the miss: one weight negative, the plane point outside
        CHECK(x[2] > 0);          // ahead of the origin, so the weight alone decides
        CHECK((vec(crossing["point"]) - (o + x[2] * d)).norm() < 1e-12);
    }

    TEST_CASE("sphere vs sphere and sphere vs AABB: the distance, Arvo's clamp and the verdict recomputed") {
        {
            const Json s = sceneJson("sphere_sphere"), t = runScene("sphere_sphere");
            const Vec3 ca = vec(s["a"]["sphere"]["center"]), cb = vec(s["b"]["sphere"]["center"]);
            const double ra = s["a"]["sphere"]["radius"], rb = s["b"]["sphere"]["radius"];
            CHECK(t["distance"].get<double>() == doctest::Approx((cb - ca).norm()).epsilon(1e-15));
            CHECK(t["reach"].get<double>() == ra + rb);
            CHECK(t["hit"].get<bool>() == ((cb - ca).squaredNorm() <= (ra + rb) * (ra + rb)));
            CHECK(t["hit"].get<bool>());  // the scene shows an overlap
        }
        {
            const Json s = sceneJson("sphere_aabb"), t = runScene("sphere_aabb");
            const Vec3 c = vec(s["a"]["sphere"]["center"]);
            const Vec3 lo = vec(s["b"]["aabb"]["min"]), hi = vec(s["b"]["aabb"]["max"]);
            const Vec3 clamped = c.cwiseMax(lo).cwiseMin(hi);
            CHECK((vec(t["closest"]) - clamped).norm() < 1e-15);
            CHECK(t["distance"].get<double>() == doctest::Approx((c - clamped).norm()).epsilon(1e-15));
            CHECK(t["hit"].get<bool>() == ((c - clamped).norm() <= s["a"]["sphere"]["radius"].get<double>()));
        }
    }

    TEST_CASE("SAT: every listed interval is the projection of the shape's corners, and the verdict follows") {
        for (const char* name : {"sat_obb_obb", "sat_obb_obb_overlap", "sat_triangle_aabb"}) {
            const Json s = sceneJson(name), t = runScene(name);
            // The corners of each shape, and the box's centre (projections are measured from it).
            auto corners = [](const Json& shape, Vec3* centre) {
                std::vector<Vec3> v;
                if (shape.contains("obb")) {
                    const Json& b = shape["obb"];
                    const Vec3 c = vec(b["center"]), e = vec(b["half_extents"]);
                    const Mat3 R = rotation(b["rotation"]);
                    for (int i = 0; i < 8; ++i)
                        v.push_back(c + R * Vec3(i & 1 ? e.x() : -e.x(), i & 2 ? e.y() : -e.y(), i & 4 ? e.z() : -e.z()));
                    if (centre) *centre = c;
                } else if (shape.contains("aabb")) {
                    const Vec3 lo = vec(shape["aabb"]["min"]), hi = vec(shape["aabb"]["max"]);
                    for (int i = 0; i < 8; ++i)
                        v.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
                    if (centre) *centre = 0.5 * (lo + hi);
                } else {
                    for (const Json& p : shape["triangle"]) v.push_back(vec(p));
                }
                return v;
            };
            const bool boxFirst = !s["a"].contains("triangle");
            Vec3 centre = Vec3::Zero();
            const std::vector<Vec3> box = corners(boxFirst ? s["a"] : s["b"], &centre);
            const std::vector<Vec3> other = corners(boxFirst ? s["b"] : s["a"], nullptr);
            const std::string boxName = boxFirst ? "A" : "box", otherName = boxFirst ? "B" : "triangle";
            bool separated = false;
            double leastOverlap = -INFINITY;
            for (const Json& axis : t["axes"]) {
                if (axis["zero_axis"].get<bool>()) continue;
                const Vec3 u = vec(axis["axis"]);
                auto interval = [&](const std::vector<Vec3>& pts) {
                    double lo = INFINITY, hi = -INFINITY;
                    for (const Vec3& p : pts) {
                        lo = std::min(lo, (p - centre).dot(u));
                        hi = std::max(hi, (p - centre).dot(u));
                    }
                    return std::pair{lo, hi};
                };
                const auto [blo, bhi] = interval(box);
                const auto [olo, ohi] = interval(other);
                // Core's intervals carry a 1e-6-relative inflation on cross-product axes (parallel edges).
                CHECK(axis[boxName][0].get<double>() == doctest::Approx(blo).epsilon(1e-5));
                CHECK(axis[boxName][1].get<double>() == doctest::Approx(bhi).epsilon(1e-5));
                CHECK(axis[otherName][0].get<double>() == doctest::Approx(olo).epsilon(1e-5));
                CHECK(axis[otherName][1].get<double>() == doctest::Approx(ohi).epsilon(1e-5));
                const double gap = std::max(olo - bhi, blo - ohi);
                CHECK(axis["separating"].get<bool>() == (gap > 0));
                separated = separated || gap > 0;
                leastOverlap = std::max(leastOverlap, gap);
            }
            CHECK(t["intersect"].get<bool>() == !separated);
            if (separated) CHECK(t["axes"].back()["separating"].get<bool>());  // the test stops at the first
            else CHECK(t["tested_axes"] == t["candidate_axes"]);
        }
        CHECK_FALSE(runScene("sat_obb_obb")["intersect"].get<bool>());
        CHECK(runScene("sat_obb_obb_overlap")["intersect"].get<bool>());
    }

    TEST_CASE("point in polygon: the verdicts agree with an exact winding count") {
        for (const char* name : {"point_in_polygon", "point_in_pentagram"}) {
            const Json s = sceneJson(name), t = runScene(name);
            std::vector<Vec2> poly;
            for (const Json& v : s["polygon"]) poly.emplace_back(v[0].get<double>(), v[1].get<double>());
            for (const Json& q : t["queries"]) {
                const Vec2 p(q["point"][0].get<double>(), q["point"][1].get<double>());
                // Signed quarter turns of v - p around p (no angle is computed).
                auto quadrant = [](const Vec2& v) { return v.x() > 0 && v.y() >= 0 ? 0 : v.x() <= 0 && v.y() > 0 ? 1 : v.x() < 0 && v.y() <= 0 ? 2 : 3; };
                int turns = 0;
                for (std::size_t i = 0; i < poly.size(); ++i) {
                    const Vec2 a = poly[i] - p, b = poly[(i + 1) % poly.size()] - p;
                    int dq = quadrant(b) - quadrant(a);
                    if (dq == 3) dq = -1;
                    if (dq == -3) dq = 1;
                    if (dq == 2 || dq == -2) dq = a.x() * b.y() - a.y() * b.x() > 0 ? 2 : -2;
                    turns += dq;
                }
                const int winding = turns / 4;
                CHECK(q["angle_sum"]["winding"].get<int>() == winding);
                CHECK(q["crossing_number"]["inside"].get<bool>() == (winding % 2 != 0));
                if (q["same_side"]["inside"].get<bool>()) CHECK(winding != 0);
            }
        }
        // The figures' claims: the notch fools the edge-side test (q2 of the non-convex polygon is
        // outside by every rule, q1 inside but rejected by an edge), the pentagram's centre is wound twice.
        const Json notch = runScene("point_in_polygon")["queries"];
        CHECK_FALSE(notch[0]["same_side"]["inside"].get<bool>());
        CHECK(notch[0]["crossing_number"]["inside"].get<bool>());
        const Json star = runScene("point_in_pentagram")["queries"];
        CHECK(std::abs(star[0]["angle_sum"]["winding"].get<int>()) == 2);
        CHECK_FALSE(star[0]["crossing_number"]["inside"].get<bool>());
    }

    TEST_CASE("sphere vs box and triangle: the closest point and the verdict recomputed") {
        {
            const Json s = sceneJson("sphere_obb"), t = runScene("sphere_obb");
            const Vec3 c = vec(s["a"]["sphere"]["center"]);
            const double r = s["a"]["sphere"]["radius"];
            const Json& b = s["b"]["obb"];
            const Mat3 R = rotation(b["rotation"]);
            const Vec3 e = vec(b["half_extents"]), centre = vec(b["center"]);
            // The nearest box point by brute force over a fine grid of the box's surface and inside.
            double best = INFINITY;
            const int n = 40;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j)
                    for (int k = 0; k <= n; ++k) {
                        const Vec3 local((2.0 * i / n - 1) * e.x(), (2.0 * j / n - 1) * e.y(), (2.0 * k / n - 1) * e.z());
                        best = std::min(best, (centre + R * local - c).norm());
                    }
            CHECK(t["distance"].get<double>() <= best + 1e-12);
            CHECK(t["distance"].get<double>() >= best - 0.06);  // the grid's spacing
            CHECK((vec(t["closest"]) - c).norm() == doctest::Approx(t["distance"].get<double>()));
            CHECK(t["hit"].get<bool>() == (t["distance"].get<double>() <= r));
        }
        {
            const Json s = sceneJson("sphere_triangle"), t = runScene("sphere_triangle");
            const Vec3 c = vec(s["a"]["sphere"]["center"]);
            const Json& tri = s["b"]["triangle"];
            const Vec3 a = vec(tri[0]), b = vec(tri[1]), d = vec(tri[2]);
            double best = INFINITY;
            const int n = 400;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; i + j <= n; ++j)
                    best = std::min(best, (a + (b - a) * (double(i) / n) + (d - a) * (double(j) / n) - c).norm());
            CHECK(t["distance"].get<double>() <= best + 1e-12);
            CHECK(t["distance"].get<double>() >= best - 0.01);
            CHECK(t["hit"].get<bool>() == (t["distance"].get<double>() <= s["a"]["sphere"]["radius"].get<double>()));
        }
    }

    TEST_CASE("moving 2D objects: touching at the time of impact, apart an instant before") {
        // The triangle against the segment: the polygon oracle's distance (long double, no GJK).
        {
            const Json s = sceneJson("moving_triangle_segment"), t = runScene("moving_triangle_segment");
            REQUIRE(t["hit"].get<bool>());
            const Vec3 v(s["velocity"][0].get<double>(), s["velocity"][1].get<double>(), 0);
            auto movedBy = [&](double time) {
                std::vector<Vec3> tri;
                for (const Json& p : s["moving"]["triangle"]) tri.push_back(Vec3(p[0].get<double>(), p[1].get<double>(), 0) + time * v);
                return oracle::polygon2(tri);
            };
            // A segment as a two-corner polygon: its edge normals both ways.
            std::vector<Vec3> seg;
            for (const Json& p : s["still"]["segment"]) seg.emplace_back(p[0].get<double>(), p[1].get<double>(), 0);
            const auto S = oracle::polygon2(seg);
            const double tc = t["t"];
            CHECK(double(oracle::polygonDistance(S, movedBy(tc))) <= 1e-9);
            CHECK(oracle::polygonDistance(S, movedBy(tc - 1e-6)) > 0);
        }
        // The circle against the rectangle: its centre at distance r from the rectangle at t, more before.
        {
            const Json s = sceneJson("moving_circle_rectangle"), t = runScene("moving_circle_rectangle");
            REQUIRE(t["hit"].get<bool>());
            const Json& rect = s["still"]["rectangle"];
            const double a = rect["angle"].get<double>() * M_PI / 180.0;
            const Vec3 c(rect["center"][0].get<double>(), rect["center"][1].get<double>(), 0);
            const Vec3 u(std::cos(a), std::sin(a), 0), w(-std::sin(a), std::cos(a), 0);
            const double hx = rect["half_extents"][0], hy = rect["half_extents"][1];
            auto distanceToRect = [&](const Vec3& p) {  // clamp in the rectangle's frame
                const double x = std::clamp((p - c).dot(u), -hx, hx), y = std::clamp((p - c).dot(w), -hy, hy);
                return (c + x * u + y * w - p).norm();
            };
            const Vec3 centre(s["moving"]["circle"]["center"][0].get<double>(), s["moving"]["circle"]["center"][1].get<double>(), 0);
            const Vec3 v(s["velocity"][0].get<double>(), s["velocity"][1].get<double>(), 0);
            const double r = s["moving"]["circle"]["radius"], tc = t["t"];
            CHECK(distanceToRect(centre + tc * v) == doctest::Approx(r).epsilon(1e-9));
            CHECK(distanceToRect(centre + (tc - 1e-6) * v) > r);
        }
    }

    TEST_CASE("bad scenes: one error naming the JSON path") {
        const std::string head = R"({"demo": "primitives", )";
        CHECK(errorOf(head + R"("test": "raycast", "ray": {"origin": [0,0,0], "direction": [0,0,0]},
                      "shape": {"sphere": {"center": [0,0,0], "radius": 1}}})")
                  .find("$.ray.direction") != std::string::npos);
        CHECK(errorOf(head + R"("test": "raycast", "ray": {"origin": [0,0,0], "direction": [1,0,0]},
                      "segment": [[0,0,0],[1,0,0]], "shape": {"sphere": {"center": [0,0,0], "radius": 1}}})")
                  .find("exactly one of 'ray' or 'segment'") != std::string::npos);
        CHECK(errorOf(head + R"("test": "sat", "a": {"sphere": {"center": [0,0,0], "radius": 1}},
                      "b": {"aabb": {"min": [0,0,0], "max": [1,1,1]}}})")
                  .find("$.a") != std::string::npos);
        CHECK(errorOf(head + R"("test": "sat", "a": {"triangle": [[0,0,0],[1,0,0],[0,1,0]]},
                      "b": {"obb": {"center": [0,0,0], "half_extents": [1,1,1]}}})")
                  .find("takes an aabb") != std::string::npos);
        CHECK(errorOf(head + R"("test": "sat", "a": {"segment": [[0,0,0],[1,0,0]]},
                      "b": {"triangle": [[0,0,0],[1,0,0],[0,1,0]]}})")
                  .find("must be a box") != std::string::npos);
        CHECK(errorOf(head + R"("test": "raycast", "ray": {"origin": [0,0,0], "direction": [1,0,0]},
                      "shape": {"aabb": {"min": [0,0,0], "max": [1,-1,1]}}})")
                  .find("$.shape.aabb.max") != std::string::npos);
        CHECK(errorOf(head + R"("test": "point_in_polygon", "polygon": [[0,0],[1,0]], "queries": [[0,0]]})")
                  .find("$.polygon") != std::string::npos);
        CHECK(errorOf(head + R"("test": "point_in_polygon", "polygon": [[0,0],[1,0],[0,1]], "queries": [[0,0]],
                      "colour": 1})")
                  .find("colour") != std::string::npos);
        CHECK(errorOf(head + R"("test": "boxes"})").find("$.test") != std::string::npos);
    }
}
