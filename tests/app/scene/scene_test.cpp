// Scene loading, bad input (one clear line, exit 2, no output) and trace comparison.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/cli/cli.h"
#include "app/catalog/catalog.h"
#include "app/harness/trace_compare.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
    fs::path dir = fs::temp_directory_path() / ("cdlab_scene_test_" + std::to_string(getpid()));
    fs::create_directories(dir);
    fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
}

std::string loadError(const std::string& file) {
    try {
        loadScene(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const char* kGood = R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"queries":[[0.2,0.2,1]]})";

}  // namespace

TEST_SUITE("scene") {
    TEST_CASE("every committed scene loads") {
        for (const auto& f : findSceneFiles(std::string(CDLAB_SOURCE_DIR) + "/golden")) {
            CAPTURE(f);
            CHECK_NOTHROW(loadScene(f));
        }
    }

    TEST_CASE("a good scene loads and runs numerically without a GL context") {
        auto scene = loadScene(writeTemp("good.json", kGood));
        DemoOutput out = scene->run(RunContext{});
        CHECK(out.frames.empty());
        CHECK(out.trace["queries"][0]["region"] == "ABC");
    }

    TEST_CASE("a misspelt key: did you mean") {
        // A required key misspelt: the key that is there is named beside the missing one.
        const std::string box = loadError(writeTemp(
            "box_typo.json",
            R"({"demo":"primitives","test":"sphere_overlap","a":{"sphere":{"center":[1,1,1],"radius":0.5}},)"
            R"("b":{"obb":{"center":[0,0,0],"half_extent":[1,1,1]}}})"));
        CHECK(box.find("$.b.obb: missing required key 'half_extents' ('half_extent' is there: a typo?)") !=
              std::string::npos);
        // An unknown key near a known one names it; one near none does not guess.
        const std::string queries = loadError(writeTemp(
            "queries.json", R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"querys":[[1,1,1]]})"));
        CHECK(queries.find("$: missing required key 'queries' ('querys' is there: a typo?)") != std::string::npos);
        const std::string near = loadError(writeTemp(
            "near.json",
            R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"queries":[[1,1,1]],"captio":"x"})"));
        CHECK(near.find("unknown key 'captio', did you mean 'caption'?") != std::string::npos);
        const std::string far = loadError(writeTemp(
            "far.json", R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"queries":[[1,1,1]],"zzzzzz":1})"));
        CHECK(far.find("unknown key 'zzzzzz' (known:") != std::string::npos);
        CHECK(far.find("did you mean") == std::string::npos);
    }

    TEST_CASE("errors name the file and the JSON path or byte position") {
        std::string missing = loadError("/nonexistent/scene.json");
        CHECK(missing.find("/nonexistent/scene.json: cannot open") == 0);

        std::string syntax = loadError(writeTemp("syntax.json", "{\"demo\": \"voronoi_triangle\",, }"));
        CHECK(syntax.find("syntax.json: byte 29:") != std::string::npos);

        std::string typo = loadError(writeTemp(
            "typo.json",
            R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"queries":[[1,1,1]],"colour":"red"})"));
        CHECK(typo.find("typo.json: $: unknown key 'colour'") != std::string::npos);

        std::string type = loadError(writeTemp(
            "type.json", R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,"x",0]],"queries":[[1,1,1]]})"));
        CHECK(type.find("type.json: $.triangle[2][1]: expected a number, got a string \"x\"") != std::string::npos);

        std::string demo = loadError(writeTemp("demo.json", R"({"demo":"voronoi_trangle"})"));
        CHECK(demo.find("$.demo: unknown value \"voronoi_trangle\"") != std::string::npos);

        std::string both = loadError(writeTemp(
            "both.json",
            R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"tetrahedron":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],"queries":[[1,1,1]]})"));
        CHECK(both.find("exactly one of 'triangle', 'tetrahedron', 'polygon' or 'box'") != std::string::npos);

        std::string layer = loadError(writeTemp(
            "layer.json",
            R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[1,0,0],[0,1,0]],"queries":[[1,1,1]],"layers":["regoins"]})"));
        CHECK(layer.find("$.layers[0]: unknown value \"regoins\"") != std::string::npos);
    }

    TEST_CASE("a bad scene exits with status 2 and writes no output") {
        fs::path out = fs::temp_directory_path() / ("cdlab_scene_test_out_" + std::to_string(getpid()));
        fs::remove_all(out);
        std::string bad =
            writeTemp("bad.json", R"({"demo":"voronoi_triangle","triangle":[[0,0,0]],"queries":[[1,1,1]]})");
        std::string outArg = out.string();
        std::vector<std::string> args = {"demo_voronoi_triangle", bad, "--out", outArg};
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        CHECK(demoMain("voronoi_triangle", int(argv.size()), argv.data()) == 2);
        CHECK_FALSE(fs::exists(out));
    }

    TEST_CASE("trace comparison: tolerance applies to numbers, structure must match") {
        Json golden = Json::parse(R"({"a":[1.0,2.0],"s":"AB","n":{"x":0.5}})");
        CHECK(compareTraces(golden, golden, 0, 0).passed());
        Json near = Json::parse(R"({"a":[1.0,2.0000000001],"s":"AB","n":{"x":0.5}})");
        CHECK(compareTraces(near, golden, 1e-9, 0).passed());
        CHECK_FALSE(compareTraces(near, golden, 1e-12, 0).passed());
        Json region = Json::parse(R"({"a":[1.0,2.0],"s":"BC","n":{"x":0.5}})");
        TraceComparison c = compareTraces(region, golden, 1, 1);
        CHECK_FALSE(c.passed());
        CHECK(c.mismatches.front().path == "$.s");
        Json shorter = Json::parse(R"({"a":[1.0],"s":"AB","n":{"x":0.5}})");
        CHECK_FALSE(compareTraces(shorter, golden, 1, 1).passed());
    }

}  // TEST_SUITE
