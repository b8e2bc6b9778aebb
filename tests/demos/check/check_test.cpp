// `cdlab check`: right answers pass (including the ones that differ from cdlab's only where the
// answer is not unique: other witness points on a face pair, a region tie at a vertex, a tied
// support point), and each kind of wrong answer fails with its reason in words; a planted GJK
// trace divergence is reported at its iteration.
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "demos/check/check.h"
#include "demos/query/query.h"

using namespace cdlab::demos;

namespace {

CheckResult check(const Json& line) { return checkLine(line.dump(), 1, CheckOptions{}); }

std::string reasons(const CheckResult& r) {
    std::string s;
    for (const std::string& x : r.reasons) s += x + "; ";
    return s;
}

const Json kBoxA = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
const Json kBoxB = {{"aabb", {{"min", {2, 0, 0}}, {"max", {3, 1, 1}}}}};

Json distanceLine(const Json& answer) { return {{"id", 1}, {"op", "distance"}, {"a", kBoxA}, {"b", kBoxB}, {"answer", answer}}; }

// A − B = [-3, -1] x [-1, 1] x [-1, 1]: a GJK run from direction +x.
Json gjkTrace(bool plantedDivergence) {
    Json steps = Json::array();
    steps.push_back({{"direction", {1, 0, 0}}, {"support", {-1, 1, 1}}, {"simplex", {{-1, 1, 1}}}});
    // Iteration 1: the segment's nearest point to the origin is its midpoint (-1, 0, 0): both
    // ends stay. The planted divergence keeps only the new point.
    Json kept = plantedDivergence ? Json{{-1, -1, -1}} : Json{{-1, 1, 1}, {-1, -1, -1}};
    steps.push_back({{"direction", {1, -1, -1}}, {"support", {{"a", {1, 0, 0}}, {"b", {2, 1, 1}}}}, {"simplex", kept}});
    // Iteration 2: along +x every point of the face x = -1 is extreme; (-1, 1, -1) is a tie.
    steps.push_back({{"direction", {1, 0, 0}}, {"support", {-1, 1, -1}}});
    return {{"algorithm", "gjk"}, {"steps", steps}};
}

}  // namespace

TEST_CASE("check: right answers pass, also where they are not cdlab's") {
    CHECK(check(distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}})).pass);
    // Other witness points on the same face pair: as right.
    const CheckResult other =
        check(distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.3, 0.9}}, {"point_b", {2, 0.3, 0.9}}}));
    CHECK_MESSAGE(other.pass, reasons(other));
    // A point exactly at vertex A: region A or AB both name it.
    for (const char* region : {"A", "AB", "CA"}) {
        const Json line = {{"op", "closest_point_triangle"}, {"point", {-1, -1, 0}}, {"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                           {"answer", {{"point", {0, 0, 0}}, {"region", region}}}};
        CHECK_MESSAGE(check(line).pass, region);
    }
    // Penetration along another axis of least overlap (a tie): valid.
    const Json cube = {{"aabb", {{"min", {0, 0, 0}}, {"max", {2, 2, 2}}}}};
    const Json corner = {{"aabb", {{"min", {1.5, 1.5, -1}}, {"max", {3, 3, 3}}}}};
    for (const Json& n : {Json{1, 0, 0}, Json{0, 1, 0}}) {
        const Json pa = n[0] == 1 ? Json{2, 1.75, 1} : Json{1.75, 2, 1};
        const Json pb = n[0] == 1 ? Json{1.5, 1.75, 1} : Json{1.75, 1.5, 1};
        const Json line = {{"op", "penetration"}, {"a", cube}, {"b", corner},
                           {"answer", {{"intersect", true}, {"depth", 0.5}, {"normal", n}, {"point_a", pa}, {"point_b", pb}}}};
        const CheckResult r = check(line);
        CHECK_MESSAGE(r.pass, reasons(r));
    }
}

TEST_CASE("check: wrong answers fail with the reason in words") {
    CheckResult r = check(distanceLine({{"intersect", true}}));
    CHECK(reasons(r).find("verdict differs") != std::string::npos);
    r = check(distanceLine({{"intersect", false}, {"distance", 1.001}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2.001, 0.5, 0.5}}}));
    CHECK(reasons(r).find("distance off by 0.001") != std::string::npos);
    CHECK(reasons(r).find("point_b is not on shape b") == std::string::npos);
    r = check(distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1.2, 0.5, 0.5}}, {"point_b", {2.2, 0.5, 0.5}}}));
    CHECK(reasons(r).find("point_a is not on shape a: 0.2 from it") != std::string::npos);
    const Json cube = {{"aabb", {{"min", {0, 0, 0}}, {"max", {2, 2, 2}}}}};
    const Json slab = {{"aabb", {{"min", {1.5, 0.5, 0.5}}, {"max", {3, 1.5, 1.5}}}}};
    r = check({{"op", "penetration"}, {"a", cube}, {"b", slab},
               {"answer", {{"intersect", true}, {"depth", 0.5}, {"normal", {0, 1, 0}}, {"point_a", {2, 1, 1}}, {"point_b", {2, 0.5, 1}}}}});
    CHECK(reasons(r).find("normal not a valid separating direction") != std::string::npos);
    r = check({{"op", "closest_point_triangle"}, {"point", {0.2, -1, 0}}, {"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
               {"answer", {{"point", {0.2, 0, 0}}, {"region", "A"}}}});
    CHECK(reasons(r).find("region differs: yours A, cdlab's AB") != std::string::npos);
    // A tolerance per line loosens it.
    Json loose = distanceLine({{"intersect", false}, {"distance", 1.001}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2.001, 0.5, 0.5}}});
    loose["tolerance"] = 1e-2;
    CHECK(check(loose).pass);
}

TEST_CASE("check: closest_point_tetrahedron — letters in any order, a boundary tie passes, a wrong face fails") {
    const Json tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const auto line = [&](const Json& p, const Json& q, const char* region) {
        return Json{{"op", "closest_point_tetrahedron"}, {"point", p}, {"tetrahedron", tet},
                    {"answer", {{"point", q}, {"region", region}}}};
    };
    const double third = 1.0 / 3.0;
    CHECK(check(line({2, 2, 2}, {third, third, third}, "DCB")).pass);
    // Below the middle of edge BC: cdlab says BC; the face ABC holds the same closest point.
    for (const char* region : {"BC", "ABC"}) {
        const CheckResult r = check(line({0.5, 0.5, -1}, {0.5, 0.5, 0}, region));
        CHECK_MESSAGE(r.pass, region << ": " << reasons(r));
    }
    const CheckResult wrong = check(line({2, 2, 2}, {third, third, third}, "ABC"));
    CHECK(reasons(wrong).find("region differs: yours ABC, cdlab's BCD") != std::string::npos);
    CHECK(check(line({0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}, "ABCD")).pass);
}

TEST_CASE("check: a closest_point_tetrahedron trace — cdlab's own passes, a wrong value and a wrong decision are found") {
    const Json query = {{"op", "closest_point_tetrahedron"}, {"point", {0.5, -1, 0.2}},
                        {"tetrahedron", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"trace", true}};
    const Json cdlab = answerQuery(query.dump());
    REQUIRE(cdlab["region"] == "ABD");
    Json line = query;
    line.erase("trace");
    line["answer"] = {{"point", cdlab["point"]}, {"region", "ABD"}};
    line["trace"] = {{"tests", cdlab["trace"]["tests"]}};
    CheckResult r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    Json wrongValue = line;
    wrongValue["trace"]["tests"][0]["terms"][0]["value"] = 0.7;
    r = check(wrongValue);
    CHECK(reasons(r).find("test 0 (A): (p-a).(b-a) = 0.7, but it is 0.5") != std::string::npos);
    CHECK(r.traceDivergence == 0);
    Json rejected = line;
    rejected["trace"]["tests"].back()["accepted"] = false;
    r = check(rejected);
    CHECK(reasons(r).find("rejected, but the point lies in this region") != std::string::npos);
    // p = (0, -1, -1): (p-a).(b-a) = 0 exactly, cdlab says A; a strict test rejects A and accepts AB,
    // whose nearest point is the same vertex: a tie, not a divergence.
    const Json tie = {{"op", "closest_point_tetrahedron"}, {"point", {0, -1, -1}},
                      {"tetrahedron", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                      {"answer", {{"point", {0, 0, 0}}, {"region", "AB"}}},
                      {"trace", {{"tests", {{{"region", "A"}, {"terms", {{{"name", "(p-a).(b-a)"}, {"value", 0.0}}}}, {"accepted", false}},
                                            {{"region", "AB"}, {"accepted", true}}}}}}};
    r = check(tie);
    CHECK_MESSAGE(r.pass, reasons(r));
    Json empty = line;
    empty["answer"]["region"] = "";
    CHECK(reasons(check(empty)).find("names no feature") != std::string::npos);
}

TEST_CASE("check: a GJK trace is checked step by step; a tie is not a divergence, a planted one is found") {
    Json line = distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    line["trace"] = gjkTrace(false);
    CheckResult r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    line["trace"] = gjkTrace(true);
    r = check(line);
    CHECK(reasons(r).find("iteration 1: wrong sub-simplex kept") != std::string::npos);
    // A support point that is not extreme along its direction.
    Json bad = gjkTrace(false);
    bad["steps"][2]["support"] = {-2, 1, -1};
    line["trace"] = bad;
    CHECK(reasons(check(line)).find("iteration 2: different support point for the same direction") != std::string::npos);
}

TEST_CASE("check: an answer with keys of the wrong type fails that line only") {
    const Json cube = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json line = {{"op", "raycast"}, {"ray", {{"origin", {-1, 0.5, 0.5}}, {"direction", {1, 0, 0}}}}, {"shape", cube},
                       {"answer", {{"hit", true}, {"t", 1.0}, {"point", {0, 0.5, 0.5}}, {"inside", "no"}}}};
    const CheckResult r = check(line);
    CHECK_FALSE(r.pass);
    CHECK(reasons(r).find("could not be read") != std::string::npos);
    Json trace = distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    trace["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {-1, 1, 1}}, {"simplex", "x"}}}}};
    CHECK_FALSE(check(trace).pass);
}

TEST_CASE("check: the summary line and the exit status") {
    std::istringstream in(
        distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}}).dump() +
        "\n\n" + distanceLine({{"intersect", true}}).dump() + "\nnot json\n");
    std::ostringstream out;
    CHECK(runCheck(in, out, CheckOptions{}) == 1);
    const std::string text = out.str();
    CHECK(text.find("line 1 (id 1): pass") != std::string::npos);
    CHECK(text.find("line 3 (id 1): FAIL: verdict differs") != std::string::npos);
    CHECK(text.find("line 4: FAIL") != std::string::npos);
    CHECK(text.find("1 passed, 2 failed\n") != std::string::npos);
}

// EPA on two cubes overlapping by 0.25 along x: A − B = [-1.75, 0.25] x [-1, 1] x [-1, 1], depth 0.25.
TEST_CASE("check: an EPA trace: each step's support is extreme, the closest face never nearer, never beyond the depth") {
    const Json a = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json b = {{"aabb", {{"min", {0.75, 0, 0}}, {"max", {1.75, 1, 1}}}}};
    const Json answer = {{"intersect", true}, {"depth", 0.25}, {"normal", {1, 0, 0}}, {"point_a", {1, 0.5, 0.5}},
                         {"point_b", {0.75, 0.5, 0.5}}};
    const auto line = [&](const Json& steps) {
        return Json{{"op", "penetration"}, {"a", a}, {"b", b}, {"answer", answer},
                    {"trace", {{"algorithm", "epa"}, {"steps", steps}}}};
    };
    const double s = 1 / std::sqrt(3.0);
    // A face with normal (1,1,1)/√3 at distance 0.1, then the face x = 0.25 (the depth): the
    // supports are extreme ((0.25, 1, 1) along the diagonal; any point of the face along +x).
    Json steps = {{{"normal", {s, s, s}}, {"distance", 0.1}, {"support", {0.25, 1, 1}}},
                  {{"normal", {1, 0, 0}}, {"distance", 0.25}, {"support", {0.25, -0.3, 0.7}}}};
    CHECK(check(line(steps)).pass);
    Json wrongSupport = steps;
    wrongSupport[1]["support"] = {0.2, 0, 0};
    CheckResult r = check(line(wrongSupport));
    CHECK(reasons(r).find("iteration 1: different support point") != std::string::npos);
    CHECK(r.traceDivergence == 1);
    Json beyond = steps;
    beyond[1]["distance"] = 0.3;
    CHECK(reasons(check(line(beyond))).find("iteration 1: the face is 0.3 from the origin, beyond the depth") !=
          std::string::npos);
    Json nearer = steps;
    nearer[0]["distance"] = 0.2;
    nearer[1]["distance"] = 0.15;
    nearer[1]["normal"] = {s, s, s};
    nearer[1]["support"] = {0.25, 1, 1};
    CHECK(reasons(check(line(nearer))).find("iteration 1: the closest face came nearer") != std::string::npos);
    Json notClosest = steps;
    notClosest[1]["polytope"] = {{{0.1, -1, -1}, {0.1, 1, -1}, {0.1, 0, 1}}, {{0.25, -1, -1}, {0.25, 1, -1}, {0.25, 0, 1}}};
    CHECK(reasons(check(line(notClosest))).find("not the closest face of your polytope") != std::string::npos);
}

TEST_CASE("check: Voronoi-region tests: values by Ericson's formulas, decisions by the conditions, ties either way") {
    const Json triangle = {{0, 0, 0}, {4, 0, 0}, {1.2, 3, 0}};
    const auto line = [&](const Json& point, const Json& answer, const Json& tests) {
        return Json{{"op", "closest_point_triangle"}, {"point", point}, {"triangle", triangle}, {"answer", answer},
                    {"trace", {{"algorithm", "ericson_regions"}, {"tests", tests}}}};
    };
    // p = (2, -1, 0.5): d1 = 8, d2 = -0.6 (A rejected), d3 = -8, d4 = -5.4 (B rejected), vc = -48 (AB).
    const Json answer = {{"point", {2, 0, 0}}, {"region", "AB"}, {"barycentric", {0.5, 0.5, 0}}, {"distance", std::sqrt(1.25)}};
    const Json tests = {
        {{"region", "A"}, {"terms", {{{"name", "d1"}, {"value", 8}}, {{"name", "d2"}, {"value", -0.6}}}}, {"accepted", false}},
        {{"region", "B"}, {"terms", {{{"name", "d3"}, {"value", -8}}, {{"name", "d4"}, {"value", -5.4}}}}, {"accepted", false}},
        {{"region", "AB"}, {"terms", {{{"name", "vc"}, {"value", -48}}}}, {"accepted", true}}};
    const Json p = {2, -1, 0.5};
    CHECK(check(line(p, answer, tests)).pass);
    Json wrongValue = tests;
    wrongValue[2]["terms"][0]["value"] = -47;
    CheckResult r = check(line(p, answer, wrongValue));
    CHECK(reasons(r).find("test 2 (AB): vc = -47, but it is -48") != std::string::npos);
    CHECK(r.traceDivergence == 2);
    Json flipped = tests;
    flipped[1]["accepted"] = true;
    CHECK(reasons(check(line(p, answer, flipped))).find("test 1 (B): accepted, but the point lies outside") !=
          std::string::npos);
    Json rejected = tests;
    rejected[2]["accepted"] = false;
    CHECK(reasons(check(line(p, answer, rejected))).find("test 2 (AB): rejected, but the point lies in this region") !=
          std::string::npos);
    // q = (0, -1, 0) lies on the boundary of A and AB (d1 = 0; d2 = -3, d3 = -16, vc = -48): rejecting
    // A and taking AB is a tie.
    const Json q = {0, -1, 0};
    const Json tieAnswer = {{"point", {0, 0, 0}}, {"region", "AB"}, {"barycentric", {1, 0, 0}}, {"distance", 1}};
    const Json tie = {
        {{"region", "A"}, {"terms", {{{"name", "d1"}, {"value", 0}}, {{"name", "d2"}, {"value", -3}}}}, {"accepted", false}},
        {{"region", "B"}, {"terms", {{{"name", "d3"}, {"value", -16}}}}, {"accepted", false}},
        {{"region", "AB"}, {"terms", {{{"name", "vc"}, {"value", -48}}}}, {"accepted", true}}};
    CHECK(check(line(q, tieAnswer, tie)).pass);
}

TEST_CASE("check: malformed traces fail their line with a reason, never crash") {
    // A support pair without "b", a support pair of short arrays.
    Json line = distanceLine({{"intersect", false}, {"distance", 1}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {{"a", {1, 0, 0}}}}}}}};
    CHECK(reasons(check(line)).find("iteration 0: expected \"direction\"") != std::string::npos);
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {{"a", Json::array()}, {"b", {0, 0, 0}}}}}}}};
    CHECK(!check(line).pass);
    // A query cdlab answers with an error (b missing): your error answer passes, the trace is not read.
    const Json broken = {{"op", "penetration"},
                         {"a", {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}}},
                         {"answer", {{"error", "b is missing"}}},
                         {"trace", {{"algorithm", "epa"}, {"steps", Json::array()}}}};
    CHECK_NOTHROW(check(broken));
    const Json brokenTriangle = {{"op", "closest_point_triangle"},
                                 {"point", {0, 0, 0}},
                                 {"triangle", {Json::array(), Json::array(), Json::array()}},
                                 {"answer", {{"error", "bad triangle"}}},
                                 {"trace", {{"tests", Json::array()}}}};
    CHECK_NOTHROW(check(brokenTriangle));
}

TEST_CASE("check: region tests in any order; ABC has its own condition; some test must accept") {
    const Json triangle = {{0, 0, 0}, {4, 0, 0}, {1.2, 3, 0}};
    // p = (-1, -1, 0) lies in region A: testing ABC first and rejecting it is right, accepting it wrong.
    const Json answer = {{"point", {0, 0, 0}}, {"region", "A"}};
    const auto line = [&](const Json& tests) {
        return Json{{"op", "closest_point_triangle"}, {"point", {-1, -1, 0}}, {"triangle", triangle}, {"answer", answer},
                    {"trace", {{"algorithm", "ericson_regions"}, {"tests", tests}}}};
    };
    CHECK(check(line({{{"region", "ABC"}, {"accepted", false}}, {{"region", "A"}, {"accepted", true}}})).pass);
    CHECK(reasons(check(line({{{"region", "ABC"}, {"accepted", true}}})))
              .find("test 0 (ABC): accepted, but the point lies outside this region") != std::string::npos);
    CHECK(reasons(check(line({{{"region", "B"}, {"accepted", false}}}))).find("no test accepted a region") !=
          std::string::npos);
    // Ericson's "AC" names cdlab's "CA".
    const Json ac = {{"op", "closest_point_triangle"}, {"point", {0, 2, 0}}, {"triangle", triangle},
                     {"answer", {{"point", {0.6896551724137931, 1.7241379310344829, 0}}, {"region", "AC"}}}};
    CHECK(check(ac).pass);
}
