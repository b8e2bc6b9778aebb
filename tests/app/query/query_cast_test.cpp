// `cdlab query` ops raycast and time_of_impact: the exact answer formats of docs/query.md, closed-form
// answers for every shape kind, power-of-two scale invariance (1e-200 .. 1e200), agreement with the
// `intersect` op, and the one-line errors.
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <string>

#include "app/query/query.h"
#include "tests/app/query/ask.h"

using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

using cdlab::test::ask;

using cdlab::test::keysOf;

Json ray(const Json& o, const Json& d) { return {{"origin", o}, {"direction", d}}; }

Json raycast(const Json& o, const Json& d, const Json& shape) {
    return {{"op", "raycast"}, {"ray", ray(o, d)}, {"shape", shape}};
}

double coord(const Json& v, int i) { return v[i].get<double>(); }

}  // namespace

TEST_SUITE("query") {
    TEST_CASE("raycast: answer formats (hit, inside, miss)") {
        const Json box = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
        const Json hit = ask(raycast({-2, 0.25, 0.5}, {4, 0, 0}, box));
        CHECK(keysOf(hit) == std::set<std::string>{"id", "hit", "t", "point", "normal"});
        CHECK(hit["hit"] == true);
        CHECK(hit["t"].get<double>() == doctest::Approx(0.5));  // t in units of the direction (|d| = 4)
        CHECK(hit["point"] == Json({0.0, 0.25, 0.5}));
        CHECK(hit["normal"] == Json({-1.0, 0.0, 0.0}));
        const Json inside = ask(raycast({0.5, 0.5, 0.5}, {1, 0, 0}, box));
        CHECK(keysOf(inside) == std::set<std::string>{"id", "hit", "t", "point", "inside"});
        CHECK(inside["inside"] == true);
        CHECK(inside["t"] == 0.0);
        CHECK(inside["point"] == Json({0.5, 0.5, 0.5}));
        const Json miss = ask(raycast({-2, 0.25, 0.5}, {-1, 0, 0}, box));
        CHECK(keysOf(miss) == std::set<std::string>{"id", "hit"});
        CHECK(miss["hit"] == false);
        Json limited = raycast({-2, 0.25, 0.5}, {1, 0, 0}, box);
        limited["max_t"] = 1.999;
        CHECK(ask(limited)["hit"] == false);
        limited["max_t"] = 2;
        CHECK(ask(limited)["hit"] == true);
    }

    TEST_CASE("raycast: closed forms for every shape kind") {
        // Sphere: from (−5, 0.6, 0) along +x, |c| = 1 at the origin: enters at x = −0.8.
        Json s = ask(raycast({-5, 0.6, 0}, {1, 0, 0}, {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}}));
        CHECK(s["t"].get<double>() == doctest::Approx(4.2).epsilon(1e-14));
        CHECK(coord(s["normal"], 0) == doctest::Approx(-0.8).epsilon(1e-14));
        CHECK(coord(s["normal"], 1) == doctest::Approx(0.6).epsilon(1e-14));
        // Capsule side and cap.
        const Json capsule = {{"capsule", {{"a", {-1, 0, 0}}, {"b", {1, 0, 0}}, {"radius", 0.5}}}};
        CHECK(ask(raycast({0.3, 0, 4}, {0, 0, -2}, capsule))["t"].get<double>() == doctest::Approx(1.75).epsilon(1e-14));
        CHECK(ask(raycast({9, 0, 0}, {-1, 0, 0}, capsule))["t"].get<double>() == doctest::Approx(7.5).epsilon(1e-14));
        // OBB rotated 45° about z: the edge at x = −√2.
        const Json obb = {{"obb", {{"center", {0, 0, 0}}, {"half_extents", {1, 1, 1}}, {"rotation", {std::cos(M_PI / 8), 0, 0, std::sin(M_PI / 8)}}}}};
        CHECK(ask(raycast({-5, 0, 0}, {1, 0, 0}, obb))["t"].get<double>() == doctest::Approx(5 - std::sqrt(2.0)).epsilon(1e-14));
        // Plane n·x = d with a non-unit normal: either side, parallel, on it.
        const Json plane = {{"plane", {{"normal", {0, 0, 2}}, {"offset", 2}}}};  // z = 1
        CHECK(ask(raycast({0, 0, 5}, {0, 0, -2}, plane))["t"].get<double>() == 2.0);
        CHECK(ask(raycast({0, 0, -5}, {0, 0, 1}, plane))["t"].get<double>() == 6.0);
        CHECK(ask(raycast({0, 0, 5}, {1, 0, 0}, plane))["hit"] == false);
        CHECK(ask(raycast({0, 0, 5}, {0, 0, 1}, plane))["hit"] == false);
        CHECK(ask(raycast({3, 4, 1}, {1, 0, 0}, plane))["inside"] == true);
        // Triangle, two-sided; a ray in its plane enters through the rim with the rim's normal.
        const Json tri = {{"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}};
        const Json up = ask(raycast({0.2, 0.2, -3}, {0, 0, 1}, tri));
        CHECK(up["t"].get<double>() == 3.0);
        CHECK(std::abs(coord(up["normal"], 2)) == 1.0);
        const Json rim = ask(raycast({-1, 0.25, 0}, {1, 0, 0}, tri));
        CHECK(rim["t"].get<double>() == 1.0);
        CHECK(rim["normal"] == Json({-1.0, 0.0, 0.0}));
        CHECK(ask(raycast({0.2, 0.2, 0}, {0, 0, 1}, tri))["inside"] == true);
        // Segment and point: hit only where the ray passes through them.
        const Json seg = {{"segment", {{0, 0, 0}, {0, 2, 0}}}};
        CHECK(ask(raycast({-1, 1, 0}, {1, 0, 0}, seg))["t"].get<double>() == 1.0);
        CHECK(ask(raycast({-1, 1, 1e-12}, {1, 0, 0}, seg))["hit"] == false);
        CHECK(ask(raycast({1, 1, 1}, {-1, -1, -1}, {{"point", {0, 0, 0}}}))["t"].get<double>() == 1.0);
        // A flat polytope (four coplanar vertices) and a polytope of one repeated point.
        const Json square = {{"polytope", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}}}};
        CHECK(ask(raycast({0.5, 0.5, 3}, {0, 0, -1}, square))["t"].get<double>() == 3.0);
        const Json dot = {{"polytope", {{"vertices", {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}}}};
        CHECK(ask(raycast({0, 0, 3}, {0, 0, -1}, dot))["t"].get<double>() == 3.0);
    }

    TEST_CASE("raycast: the same answer at every power-of-two scale, and from far away") {
        const Json sphere = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}};
        for (int e : {-600, -300, -100, 0, 100, 300, 600}) {
            const double s = std::ldexp(1.0, e);
            if (!std::isfinite(s * 5) || s * 1 == 0) continue;
            const Json scaledSphere = {{"sphere", {{"center", {0, 0, 0}}, {"radius", s}}}};
            const Json h = ask(raycast({-5 * s, 0, 0}, {s, 0, 0}, scaledSphere));
            CAPTURE(e);
            REQUIRE(h["hit"] == true);
            CHECK(h["t"].get<double>() == 4.0);
            CHECK(coord(h["point"], 0) == -s);
        }
        CHECK(ask(raycast({-5, 0, 0}, {1e-300, 0, 0}, sphere))["t"].get<double>() == doctest::Approx(4e300));
        // A ray from 1e9 through a unit box (the Minkowski segment is 1e9 long: the verdict clips it).
        const Json far = ask(raycast({1e9, 0.5, 0.5}, {-1, 0, 0}, {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}));
        REQUIRE(far["hit"] == true);
        CHECK(far["t"].get<double>() == 1e9 - 1);
    }

    TEST_CASE("distance: a segment 1e9 .. 1e15 long through a unit box intersects it, and misses it beside") {
        // GJK's segment step from the far end erased v's component along the segment (0.7 short).
        const Json box = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
        for (double far : {1e9, 1e12, 1e15}) {
            CAPTURE(far);
            CHECK(ask({{"op", "intersect"}, {"a", {{"segment", {{far, 0.5, 0.5}, {-1, 0.5, 0.5}}}}}, {"b", box}})["intersect"] ==
                  true);
            if (far > 1e12) continue;  // 0.5 is below the touching rule's 1e-13 of a 1e15-long extent
            const Json beside = ask({{"op", "distance"}, {"a", {{"segment", {{far, 1.5, 0.5}, {-1, 1.5, 0.5}}}}}, {"b", box}});
            CHECK(beside["distance"].get<double>() == doctest::Approx(0.5).epsilon(1e-12));
        }
    }

    TEST_CASE("raycast: the hit verdict is the intersect op's on the segment up to max_t") {
        std::uint64_t state = 99;
        const auto uniform = [&]() {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            return double(state >> 11) * 0x1.0p-53 * 2 - 1;
        };
        int hits = 0, misses = 0;
        for (int trial = 0; trial < 300; ++trial) {
            Json vertices = Json::array();
            for (int i = 0; i < 6; ++i) vertices.push_back({uniform(), uniform(), uniform()});
            const Json shape = trial % 2 ? Json{{"polytope", {{"vertices", vertices}}}}
                                         : Json{{"capsule", {{"a", vertices[0]}, {"b", vertices[1]}, {"radius", 0.3}}}};
            const Json o = {3 * uniform(), 3 * uniform(), 3 * uniform()};
            // Aimed at a point within 0.8 of the centre: hits and misses both.
            const Json d = {(0.8 * uniform() - coord(o, 0)) / 2, (0.8 * uniform() - coord(o, 1)) / 2,
                            (0.8 * uniform() - coord(o, 2)) / 2};
            Json q = raycast(o, d, shape);
            q["max_t"] = 3;
            const Json cast = ask(q);
            const Json end = {coord(o, 0) + 3 * coord(d, 0), coord(o, 1) + 3 * coord(d, 1), coord(o, 2) + 3 * coord(d, 2)};
            const Json meet = ask({{"op", "distance"}, {"a", {{"segment", {o, end}}}}, {"b", shape}});
            CAPTURE(q.dump());
            if (meet["distance"].get<double>() > 1e-9) {
                CHECK(cast["hit"] == false);
                ++misses;
            }
            if (meet["intersect"] == true) {
                CHECK(cast["hit"] == true);
                ++hits;
            }
        }
        CHECK(hits > 50);
        CHECK(misses > 50);
    }

    TEST_CASE("time_of_impact: answer formats and closed forms") {
        const Json a = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}};
        const Json b = {{"sphere", {{"center", {10, 0, 0}}, {"radius", 1}}}};
        const Json hit = ask({{"op", "time_of_impact"}, {"a", a}, {"b", b}, {"motion_a", {2, 0, 0}}, {"motion_b", {-8, 0, 0}}});
        CHECK(keysOf(hit) == std::set<std::string>{"id", "hit", "t", "normal", "point_a", "point_b"});
        CHECK(hit["t"].get<double>() == doctest::Approx(0.8).epsilon(1e-14));
        CHECK(hit["normal"] == Json({1.0, 0.0, 0.0}));
        CHECK(coord(hit["point_a"], 0) == doctest::Approx(2.6).epsilon(1e-14));  // 0 + 0.8·2 + 1
        CHECK(coord(hit["point_b"], 0) == doctest::Approx(2.6).epsilon(1e-14));  // 10 − 0.8·8 − 1
        const Json over = ask({{"op", "time_of_impact"}, {"a", a}, {"b", a}});
        CHECK(keysOf(over) == std::set<std::string>{"id", "hit", "t", "initially_overlapping"});
        CHECK(over["initially_overlapping"] == true);
        CHECK(over["t"] == 0.0);
        const Json none = ask({{"op", "time_of_impact"}, {"a", a}, {"b", b}, {"motion_b", {-7.9, 0, 0}}});
        CHECK(keysOf(none) == std::set<std::string>{"id", "hit"});
        CHECK(none["hit"] == false);
        CHECK(ask({{"op", "time_of_impact"}, {"a", a}, {"b", b}})["hit"] == false);  // no motion
        // A plane as either shape: the capsule's lowest point reaches z = −3 at t = 2.5 / 4.
        const Json capsule = {{"capsule", {{"a", {0, 0, 0}}, {"b", {0, 0, 2}}, {"radius", 0.5}}}};
        const Json floor = {{"plane", {{"normal", {0, 0, 1}}, {"offset", -3}}}};
        const Json down = ask({{"op", "time_of_impact"}, {"a", capsule}, {"b", floor}, {"motion_a", {0, 0, -4}}});
        CHECK(down["t"].get<double>() == 0.625);
        CHECK(down["normal"] == Json({0.0, 0.0, -1.0}));
        const Json up = ask({{"op", "time_of_impact"}, {"a", floor}, {"b", capsule}, {"motion_a", {0, 0, 4}}});
        CHECK(up["t"].get<double>() == 0.625);
        CHECK(up["normal"] == Json({0.0, 0.0, 1.0}));
        // Coplanar triangle and segment: the segment's end runs into the triangle's edge x = 0.
        const Json rim = ask({{"op", "time_of_impact"},
                              {"a", {{"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}},
                              {"b", {{"segment", {{-1, 0.3, 0}, {-0.5, 0.3, 0}}}}},
                              {"motion_b", {2, 0, 0}}});
        CHECK(rim["t"].get<double>() == 0.25);
        CHECK(rim["normal"] == Json({-1.0, 0.0, 0.0}));
        // Far from the origin, scaled: t does not change.
        const Json farA = {{"sphere", {{"center", {1e9, 0, 0}}, {"radius", 1}}}};
        const Json farB = {{"sphere", {{"center", {1e9, 3, 0}}, {"radius", 1}}}};
        CHECK(ask({{"op", "time_of_impact"}, {"a", farA}, {"b", farB}, {"motion_b", {0, -2, 0}}})["t"].get<double>() == 0.5);
        const Json tinyA = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1e-200}}}};
        const Json tinyB = {{"sphere", {{"center", {0, 3e-200, 0}}, {"radius", 1e-200}}}};
        CHECK(ask({{"op", "time_of_impact"}, {"a", tinyA}, {"b", tinyB}, {"motion_b", {0, -2e-200, 0}}})["t"].get<double>() ==
              doctest::Approx(0.5).epsilon(1e-14));
    }

    TEST_CASE("raycast and time_of_impact: one-line errors at the JSON path") {
        const Json point = {{"point", {0, 0, 0}}};
        const auto error = [](const Json& q) { return ask(q).value("error", std::string()); };
        CHECK(error(raycast({0, 0, 1}, {0, 0, 0}, point)).find("$.ray.direction: ray direction must be non-zero") !=
              std::string::npos);
        CHECK(error(raycast({0, 0, 1}, {0, 0, 1}, {{"ray", ray({0, 0, 0}, {1, 0, 0})}})).find("$.shape") != std::string::npos);
        Json negative = raycast({0, 0, 1}, {0, 0, 1}, point);
        negative["max_t"] = -1;
        CHECK(error(negative).find("$.max_t") != std::string::npos);
        CHECK(error({{"op", "raycast"}, {"ray", ray({0, 0, 1}, {0, 0, 1})}}).find("shape") != std::string::npos);
        const Json plane = {{"plane", {{"normal", {0, 0, 1}}, {"offset", 0}}}};
        CHECK(error({{"op", "time_of_impact"}, {"a", plane}, {"b", plane}}).find("$.b: time_of_impact: two planes") !=
              std::string::npos);
        CHECK(error({{"op", "time_of_impact"}, {"a", {{"ray", ray({0, 0, 0}, {1, 0, 0})}}}, {"b", point}}).find("$.a") !=
              std::string::npos);
        CHECK(error({{"op", "time_of_impact"}, {"a", point}, {"b", point}, {"motion_b", {1, 0}}}).find("$.motion_b") !=
              std::string::npos);
        CHECK(error({{"op", "time_of_impact"}, {"a", point}, {"b", point}, {"speed", 1}}).find("speed") != std::string::npos);
    }
}
