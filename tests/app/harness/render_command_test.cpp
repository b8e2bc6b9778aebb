// `cdlab render`: a scene file from anywhere renders into out/render/<file stem>/ (or --out), one
// starter per demo from `--template` renders as it is, --frame writes the chosen frames only, and
// no output folder can be inside golden/.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/catalog/catalog.h"
#include "app/harness/scene_runner.h"
#include "render/image.h"

namespace fs = std::filesystem;
using namespace cdlab::demos;

namespace {

struct TempFolder {
    fs::path root = fs::temp_directory_path() / ("cdlab_render_test_" + std::to_string(getpid()));
    TempFolder() {
        fs::remove_all(root);
        fs::create_directories(root);
    }
    ~TempFolder() { fs::remove_all(root); }
};

RunnerOptions renderOptions(const fs::path& out, bool outIsFolder) {
    RunnerOptions o;
    o.outDir = out.string();
    o.perFileOutput = true;
    o.outIsFolder = outIsFolder;
    return o;
}

std::string write(const fs::path& file, const std::string& text) {
    std::ofstream(file) << text;
    return file.string();
}

}  // namespace

TEST_CASE("render: every demo's template renders as it is into <out>/<file stem>/") {
    TempFolder t;
    std::vector<std::string> files;
    for (const Demo* d : allDemos()) {
        const std::string text = sceneTemplate(d->name(), RunnerOptions{});
        CHECK(text.find("\"golden\"") == std::string::npos);
        files.push_back(write(t.root / ("my_" + d->name() + ".json"), text));
    }
    REQUIRE(renderSceneFiles(files, renderOptions(t.root / "out", false)) == 0);
    for (const Demo* d : allDemos()) {
        const fs::path dir = t.root / "out" / ("my_" + d->name());
        CHECK_MESSAGE(fs::exists(dir / "manifest.json"), dir);
        CHECK_MESSAGE(fs::exists(dir / "trace.json"), dir);
        int pngs = 0;
        for (const auto& e : fs::directory_iterator(dir)) pngs += e.path().extension() == ".png";
        CHECK_MESSAGE(pngs >= 1, dir);
    }
    CHECK_THROWS_AS(sceneTemplate("no_such_demo", RunnerOptions{}), InputError);
}

TEST_CASE("render: --frame writes the chosen frames only, --out with one file is the folder itself") {
    TempFolder t;
    const std::string file = write(t.root / "pair.json", sceneTemplate("gjk", RunnerOptions{}));
    RunnerOptions o = renderOptions(t.root / "figure", true);
    o.frames = {"step_0*", "result"};
    REQUIRE(renderSceneFiles({file}, o) == 0);
    CHECK(fs::exists(t.root / "figure" / "result.png"));
    CHECK(fs::exists(t.root / "figure" / "step_01.png"));
    CHECK_FALSE(fs::exists(t.root / "figure" / "contact_sheet.png"));
    CHECK_FALSE(fs::exists(t.root / "figure" / "animation.gif"));
    // A frame that does not exist is an error (the scene fails, nothing half-written).
    RunnerOptions none = renderOptions(t.root / "none", true);
    none.frames = {"no_such_frame"};
    CHECK(renderSceneFiles({file}, none) == 2);
    CHECK_FALSE(fs::exists(t.root / "none" / "manifest.json"));
}

TEST_CASE("render: never writes inside golden/") {
    TempFolder t;
    const std::string file = write(t.root / "pair.json", sceneTemplate("gjk", RunnerOptions{}));
    const fs::path golden = fs::path(CDLAB_SOURCE_DIR) / "golden" / "gjk";
    const auto before = fs::last_write_time(golden);
    CHECK(renderSceneFiles({file}, renderOptions(golden, true)) == 2);
    CHECK(renderSceneFiles({file}, renderOptions(fs::path(CDLAB_SOURCE_DIR) / "golden", false)) == 2);
    CHECK_FALSE(fs::exists(golden / "pair"));
    CHECK(fs::last_write_time(golden) == before);
}

TEST_CASE("render: --scale 2 is the same figure at twice the pixels (text, lines and layout scaled)") {
    TempFolder t;
    const std::string file = write(t.root / "pair.json", sceneTemplate("gjk", RunnerOptions{}));
    RunnerOptions one = renderOptions(t.root / "one", true), two = renderOptions(t.root / "two", true);
    two.scale = 2;
    REQUIRE(renderSceneFiles({file}, one) == 0);
    REQUIRE(renderSceneFiles({file}, two) == 0);
    for (const char* frame : {"step_01.png", "result.png", "contact_sheet.png"}) {
        const cdlab::render::Image a = cdlab::render::readPng((t.root / "one" / frame).string());
        const cdlab::render::Image b = cdlab::render::readPng((t.root / "two" / frame).string());
        CHECK_MESSAGE(b.width == 2 * a.width, frame);
        CHECK_MESSAGE(b.height == 2 * a.height, frame);
    }
    // Every label's box in the manifest is twice the scale-1 box (the same layout, not a new one).
    const Json m1 = Json::parse(std::ifstream(t.root / "one" / "manifest.json"));
    const Json m2 = Json::parse(std::ifstream(t.root / "two" / "manifest.json"));
    REQUIRE(m1["frames"].size() == m2["frames"].size());
    int labels = 0;
    for (std::size_t f = 0; f < m1["frames"].size(); ++f) {
        const Json& l1 = m1["frames"][f]["layout"]["labels"];
        const Json& l2 = m2["frames"][f]["layout"]["labels"];
        REQUIRE(l1.size() == l2.size());
        for (std::size_t i = 0; i < l1.size(); ++i, ++labels)
            for (int k = 0; k < 4; ++k)
                CHECK(std::abs(l2[i]["box"][k].get<double>() - 2 * l1[i]["box"][k].get<double>()) <= 0.5);
    }
    CHECK(labels > 20);
}
