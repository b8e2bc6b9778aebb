// `cdlab query` "contact" for spheres and capsules (issue 21 §2) against closed forms: a sphere or
// capsule on a plane (signed distances of the ends), on a box face (clamped distances, the segment
// clipped to the face by hand), sphere pairs; the answer conventions of every contact.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "app/query/query.h"
#include "tests/app/query/ask.h"

using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

using cdlab::test::ask;
Json roundedContact(const Json& a, const Json& b, int maxPoints = 4) {
    return ask({{"op", "contact"}, {"a", a}, {"b", b}, {"max_points", maxPoints}});
}
double at(const Json& v, int i) { return v[i].get<double>(); }

// Every point: point_a − point_b = depth·n.
void checkRoundedConvention(const Json& r) {
    for (const Json& p : r["points"])
        for (int i = 0; i < 3; ++i)
            CHECK(at(p["point_a"], i) - at(p["point_b"], i) ==
                  doctest::Approx(p["depth"].get<double>() * at(r["normal"], i)).epsilon(1e-12).scale(1));
}

const Json kGroundZ = {{"plane", {{"normal", {0, 0, 2}}, {"offset", 0}}}};  // z <= 0, non-unit normal

}  // namespace

TEST_SUITE("query") {
    TEST_CASE("contact: a sphere on a plane, either order, and separated") {
        const Json sphere = {{"sphere", {{"center", {0.3, -0.2, 0.9}}, {"radius", 1}}}};
        const Json r = roundedContact(sphere, kGroundZ);
        REQUIRE(r["colliding"] == true);
        CHECK(r["depth"].get<double>() == doctest::Approx(0.1));
        CHECK(r["normal"] == Json({0.0, 0.0, -1.0}));
        REQUIRE(r["points"].size() == 1);
        CHECK(r["feature_a"] == Json({{"type", "vertex"}, {"vertices", {0}}}));
        CHECK(r["feature_b"] == Json({{"type", "plane"}}));
        checkRoundedConvention(r);
        const Json swapped = roundedContact(kGroundZ, sphere);
        CHECK(swapped["normal"] == Json({0.0, 0.0, 1.0}));
        checkRoundedConvention(swapped);
        // Below the ground entirely: the half-space is solid, the depth is to its surface.
        CHECK(roundedContact({{"sphere", {{"center", {0, 0, -3}}, {"radius", 1}}}}, kGroundZ)["depth"].get<double>() == 4.0);
        const Json apart = roundedContact({{"sphere", {{"center", {0, 0, 1.5}}, {"radius", 1}}}}, kGroundZ);
        CHECK(apart["colliding"] == false);
        CHECK(apart["distance"].get<double>() == 0.5);
    }

    TEST_CASE("contact: a capsule on a plane keeps both ends when both reach it, one when tilted") {
        const Json flat = {{"capsule", {{"a", {-1, 0, 0.45}}, {"b", {1, 0, 0.45}}, {"radius", 0.5}}}};
        const Json r = roundedContact(flat, kGroundZ);
        REQUIRE(r["points"].size() == 2);
        for (const Json& p : r["points"]) CHECK(p["depth"].get<double>() == doctest::Approx(0.05));
        CHECK(r["feature_a"] == Json({{"type", "edge"}, {"vertices", {0, 1}}}));
        checkRoundedConvention(r);
        CHECK(roundedContact(flat, kGroundZ, 1)["points"].size() == 1);
        const Json tilted = {{"capsule", {{"a", {-1, 0, 0.45}}, {"b", {1, 0, 0.6}}, {"radius", 0.5}}}};
        const Json t = roundedContact(tilted, kGroundZ);
        REQUIRE(t["points"].size() == 1);
        CHECK(t["feature_a"] == Json({{"type", "vertex"}, {"vertices", {0}}}));
        CHECK(at(t["points"][0]["point_a"], 0) == -1.0);
    }

    TEST_CASE("contact: a capsule on a box face is clipped to the face, across an edge it is one point") {
        const Json capsule = {{"capsule", {{"a", {-1, 0, 0.45}}, {"b", {1, 0, 0.45}}, {"radius", 0.5}}}};
        const Json narrow = {{"aabb", {{"min", {-0.5, -5, -1}}, {"max", {0.5, 5, 0}}}}};
        const Json r = roundedContact(narrow, capsule);
        REQUIRE(r["colliding"] == true);
        CHECK(r["normal"] == Json({0.0, 0.0, 1.0}));
        REQUIRE(r["points"].size() == 2);
        std::vector<double> xs = {at(r["points"][0]["point_a"], 0), at(r["points"][1]["point_a"], 0)};
        std::sort(xs.begin(), xs.end());
        CHECK(xs[0] == doctest::Approx(-0.5));  // clipped to the face's sides x = ±0.5
        CHECK(xs[1] == doctest::Approx(0.5));
        CHECK(r["feature_a"]["type"] == "face");
        CHECK(r["feature_b"] == Json({{"type", "edge"}, {"vertices", {0, 1}}}));
        checkRoundedConvention(r);
        // Over the box's edge x = 0.5, z = 0 at 45°: the normal is the edge's, one point.
        const Json over = {{"capsule", {{"a", {0.8, -1, 0.3}}, {"b", {0.8, 1, 0.3}}, {"radius", 0.5}}}};
        const Json e = roundedContact(narrow, over);
        REQUIRE(e["colliding"] == true);
        CHECK(e["points"].size() == 1);
        CHECK(e["depth"].get<double>() == doctest::Approx(0.5 - std::hypot(0.3, 0.3)).epsilon(1e-12));
        checkRoundedConvention(e);
    }

    TEST_CASE("contact: a face split in two by a vertex 1e-9 off its plane still gives the deepest end") {
        // The top of a 4 x 4 x 1 box with one corner raised by 1e-9 is two triangles; the capsule's
        // contact keeps its deeper end (the penetration, 0.55), not only the end over the triangle met
        // first (0.50). Planar, the same capsule keeps both ends on the face.
        for (double raise : {0.0, 1e-9}) {
            const Json box = {{"polytope",
                               {{"vertices",
                                 {{-2, -2, -0.5}, {-2, -2, 0.5}, {-2, 2, -0.5}, {-2, 2, 0.5}, {2, -2, -0.5}, {2, -2, 0.5},
                                  {2, 2, -0.5}, {2, 2, 0.5 + raise}}}}}};
            const Json capsule = {{"capsule", {{"a", {1.5, -1.2, 0.05}}, {"b", {-1.2, 1.5, 0.15}}, {"radius", 0.1}}}};
            const Json r = roundedContact(box, capsule);
            CAPTURE(raise);
            REQUIRE(r["colliding"] == true);
            CHECK(r["depth"].get<double>() == doctest::Approx(0.55).epsilon(1e-8));
            checkRoundedConvention(r);
            if (raise == 0.0) CHECK(r["points"].size() == 2);
        }
    }

    TEST_CASE("contact: spheres against boxes and spheres match the clamped closed form") {
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> u(-2, 2);
        int colliding = 0;
        for (int trial = 0; trial < 200; ++trial) {
            const double c[3] = {u(rng), u(rng), u(rng)}, r = 0.3 + std::abs(u(rng)) / 2;
            const Json sphere = {{"sphere", {{"center", {c[0], c[1], c[2]}}, {"radius", r}}}};
            const Json box = {{"aabb", {{"min", {-1, -0.5, -0.7}}, {"max", {1, 0.5, 0.7}}}}};
            const double lo[3] = {-1, -0.5, -0.7}, hi[3] = {1, 0.5, 0.7};
            double d2 = 0;
            bool inside = true;
            for (int i = 0; i < 3; ++i) {
                const double q = std::clamp(c[i], lo[i], hi[i]);
                d2 += (c[i] - q) * (c[i] - q);
                inside = inside && q == c[i];
            }
            if (inside) continue;  // centre inside: EPA's answer, checked by the penetration tests
            const Json ans = roundedContact(box, sphere);
            CAPTURE(trial);
            const double gap = std::sqrt(d2) - r;
            if (gap < -1e-9) {
                REQUIRE(ans["colliding"] == true);
                CHECK(ans["depth"].get<double>() == doctest::Approx(-gap).epsilon(1e-12));
                CHECK(ans["points"].size() == 1);
                checkRoundedConvention(ans);
                ++colliding;
            } else if (gap > 1e-9) {
                CHECK(ans["colliding"] == false);
                CHECK(ans["distance"].get<double>() == doctest::Approx(gap).epsilon(1e-12));
            }
        }
        CHECK(colliding > 30);
        const Json two = roundedContact({{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}},
                                 {{"sphere", {{"center", {1.5, 0, 0}}, {"radius", 1}}}});
        CHECK(two["depth"].get<double>() == 0.5);
        CHECK(two["normal"] == Json({1.0, 0.0, 0.0}));
        checkRoundedConvention(two);
    }

    TEST_CASE("contact: shapes it does not take are one error at their path") {
        const Json r = roundedContact({{"segment", {{0, 0, 0}, {1, 0, 0}}}}, kGroundZ);
        CHECK(r["error"].get<std::string>().find("$.a") != std::string::npos);
        CHECK(r["error"].get<std::string>().find("sphere, capsule") != std::string::npos);
    }
}
