// golden/world run numerically, their traces checked against what the scenes imply without the
// world's own numbers: momentum of the sphere row from its final velocities and the scene's masses,
// the stack's boxes on their column, the bin's boxes inside its walls and above the ground, the pile's
// bodies above the ground; and every hostile scene refused with one error naming its key.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace world_scene_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

Json traceOf(const std::string& file) { return loadScene(file)->run(RunContext{}).trace; }

}  // namespace world_scene_test

using namespace world_scene_test;

TEST_CASE("world scenes: the sphere row keeps the striker's momentum, recomputed from the final velocities") {
    const std::string file = "golden/world/sphere_row.json";
    const Json s = readJsonFile(file), t = traceOf(file);
    Vec3 p0 = Vec3::Zero(), p1 = Vec3::Zero();
    const auto& bodies = s["bodies"];
    REQUIRE(t["final"].size() == bodies.size());  // no ground: the scene's bodies in order
    double scale = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const double r = bodies[i]["sphere"]["radius"].get<double>();
        const double m = 4.0 / 3.0 * std::numbers::pi * r * r * r;  // density 1
        if (bodies[i].contains("velocity")) p0 += m * vec(bodies[i]["velocity"]);
        const Vec3 v = vec(t["final"][i]["linear_velocity"]);
        p1 += m * v;
        scale += m * v.norm();
    }
    CHECK((p1 - p0).norm() <= 1e-13 * scale);
    for (const Json& st : t["steps"]) CHECK((vec(st["momentum"]) - p0).norm() <= 1e-13 * scale);
    // e = 1: the far sphere leaves faster than the row would move as one block.
    double mass = 0.0;
    for (const Json& b : bodies) mass += 4.0 / 3.0 * std::numbers::pi * std::pow(b["sphere"]["radius"].get<double>(), 3);
    CHECK(vec(t["final"].back()["linear_velocity"]).x() > 1.2 * p0.x() / mass);
}

TEST_CASE("world scenes: the stack stands, the bin and the pile hold their bodies above the ground") {
    {
        const Json t = traceOf("golden/world/stack_10.json");
        for (std::size_t i = 1; i < t["final"].size(); ++i) {  // [0] is the ground
            const Vec3 p = vec(t["final"][i]["position"]);
            CHECK(std::hypot(p.x(), p.y()) < 0.05);
            CHECK(std::abs(p.z() - (0.5 + double(i - 1))) < 0.06);  // ten slops at most
        }
    }
    for (const char* file : {"golden/world/bin_100.json", "golden/world/pile_1000.json"}) {
        CAPTURE(file);
        const Json s = readJsonFile(file), t = traceOf(file);
        const double hx = s["bin"]["half_extents"][0].get<double>(), hy = s["bin"]["half_extents"][1].get<double>();
        int inside = 0, dynamic = 0;
        for (const Json& b : t["final"]) {
            if (b["kind"] == "plane") continue;
            const Vec3 p = vec(b["position"]);
            if (std::abs(p.x()) > hx + 1 || std::abs(p.y()) > hy + 1) continue;  // a wall (they stand outside)
            ++dynamic;
            CHECK(p.z() > 0.0);
            inside += std::abs(p.x()) < hx && std::abs(p.y()) < hy;
        }
        CHECK(dynamic >= s["lattice"]["count"].get<int>());
        CHECK(inside == s["lattice"]["count"].get<int>());  // every dropped body landed inside the bin
        const Json& last = t["steps"].back();
        CHECK(last["deepest_penetration"].get<double>() < 0.03);
    }
}

TEST_CASE("world scenes: hostile input is one error naming its key") {
    const std::string base = R"({"demo": "world", "title": "t", )";
    const std::pair<const char*, const char*> bad[] = {
        {R"("bodies": [{"box": {"half_extents": [1, 1, 1]}, "sphere": {"radius": 1}}]})", "bodies[0]"},
        {R"("bodies": [{"sphere": {"radius": -1}}]})", "radius"},
        {R"("bodies": [{"capsule": {"half_height": -1, "radius": 1}}]})", "half_height"},
        {R"("bodies": [{"hull": {"points": [[0,0,0],[1,0,0],[0,1,0]]}}]})", "points"},
        {R"("bodies": [{"hull": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}}]})", "points"},
        {R"("bodies": [{"box": {"half_extents": [1, 1, 1]}, "restitution": 2}]})", "restitution"},
        {R"("bodies": [{"box": {"half_extents": [1, 1, 1]}, "velocity": [1e9, 0, 0]}]})", "velocity"},
        {R"("bodies": [{"box": {"half_extents": [1e3, 1, 1]}}]})", "half_extents"},
        {R"("bodies": [{"box": {"half_extents": [1, 1, 1]}, "colour": 1}]})", "colour"},
        {R"("lattice": {"count": 10, "columns": 3, "spacing": 0.5, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1}})",
         "size"},  // a box corner reaches 0.35 > spacing / 2: bodies would start overlapping
        {R"("lattice": {"count": 3000, "columns": 3, "spacing": 1, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1}})",
         "lattice"},
        {R"("lattice": {"count": 10, "columns": 3, "spacing": 1, "origin": [0,0,1], "shapes": ["cone"], "size": [0.1, 0.2], "seed": 1}})",
         "shapes[0]"},
        {R"("lattice": {"count": 1900, "columns": 20, "spacing": 1, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1},
             "simulation": {"duration": 20}})",
         "6e5 body-steps"},
        {R"("simulation": {"broad_phase": "octree"}})", "broad_phase"},
        {R"("simulation": {"time_step": 0.5}})", "time_step"},
        {R"("simulation": {"substeps": 0}})", "substeps"},
        {R"("simulation": {"duration": 1e6}})", "simulation"},
        {R"("simulation": {"gravity": 1e9}})", "gravity"},
        {R"("frame_every": 1})", "frame_every"},
        {R"("pipeline_step": 100000})", "pipeline_step"},
        {R"("bin": {"half_extents": [1], "height": 1}})", "half_extents"},
        // The hostile review's: count not a number, a lattice past the coordinates, bodies below the
        // slop, gravity moving a body past a quarter of it in a step, sweeps multiplying the work.
        {R"("lattice": {"count": "abc", "columns": 3, "spacing": 1, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1}})",
         "lattice.count"},
        {R"("lattice": {"count": 10, "columns": 3, "spacing": 1e300, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1}})",
         "lattice.spacing"},
        {R"("lattice": {"count": 10, "columns": 3, "spacing": 1, "origin": [0,0,1], "shapes": ["box"], "size": [1e-9, 1e-9], "seed": 1}})",
         "lattice.size"},
        {R"("lattice": {"count": 10, "columns": 3, "spacing": 0.2, "origin": [0,0,1], "shapes": ["hull"], "size": [0.1, 0.1], "seed": 1}})",
         "lattice.size"},  // a recentred hull reaches past its radius
        {R"("bodies": [{"box": {"half_extents": [1e-4, 1e-4, 1e-4]}}]})", "smaller than the slop"},
        {R"("bodies": [{"box": {"half_extents": [0.01, 0.01, 0.01]}}], "simulation": {"time_step": 0.1}})", "time_step"},
        {R"("lattice": {"count": 1000, "columns": 10, "spacing": 1, "origin": [0,0,1], "shapes": ["box"], "size": [0.1, 0.2], "seed": 1},
             "simulation": {"duration": 2, "substeps": 16, "velocity_iterations": 100}})",
         "sweeps a step"}};
    for (const auto& [keys, what] : bad) {
        const std::string input(keys);
        CAPTURE(input);
        const std::string error = test::sceneTextError(base + keys);
        CHECK(error.find(what) != std::string::npos);
        CHECK(error.find('\n') == std::string::npos);
    }
    CHECK(test::sceneTextError(base + R"("bodies": [{"sphere": {"radius": 0.5}, "position": [0, 0, 1]}]})") == "");
}

TEST_CASE("world scenes: bodies heaped on one point stop the run at the pair limit, one error line") {
    std::string bodies;
    for (int i = 0; i < 300; ++i) bodies += std::string(i ? ", " : "") + R"({"sphere": {"radius": 1}, "position": [0, 0, 5]})";
    const std::string text = R"({"demo": "world", "title": "heap", "bodies": [)" + bodies + R"(], "simulation": {"duration": 0.1}})";
    std::string error;
    try {
        loadSceneText(text, "heap.json")->run(RunContext{});
    } catch (const InputError& e) {
        error = e.what();
    }
    CHECK(error.find("heap.json") == 0);
    CHECK(error.find("44850 pairs") != std::string::npos);  // 300 · 299 / 2, over 20 a body
    CHECK(error.find('\n') == std::string::npos);
}
