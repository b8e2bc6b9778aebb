// Hostile input, round two: the scene items. Each test opens with its reproducer. Every quantity a
// scene controls that multiplies work or memory has a limit checked when the scene is prepared
// (before anything is computed or written), with the file and JSON path in the error; a NaN that
// still reaches a trace or a frame's text is an error naming the scene and the quantity.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/catalog/catalog.h"
#include "app/harness/scene_runner.h"
#include "app/scene/scene.h"
#include "app/scene/scene_limits.h"
#include "tests/scene_error.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {

// The error of preparing a scene file or text ("" when it prepares).
std::string prepareError(const std::string& file) { return cdlab::test::sceneFileError(file); }
std::string prepareTextError(const std::string& text, const std::string& source = "scene.json") {
    return cdlab::test::sceneTextError(text, source);
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const std::string kSeeds = CDLAB_SOURCE_DIR "/tests/fuzz/seeds/scenes/";
const std::string kGjk =
    R"({"demo":"gjk","dimension":3,"shapes":[{"box":{"half_extents":[1,1,1]}},{"box":{"half_extents":[0.6,0.6,0.6],"position":[2.4,0.5,0.3]}}]})";

// A scene whose run produces what the test says, to drive PreparedScene::run's check.
class FixedOutputScene final : public PreparedScene {
public:
    FixedOutputScene(SceneCommon common, DemoOutput out) : PreparedScene(std::move(common)), out_(std::move(out)) {}

protected:
    DemoOutput execute(const RunContext&) const override { return out_; }

private:
    DemoOutput out_;
};

}  // namespace

TEST_SUITE("hostile scene") {
    TEST_CASE("a scene file name that cannot name an output folder is refused where it would name one") {
        // Reproducer: a scene file named `...json` has the name "..", whose output folder
        // <out>/<demo>/.. is <out> itself (and golden/<demo>/.. is golden/). The scene reads (`render
        // "é scene.json" --out DIR` names its folder itself); sceneOutputDir refuses the name.
        for (const std::string bad : {"...json", "..json", ".hidden.json", "a b.json", "x\"y.json"}) {
            CHECK_MESSAGE(prepareTextError(kGjk, "/tmp/" + bad) == "", bad);
            const std::string name = std::filesystem::path(bad).stem().string();
            CHECK_THROWS_WITH_AS(sceneOutputDir("/tmp/out", "gjk", name), doctest::Contains("cannot name an output folder"),
                                 InputError);
        }
        for (const std::string good : {"box_box.json", "box-box.2.json", "A9.json"})
            CHECK(prepareTextError(kGjk, good) == "");
        CHECK(isPlainName("box_box"));
        CHECK_FALSE(isPlainName(".."));
        CHECK_FALSE(isPlainName(""));
        CHECK_FALSE(isPlainName("a/b"));
    }

    TEST_CASE("the reproducers of unbounded work are refused when prepared, naming file, JSON path and limit") {
        // Each file in tests/fuzz/seeds/scenes is one reproducer of the hostile-input list (and seeds
        // the fuzzers): e.g. "grid_cell": 1e-9 drew one line per cell (OOM at 23.8 GB); two
        // 2000-vertex polytopes built the hull of 4·10^6 differences (18 s, 1.25 GB); an 8192² image
        // took 146 s and 7.7 GB; at scale 4 an OpenGL error without file or JSON path.
        const std::pair<const char*, const char*> cases[] = {
            {"space_partition_grid_cell_1e-9.json", "$.grid_cell: the number of grid cells"},
            {"gjk_two_2000_vertex_polytopes.json",
             "$.shapes[0].polytope.vertices: the number of vertices is 2000, above the limit of 1000"},
            {"gjk_image_8192.json", "$.image.width: expected an integer in [16, 4096]"},
            {"gjk_image_4096_scale_4.json", "$.image: width x height x scale² (supersampled pixels)"},
            {"bvh_torus_major_radius_1e308.json", "$.meshes[0].torus.major_radius: size 1.1e+308 is outside"},
            {"drop_density_1e300.json", "$.density: density is 1e+300, above the limit"},
            {"drop_gravity_1e300.json", "$.gravity: gravity is 1e+300, above the limit"},
            {"drop_velocity_1e300.json", "$.velocity[0]: coordinate 1e+300 is beyond the limit"},
            {"vclip_orbit_degrees_1e308.json", "$.motion.orbit_degrees: expected degrees per call in [-360, 360]"},
            {"vclip_bodies_at_1e300.json", "$.bodies[0].icosahedron.position[0]: coordinate 1e+300"},
            {"voronoi_triangle_at_1e300.json", "$.triangle[1][0]: coordinate 4e+300"},
            {"bounding_volumes_flat_cloud.json", "$.shape.cloud.stretch[2]: size 1e-300 is outside"},
        };
        for (const auto& [file, expected] : cases) {
            const std::string e = prepareError(kSeeds + file);
            CHECK_MESSAGE(contains(e, kSeeds + file + ": " + expected), file << ": " << e);
        }
    }

    TEST_CASE("limits are inclusive and the largest allowed image prepares") {
        CHECK(
            prepareTextError(
                R"({"demo":"gjk","image":{"width":4096,"height":4096},"shapes":[{"sphere":{"radius":1}},{"sphere":{"radius":1,"position":[3,0,0]}}]})") ==
            "");
        CHECK(contains(
            prepareTextError(
                R"({"demo":"gjk","image":{"width":4096,"height":4096,"scale":2},"shapes":[{"sphere":{"radius":1}},{"sphere":{"radius":1,"position":[3,0,0]}}]})"),
            "scene.json: $.image: width x height x scale²"));
        CHECK(
            prepareTextError(
                R"({"demo":"gjk","shapes":[{"sphere":{"radius":1e5}},{"sphere":{"radius":1e-5,"position":[-1e5,0,0]}}]})") ==
            "");
        CHECK(contains(
            prepareTextError(
                R"({"demo":"gjk","shapes":[{"sphere":{"radius":1}},{"sphere":{"radius":1,"position":[100001,0,0]}}]})"),
            "$.shapes[1].sphere.position[0]: coordinate 100001 is beyond the limit of ±100000"));
    }

    TEST_CASE("--scale is checked against the same pixel budget, naming the scene file") {
        // Reproducer: `--scale 4` on a 4096² scene asked GL for a 16384² framebuffer: an OpenGL error
        // that named neither the file nor the key.
        auto scene = loadSceneText(
            R"({"demo":"gjk","image":{"width":2048,"height":2048},"shapes":[{"sphere":{"radius":1}},{"sphere":{"radius":1,"position":[3,0,0]}}]})",
            "big.json");
        CHECK_NOTHROW(checkImageBudget(scene->common(), 0));
        CHECK_NOTHROW(checkImageBudget(scene->common(), 2));
        CHECK_THROWS_WITH_AS(checkImageBudget(scene->common(), 3),
                             doctest::Contains("big.json: $.image: 2048 x 2048 at scale 3"), InputError);
    }

    TEST_CASE("a NaN in a trace, a caption or a drawn text is an error naming the scene and the quantity") {
        // A NaN that reaches a trace, a caption or a drawn text (drop with gravity 1e300 would draw
        // "E = -nan J" and write null into trace.json; likewise vclip or a voronoi triangle at 1e300)
        // fails the scene. The limits above refuse those scenes first; this check is the last line of
        // defence.
        SceneCommon common;
        common.file = "golden/drop/box.json";
        DemoOutput nanTrace;
        nanTrace.trace = {{"steps", Json::array({Json{{"energy", 1.0}}, Json{{"energy", std::nan("")}}})}};
        CHECK_THROWS_WITH_AS(requireFiniteOutput(common, nanTrace, {}),
                             doctest::Contains("golden/drop/box.json: trace $.steps[1].energy is NaN"), InputError);
        DemoOutput infTrace;
        infTrace.trace = {{"max_energy", INFINITY}};
        CHECK_THROWS_WITH_AS(requireFiniteOutput(common, infTrace, {}),
                             doctest::Contains("trace $.max_energy is infinite"), InputError);
        DemoOutput caption;
        caption.frames.push_back({"step_03", "E = -nan J, max energy rise 0", {}});
        CHECK_THROWS_WITH_AS(requireFiniteOutput(common, caption, {}), doctest::Contains("frame 'step_03'"),
                             InputError);
        CHECK_THROWS_WITH_AS(requireFiniteOutput(common, DemoOutput{}, {"p = (1, inf, 0)"}),
                             doctest::Contains("\"p = (1, inf, 0)\""), InputError);
        CHECK_THROWS_AS(requireFiniteOutput(common, DemoOutput{}, {"depth NaN"}), InputError);
        // Words that contain the letters are not numbers.
        CHECK_NOTHROW(
            requireFiniteOutput(common, DemoOutput{}, {"infinite plane", "Finance", "nano", "inflate", "info"}));
        // Through PreparedScene::run: the demo's output is checked on the way out.
        DemoOutput bad;
        bad.trace = {{"distance", std::nan("")}};
        const FixedOutputScene scene(common, bad);
        CHECK_THROWS_WITH_AS(scene.run(RunContext{}), doctest::Contains("trace $.distance is NaN"), InputError);
        const FixedOutputScene fine(common, DemoOutput{});
        CHECK_NOTHROW(scene.common());
        CHECK_NOTHROW(fine.run(RunContext{}));
    }

    TEST_CASE("bsp_shape polygons: clockwise and self-crossing ones are refused, naming the path") {
        // Reproducer: echo '{"demo":"space_partition","figure":"bsp_shape","polygon":[[0,0],[0,2],[2,2],
        // [2,0]],"queries":[[1,1],[50,50]]}' > cw.json && cdlab render --out /tmp/o cw.json: (1, 1)
        // inside the square was classified outside and (50, 50) inside; the bow-tie
        // [[0,0],[2,2],[2,0],[0,2]] was accepted.
        const auto bsp = [](const std::string& polygon) {
            return prepareTextError(R"({"demo":"space_partition","figure":"bsp_shape","polygon":)" + polygon + "}");
        };
        CHECK(bsp("[[0,0],[2,0],[2,2],[0,2]]") == "");
        CHECK(bsp("[[0,0],[2,0],[1,0.5],[2,2],[0,2]]") == "");  // non-convex, counter-clockwise
        CHECK(bsp("[[0,0],[1,0],[2,0],[2,2],[0,2]]") == "");    // a straight angle at (1, 0)
        CHECK(contains(bsp("[[0,0],[0,2],[2,2],[2,0]]"),
                       "scene.json: $.polygon: the polygon is clockwise (signed area -4); give its vertices "
                       "counter-clockwise"));
        CHECK(contains(bsp("[[0,0],[2,2],[2,0],[0,2]]"),
                       "scene.json: $.polygon: the edge from vertex 0 to 1 and the edge from vertex 2 to 3 meet: the "
                       "polygon crosses itself"));
        // A vertex on another edge, an edge folding back along its neighbour, a repeated vertex.
        CHECK(contains(bsp("[[0,0],[4,0],[4,4],[2,0],[0,4]]"),
                       "the edge from vertex 0 to 1 and the edge from vertex 2 to 3 meet"));
        CHECK(contains(bsp("[[0,0],[2,0],[1,0],[1,1]]"), "folds back on itself"));
        CHECK(contains(bsp("[[0,0],[2,0],[2,0],[0,2]]"), "$.polygon[2]: repeats the vertex before it"));
        CHECK(contains(bsp("[[0,0],[1,1],[2,2]]"), "folds back on itself"));  // no area
        // 256 vertices (the limit) on a circle: the O(n²) test is quick, the polygon accepted.
        std::string circle = "[";
        for (int i = 0; i < 256; ++i)
            circle += (i ? "," : "") + ("[" + std::to_string(100 * std::cos(i * M_PI / 128)) + "," +
                                        std::to_string(100 * std::sin(i * M_PI / 128)) + "]");
        CHECK(bsp(circle + "]") == "");
    }

    TEST_CASE("all the frames of a scene together have a pixel budget, checked before anything is drawn") {
        // Reproducer: cdlab render --out /tmp/o q64.json, q64.json = voronoi(4096, true) below (a
        // triangle, 64 queries, "steps": true): 0.93 GB at 1024², 1.87 GB at 2048², std::bad_alloc
        // under 4 GB at 4096² (every frame is kept until the scene is written).
        std::string queries = "[";
        for (int i = 0; i < 64; ++i) queries += (i ? ",[" : "[") + std::to_string(0.1 * i) + ",0.3,0.5]";
        queries += "]";
        const auto voronoi = [&](int side, bool steps) {
            return R"({"demo":"voronoi_triangle","triangle":[[0,0,0],[4,0,0],[0,4,0]],"queries":)" + queries +
                   R"(,"steps":)" + (steps ? "true" : "false") + R"(,"image":{"width":)" + std::to_string(side) +
                   R"(,"height":)" + std::to_string(side) + "}}";
        };
        CHECK(contains(prepareTextError(voronoi(4096, true)),
                       "scene.json: $.image: 67 frames (with per-step frames) of 4096 x 4096 at scale 1 are "
                       "1124073472 supersampled pixels, above the limit of 134217728 for one scene"));
        CHECK(prepareTextError(voronoi(4096, false)) == "");  // the two views
        CHECK(prepareTextError(voronoi(1024, true)) == "");   // the most queries at the default size
        // --scale and --steps are checked against the same budget.
        auto scene = loadSceneText(voronoi(1024, true), "q64.json");
        CHECK_THROWS_WITH_AS(checkImageBudget(scene->common(), 2),
                             doctest::Contains("q64.json: $.image: 67 frames (with per-step frames) of 1024 x 1024 "
                                               "at scale 2"),
                             InputError);
        auto views = loadSceneText(voronoi(2048, false), "views.json");
        CHECK_NOTHROW(checkImageBudget(views->common(), 0));
        CHECK_THROWS_WITH_AS(checkImageBudget(views->common(), 0, true),
                             doctest::Contains("views.json: $.image: 67 frames (with per-step frames)"), InputError);

        // drop: each frame is the image with a side view 0.45 of its width beside it; at 4096 wide
        // the frames came out 5939 x 4096, above the per-side and the 2^24-pixel limits.
        const auto drop = [](int width, int height) {
            return R"({"demo":"drop","body":{"box":{"half_extents":[0.5,0.5,0.5]}},"position":[0,0,1],"image":{"width":)" +
                   std::to_string(width) + R"(,"height":)" + std::to_string(height) + "}}";
        };
        CHECK(contains(prepareTextError(drop(4096, 4096)),
                       "scene.json: $.image: the drop frames are 5939 x 4096 (wider than the image) at scale 1"));
        CHECK(contains(prepareTextError(drop(2826, 1000)), "the drop frames are 4098 x 1000"));
        CHECK(prepareTextError(drop(2825, 1000)) == "");  // 4096 x 1000 frames
    }

    TEST_CASE("drop: the smallest density, mass and inertia keep the run finite") {
        // Reproducer: echo '{"demo":"drop","body":{"box":{"half_extents":[0.5,0.5,0.5]}},"position":
        // [0,0,1],"density":1e-300}' > d.json && cdlab render --out /tmp/o d.json: within the documented
        // limits (density had only an upper one) it ended in a "... is NaN" error: the inverse inertia
        // tensor underflowed.
        const auto drop = [](const std::string& body, const std::string& extra) {
            return R"({"demo":"drop","body":)" + body + extra + "}";
        };
        const std::string unitBox = R"({"box":{"half_extents":[0.5,0.5,0.5]}},"position":[0,0,1])";
        CHECK(contains(prepareTextError(drop(unitBox, R"(,"density":1e-300)")),
                       "scene.json: $.density: density is 1e-300, below the limit of 0.001"));
        // The smallest body at the smallest density prepares and runs to finite numbers (run()
        // throws on a NaN or an infinity in the trace).
        const std::string tinyBox =
            R"({"box":{"half_extents":[1e-5,1e-5,1e-5]}},"position":[0,0,2e-5],"simulation":{"duration":0.25})";
        REQUIRE(prepareTextError(drop(tinyBox, R"(,"density":1e-3)")) == "");
        CHECK_NOTHROW(loadSceneText(drop(tinyBox, R"(,"density":1e-3)"), "tiny.json")->run(RunContext{}));
        // A body below the mass limit however small its density (a 1e-30 polytope) is refused at $.body.
        const std::string e = prepareTextError(
            drop(R"({"polytope":{"vertices":[[0,0,0],[1e-30,0,0],[0,1e-30,0],[0,0,1e-30]]}},"position":[0,0,1])", ""));
        CHECK_MESSAGE(contains(e, "scene.json: $.body"), e);
        CHECK_MESSAGE(contains(e, "mass"), e);
    }

    TEST_CASE("every text of a scene has a length limit, refused with its JSON path and length") {
        // Reproducer: cdlab render --out /tmp/o t.json, t.json = gjkWith("title", 100000) below: 2.8 GB
        // and 9-13 s (300 KB: std::bad_alloc); a 30 KB "caption" made a 1008 x 18678 contact sheet and
        // then a GL error blaming the supersampling factor.
        const auto gjkWith = [](const std::string& key, std::size_t length) {
            return kGjk.substr(0, kGjk.size() - 1) + ",\"" + key + "\":\"" + std::string(length, 'x') + "\"}";
        };
        CHECK(prepareTextError(gjkWith("title", kMaxTitleChars)) == "");
        CHECK(contains(prepareTextError(gjkWith("title", 100000)),
                       "scene.json: $.title: the text is 100000 characters, above the limit of 200 for a title"));
        CHECK(prepareTextError(gjkWith("caption", kMaxCaptionChars)) == "");
        CHECK(contains(prepareTextError(gjkWith("caption", kMaxCaptionChars + 1)),
                       "scene.json: $.caption: the text is 1001 characters, above the limit of 1000 for a caption"));
        // Characters, not bytes: 200 two-byte characters are a title within the limit.
        std::string accented;
        for (std::size_t i = 0; i < kMaxTitleChars; ++i) accented += "\xc3\xa9";
        CHECK(prepareTextError(kGjk.substr(0, kGjk.size() - 1) + ",\"title\":\"" + accented + "\"}") == "");
        // A label drawn on a frame (polyhedron_plane's pose labels), and any other text of a scene.
        const std::string poses =
            R"({"demo":"polyhedron_plane","mode":"plane","body":{"box":{"half_extents":[0.5,0.5,0.5]}},"poses":[{"position":[0,0,0.4],"label":")" +
            std::string(kMaxLabelChars + 1, 'x') + "\"}]}";
        CHECK(contains(prepareTextError(poses),
                       "scene.json: $.poses[0].label: the text is 101 characters, above the "
                       "limit of 100 for a label"));
        // A comment is not drawn: any length (up to the file's).
        CHECK(prepareTextError(gjkWith("_comment", 100000)) == "");
    }

    TEST_CASE("every golden scene is within the limits") {
        int scenes = 0;
        for (const auto& demo : fs::directory_iterator(CDLAB_SOURCE_DIR "/golden"))
            if (demo.is_directory())
                for (const auto& f : fs::directory_iterator(demo.path()))
                    if (f.path().extension() == ".json") {
                        ++scenes;
                        CHECK_MESSAGE(prepareError(f.path().string()) == "", f.path());
                    }
        CHECK(scenes >= 51);
    }

}  // TEST_SUITE
