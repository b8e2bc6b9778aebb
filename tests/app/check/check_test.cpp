// `cdlab check`: right answers pass (including the ones that differ from cdlab's only where the
// answer is not unique: other witness points on a face pair, a region tie at a vertex, a tied
// support point), and each kind of wrong answer fails with its reason in words; a planted GJK
// trace divergence is reported at its iteration.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "app/check/check.h"
#include "app/check/check_figure.h"
#include "app/check/check_values.h"
#include "app/check/trace_check.h"
#include "app/query/query.h"
#include "app/query/query_limits.h"

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
    // A tolerance per line sets it, up to the check's own (--tolerance).
    Json loose = distanceLine({{"intersect", false}, {"distance", 1.001}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2.001, 0.5, 0.5}}});
    loose["tolerance"] = 1e-3;
    CheckOptions grader;
    grader.tolerance = 1e-3;
    CHECK(checkLine(loose.dump(), 1, grader).pass);
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

TEST_CASE("check: a GJK trace is checked step by step, a tie is not a divergence, a planted one is found") {
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

TEST_CASE("check: the broken step of a wrong answer is reported first, with the answer's verdict") {
    // The usual case of a student's bug: the answer is wrong too. The trace is still checked and its
    // first broken step leads the verdict (the figure draws that step: check_figure_test).
    Json line = distanceLine({{"intersect", false}, {"distance", 1.5}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    line["trace"] = gjkTrace(true);
    const CheckResult r = check(line);
    REQUIRE(r.reasons.size() >= 2);
    CHECK(r.reasons[0].rfind("trace: iteration 1: wrong sub-simplex kept", 0) == 0);
    CHECK(reasons(r).find("distance off by 0.5") != std::string::npos);
    CHECK(r.traceDivergence == 1);
}

TEST_CASE("check: names the region a wrong reduction missed") {
    // gjkTrace(true): iteration 1 keeps w(1) = (-1, -1, -1) alone, 1.73 from the origin, where the
    // segment w(0) w(1) is nearest it at its midpoint (-1, 0, 0), in the edge's Voronoi region.
    Json line = distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    line["trace"] = gjkTrace(true);
    CHECK(reasons(check(line)).find("iteration 1: wrong sub-simplex kept: the simplex w(0), w(1) is nearest the origin on "
                                    "its edge w(0), w(1) (the origin is in that edge's Voronoi region): keep w(0), w(1), 1 "
                                    "from the origin; yours, w(1), is 1.73 from it") != std::string::npos);
    // A − B = [-3, -1] x [-1, 1]^2. The triangle w(0) = (-3, 1, 1), w(1) = (-1, -1, -1), w(2) = (-1, 1, 1)
    // is nearest the origin at (-1, 0, 0), inside its edge w(1) w(2); keeping w(0), w(1) fails.
    Json steps = Json::array();
    steps.push_back({{"direction", {-1, 0, 0}}, {"support", {-3, 1, 1}}, {"simplex", {{-3, 1, 1}}}});
    steps.push_back({{"direction", {3, -1, -1}}, {"support", {-1, -1, -1}}, {"simplex", {{-3, 1, 1}, {-1, -1, -1}}}});
    steps.push_back({{"direction", {4, 2, 2}}, {"support", {-1, 1, 1}}, {"simplex", {{-3, 1, 1}, {-1, -1, -1}}}});
    line["trace"] = {{"algorithm", "gjk"}, {"steps", steps}};
    CHECK(reasons(check(line)).find("iteration 2: wrong sub-simplex kept: the simplex w(0), w(1), w(2) is nearest the "
                                    "origin on its edge w(1), w(2)") != std::string::npos);
}

TEST_CASE("check: names the support that is not extreme") {
    // Two tetrahedra 2 apart along x; along the unit d = (0.48, 0.64, 0.6): s_A(d) = (0, 1, 0) (reaching
    // 0.64), s_B(-d) = (3, 0, 0) (reaching -1.44 along -d), each unique; w = (-3, 1, 0).
    const Json tetA = {{"polytope", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}}};
    const Json tetB = {{"polytope", {{"vertices", {{3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 1}}}}}};
    Json line = {{"op", "distance"}, {"a", tetA}, {"b", tetB},
                 {"answer", {{"intersect", false}, {"distance", 2.0}, {"point_a", {1, 0, 0}}, {"point_b", {3, 0, 0}}}}};
    const auto stepWith = [&](const Json& w) {
        line["trace"] = {{"algorithm", "gjk"}, {"steps", Json::array({{{"direction", {0.48, 0.64, 0.6}}, {"support", w}}})}};
        return reasons(check(line));
    };
    CHECK(stepWith({-3, 1, 0}).find("iteration 0") == std::string::npos);
    // w = (0, 0, 1) − (3, 0, 0), the only way: A's vertex (0, 0, 1) is not A's extreme, B's is.
    CHECK(stepWith({-3, 0, 1}).find("s_A is not extreme: your w is a − s_B(−d) with a = (0, 0, 1) of A, reaching 0.6 "
                                    "along d, where A reaches 0.64") != std::string::npos);
    // w = (0, 1, 0) − (3, 0, 1): B's vertex (3, 0, 1) is not B's extreme along −d.
    CHECK(stepWith({-3, 1, -1}).find("s_B is not extreme: your w is s_A(d) − b with b = (3, 0, 1) of B, reaching -2.04 "
                                     "along −(d), where B reaches -1.44") != std::string::npos);
    // w = (1, 0, 0) − (3, 1, 0), the only way: neither vertex is extreme.
    CHECK(stepWith({-2, -1, 0}).find("neither s_A nor s_B is extreme") != std::string::npos);
    // w = (0, 0, 1) − (3, 0, 1) = (0, 0, 0) − (3, 0, 0) = (0, 1, 0) − (3, 1, 0): the ways disagree.
    CHECK(stepWith({-3, 0, 0}).find("s_A or s_B is not extreme") != std::string::npos);
    // Short of A − B but no vertex difference at all.
    CHECK(stepWith({-2.5, 0.3, 0.1}).find("w is no vertex of A minus a vertex of B") != std::string::npos);

    // Ties (the review's case): boxes along +x have four extreme vertices each. w = (−2, −1, −1) is
    // (0, 0, 0) − (2, 1, 1) (A's vertex not extreme) and (1, 0, 0) − (3, 1, 1) (B's not): either.
    Json boxes = distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    boxes["trace"] = {{"algorithm", "gjk"}, {"steps", Json::array({{{"direction", {1, 0, 0}}, {"support", {-2, -1, -1}}}})}};
    CHECK(reasons(check(boxes)).find("s_A or s_B is not extreme") != std::string::npos);
    // A point's support is always extreme: the blame is B's.
    Json point = {{"op", "distance"}, {"a", {{"point", {0, 0, 0}}}}, {"b", {{"aabb", {{"min", {3, -1, -1}}, {"max", {4, 1, 1}}}}}},
                  {"answer", {{"intersect", false}, {"distance", 3.0}, {"point_a", {0, 0, 0}}, {"point_b", {3, 0, 0}}}},
                  {"trace", {{"algorithm", "gjk"}, {"steps", Json::array({{{"direction", {1, 0, 0}}, {"support", {-4, -1, 1}}}})}}}};
    CHECK(reasons(check(point)).find("s_B is not extreme") != std::string::npos);
}

TEST_CASE("check: a trace that cannot be read keeps the answer's reasons") {
    Json line = {{"op", "closest_point_triangle"}, {"point", {0.2, 0.2, 5}}, {"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                 {"answer", {{"point", {9, 9, 9}}, {"region", "ABC"}}},
                 {"trace", {{"algorithm", "ericson_regions"}, {"tests", Json::array({{{"region", 5}, {"accepted", true}}})}}}};
    const std::string why = reasons(check(line));
    CHECK(why.find("your trace could not be read") != std::string::npos);
    CHECK(why.find("point off by") != std::string::npos);
}

TEST_CASE("check: after a step without a simplex the next direction is not held to an older one") {
    // Iteration 1 gives no simplex (allowed): iteration 2's direction comes from your reduction, which
    // the check does not have; it must not be compared with iteration 0's simplex.
    Json line = distanceLine({{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    Json steps = Json::array();
    steps.push_back({{"direction", {1, 0, 0}}, {"support", {-1, 1, 1}}, {"simplex", {{-1, 1, 1}}}});
    steps.push_back({{"direction", {1, -1, -1}}, {"support", {-1, -1, -1}}});
    steps.push_back({{"direction", {1, 0, 0}}, {"support", {-1, 1, -1}}});
    line["trace"] = {{"algorithm", "gjk"}, {"steps", steps}};
    const CheckResult r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
}

TEST_CASE("check: an answer with keys of the wrong type fails that line only") {
    const Json cube = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json line = {{"op", "raycast"}, {"ray", {{"origin", {-1, 0.5, 0.5}}, {"direction", {1, 0, 0}}}}, {"shape", cube},
                       {"answer", {{"hit", true}, {"t", 1.0}, {"point", {0, 0.5, 0.5}}, {"inside", "no"}}}};
    const CheckResult r = check(line);
    CHECK_FALSE(r.pass);
    CHECK(reasons(r).find("your \"inside\" is not true or false") != std::string::npos);
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

TEST_CASE("check: a trace that is no object, an algorithm that is no string, a zero direction: each a FAIL") {
    // Reproducer: "trace": [] passed; {"algorithm": 7} printed a raw [json.exception.type_error.302];
    // a step with "direction": [0, 0, 0] and a support point outside A − B ([1, 2, 3]) passed.
    Json line = distanceLine({{"intersect", false}, {"distance", 1}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}});
    line["trace"] = Json::array();
    CHECK(reasons(check(line)).find("trace: expected an object") != std::string::npos);
    line["trace"] = {{"algorithm", 7}, {"steps", Json::array()}};
    CHECK(reasons(check(line)).find("trace: \"algorithm\" must be a string (gjk, epa or ericson_regions), got the "
                                    "number 7") != std::string::npos);
    line["trace"] = {{"algorithm", "gjk"}, {"steps", {{{"direction", {0, 0, 0}}, {"support", {1, 2, 3}}}}}};
    CHECK(reasons(check(line)).find("iteration 0: the search direction is zero") != std::string::npos);
}

TEST_CASE("check: region tests in any order, ABC has its own condition, some test must accept") {
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

namespace {

// The line with cdlab's own answer (`cdlab query`'s output for it, "id" included) as its "answer".
Json withOwnAnswer(Json line) {
    line["answer"] = answerQuery(line.dump());
    return line;
}

Json box(double lo, double hi, double scale) {
    return {{"aabb", {{"min", {lo * scale, 0, 0}}, {"max", {hi * scale, scale, scale}}}}};
}

std::string runText(const std::string& input, const CheckOptions& options = CheckOptions{}) {
    std::istringstream in(input);
    std::ostringstream out;
    runCheck(in, out, options);
    return out.str();
}

// An input of `size` bytes of 'x', a newline, then `tail`: an over-long line no test holds in memory.
class LongLineInput : public std::streambuf {
public:
    LongLineInput(std::size_t size, const std::string& tail) : left_(size), tail_("\n" + tail) {}

protected:
    int_type underflow() override {
        if (left_ > 0) {
            const std::size_t n = std::min(left_, chunk_.size());
            left_ -= n;
            setg(chunk_.data(), chunk_.data(), chunk_.data() + n);
            return traits_type::to_int_type(chunk_[0]);
        }
        if (!tailGiven_) {
            tailGiven_ = true;
            setg(tail_.data(), tail_.data(), tail_.data() + tail_.size());
            return traits_type::to_int_type(tail_[0]);
        }
        return traits_type::eof();
    }

private:
    std::size_t left_;
    std::string tail_;
    bool tailGiven_ = false;
    std::string chunk_ = std::string(std::size_t(1) << 16, 'x');
};

const Json kRightDistance = {{"intersect", false}, {"distance", 1.0}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}};

}  // namespace

TEST_CASE("check: cdlab's own mass_properties answer passes, the echoed id is not part of the answer") {
    // Reproducer: echo '{"op":"mass_properties","a":{"polytope":{"vertices":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}},"answer":{"center_of_mass":[0.25,0.25,0.25],"id":null,"inertia":[[0.012500000000000002,0.0020833333333333333,0.0020833333333333333],[0.0020833333333333333,0.012500000000000002,0.0020833333333333333],[0.0020833333333333333,0.0020833333333333333,0.012500000000000002]],"mass":0.16666666666666666,"volume":0.16666666666666666}}' | cdlab check
    const Json query = {{"op", "mass_properties"}, {"a", {{"polytope", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}}}}};
    Json line = withOwnAnswer(query);  // "id": null among the answer's keys, as `cdlab query` writes it
    REQUIRE(line["answer"].contains("volume"));
    CheckResult r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    line["answer"].erase("id");
    r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    line["id"] = 5;
    r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    line["answer"].erase("volume");
    CHECK(reasons(check(line)).find("your answer has no volume") != std::string::npos);
}

TEST_CASE("check: cdlab's own answers pass at coordinates of 1e160 and 1e-160 (no norm overflows or underflows)") {
    // Reproducer: echo '{"id":1,"op":"distance","a":{"aabb":{"min":[0,0,0],"max":[1e160,1e160,1e160]}},"b":{"aabb":{"min":[2e160,0,0],"max":[3e160,1e160,1e160]}},"answer":{"intersect":false,"distance":1e160,"point_a":[1e160,5e159,5e159],"point_b":[2e160,5e159,5e159]}}' | cdlab check
    for (const double scale : {1e160, 1e200, 1e300, 1e-160, 1e-200, 1e-300}) {
        for (const char* op : {"distance", "penetration", "contact"}) {
            const Json line = withOwnAnswer({{"id", 1}, {"op", op}, {"a", box(0, 1, scale)}, {"b", box(2, 3, scale)}});
            const CheckResult r = check(line);
            CHECK_MESSAGE(r.pass, op << " at " << scale << ": " << reasons(r));
            const Json overlapping = withOwnAnswer({{"id", 2}, {"op", op}, {"a", box(0, 1, scale)}, {"b", box(0.75, 1.75, scale)}});
            const CheckResult o = check(overlapping);
            CHECK_MESSAGE(o.pass, op << " overlapping at " << scale << ": " << reasons(o));
        }
        // A region tie (p at vertex A: A, AB and CA name its closest point) at that scale.
        for (const char* region : {"A", "AB", "CA"}) {
            const Json tie = {{"op", "closest_point_triangle"}, {"point", {-scale, -scale, 0}},
                              {"triangle", {{0, 0, 0}, {scale, 0, 0}, {0, scale, 0}}},
                              {"answer", {{"point", {0, 0, 0}}, {"region", region}}}};
            const CheckResult t = check(tie);
            CHECK_MESSAGE(t.pass, region << " at " << scale << ": " << reasons(t));
        }
        // The witness relation itself: |point_b − point_a| is 1e160, not inf; 1e-160, not 0.
        Json line = distanceLine(kRightDistance);
        line["a"] = box(0, 1, scale);
        line["b"] = box(2, 3, scale);
        line["answer"] = {{"intersect", false}, {"distance", scale}, {"point_a", {scale, 0.5 * scale, 0.5 * scale}},
                          {"point_b", {2 * scale, 0.5 * scale, 0.5 * scale}}};
        const CheckResult r = check(line);
        CHECK_MESSAGE(r.pass, scale << ": " << reasons(r));
    }
}

TEST_CASE("check: cdlab's own answer to every query of the fuzz corpus passes (selfCheckPasses)") {
    // Reproducer: ./cdlab query < tests/fuzz/seeds/queries.jsonl, each answer put into its line as
    // "answer", | cdlab check (mass_properties lines failed "your answer has no id").
    std::ifstream corpus(CDLAB_SOURCE_DIR "/tests/fuzz/seeds/queries.jsonl");
    REQUIRE(corpus);
    std::vector<std::string> lines;
    for (std::string line; std::getline(corpus, line);)
        if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
    CHECK(lines.size() >= 40);
    // Lines like the query tests' besides: every op, rotations, separated and touching contacts.
    const Json cube = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json turned = {{"obb", {{"center", {1.4, 0.6, 0.5}}, {"half_extents", {0.5, 0.5, 0.5}}, {"rotation", {0.9, 0.1, 0.3, 0.2}}}}};
    const Json capsule = {{"capsule", {{"a", {0, -1, 0}}, {"b", {0, 1, 0}}, {"radius", 0.25}}}};
    const Json sphere = {{"sphere", {{"center", {0.5, 2.2, 0.5}}, {"radius", 1}}}};
    for (const Json& q : {
             Json{{"op", "penetration"}, {"a", cube}, {"b", turned}},
             Json{{"op", "contact"}, {"a", cube}, {"b", turned}},
             Json{{"op", "contact"}, {"a", cube}, {"b", kBoxB}},
             Json{{"op", "contact"}, {"a", cube}, {"b", sphere}, {"max_points", 8}},
             Json{{"op", "distance"}, {"a", capsule}, {"b", turned}},
             Json{{"op", "penetration"}, {"a", capsule}, {"b", sphere}},
             Json{{"op", "raycast"}, {"ray", {{"origin", {-2, 0.5, 0.25}}, {"direction", {1, 0.1, 0}}}}, {"shape", turned}},
             Json{{"op", "time_of_impact"}, {"a", sphere}, {"b", cube}, {"motion_a", {0, -3, 0}}},
             Json{{"op", "closest_point_tetrahedron"}, {"point", {2, 2, 2}}, {"tetrahedron", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}},
             Json{{"op", "mass_properties"}, {"a", turned}},
             Json{{"op", "distance"}, {"a", cube}, {"b", turned}, {"trace", true}},
         })
        lines.push_back(q.dump());
    for (const std::string& line : lines) {
        std::string why;
        CHECK_MESSAGE(selfCheckPasses(line, &why), line.substr(0, 160) << ": " << why);
    }
}

TEST_CASE("check: GJK rule 1 holds both ways: a support point beyond A − B fails, naming the one of the pair") {
    // Reproducer: echo '{"id":1,"op":"distance","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[2,0,0],"max":[3,1,1]}},"answer":{"intersect":false,"distance":1,"point_a":[1,0.5,0.5],"point_b":[2,0.5,0.5]},"trace":{"steps":[{"direction":[1,0,0],"support":[5,0,0]}]}}' | cdlab check
    Json line = distanceLine(kRightDistance);
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {5, 0, 0}}}}}};
    CheckResult r = check(line);
    CHECK(reasons(r).find("iteration 0: different support point for the same direction: yours reaches 5 along it, "
                          "A − B reaches -1 (yours lies beyond A − B)") != std::string::npos);
    CHECK(r.traceDivergence == 0);
    // A pair: a beyond A, b extreme.
    line["trace"] = {{"steps", {{{"direction", {2, 0, 0}}, {"support", {{"a", {4, 0.5, 0.5}}, {"b", {2, 0.5, 0.5}}}}}}}};
    r = check(line);
    CHECK(reasons(r).find("your a reaches 4 along d, beyond A's extreme 1: not a point of A") != std::string::npos);
    // a beyond A by 2, b short of B's extreme by 2: w · d is h(d), but neither point is right.
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {{"a", {3, 0.5, 0.5}}, {"b", {4, 0.5, 0.5}}}}}}}};
    r = check(line);
    CHECK(reasons(r).find("your a reaches 3 along d, beyond A's extreme 1: not a point of A") != std::string::npos);
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {{"a", {1, 0.5, 0.5}}, {"b", {3, 0.5, 0.5}}}}}}}};
    r = check(line);
    CHECK(reasons(r).find("your b is not extreme in B along −(d): it reaches -3, B reaches -2") != std::string::npos);
    // Short of it, as before: another point reaches further.
    line["trace"] = {{"steps", {{{"direction", {1, 0, 0}}, {"support", {-2, 0, 0}}}}}};
    CHECK(reasons(check(line)).find("yours reaches -2 along it, A − B reaches -1") != std::string::npos);
    // An EPA support beyond A − B along the face's normal fails the same way.
    const Json a = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json b = {{"aabb", {{"min", {0.75, 0, 0}}, {"max", {1.75, 1, 1}}}}};
    const Json epa = {{"op", "penetration"}, {"a", a}, {"b", b},
                      {"answer", {{"intersect", true}, {"depth", 0.25}, {"normal", {1, 0, 0}}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {0.75, 0.5, 0.5}}}},
                      {"trace", {{"algorithm", "epa"}, {"steps", {{{"normal", {1, 0, 0}}, {"distance", 0.25}, {"support", {5, 0, 0}}}}}}}};
    CHECK(reasons(check(epa)).find("iteration 0: different support point for the face's normal: yours reaches 5 along it, "
                                   "A − B reaches 0.25 (yours lies beyond A − B)") != std::string::npos);
}

TEST_CASE("check: a line whose op is not a string fails alone, the run goes on") {
    // Reproducer: printf '%s\n' '{"id":1,"op":7,"answer":{}}' '{"id":2,"op":null,"answer":{}}' | cdlab check
    static_assert(noexcept(checkLine(std::string(), 1, CheckOptions{})));
    const std::string text = runText(R"({"id":1,"op":7,"answer":{}})" "\n" R"({"id":2,"op":null,"answer":{}})" "\n"
                                     R"({"id":3,"answer":{}})" "\n" R"({"id":4,"op":[],"answer":{"error":"x"}})" "\n" +
                                     distanceLine(kRightDistance).dump() + "\n");
    CHECK(text.find("line 1 (id 1): FAIL: line 1: expected \"op\": the name of the query's operation, a string, got 7\n") !=
          std::string::npos);
    CHECK(text.find("line 2 (id 2): FAIL: line 2: expected \"op\"") != std::string::npos);
    CHECK(text.find("line 3 (id 3): FAIL: line 3: expected \"op\"") != std::string::npos);
    CHECK(text.find("line 4 (id 4): FAIL: line 4: expected \"op\"") != std::string::npos);
    CHECK(text.find("line 5 (id 1): pass\n") != std::string::npos);
    CHECK(text.find("1 passed, 4 failed\n") != std::string::npos);
    CHECK(text.find("json.exception") == std::string::npos);
}

TEST_CASE("check: an answer missing depth, distance or t fails naming the field (no read of a missing key)") {
    // Reproducer: echo '{"op":"penetration","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[0.75,0,0],"max":[1.75,1,1]}},"answer":{"intersect":true,"normal":[1,0,0],"point_a":[1,0.5,0.5],"point_b":[0.75,0.5,0.5]}}' | cdlab check
    const Json a = {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}};
    const Json b = {{"aabb", {{"min", {0.75, 0, 0}}, {"max", {1.75, 1, 1}}}}};
    CheckResult r = check({{"op", "penetration"}, {"a", a}, {"b", b},
                           {"answer", {{"intersect", true}, {"normal", {1, 0, 0}}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {0.75, 0.5, 0.5}}}}});
    CHECK(reasons(r).find("your answer has no depth number") != std::string::npos);
    r = check({{"op", "penetration"}, {"a", kBoxA}, {"b", kBoxB},
               {"answer", {{"intersect", false}, {"normal", {1, 0, 0}}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}}}});
    CHECK(reasons(r).find("your answer has no distance number") != std::string::npos);
    r = check(distanceLine({{"intersect", false}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2, 0.5, 0.5}}}));
    CHECK(reasons(r).find("your answer has no distance number") != std::string::npos);
    const Json sphere = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}};
    const Json far = {{"sphere", {{"center", {5, 0, 0}}, {"radius", 1}}}};
    r = check({{"op", "time_of_impact"}, {"a", sphere}, {"b", far}, {"motion_a", {6, 0, 0}},
               {"answer", {{"hit", true}, {"normal", {1, 0, 0}}, {"point_a", {4, 0, 0}}, {"point_b", {4, 0, 0}}}}});
    CHECK(reasons(r).find("your answer has no t number") != std::string::npos);
    r = check({{"op", "raycast"}, {"ray", {{"origin", {-1, 0.5, 0.5}}, {"direction", {1, 0, 0}}}}, {"shape", kBoxA},
               {"answer", {{"hit", true}, {"point", {0, 0.5, 0.5}}, {"normal", {-1, 0, 0}}}}});
    CHECK(reasons(r).find("your answer has no t number") != std::string::npos);
    // Contact entries that are not objects, a region that is not a string: reasons, not reads.
    r = check({{"op", "contact"}, {"a", a}, {"b", b}, {"answer", {{"colliding", true}, {"depth", 0.25}, {"normal", {1, 0, 0}}, {"points", {1, 2}}}}});
    CHECK(reasons(r).find("points[0]: your answer has no point_a") != std::string::npos);
    r = check({{"op", "closest_point_tetrahedron"}, {"point", {2, 2, 2}}, {"tetrahedron", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
               {"answer", {{"point", {0.3, 0.3, 0.3}}, {"region", 4}}}});
    CHECK(reasons(r).find("your answer has no \"region\"") != std::string::npos);
}

TEST_CASE("check: verdict lines are escaped: an answer's strings cannot forge lines or terminal escapes") {
    // Reproducer: printf '%s\n' '{"id":1,"op":"closest_point_triangle","point":[0.2,-1,0],"triangle":[[0,0,0],[1,0,0],[0,1,0]],"answer":{"point":[0.2,0,0],"region":"\n2 passed, 0 failed\u001b[8m"}}' | cdlab check
    const Json line = {{"id", 1}, {"op", "closest_point_triangle"}, {"point", {0.2, -1, 0}}, {"triangle", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                       {"answer", {{"point", {0.2, 0, 0}}, {"region", "\n2 passed, 0 failed\x1b[8m"}}}};
    Json idLine = distanceLine({{"intersect", true}});
    idLine["id"] = "\x7f\xc2\x85\xe2\x80\xae x";
    const std::string text = runText(line.dump() + "\n" + idLine.dump() + "\n");
    CHECK(std::count(text.begin(), text.end(), '\n') == 3);  // one line per input line, then the summary
    CHECK(text.find('\x1b') == std::string::npos);
    CHECK(text.find('\x7f') == std::string::npos);
    CHECK(text.find("\xc2\x85") == std::string::npos);
    CHECK(text.find("\xe2\x80\xae") == std::string::npos);
    CHECK(text.find("region differs: yours \\n2 passed, 0 failed\\x1b[8m, cdlab's AB") != std::string::npos);
    CHECK(text.find("0 passed, 2 failed\n") != std::string::npos);
    CHECK(printable("a\tb\r\xff\xc3\xa9") == "a\\tb\\r\\xff\xc3\xa9");  // é stays, a stray byte does not
    // An id cannot put a verdict of its own into a line: its colons are written \u003a.
    Json forged = distanceLine(kRightDistance);
    forged["id"] = "x: FAIL: y";
    CHECK(runText(forged.dump() + "\n").find("line 1 (id \"x\\u003a FAIL\\u003a y\"): pass\n") != std::string::npos);
}

TEST_CASE("check: a line's tolerance may only tighten the check's (--tolerance caps it)") {
    // Reproducer: echo '{"id":1,"op":"distance","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[2,0,0],"max":[3,1,1]}},"answer":{"intersect":false,"distance":5,"point_a":[1,0.5,0.5],"point_b":[6,0.5,0.5]},"tolerance":1e300}' | cdlab check
    Json wrong = distanceLine({{"intersect", false}, {"distance", 5}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {6, 0.5, 0.5}}});
    wrong["tolerance"] = 1e300;
    CheckResult r = check(wrong);
    CHECK_FALSE(r.pass);
    CHECK(reasons(r).find("\"tolerance\" 1e+300 is over the check's tolerance 1e-09 (--tolerance): a line may tighten it, "
                          "never loosen it") != std::string::npos);
    Json tight = distanceLine(kRightDistance);
    tight["tolerance"] = 1e-12;
    CHECK(check(tight).pass);
    // Directions do not size the problem: a huge "initial_direction" (a valid GJK start) leaves
    // the tolerance where it was (directions).
    Json inflated = distanceLine({{"intersect", false}, {"distance", 1.5}, {"point_a", {1, 0.5, 0.5}}, {"point_b", {2.5, 0.5, 0.5}}});
    inflated["initial_direction"] = {1e300, 0, 0};
    CHECK(reasons(check(inflated)).find("distance off by 0.5") != std::string::npos);
    // The check's own tolerance: finite, in (0, kMaxCheckTolerance] (the command line refuses others).
    for (const double bad : {double(INFINITY), double(NAN), 0.0, -1.0, 2 * kMaxCheckTolerance}) {
        CheckOptions o;
        o.tolerance = bad;
        CHECK_FALSE(checkLine(distanceLine(kRightDistance).dump(), 1, o).pass);
    }
}

TEST_CASE("check: trace step limit, steps without a simplex cost linear time") {
    // Reproducer: python3 -c 'import json; s=[{"direction":[1,0,0],"support":[-1,1,1]}]*100000; print(json.dumps({"op":"distance","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[2,0,0],"max":[3,1,1]}},"answer":{"intersect":False,"distance":1,"point_a":[1,0.5,0.5],"point_b":[2,0.5,0.5]},"trace":{"steps":s}}))' | cdlab check
    Json line = distanceLine(kRightDistance);
    const Json step = {{"direction", {1, 0, 0}}, {"support", {-1, 1, 1}}};
    Json steps = Json::array();
    for (std::size_t i = 0; i < kMaxTraceSteps; ++i) steps.push_back(step);
    steps.back()["simplex"] = {{-1, 1, 1}};  // the last step keeps one point of the long run
    line["trace"] = {{"steps", steps}};
    CheckResult r = check(line);
    CHECK_MESSAGE(r.pass, reasons(r));
    steps.push_back(step);
    line["trace"] = {{"steps", steps}};
    r = check(line);
    CHECK(reasons(r).find("trace: 10001 steps, over the limit of 10000 steps a trace may have") != std::string::npos);
    line["trace"] = {{"algorithms", Json::array({Json{{"steps", Json::array()}}, Json{{"algorithms", Json::array()}}})}};
    CHECK(reasons(check(line)).find("\"algorithms\" inside \"algorithms\"") != std::string::npos);
}

TEST_CASE("check: a line over cdlab query's length limit fails naming its length, the next line is checked") {
    // Reproducer: python3 -c 'print("x" * (64 * 2**20 + 1))' | cdlab check
    LongLineInput input(kMaxQueryLineBytes + 1, distanceLine(kRightDistance).dump() + "\n");
    std::istream in(&input);
    std::ostringstream out;
    CHECK(runCheck(in, out, CheckOptions{}) == 1);
    const std::string text = out.str();
    CHECK(text.find("line 1: FAIL: line 1: the line is " + std::to_string(kMaxQueryLineBytes + 1) +
                    " bytes, over the limit of 64 MiB for one line\n") != std::string::npos);
    CHECK(text.find("line 2 (id 1): pass\n") != std::string::npos);
    CHECK(text.find("1 passed, 1 failed\n") != std::string::npos);
}

TEST_CASE("check --figures: no trace figure where the hull of A − B is over the scenes' cap") {
    // Reproducer: two 2000-vertex polytopes and a GJK trace that breaks a rule | cdlab check --figures out/check
    const auto polytope = [](int n, double x) {
        Json v = Json::array();
        for (int i = 0; i < n; ++i) {
            const double t = 0.01 * i;
            v.push_back({x + std::cos(t), std::sin(t), 0.001 * i});
        }
        return Json{{"polytope", {{"vertices", v}}}};
    };
    const Json over = {{"op", "distance"}, {"a", polytope(501, 0)}, {"b", polytope(500, 5)}};
    CHECK(traceFigureRefusal(over).find("no figure: A − B would be the hull of 501 x 500 differences of vertices, over the "
                                        "limit of 250000") != std::string::npos);
    const Json within = {{"op", "distance"}, {"a", polytope(500, 0)}, {"b", polytope(500, 5)}};
    CHECK(traceFigureRefusal(within).empty());
}

TEST_CASE("check --figures: no figure of a polytope over the scenes' vertex limit") {
    // Reproducer: a penetration line of two 500 000-vertex polytopes with a wrong depth | cdlab check
    // --figures FIG -> 63 s, 2.75 GB, then "LLVM ERROR: Unable to allocate section memory!".
    Json v = Json::array();
    for (int i = 0; i < 1001; ++i) v.push_back({std::cos(0.01 * i), std::sin(0.01 * i), 0.001 * i});
    const Json big = {{"op", "penetration"}, {"a", {{"polytope", {{"vertices", v}}}}}, {"b", kBoxB}};
    CHECK(traceFigureRefusal(big) == "no figure: a is a polytope of 1001 vertices, over the limit of 1000 the figures draw");
}

TEST_CASE("check: a contact's depth may be the least overlap or cdlab's face preference, nothing beyond") {
    // Issue 41 (a): a box and a wedge; cdlab answers face A at depth 0.2, the least overlap is 0.199007 along
    // the wedge's tilted face. The contract: least overlap <= depth <= least overlap · 1.02 + tolerance.
    const Json box = {{"aabb", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
    const Json wedge = {{"polytope",
                         {{"vertices", {{-1, -1, 0.8}, {1, -1, 1.0}, {-1, 1, 0.8}, {1, 1, 1.0}, {-1, -1, 3}, {1, -1, 3}, {-1, 1, 3}, {1, 1, 3}}}}}};
    using Vec3 = Eigen::Vector3d;
    const double s = 1 / std::sqrt(1.01);  // the tilted face's normal (-0.1, 0, 1) / |.|
    const Vec3 n(-0.1 * s, 0, s);
    const double least = 0.2 * s;  // A's support (-1, y, 1) against the plane z = 0.9 + 0.1 x
    const Vec3 pa(-1, 0, 1), pb = pa - least * n;
    const auto answer = [&](double depth, const Vec3& normal, const Vec3& b) {
        return Json{{"op", "contact"}, {"a", box}, {"b", wedge},
                    {"answer", {{"colliding", true}, {"depth", depth}, {"normal", {normal.x(), normal.y(), normal.z()}},
                                {"points", {{{"point_a", {pa.x(), pa.y(), pa.z()}}, {"point_b", {b.x(), b.y(), b.z()}}, {"depth", depth}}}}}}};
    };
    // The least overlap passes, though cdlab's depth is 0.2.
    CheckResult r = check(answer(least, n, pb));
    CHECK_MESSAGE(r.pass, reasons(r));
    // 3 % above cdlab's face depth: outside the range.
    const Vec3 up(0, 0, 1);
    r = check(answer(0.2 * 1.03, up, pa - 0.2 * 1.03 * up));
    CHECK_FALSE(r.pass);
    CHECK(reasons(r).find("depth 0.206 outside [") != std::string::npos);
    // Inside the range, but the normal does not realise it (its overlap is 0.2).
    r = check(answer(0.201, up, pa - 0.201 * up));
    CHECK_FALSE(r.pass);
    CHECK(reasons(r).find("normal does not realise your depth") != std::string::npos);
}
