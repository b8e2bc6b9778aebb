// The golden harness itself: it passes on its own output, and it fails — with a report — when a
// golden image is perturbed, is not a PNG, or is missing, and when a trace number moves.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <sstream>

#include "app/harness/scene_runner.h"
#include "app/scene/json_reader.h"
#include "render/image.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {

fs::path makeGoldenDir() {
    fs::path root = fs::temp_directory_path() / ("cdlab_golden_runner_test_" + std::to_string(getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "voronoi_triangle");
    std::ofstream(root / "voronoi_triangle" / "small.json") << R"({
      "demo": "voronoi_triangle", "title": "small", "image": {"width": 256, "height": 256},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[-0.5, -0.5, 0.2], [1.0, 0.5, 0.5]],
      "views": ["plane"],
      "layers": ["regions", "boundaries", "closest", "queries"]})";
    return root;
}

RunnerOptions options(const fs::path& root, const std::string& update = "") {
    RunnerOptions o;
    o.goldenDir = root.string();
    o.reportDir = (root / "report").string();
    o.update = update;
    return o;
}

}  // namespace

TEST_CASE("golden runner: creates, passes, and rejects perturbed or broken goldens") {
    fs::path root = makeGoldenDir();
    fs::path png = root / "voronoi_triangle" / "small" / "plane.png";
    fs::path trace = root / "voronoi_triangle" / "small" / "trace.json";

    // Missing goldens fail (CI never creates them silently) ...
    CHECK(runGolden(options(root)) == 1);
    CHECK_FALSE(fs::exists(png));
    // ... until asked to update; then the same scene passes against its own output.
    CHECK(runGolden(options(root, "failing")) == 0);
    REQUIRE(fs::exists(png));
    CHECK(runGolden(options(root)) == 0);

    // A perturbed golden fails and produces actual / expected / diff PNGs and the HTML report.
    cdlab::render::Image img = cdlab::render::readPng(png.string());
    for (int y = 100; y < 110; ++y)
        for (int x = 100; x < 110; ++x) img.pixel(x, y)[0] ^= 0x80;
    cdlab::render::writePngAtomic(png.string(), img);
    CHECK(runGolden(options(root)) == 1);
    CHECK(fs::exists(root / "report" / "index.html"));
    CHECK(fs::exists(root / "report" / "voronoi_triangle" / "small" / "plane.diff.png"));
    CHECK(fs::exists(root / "report" / "voronoi_triangle" / "small" / "plane.expected.png"));

    // A golden that is not a PNG fails cleanly.
    std::ofstream(png, std::ios::trunc) << "not a png";
    CHECK(runGolden(options(root)) == 1);
    CHECK(runGolden(options(root, "failing")) == 0);  // repaired by an explicit update

    // A trace number moved beyond the tolerance fails even though the pixels match.
    Json t = readJsonFile(trace.string());
    t["queries"][0]["distance"] = t["queries"][0]["distance"].get<double>() + 1e-6;
    std::ofstream(trace, std::ios::trunc) << t.dump(1);
    CHECK(runGolden(options(root)) == 1);
    // ... and the HTML report says so (it listed image failures only): the entry, with the path.
    std::ifstream html(root / "report" / "index.html");
    const std::string report((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
    CHECK(report.find("voronoi_triangle/small/trace.json") != std::string::npos);
    CHECK(report.find("$.queries[0].distance") != std::string::npos);
    CHECK(report.find("1 failure (0 of images, 1 of traces or legibility)") != std::string::npos);
    fs::remove_all(root);
}

TEST_CASE("golden runner: an illegible frame fails with its worst offender named") {
    fs::path root = makeGoldenDir();
    // A figure 3000 px tall whose 18-28 px labels are under 1.5 % of its height: too small for a slide.
    std::ofstream(root / "voronoi_triangle" / "small.json") << R"({
      "demo": "voronoi_triangle", "title": "small", "image": {"width": 256, "height": 3000},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[-0.5, -0.5, 0.2], [1.0, 0.5, 0.5]],
      "views": ["plane"]})";
    CHECK(runGolden(options(root, "failing")) == 1);  // goldens written, the legibility check still fails
    std::ostringstream captured;
    std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
    const int status = runGolden(options(root));
    std::cout.rdbuf(old);
    CHECK(status == 1);
    CHECK(captured.str().find("FAIL voronoi_triangle/small/plane: not slide-legible") != std::string::npos);
    CHECK(captured.str().find("legibility: ") != std::string::npos);
    // Without the labels the same frame passes.
    std::ofstream(root / "voronoi_triangle" / "small.json") << R"({
      "demo": "voronoi_triangle", "title": "small", "image": {"width": 256, "height": 256},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[-0.5, -0.5, 0.2], [1.0, 0.5, 0.5]],
      "views": ["plane"], "layers": ["regions", "boundaries", "closest", "queries"]})";
    CHECK(runGolden(options(root, "failing")) == 0);
    CHECK(runGolden(options(root)) == 0);
    fs::remove_all(root);
}
