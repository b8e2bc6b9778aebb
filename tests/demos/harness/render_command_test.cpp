// `cdlab render`: a scene file from anywhere renders into out/render/<file stem>/ (or --out), one
// starter per demo from `--template` renders as it is, --frame writes the chosen frames only, and
// no output folder can be inside golden/.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "demos/catalog/catalog.h"
#include "demos/harness/scene_runner.h"

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

TEST_CASE("render: --frame writes the chosen frames only; --out with one file is the folder itself") {
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
