// Hostile input, round two: the scene items. Each test opens with its reproducer. Every quantity a
// scene controls that multiplies work or memory has a limit checked when the scene is prepared
// (before anything is computed or written), with the file and JSON path in the error; a NaN that
// still reaches a trace or a frame's text is an error naming the scene and the quantity.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "demos/catalog/catalog.h"
#include "demos/scene/scene.h"
#include "demos/scene/scene_limits.h"
#include "tests/demos/scene_error.h"

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
    TEST_CASE("a scene file name that cannot name an output folder is refused") {
        // Reproducer: a scene file named `...json` has the name "..", whose output folder
        // <out>/<demo>/.. is <out> itself (and golden/<demo>/.. is golden/).
        for (const std::string bad : {"...json", "..json", ".hidden.json", "a b.json", "x\"y.json"})
            CHECK_MESSAGE(contains(prepareTextError(kGjk, "/tmp/" + bad), "cannot name an output folder"), bad);
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
        // Reproducer: drop with gravity 1e300 drew "E = -nan J", reported "max energy rise 0" and wrote
        // null into trace.json, exit 0 (likewise vclip at 1e300 and a voronoi triangle at 1e300). The
        // limits above now refuse those scenes; this check is the last line of defence.
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
