// The architecture's arrows, checked on every #include of the tree (docs/architecture.md):
//   core/ includes only core/ (and the standard library and Eigen), and a core folder only folders
//   at or below its layer; render/ includes only render/; production code never includes tests/;
//   a demo's folder includes only its own folder and the shared ones (scene, draw, measure,
//   oracles), and only app/catalog (the list of every demo) and the executables' mains include
//   demo folders.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Core's folders from the bottom up: a folder may include its own and every folder before it.
const std::vector<std::string> kCoreLayers = {"base",    "geometry", "closest", "overlap", "gjk_epa", "cast", "feature_walk",
                                              "contact", "bounding", "bvh",     "broadphase", "spatial", "dynamics", "query", "world"};
// Folders a demo may include besides its own.
const std::vector<std::string> kSharedForDemos = {"demos/draw", "app/scene", "app/measure"};

struct Include {
    std::string file;  // relative to the source root
    int line;
    std::string target;  // the quoted or angled path
    bool angled;
};

std::vector<std::string> split(const std::string& path) {
    std::vector<std::string> parts;
    std::stringstream ss(path);
    for (std::string p; std::getline(ss, p, '/');) parts.push_back(p);
    return parts;
}

bool contains(const std::vector<std::string>& v, const std::string& x) {
    return std::find(v.begin(), v.end(), x) != v.end();
}

std::vector<Include> includesUnder(const fs::path& root, const std::string& top) {
    std::vector<Include> out;
    const std::regex rx(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
        std::ifstream in(e.path());
        int n = 0;
        for (std::string line; std::getline(in, line);) {
            ++n;
            std::smatch m;
            if (std::regex_search(line, m, rx))
                out.push_back({fs::relative(e.path(), root).string(), n, m[2].str(), m[1].str() == "<"});
        }
    }
    return out;
}

// What is wrong with one include ("" when it follows the arrows).
std::string violation(const Include& inc) {
    const std::vector<std::string> from = split(inc.file), to = split(inc.target);
    if (inc.angled) {  // third-party headers: core and render have their own short lists
        if (from[0] == "core" && to[0] != "Eigen" && inc.target.find('/') != std::string::npos)
            return "core includes a third-party header other than Eigen";
        return "";
    }
    if (to[0] == "tests" && from[0] != "tests") return "production code includes tests/";
    if (from[0] == "core") {
        if (to[0] != "core") return "core includes " + to[0] + "/";
        if (from.size() == 2 && from[1] == "cdlab.h" && to.size() >= 3) return "";  // the umbrella header
        if (from.size() < 3 || to.size() < 3) return "a core file outside core's folders";
        const auto layer = [](const std::string& f) {
            return std::find(kCoreLayers.begin(), kCoreLayers.end(), f) - kCoreLayers.begin();
        };
        if (layer(from[1]) == std::ptrdiff_t(kCoreLayers.size()) || layer(to[1]) == std::ptrdiff_t(kCoreLayers.size()))
            return "a core folder that is not in the layer list";
        if (layer(to[1]) > layer(from[1])) return "core/" + from[1] + " reaches up into core/" + to[1];
        return "";
    }
    if (from[0] == "render") return to[0] == "render" ? "" : "render includes " + to[0] + "/";
    if (from[0] == "verification")
        return to[0] == "core" || to[0] == "verification" ? "" : "verification includes " + to[0] + "/";
    const auto isDemo = [](const std::vector<std::string>& p) {
        return p.size() >= 3 && p[0] == "demos" && p[1] != "draw";
    };
    const std::string dst = to.size() >= 3 ? to[0] + "/" + to[1] : to[0];
    if (isDemo(from)) {
        if (isDemo(to) && to[1] != from[1]) return "demos/" + from[1] + " reaches into the demo folder " + dst;
        if (!isDemo(to) && to[0] != "core" && to[0] != "render" && to[0] != "verification" &&
            !contains(kSharedForDemos, dst))
            return "the demo folder demos/" + from[1] + " includes " + dst +
                   " (a demo uses only core, render, demos/draw, app/scene, app/measure, verification)";
    }
    if (from[0] == "demos" && from.size() >= 3 && from[1] == "draw" && isDemo(to))
        return "demos/draw reaches into the demo folder " + dst;
    if (from[0] == "app" && isDemo(to) && !(from.size() >= 3 && from[1] == "catalog"))
        return inc.file + " reaches into the demo folder " + dst + " (only app/catalog lists the demos)";
    return "";
}

}  // namespace

TEST_CASE("every #include follows the architecture's arrows") {
    const fs::path root = CDLAB_SOURCE_DIR;
    std::vector<std::string> problems;
    int checked = 0;
    for (const char* top : {"core", "render", "verification", "demos", "app"})
        for (const Include& inc : includesUnder(root, top)) {
            ++checked;
            if (std::string v = violation(inc); !v.empty())
                problems.push_back(inc.file + ":" + std::to_string(inc.line) + ": #include " + inc.target + ": " + v);
        }
    for (const std::string& p : problems) MESSAGE(p);
    CHECK(checked > 500);
    CHECK(problems.empty());
}

TEST_CASE("the arrow check catches what it should") {
    CHECK(violation({"core/closest/feature_distance.h", 1, "core/contact/contact_manifold.h", false}) != "");
    CHECK(violation({"core/contact/contact_sat.h", 1, "core/closest/closest_point.h", false}) == "");
    CHECK(violation({"core/base/types.h", 1, "render/canvas.h", false}) != "");
    CHECK(violation({"core/base/types.h", 1, "nlohmann/json.hpp", true}) != "");
    CHECK(violation({"core/base/types.h", 1, "Eigen/Dense", true}) == "");
    CHECK(violation({"app/stress/stress.cpp", 1, "tests/core/closest_test_oracle.h", false}) != "");
    CHECK(violation({"demos/lin_canny/lin_canny_demo.cpp", 1, "demos/vclip/vclip_demo.h", false}) != "");
    CHECK(violation({"demos/lin_canny/lin_canny_demo.cpp", 1, "demos/draw/plot.h", false}) == "");
    CHECK(violation({"demos/lin_canny/lin_canny_demo.cpp", 1, "app/scene/scene.h", false}) == "");
    CHECK(violation({"demos/gjk/gjk_demo.cpp", 1, "verification/closest_oracle.h", false}) == "");
    CHECK(violation({"app/catalog/catalog.cpp", 1, "demos/vclip/vclip_demo.h", false}) == "");
    CHECK(violation({"app/query/query.cpp", 1, "demos/vclip/vclip_demo.h", false}) != "");
    CHECK(violation({"demos/gjk/gjk_demo.cpp", 1, "app/query/query.h", false}) != "");
    CHECK(violation({"demos/draw/plot.cpp", 1, "demos/gjk/gjk_demo.h", false}) != "");
    CHECK(violation({"verification/closest_oracle.h", 1, "app/scene/scene.h", false}) != "");
    CHECK(violation({"render/canvas.cpp", 1, "core/base/types.h", false}) != "");
}
