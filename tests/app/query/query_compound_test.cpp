// `cdlab query` with compounds and meshes (docs/query.md, "Compounds and meshes"): answer formats, a
// non-convex mesh whose notch a sphere sits in (its hull would overlap the sphere), bodies inside
// bodies, and a random sample against an oracle that shares no code with the query (long-double
// point-triangle distances and a closed-form inside test for spheres against an L-shaped prism;
// sphere-sphere closed forms for compounds); the one-line errors for meshes that bound no solid.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include "verification/closest_oracle.h"
#include "app/query/query.h"
#include "tests/app/query/ask.h"

using cdlab::Vec3;
using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

using cdlab::test::ask;

using cdlab::test::keysOf;

const double kXY[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

// The L-shaped prism {(x, y) in [0,2]^2 minus (1,2]^2} x [0, 1] as query JSON.
Json lMesh(const Vec3& offset = Vec3::Zero()) {
    Json vertices = Json::array(), triangles = Json::array();
    for (double z : {0.0, 1.0})
        for (const auto& p : kXY) vertices.push_back({p[0] + offset.x(), p[1] + offset.y(), z + offset.z()});
    const int n = 6;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        triangles.push_back({i, j, n + j});
        triangles.push_back({i, n + j, n + i});
    }
    const int fan[4][3] = {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}};
    for (const auto& t : fan) {
        triangles.push_back({n + t[0], n + t[1], n + t[2]});
        triangles.push_back({t[0], t[2], t[1]});
    }
    return {{"mesh", {{"vertices", vertices}, {"triangles", triangles}}}};
}

Json sphere(const Vec3& c, double r) { return {{"sphere", {{"center", {c.x(), c.y(), c.z()}}, {"radius", r}}}}; }

Json query(const char* op, const Json& a, const Json& b) { return {{"op", op}, {"a", a}, {"b", b}}; }

Vec3 vec(const Json& v) { return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>()); }

// Oracle: the distance from a sphere to the L prism (0 when they meet), from long-double
// point-triangle distances to the prism's faces as rectangles split in two triangles.
double oracleDistance(const Vec3& c, double r) {
    const bool inside = c.x() > 0 && c.x() < 2 && c.y() > 0 && c.y() < 2 && c.z() > 0 && c.z() < 1 &&
                        !(c.x() > 1 && c.y() > 1);
    if (inside) return 0;
    long double best = INFINITY;
    const auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
        best = std::min(best, oracle::triangleDistance2(c, a, b, d));
    };
    for (int i = 0; i < 6; ++i) {  // side walls
        const auto& p = kXY[i];
        const auto& q = kXY[(i + 1) % 6];
        const Vec3 a(p[0], p[1], 0), b(q[0], q[1], 0), a1(p[0], p[1], 1), b1(q[0], q[1], 1);
        tri(a, b, b1);
        tri(a, b1, a1);
    }
    for (double z : {0.0, 1.0}) {  // the L as two rectangles [0,2]x[0,1] and [0,1]x[1,2]
        tri(Vec3(0, 0, z), Vec3(2, 0, z), Vec3(2, 1, z));
        tri(Vec3(0, 0, z), Vec3(2, 1, z), Vec3(0, 1, z));
        tri(Vec3(0, 1, z), Vec3(1, 1, z), Vec3(1, 2, z));
        tri(Vec3(0, 1, z), Vec3(1, 2, z), Vec3(0, 2, z));
    }
    return std::max(0.0, double(std::sqrt(best)) - r);
}

}  // namespace

TEST_SUITE("query") {
    TEST_CASE("compound and mesh: answer formats of intersect, distance and penetration") {
        const Json apart = query("distance", lMesh(), sphere(Vec3(1.6, 1.6, 0.5), 0.2));
        const Json d = ask(apart);
        CHECK(keysOf(d) == std::set<std::string>{"id", "intersect", "distance", "point_a", "point_b"});
        Json p = apart;
        p["op"] = "penetration";
        CHECK(keysOf(ask(p)) == std::set<std::string>{"id", "intersect", "distance", "normal", "point_a", "point_b"});
        const Json deep = query("penetration", lMesh(), sphere(Vec3(0.5, 0.5, 0.5), 0.2));
        CHECK(keysOf(ask(deep)) == std::set<std::string>{"id", "intersect", "depth", "normal", "point_a", "point_b"});
        const Json i = ask(query("intersect", lMesh(), sphere(Vec3(1.6, 1.6, 0.5), 0.2)));
        CHECK(keysOf(i) == std::set<std::string>{"id", "intersect"});
    }

    TEST_CASE("mesh: a sphere in the notch of an L is apart, though it overlaps the L's hull") {
        const Json s = sphere(Vec3(1.6, 1.6, 0.5), 0.2);
        CHECK(ask(query("intersect", lMesh(), s))["intersect"] == false);
        const Json d = ask(query("distance", lMesh(), s));
        const double expected = 0.4;  // to the face y = 1 of the arm [0,2] x [0,1] (the hull: 0.2 - 0.1414 deep)
        CHECK(d["distance"].get<double>() == doctest::Approx(expected).epsilon(1e-14));
        CHECK((vec(d["point_a"]) - Vec3(1.6, 1, 0.5)).norm() < 1e-14);
        CHECK((vec(d["point_b"]) - Vec3(1.6, 1.4, 0.5)).norm() < 1e-14);
        // The same L as a compound of two boxes gives the same distance.
        const Json l2 = {{"compound",
                          {{{"aabb", {{"min", {0, 0, 0}}, {"max", {2, 1, 1}}}}},
                           {{"aabb", {{"min", {0, 1, 0}}, {"max", {1, 2, 1}}}}}}}};
        CHECK(ask(query("distance", l2, s))["distance"].get<double>() == doctest::Approx(expected).epsilon(1e-14));
        // Order of a and b: the same distance, points swapped.
        const Json swapped = ask(query("distance", s, lMesh()));
        CHECK(swapped["distance"].get<double>() == doctest::Approx(expected).epsilon(1e-14));
        CHECK((vec(swapped["point_b"]) - Vec3(1.6, 1, 0.5)).norm() < 1e-14);
        // On the notch's diagonal both inner faces are nearest (a tie): either witness, the same distance.
        const Json corner = ask(query("distance", lMesh(), sphere(Vec3(1.5, 1.5, 0.5), 0.2)));
        CHECK(corner["distance"].get<double>() == doctest::Approx(0.3).epsilon(1e-14));
        const Vec3 pa = vec(corner["point_a"]);
        CHECK(std::min((pa - Vec3(1.5, 1, 0.5)).norm(), (pa - Vec3(1, 1.5, 0.5)).norm()) < 1e-14);
    }

    TEST_CASE("mesh: bodies inside bodies intersect") {
        // A small sphere wholly inside the L meets no triangle; its centre's winding number says inside.
        CHECK(ask(query("intersect", lMesh(), sphere(Vec3(0.5, 0.5, 0.5), 0.1)))["intersect"] == true);
        const Json d = ask(query("distance", sphere(Vec3(0.5, 1.5, 0.5), 0.1), lMesh()));
        CHECK(d["intersect"] == true);
        CHECK(d["distance"].get<double>() == 0.0);
        // The L wholly inside a large sphere.
        CHECK(ask(query("intersect", sphere(Vec3(1, 1, 0.5), 5), lMesh()))["intersect"] == true);
        // Two meshes, one inside the other's arm: a tiny L inside the big one's first arm.
        Json tiny = lMesh();
        for (auto& v : tiny["mesh"]["vertices"])
            for (auto& x : v) x = x.get<double>() * 0.1 + 0.2;
        CHECK(ask(query("intersect", lMesh(), tiny))["intersect"] == true);
        CHECK(ask(query("intersect", tiny, lMesh()))["intersect"] == true);
        // Mesh against mesh, apart along x: the closed-form gap.
        CHECK(ask(query("distance", lMesh(), lMesh(Vec3(2.75, 0, 0))))["distance"].get<double>() ==
              doctest::Approx(0.75).epsilon(1e-14));
        // Touching meshes intersect (closed sets).
        CHECK(ask(query("intersect", lMesh(), lMesh(Vec3(2, 0, 0))))["intersect"] == true);
    }

    TEST_CASE("mesh: distance and intersect agree with an independent oracle on random spheres") {
        std::mt19937_64 rng(17);
        std::uniform_real_distribution<double> u(-0.6, 2.6), uz(-0.6, 1.6), ur(0.01, 0.3);
        int apart = 0, meeting = 0;
        for (int k = 0; k < 400; ++k) {
            const Vec3 c(u(rng), u(rng), uz(rng));
            const double r = ur(rng);
            const double expected = oracleDistance(c, r);
            if (expected > 0 && expected < 1e-9) continue;  // within rounding of touching
            const Json d = ask(query("distance", lMesh(), sphere(c, r)));
            const Json i = ask(query("intersect", sphere(c, r), lMesh()));
            CHECK(i["intersect"] == (expected == 0));
            CHECK(d["intersect"] == (expected == 0));
            CHECK(d["distance"].get<double>() == doctest::Approx(expected).epsilon(1e-12));
            (expected == 0 ? meeting : apart)++;
        }
        CHECK(apart > 100);
        CHECK(meeting > 50);
    }

    TEST_CASE("compound: penetration is the deepest pair's, distance the nearest pair's") {
        // Two spheres as one compound against a third sphere: closed forms.
        const Json pair = {{"compound", {sphere(Vec3(0, 0, 0), 1), sphere(Vec3(5, 0, 0), 1)}}};
        const Json far = ask(query("distance", pair, sphere(Vec3(5, 3.5, 0), 1)));
        CHECK(far["distance"].get<double>() == doctest::Approx(1.5).epsilon(1e-14));
        CHECK((vec(far["point_a"]) - Vec3(5, 1, 0)).norm() < 1e-14);
        const Json pen = ask(query("penetration", pair, sphere(Vec3(5, 1.5, 0), 1)));
        CHECK(pen["intersect"] == true);
        CHECK(pen["depth"].get<double>() == doctest::Approx(0.5).epsilon(1e-14));
        CHECK((vec(pen["normal"]) - Vec3(0, 1, 0)).norm() < 1e-14);
        const Vec3 pa = vec(pen["point_a"]), pb = vec(pen["point_b"]);
        CHECK((pa - pb - 0.5 * Vec3(0, 1, 0)).norm() < 1e-14);
        // Compound against compound: the deeper of two overlapping pairs wins.
        const Json other = {{"compound", {sphere(Vec3(0, 1.8, 0), 1), sphere(Vec3(5, 1.2, 0), 1)}}};
        CHECK(ask(query("penetration", pair, other))["depth"].get<double>() == doctest::Approx(0.8).epsilon(1e-14));
        // A mesh penetrated by a sphere: depth > 0 and docs/query.md's relation point_a - point_b = depth n.
        const Json m = ask(query("penetration", lMesh(), sphere(Vec3(0.5, 0.5, 1.05), 0.2)));
        CHECK(m["intersect"] == true);
        const double depth = m["depth"].get<double>();
        CHECK(depth == doctest::Approx(0.15).epsilon(1e-12));  // through the top face, the nearest way out
        CHECK((vec(m["point_a"]) - vec(m["point_b"]) - depth * vec(m["normal"])).norm() < 1e-12);
    }

    TEST_CASE("mesh: answers scale with the input (1e-300 .. 1e300, powers of two exact)") {
        for (const double k : {std::ldexp(1.0, -1000), std::ldexp(1.0, 1000)}) {
            Json l = lMesh();
            for (auto& v : l["mesh"]["vertices"])
                for (auto& x : v) x = x.get<double>() * k;
            const Json inside = sphere(Vec3(0.5, 0.5, 0.5) * k, 0.1 * k), notch = sphere(Vec3(1.6, 1.6, 0.5) * k, 0.2 * k);
            CHECK(ask(query("intersect", l, inside))["intersect"] == true);
            const Json d = ask(query("distance", l, notch));
            CHECK(d["distance"].get<double>() == doctest::Approx(0.4 * k).epsilon(1e-13));
            const Json p = ask(query("penetration", l, sphere(Vec3(0.5, 0.5, 1.05) * k, 0.2 * k)));
            REQUIRE(p.contains("depth"));
            CHECK(p["depth"].get<double>() == doctest::Approx(0.15 * k).epsilon(1e-12));
        }
    }

    TEST_CASE("compound and mesh: one-line errors with the JSON path") {
        const auto error = [](const Json& q) {
            const Json a = ask(q);
            REQUIRE(a.contains("error"));
            return a["error"].get<std::string>();
        };
        Json open = lMesh();
        open["mesh"]["triangles"].erase(open["mesh"]["triangles"].size() - 1);
        const std::string e1 = error(query("distance", open, sphere(Vec3(5, 0, 0), 1)));
        CHECK(e1.find("$.a.mesh.triangles[") != std::string::npos);
        CHECK(e1.find("not closed") != std::string::npos);
        Json flipped = lMesh();
        std::swap(flipped["mesh"]["triangles"][4][1], flipped["mesh"]["triangles"][4][2]);
        CHECK(error(query("intersect", sphere(Vec3(5, 0, 0), 1), flipped)).find("consistently oriented") !=
              std::string::npos);
        Json badIndex = lMesh();
        badIndex["mesh"]["triangles"][0][1] = 12;
        CHECK(error(query("intersect", badIndex, sphere(Vec3(5, 0, 0), 1))).find("$.a.mesh.triangles[0][1]") !=
              std::string::npos);
        const Json withPlane = {{"compound", {sphere(Vec3(0, 0, 0), 1), {{"plane", {{"normal", {0, 0, 1}}, {"offset", 0}}}}}}};
        CHECK(error(query("distance", withPlane, sphere(Vec3(5, 0, 0), 1))).find("$.a.compound[1]") != std::string::npos);
        CHECK(error(query("contact", lMesh(), sphere(Vec3(5, 0, 0), 1))).find("intersect, distance and penetration") !=
              std::string::npos);
        CHECK(error(query("distance", Json{{"compound", Json::array()}}, sphere(Vec3(5, 0, 0), 1))).find("non-empty") !=
              std::string::npos);
        // An inward-facing mesh bounds the same solid.
        Json inward = lMesh();
        for (auto& t : inward["mesh"]["triangles"]) std::swap(t[1], t[2]);
        CHECK(ask(query("intersect", inward, sphere(Vec3(0.5, 0.5, 0.5), 0.1)))["intersect"] == true);
    }
}
