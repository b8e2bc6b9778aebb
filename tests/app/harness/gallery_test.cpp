// The figure gallery opens in a real headless browser (Debian chromium) offline, and its images
// load: the screenshot shows the figure's region colours, not broken-image icons.
#include <doctest/doctest.h>

#include <unistd.h>
#include <cstdlib>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "app/harness/scene_runner.h"
#include "render/image.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {

const char* const kChromium = "/usr/bin/chromium";

// Headless chromium on a local page, `width` px wide, doing `what` (--screenshot=FILE, --dump-dom).
// Flags: no sandbox (root), no GPU, and no background networking (the machine is offline).
std::string chromiumCommand(const fs::path& root, int width, const std::string& what, const fs::path& html) {
    return std::string("timeout 120 ") + kChromium +
           " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
           " --disable-background-networking --disable-component-update --disable-sync --user-data-dir=" +
           (root / "profile").string() + " --window-size=" + std::to_string(width) + ",700 " + what + " file://" +
           html.string();
}

}  // namespace

TEST_CASE("gallery: the index and a scene page render in headless chromium with their images") {
    REQUIRE_MESSAGE(fs::exists(kChromium), "Debian chromium is needed (./cdlab test installs it)");

    fs::path root = fs::temp_directory_path() / ("cdlab_gallery_test_" + std::to_string(getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "golden" / "voronoi_triangle");
    std::ofstream(root / "golden" / "voronoi_triangle" / "gallery.json") << R"({
      "demo": "voronoi_triangle", "title": "gallery check", "caption": "regions in the plane",
      "image": {"width": 320, "height": 320},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[-0.5, -0.5, 0.2]], "views": ["plane"]})";
    std::ofstream(root / "golden" / "voronoi_triangle" / "gallery2.json") << R"({
      "demo": "voronoi_triangle", "title": "gallery check 2", "image": {"width": 320, "height": 320},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[1, 1, 0.2]], "views": ["plane"]})";
    RunnerOptions o;
    o.goldenDir = (root / "golden").string();
    o.outDir = (root / "out").string();
    REQUIRE(runFigures(o) == 0);
    fs::path index = root / "out" / "index.html";
    REQUIRE(fs::exists(index));

    // The index links each scene to its page, and the page shows every frame.
    const fs::path page = root / "out" / "voronoi_triangle" / "gallery.html";
    REQUIRE(fs::exists(page));
    std::ifstream indexIn(index), pageIn(page);
    const std::string indexText((std::istreambuf_iterator<char>(indexIn)), std::istreambuf_iterator<char>());
    const std::string pageText((std::istreambuf_iterator<char>(pageIn)), std::istreambuf_iterator<char>());
    CHECK(indexText.find("href=\"voronoi_triangle/gallery.html\"") != std::string::npos);
    CHECK(pageText.find("src=\"gallery/plane.png\"") != std::string::npos);
    CHECK(pageText.find("href=\"gallery/trace.json\"") != std::string::npos);
    CHECK(pageText.find("<script") == std::string::npos);
    // The navigation links are apart (whitespace between them), so a narrow window wraps them.
    CHECK(pageText.find("all figures</a>\n<a href=\"../voronoi_triangle/gallery2.html\">") != std::string::npos);
    CHECK(pageText.find("</a><a") == std::string::npos);
    CHECK(indexText.find("</a><a") == std::string::npos);

    for (const fs::path& html : {index, page}) {
        fs::path shot = root / "shot.png";
        fs::remove(shot);
        const std::string cmd = chromiumCommand(root, 900, "--screenshot=" + shot.string(), html) + " >" +
                                (root / "chromium.log").string() + " 2>&1";
        REQUIRE_MESSAGE(std::system(cmd.c_str()) == 0, "chromium failed: see " << (root / "chromium.log").string());
        REQUIRE(fs::exists(shot));
        cdlab::render::Image img = cdlab::render::readPng(shot.string());
        // Count pixels of the region palette (saturated colours): a broken image shows none.
        long coloured = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const auto* p = img.pixel(x, y);
                int mx = std::max({p[0], p[1], p[2]}), mn = std::min({p[0], p[1], p[2]});
                if (mx - mn > 60) ++coloured;
            }
        CHECK_MESSAGE(coloured > 5000, html);
    }
    fs::remove_all(root);
}

TEST_CASE("gallery: the index's demo line of 15 demos wraps in a 1000-px and a 1400-px window") {
    // Measured in headless chromium: a copy of the index beside it, with a script that puts the
    // page's scroll width and the window's client width in its title (the gallery itself has no script),
    // read back with --dump-dom. Wider than the window = a horizontal scrollbar (issue 43 §3).
    REQUIRE_MESSAGE(fs::exists(kChromium), "Debian chromium is needed (./cdlab test installs it)");
    fs::path root = fs::temp_directory_path() / ("cdlab_gallery_width_test_" + std::to_string(getpid()));
    fs::remove_all(root);
    // One scene rendered, its folder copied under the 14 other demos' names: the index is built
    // from every scene folder in out/, so it lists 15 demos as the real gallery does.
    fs::create_directories(root / "golden" / "voronoi_triangle");
    std::ofstream(root / "golden" / "voronoi_triangle" / "s.json") << R"({"demo": "voronoi_triangle", "title": "t",
      "image": {"width": 160, "height": 160}, "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]],
      "queries": [[1, 1, 0.2]], "views": ["plane"]})";
    RunnerOptions o;
    o.goldenDir = (root / "golden").string();
    o.outDir = (root / "out").string();
    REQUIRE(runFigures(o) == 0);
    for (const char* demo : {"accuracy", "bounding_volumes", "bvh", "drop", "epa", "gjk", "lin_canny", "mtd_backtracking",
                             "nonconvex", "polyhedron_plane", "primitives", "space_partition", "sweep_and_prune", "vclip"}) {
        fs::create_directories(root / "out" / demo);
        fs::copy(root / "out" / "voronoi_triangle" / "s", root / "out" / demo / "s", fs::copy_options::recursive);
    }
    REQUIRE(runFigures(o) == 0);
    std::ifstream indexIn(root / "out" / "index.html");
    const std::string indexText((std::istreambuf_iterator<char>(indexIn)), std::istreambuf_iterator<char>());
    REQUIRE(indexText.find("href=\"#sweep_and_prune\"") != std::string::npos);
    std::ofstream(root / "out" / "probe.html")
        << indexText << "<script>const e = document.documentElement; document.title = (e.scrollWidth <= e.clientWidth ? "
           "'fits ' : 'overflows ') + e.scrollWidth + ' in ' + e.clientWidth</script>\n";
    for (int width : {1000, 1400}) {
        const fs::path dom = root / "dom.html";
        const std::string cmd = chromiumCommand(root, width, "--dump-dom", root / "out" / "probe.html") + " >" +
                                dom.string() + " 2>" + (root / "chromium.log").string();
        REQUIRE_MESSAGE(std::system(cmd.c_str()) == 0, "chromium failed: see " << (root / "chromium.log").string());
        std::ifstream domIn(dom);
        const std::string text((std::istreambuf_iterator<char>(domIn)), std::istreambuf_iterator<char>());
        const std::string want = "<title>fits ";  // the page no wider than the window's client area
        const std::size_t title = text.find("<title>");
        CHECK_MESSAGE(text.find(want) != std::string::npos, "window " << width << ": " << text.substr(title, 60));
    }
    fs::remove_all(root);
}
