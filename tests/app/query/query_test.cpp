// `cdlab query` answers checked against oracles that share no code with GJK / EPA: brute-force
// facets of the convex hull of the Minkowski difference {a_i - b_j} in long double, and
// closed-form answers for spheres, capsules, planes and rays.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "verification/minkowski_facet_oracle.h"
#include "app/query/query.h"
#include "tests/app/query/ask.h"

using cdlab::Vec3;
using cdlab::demos::answerQuery;
using cdlab::demos::Json;
using cdlab::demos::runQueries;

namespace {

std::uint64_t rngState = 0x1234567;
double uniform() {  // splitmix64 -> [0, 1)
    std::uint64_t z = (rngState += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

std::vector<std::array<double, 3>> randomCloud(int n, double size) {
    std::vector<std::array<double, 3>> v;
    for (int i = 0; i < n; ++i)
        v.push_back({(uniform() - 0.5) * size, (uniform() - 0.5) * size, (uniform() - 0.5) * size});
    return v;
}

Json polytopeJson(const std::vector<std::array<double, 3>>& v, const std::array<double, 3>& pos) {
    return {{"polytope", {{"vertices", v}, {"position", pos}}}};
}

// h_{A-B}(n) in long double, both sides relative to a_0 (well conditioned at offsets of 1e6).
double hSupport(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Json& n) {
    return double(cdlab::test::supportValueL(a, b, Vec3(n[0].get<double>(), n[1].get<double>(), n[2].get<double>())));
}

using cdlab::test::ask;

}  // namespace

TEST_SUITE("query") {
    TEST_CASE("random polytope pairs: distance and penetration match the Minkowski-hull oracle") {
        int separated = 0, overlapping = 0;
        double worstDistance = 0, worstDepth = 0, worstNormal = 0;
        const double sizes[] = {1e-3, 1.0, 1e3};
        const double offsets[] = {0.0, 1e4, 1e6};
        for (int trial = 0; trial < 150; ++trial) {
            const double size = sizes[trial % 3];
            const double offset = offsets[(trial / 3) % 3];
            auto va = randomCloud(8, size), vb = randomCloud(8, size);
            std::array<double, 3> pa = {offset, -offset, 0.5 * offset};
            std::array<double, 3> pb = {pa[0] + (uniform() - 0.5) * 1.6 * size, pa[1] + (uniform() - 0.5) * 1.6 * size,
                                        pa[2] + (uniform() - 0.5) * 1.6 * size};
            // The oracle sees the same world vertices the query builds (rotation identity: v + position).
            std::vector<Vec3> worldA, worldB;
            for (const auto& a : va) worldA.push_back(Vec3(a[0] + pa[0], a[1] + pa[1], a[2] + pa[2]));
            for (const auto& b : vb) worldB.push_back(Vec3(b[0] + pb[0], b[1] + pb[1], b[2] + pb[2]));
            const cdlab::test::HullOracle o = cdlab::test::hullOracle(worldA, worldB);
            Json q = {{"op", "penetration"}, {"a", polytopeJson(va, pa)}, {"b", polytopeJson(vb, pb)}};
            Json ans = ask(q);
            REQUIRE_MESSAGE(!ans.contains("error"), ans.dump());
            REQUIRE(ans["intersect"].get<bool>() == o.inside);
            if (o.inside) {
                ++overlapping;
                double depth = ans["depth"];
                double rel = std::fabs(depth - double(o.depth)) / double(o.depth);
                worstDepth = std::max(worstDepth, rel);
                CHECK_MESSAGE(rel <= 1e-12, "depth " << depth << " oracle " << double(o.depth));
                double hn = hSupport(worldA, worldB, ans["normal"]);
                worstNormal = std::max(worstNormal, std::fabs(hn - depth) / depth);
                CHECK(std::fabs(hn - depth) <= 1e-12 * depth);
                for (int i = 0; i < 3; ++i) {
                    double lhs = ans["point_a"][i].get<double>() - ans["point_b"][i].get<double>();
                    CHECK(std::fabs(lhs - depth * ans["normal"][i].get<double>()) <= 1e-9 * size + 1e-15 * offset);
                }
            } else {
                ++separated;
                Json qd = q;
                qd["op"] = "distance";
                Json d = ask(qd);
                double dist = d["distance"];
                double rel = std::fabs(dist - double(o.distance)) / double(o.distance);
                worstDistance = std::max(worstDistance, rel);
                CHECK_MESSAGE(rel <= 1e-12, "distance " << dist << " oracle " << double(o.distance));
            }
        }
        MESSAGE("separated " << separated << ", overlapping " << overlapping << "; worst relative error: distance "
                             << worstDistance << ", depth " << worstDepth << ", normal support " << worstNormal);
        CHECK(separated > 20);
        CHECK(overlapping > 20);
    }

    TEST_CASE("spheres and capsules: closed-form answers") {
        Json d = ask(Json::parse(
            R"({"op":"distance","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"sphere":{"center":[3,4,0],"radius":2}}})"));
        CHECK(d["distance"].get<double>() == doctest::Approx(2.0).epsilon(1e-15));
        CHECK(d["point_a"][0].get<double>() == doctest::Approx(0.6));
        Json p = ask(Json::parse(
            R"({"op":"penetration","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"sphere":{"center":[1,0,0],"radius":1}}})"));
        CHECK(p["intersect"] == true);
        CHECK(p["depth"].get<double>() == doctest::Approx(1.0).epsilon(1e-15));
        CHECK(p["normal"][0].get<double>() == doctest::Approx(1.0));
        // Crossing capsules: the cores (segments) intersect; depth = r1 + r2 along the common normal.
        Json c = ask(Json::parse(
            R"({"op":"penetration","a":{"capsule":{"a":[0,-1,0],"b":[0,1,0],"radius":0.25}},"b":{"capsule":{"a":[-1,0,0],"b":[1,0,0],"radius":0.5}}})"));
        CHECK(c["depth"].get<double>() == doctest::Approx(0.75).epsilon(1e-15));
        CHECK(std::fabs(c["normal"][2].get<double>()) == doctest::Approx(1.0));
        // Cores 2.75e-14 apart: the cores' axis, depth r1 + r2 - 2.75e-14, not EPA's answer (its start
        // needs a simplex holding the origin: 0.327 along +z).
        Json n = ask(Json::parse(
            R"({"op":"penetration","a":{"capsule":{"a":[-0.087361662159125636,0.12180682528121861,0.064072713244759938],"b":[0.39644674898118304,-0.59631227169508572,0.56430704220252648],"radius":0.05}},"b":{"capsule":{"a":[0.17705241975889738,-0.27066423839308734,0.33746399332504823],"b":[-0.65614398891109804,-0.71986314770682935,0.6599606358668999],"radius":0.05}}})"));
        CHECK(n["depth"].get<double>() == doctest::Approx(0.1 - 2.75e-14).epsilon(1e-14));
        CHECK(std::fabs(n["normal"][2].get<double>()) < 0.2);  // (-0.858, -0.503, 0.108): the segments' common perpendicular
        // A capsule core 1e-6 long at 1e9 from the origin: the pair is moved next to the origin first
        // (exactly), so its nearer end is not chosen by rounding d · x of coordinates 1e9; they overlap
        // by 2.5404069958e-9 (rounding there answers them 1.3e-10 apart).
        const std::string far =
            R"({"op":"penetration","a":{"capsule":{"a":[1000000000.0,0.0,0.0],"b":[1000000000.0,7.668953380392842e-07,6.413366727701596e-07],"radius":1.0}},"b":{"sphere":{"center":[1000000000.2258492,-1.2707238588552776,1.527826245280321],"radius":1.0}}})";
        Json f = ask(Json::parse(far));
        REQUIRE(f["intersect"] == true);
        CHECK(f["depth"].get<double>() == doctest::Approx(2.5404069958e-9).epsilon(1e-6));
        CHECK(f["point_a"][0].get<double>() == doctest::Approx(1e9 + 0.1129246).epsilon(1e-15));
        // Nearly parallel cores crossing 5.6e-18 apart: depth r1 + r2, and the deepest points where the
        // cores cross, on each capsule (EPA's blown-up flat start had put point_a 0.39 off A).
        const Vec3 a0(-0.06384617321017472, -0.042449289430044015, -0.0775290882964929),
            a1(1.2731867605939553, 0.36920813999860513, -0.31357009551208964),
            b0(-0.5154235067889756, -0.18152815246451445, 0.0021401574709631332),
            b1(1.3605382611563082, 0.39618603910536876, -0.32888983667686805);
        const auto vecJson = [](const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); };
        Json x = ask(Json{{"op", "penetration"},
                          {"a", {{"capsule", {{"a", vecJson(a0)}, {"b", vecJson(a1)}, {"radius", 0.1}}}}},
                          {"b", {{"capsule", {{"a", vecJson(b0)}, {"b", vecJson(b1)}, {"radius", 0.05}}}}}});
        CHECK(x["depth"].get<double>() == doctest::Approx(0.15).epsilon(1e-14));
        const auto toSegment = [](const Vec3& p, const Vec3& s0, const Vec3& s1) {
            const Vec3 e = s1 - s0;
            return (p - (s0 + std::clamp((p - s0).dot(e) / e.squaredNorm(), 0.0, 1.0) * e)).norm();
        };
        const auto point = [](const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); };
        CHECK(toSegment(point(x["point_a"]), a0, a1) == doctest::Approx(0.1).epsilon(1e-12));
        CHECK(toSegment(point(x["point_b"]), b0, b1) == doctest::Approx(0.05).epsilon(1e-12));
        // Touching spheres count as intersecting (closed sets).
        Json t = ask(Json::parse(
            R"({"op":"intersect","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"sphere":{"center":[2,0,0],"radius":1}}})"));
        CHECK(t["intersect"] == true);
    }

    TEST_CASE("the scenes' words: box, hull and position give the same answers as obb, polytope and center") {
        const Json obb = {{"obb", {{"center", {0.2, 0.1, 0}}, {"half_extents", {1, 0.5, 0.25}}, {"rotation", {0.9, 0.1, 0.3, 0.2}}}}};
        const Json box = {{"box", {{"position", {0.2, 0.1, 0}}, {"half_extents", {1, 0.5, 0.25}}, {"rotation", {0.9, 0.1, 0.3, 0.2}}}}};
        const Json vertices = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
        const Json poly = {{"polytope", {{"vertices", vertices}, {"position", {1.5, 0, 0}}}}};
        const Json hull = {{"hull", {{"vertices", vertices}, {"position", {1.5, 0, 0}}}}};
        for (const char* op : {"distance", "penetration", "contact"})
            CHECK(ask({{"op", op}, {"a", box}, {"b", hull}}) == ask({{"op", op}, {"a", obb}, {"b", poly}}));
        CHECK(ask({{"op", "distance"}, {"a", {{"sphere", {{"position", {0, 0, 3}}, {"radius", 1}}}}}, {"b", box}}) ==
              ask({{"op", "distance"}, {"a", {{"sphere", {{"center", {0, 0, 3}}, {"radius", 1}}}}}, {"b", obb}}));
        // A box's position defaults to the origin; an obb's center is required; not both keys.
        const Json point = {{"point", {3, 0, 0}}};
        const Json unitBox = {{"box", {{"half_extents", {1, 1, 1}}}}};
        const Json noCenter = {{"obb", {{"half_extents", {1, 1, 1}}}}};
        const Json both = {{"sphere", {{"center", {0, 0, 0}}, {"position", {0, 0, 0}}, {"radius", 1}}}};
        const Json atOrigin = ask({{"op", "distance"}, {"a", unitBox}, {"b", point}});
        CHECK(atOrigin["distance"] == 2.0);
        const Json missing = ask({{"op", "distance"}, {"a", noCenter}, {"b", point}});
        CHECK(missing.value("error", "").find("missing required key 'center'") != std::string::npos);
        const Json twice = ask({{"op", "distance"}, {"a", both}, {"b", point}});
        CHECK(twice.contains("error"));
    }

    TEST_CASE("touching and face-to-face boxes: depth 0 or exact overlap, never NaN") {
        Json t = ask(Json::parse(
            R"({"op":"penetration","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[1,0,0],"max":[2,1,1]}}})"));
        REQUIRE(t["intersect"] == true);
        CHECK(t["depth"].get<double>() == 0.0);
        CHECK(std::fabs(t["normal"][0].get<double>()) == doctest::Approx(1.0));
        Json o = ask(Json::parse(
            R"({"op":"penetration","a":{"obb":{"center":[0,0,0],"half_extents":[1,1,1]}},"b":{"obb":{"center":[0,1.5,0],"half_extents":[1,1,1]}}})"));
        CHECK(o["depth"].get<double>() == doctest::Approx(0.5).epsilon(1e-15));
        CHECK(o["normal"][1].get<double>() == doctest::Approx(1.0));
    }

    TEST_CASE("planes and rays") {
        Json d = ask(Json::parse(
            R"({"op":"distance","a":{"plane":{"normal":[0,2,0],"offset":2}},"b":{"sphere":{"center":[0,5,0],"radius":1}}})"));
        CHECK(d["distance"].get<double>() == doctest::Approx(3.0));
        Json p = ask(Json::parse(
            R"({"op":"penetration","a":{"plane":{"normal":[0,1,0],"offset":0}},"b":{"sphere":{"center":[0,0.25,0],"radius":1}}})"));
        CHECK(p["depth"].get<double>() == doctest::Approx(0.75));
        CHECK(p["normal"][1].get<double>() == doctest::Approx(1.0));
        Json r = ask(Json::parse(
            R"({"op":"distance","a":{"ray":{"origin":[-5,2,0],"direction":[1,0,0]}},"b":{"sphere":{"center":[0,0,0],"radius":1}}})"));
        CHECK(r["distance"].get<double>() == doctest::Approx(1.0));
        Json behind = ask(Json::parse(
            R"({"op":"intersect","a":{"ray":{"origin":[5,0,0],"direction":[1,0,0]}},"b":{"sphere":{"center":[0,0,0],"radius":1}}})"));
        CHECK(behind["intersect"] == false);
        Json rp = ask(Json::parse(
            R"({"op":"intersect","a":{"ray":{"origin":[0,1,0],"direction":[1,-1,0]}},"b":{"plane":{"normal":[0,1,0],"offset":0}}})"));
        CHECK(rp["intersect"] == true);
        Json rr = ask(Json::parse(
            R"({"op":"distance","a":{"ray":{"origin":[0,0,0],"direction":[1,0,0]}},"b":{"ray":{"origin":[-1,1,1],"direction":[0,0,1]}}})"));
        CHECK(rr["distance"].get<double>() == doctest::Approx(std::sqrt(3.0)));  // t = s = 0: both origins;
    }

    TEST_CASE("tiny and huge scales: answers scale exactly, no underflow or overflow") {
        // The same configuration at 1, 2^-990 and 2^1000: distances scale by the same power of two.
        for (int k : {0, -990, 1000}) {
            CAPTURE(k);
            const double s = std::ldexp(1.0, k);
            Json q = {{"op", "distance"},
                      {"a", {{"segment", {{0.0, 0.0, 0.0}, {s, 0.0, 0.0}}}}},
                      {"b", {{"point", {0.5 * s, 0.75 * s, 0.0}}}}};
            Json d = ask(q);
            REQUIRE_MESSAGE(!d.contains("error"), d.dump());
            CHECK(d["distance"].get<double>() == 0.75 * s);
            Json t = ask({{"op", "closest_point_triangle"},
                          {"point", {2 * s, -s, 0.5 * s}},
                          {"triangle", {{0.0, 0.0, 0.0}, {4 * s, 0.0, 0.0}, {s, 3 * s, 0.0}}}});
            CHECK(t["region"] == "AB");
            CHECK(t["point"][0].get<double>() == 2 * s);
        }
        Json over = ask(Json::parse(R"({"op":"distance","a":{"point":[1e308,0,0]},"b":{"point":[-1e308,0,0]}})"));
        CHECK(over["error"].get<std::string>().find("overflows") != std::string::npos);
    }

    TEST_CASE("closest_point_triangle answers point and region") {
        Json a = ask(Json::parse(
            R"({"id":"x","op":"closest_point_triangle","point":[2,-1,0.5],"triangle":[[0,0,0],[4,0,0],[1,3,0]]})"));
        CHECK(a["id"] == "x");
        CHECK(a["region"] == "AB");
        CHECK(a["point"][0].get<double>() == 2.0);
    }

    TEST_CASE("bad lines answer an error on that line, the tool goes on, exit status 1") {
        std::istringstream in(
            "{\"id\":1,\"op\":\"distance\",\"a\":{\"point\":[0,0,0]},\"b\":{\"point\":[1,0,0]}}\n"
            "not json\n"
            "{\"id\":3,\"op\":\"nope\"}\n"
            "{\"id\":4,\"op\":\"distance\",\"a\":{\"sphere\":{\"center\":[0,0,0],\"radius\":-1}},\"b\":{\"point\":[1,1,"
            "1]}}\n"
            "{\"id\":5,\"op\":\"penetration\",\"a\":{\"polytope\":{\"vertices\":[[0,0,0],[1,0,0],[0,1,0]]}},\"b\":{"
            "\"point\":[1,1,1]}}\n"
            "{\"id\":6,\"op\":\"distance\",\"a\":{\"blob\":{}},\"b\":{\"point\":[1,1,1]}}\n"
            "{\"id\":7,\"op\":\"distance\",\"a\":{\"point\":[0,0,0]},\"b\":{\"point\":[1,1,1]},\"colour\":1}\n"
            "{\"id\":8,\"op\":\"intersect\",\"a\":{\"point\":[0,0]},\"b\":{\"point\":[1,1,1]}}\n");
        std::ostringstream out;
        CHECK(runQueries(in, out) == 1);
        std::istringstream lines(out.str());
        std::string line;
        std::vector<Json> answers;
        while (std::getline(lines, line)) answers.push_back(Json::parse(line));
        REQUIRE(answers.size() == 8);
        CHECK(answers[0]["distance"].get<double>() == 1.0);
        CHECK(out.str().rfind("{\"id\":1,", 0) == 0);  // id first
        for (int i = 1; i < 8; ++i) CHECK_MESSAGE(answers[i].contains("error"), answers[i].dump());
        CHECK(answers[2]["id"] == 3);
        CHECK(answers[3]["error"].get<std::string>().find("$.a.sphere.radius") != std::string::npos);
        CHECK(answers[4]["error"].get<std::string>().find("at least 4") != std::string::npos);
        CHECK(answers[6]["error"].get<std::string>().find("colour") != std::string::npos);
    }

}  // TEST_SUITE
