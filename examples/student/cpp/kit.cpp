// The cases in and the lines for `cdlab check` out (kit.h). One case per line; a line that cannot
// be read is reported on stderr and skipped.
#include "kit.h"

#include <iostream>
#include <nlohmann/json.hpp>

namespace kit {
namespace {

using Json = nlohmann::json;

V3 v3(const Json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }
Json json(V3 p) { return Json::array({p.x, p.y, p.z}); }
std::vector<V3> vertices(const Json& shape) {
    std::vector<V3> v;
    for (const Json& p : shape.at("polytope").at("vertices")) v.push_back(v3(p));
    return v;
}

// Each case on stdin, answered by `answer` (which adds "answer" and maybe "trace"), printed.
template <class F>
int forEachCase(F answer) {
    std::string line;
    for (int n = 1; std::getline(std::cin, line); ++n) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        try {
            Json c = Json::parse(line);
            answer(c);
            std::cout << c.dump() << "\n";
        } catch (const std::exception& e) {
            std::cerr << "case line " << n << ": " << e.what() << "\n";
        }
    }
    return 0;
}

}  // namespace

int runTriangleCases(TriangleAnswer (*closestPointTriangle)(V3, V3, V3, V3)) {
    return forEachCase([&](Json& c) {
        const Json& t = c.at("triangle");
        const TriangleAnswer r = closestPointTriangle(v3(c.at("point")), v3(t.at(0)), v3(t.at(1)), v3(t.at(2)));
        c["answer"] = {{"point", json(r.point)}, {"region", r.region}};
        Json tests = Json::array();
        for (const RegionTest& test : r.tests) {
            Json terms = Json::array();
            for (const auto& [name, value] : test.terms) terms.push_back({{"name", name}, {"value", value}});
            tests.push_back({{"region", test.region}, {"terms", terms}, {"accepted", test.accepted}});
        }
        c["trace"] = {{"algorithm", "ericson_regions"}, {"tests", tests}};
    });
}

int runGjkCases(GjkAnswer (*gjk)(const std::vector<V3>&, const std::vector<V3>&, V3)) {
    return forEachCase([&](Json& c) {
        const V3 first = c.contains("initial_direction") ? v3(c["initial_direction"]) : V3{1, 0, 0};
        const GjkAnswer r = gjk(vertices(c.at("a")), vertices(c.at("b")), first);
        c["answer"] = r.intersect ? Json{{"intersect", true}, {"distance", 0}}
                                  : Json{{"intersect", false}, {"distance", r.distance}, {"point_a", json(r.pointA)},
                                         {"point_b", json(r.pointB)}};
        Json steps = Json::array();
        for (const GjkStep& s : r.steps) {
            Json step = {{"direction", json(s.direction)}, {"support", {{"a", json(s.a)}, {"b", json(s.b)}}}};
            if (!s.simplex.empty()) {
                step["simplex"] = Json::array();
                for (V3 p : s.simplex) step["simplex"].push_back(json(p));
            }
            steps.push_back(step);
        }
        c["trace"] = {{"algorithm", "gjk"}, {"steps", steps}};
    });
}

int runPlaneCases(PlaneAnswer (*contact)(const std::vector<V3>&, V3, double)) {
    return forEachCase([&](Json& c) {
        const Json& plane = c.at("b").at("plane");
        const PlaneAnswer r = contact(vertices(c.at("a")), v3(plane.at("normal")), plane.at("offset").get<double>());
        Json points = Json::array();
        for (const ContactPoint& p : r.points) {
            Json point = {{"point_a", json(p.pointA)}, {"point_b", json(p.pointB)}};
            if (r.colliding) point["depth"] = p.depth;
            points.push_back(point);
        }
        c["answer"] = {{"colliding", r.colliding}, {r.colliding ? "depth" : "distance", r.depthOrDistance},
                       {"normal", json(r.normal)}, {r.colliding ? "points" : "closest", points}};
    });
}

}  // namespace kit
