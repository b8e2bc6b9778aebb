// `cdlab check --figures DIR` (app/check/check_figure.h): a failing line of two convex shapes gets
// DIR/line_<n>.png with cdlab's answer and yours side by side, named on its verdict line; a passing
// line gets none; a line whose shapes the figure does not draw says so and writes nothing; a trace
// that breaks a rule at step k gets the configuration space at step k, cdlab's beside yours.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "app/check/check.h"
#include "app/query/query.h"
#include "render/canvas.h"
#include "render/image.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

// `check --figures` over `lines` into a fresh folder under the temp directory.
struct FigureRun {
    std::filesystem::path dir;
    std::string out;  // the verdict lines and the summary
    int status = 0;
};
FigureRun checkWithFigures(const std::string& lines, const std::string& folder) {
    FigureRun run;
    run.dir = std::filesystem::temp_directory_path() / folder;
    std::filesystem::remove_all(run.dir);
    std::istringstream in(lines);
    std::ostringstream out;
    CheckOptions options;
    options.figuresDir = run.dir.string();
    run.status = runCheck(in, out, options);
    run.out = out.str();
    return run;
}

// Values that differ between the left and the right panel below the headings (y >= 120) and
// above the caption (y < 560), over the first `channels` colour channels.
long panelDifference(const render::Image& image, int channels) {
    long differing = 0;
    const int half = image.width / 2;
    for (int y = 120; y < 560; ++y)
        for (int x = 0; x < half; ++x)
            for (int c = 0; c < channels; ++c)
                differing += image.rgba[(std::size_t(y) * image.width + x) * 4 + c] !=
                             image.rgba[(std::size_t(y) * image.width + x + half) * 4 + c];
    return differing;
}

}  // namespace

TEST_CASE("check --figures: one figure per failing line, cdlab's answer beside yours") {
    const FigureRun run = checkWithFigures(
        R"({"op":"distance","a":{"obb":{"center":[0,0,0],"half_extents":[1,0.5,0.5]}},"b":{"polytope":{"vertices":[[2.5,0,0],[3.5,0.3,0],[3,1,0.2],[3,0.4,1]]}},"answer":{"intersect":false,"distance":1.2,"point_a":[1.2,0,0],"point_b":[2.5,0,0]}})"
        "\n"
        R"({"op":"intersect","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"sphere":{"center":[3,0,0],"radius":1}},"answer":{"intersect":false}})"
        "\n"
        R"({"op":"distance","a":{"capsule":{"a":[0,0,0],"b":[1,0,0],"radius":0.2}},"b":{"sphere":{"center":[3,0,0],"radius":1}},"answer":{"intersect":false,"distance":5,"point_a":[1.2,0,0],"point_b":[2,0,0]}})"
        "\n",
        "cdlab_check_figures_test");
    const std::filesystem::path& dir = run.dir;
    CHECK(run.status == 1);
    std::istringstream lines(run.out);
    std::string l1, l2, l3;
    std::getline(lines, l1);
    std::getline(lines, l2);
    std::getline(lines, l3);
    const std::string figure = (dir / "line_1.png").string();
    CHECK(l1.find("FAIL: distance off by") != std::string::npos);
    CHECK(l1.find("[figure " + figure + "]") != std::string::npos);
    CHECK(l2 == "line 2: pass");
    CHECK(l3.find("[no figure: it draws polytopes, aabbs, obbs, spheres, cylinders and cones]") != std::string::npos);
    CHECK(!std::filesystem::exists(dir / "line_2.png"));
    CHECK(!std::filesystem::exists(dir / "line_3.png"));

    const render::Image image = render::readPng(figure);
    REQUIRE(image.width == 1280);
    REQUIRE(image.height == 640);
    // The two panels draw the same bodies with different witness points: the halves differ.
    CHECK(panelDifference(image, 3) > 100);
    std::filesystem::remove_all(dir);
}

TEST_CASE("check --figures: a cylinder and a cone are drawn as themselves") {
    const FigureRun run = checkWithFigures(
        R"({"op":"distance","a":{"cylinder":{"radius":1,"half_height":1,"rotation":[0.9,0.3,0,0.1]}},"b":{"cone":{"radius":0.6,"half_height":0.8,"position":[3,0.5,0]}},"answer":{"intersect":false,"distance":1.0,"point_a":[1,0,0],"point_b":[2,0,0]}})"
        "\n",
        "cdlab_check_curved_figure_test");
    const std::string figure = (run.dir / "line_1.png").string();
    CHECK(run.out.find("[figure " + figure + "]") != std::string::npos);
    const render::Image image = render::readPng(figure);
    REQUIRE(image.width == 1280);
    CHECK(panelDifference(image, 3) > 100);  // the same bodies, different witness points
    std::filesystem::remove_all(run.dir);
}

TEST_CASE("check --figures: a trace that breaks a rule at step k gets cdlab's step k beside yours") {
    // Your trace: cdlab's own run written in the check schema (a first step keeping the first
    // support alone), then step 2 planted to keep only its point farthest from the origin.
    const Json query = Json::parse(
        R"({"op":"distance","a":{"obb":{"center":[0,0,0],"half_extents":[1,0.5,0.5],"rotation":[0.92,0,0.38,0]}},)"
        R"("b":{"polytope":{"vertices":[[2.5,0,0],[3.5,0.3,0],[3,1,0.2],[3,0.4,1]]}},"initial_direction":[-1,0.2,0.1]})");
    Json traced = query;
    traced["trace"] = true;
    const Json answer = answerQuery(traced.dump());
    const Json& cdlabSteps = answer["trace"]["algorithms"][0]["steps"];
    REQUIRE(cdlabSteps.size() >= 2);
    const Json first = cdlabSteps[0]["simplex"][0];
    Json steps = Json::array({{{"direction", query["initial_direction"]}, {"support", first}, {"simplex", {first}}}});
    for (const Json& s : cdlabSteps)
        steps.push_back({{"direction", s["direction"]},
                         {"support", {{"a", s["support_a"]}, {"b", s["support_b"]}}},
                         {"simplex", s["simplex"]}});
    Json farthest = steps[2]["simplex"][0];
    for (const Json& p : steps[2]["simplex"])
        if (Vec3(p[0], p[1], p[2]).norm() > Vec3(farthest[0], farthest[1], farthest[2]).norm()) farthest = p;
    steps[2]["simplex"] = Json::array({farthest});
    Json line = query;
    line["answer"] = {{"intersect", answer["intersect"]},
                      {"distance", answer["distance"]},
                      {"point_a", answer["point_a"]},
                      {"point_b", answer["point_b"]}};
    line["trace"] = {{"algorithm", "gjk"}, {"steps", steps}};

    const FigureRun run = checkWithFigures(line.dump() + "\n", "cdlab_check_trace_figure_test");
    const std::filesystem::path& dir = run.dir;
    CHECK(run.status == 1);
    CHECK(run.out.find("FAIL: trace: iteration 2: wrong sub-simplex kept") != std::string::npos);
    CHECK(run.out.find("[figure " + (dir / "line_1.png").string() + "]") != std::string::npos);
    const render::Image image = render::readPng((dir / "line_1.png").string());
    CHECK(image.width == 1280);
    std::filesystem::remove_all(dir);
}

TEST_CASE("check --figures: a sphere's trace is drawn against cdlab's GJK on the whole sphere") {
    // A sphere (centre (3, 0, 0), radius 1) and a cube: your step 0 is right (along -x: the sphere's
    // point (2, 0, 0) minus the cube's corner (1, 1, 1), a tie on its +x face); step 1 takes the
    // sphere's centre, not its extreme point along the new direction.
    const Json a = {{"sphere", {{"center", {3, 0, 0}}, {"radius", 1}}}};
    const Json b = {{"aabb", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
    const Json w0 = {1, -1, -1}, w1 = {2, 1, 1};  // w1 = (3, 0, 0) - (1, -1, -1): not extreme along (-1, 1, 1)
    Json line = {{"op", "distance"},
                 {"a", a},
                 {"b", b},
                 {"answer", {{"intersect", false}, {"distance", 1}, {"point_a", {2, 0, 0}}, {"point_b", {1, 0, 0}}}},
                 {"trace", {{"algorithm", "gjk"},
                            {"steps", {{{"direction", {-1, 0, 0}}, {"support", w0}, {"simplex", {w0}}},
                                       {{"direction", {-1, 1, 1}},
                                        {"support", {{"a", {3, 0, 0}}, {"b", {1, -1, -1}}}},
                                        {"simplex", {w0, w1}}}}}}}};
    const FigureRun run = checkWithFigures(line.dump() + "\n", "cdlab_check_sphere_trace_figure_test");
    const std::filesystem::path& dir = run.dir;
    CHECK(run.status == 1);
    CHECK(run.out.find("FAIL: trace: iteration 1: different support point") != std::string::npos);
    REQUIRE(run.out.find("[figure " + (dir / "line_1.png").string() + "]") != std::string::npos);
    const render::Image image = render::readPng((dir / "line_1.png").string());
    CHECK(image.width == 1280);
    CHECK(panelDifference(image, 3) > 2000);  // cdlab's extreme support point beside your centre
    // An EPA trace on a sphere says why it has no figure (a right answer, a support point that is not
    // extreme along its normal at step 0).
    line["op"] = "penetration";
    line["a"]["sphere"]["center"] = {1.5, 0, 0};
    line["answer"] = {{"intersect", true}, {"depth", 0.5}, {"normal", {-1, 0, 0}}, {"point_a", {0.5, 0, 0}}, {"point_b", {1, 0, 0}}};
    line["trace"] = {{"algorithm", "epa"}, {"steps", {{{"normal", {-1, 0, 0}}, {"distance", 0.5}, {"support", {0, 0, 0}}}}}};
    const FigureRun epa = checkWithFigures(line.dump() + "\n", "cdlab_check_sphere_epa_figure_test");
    CHECK(epa.out.find("trace (epa): iteration 0: different support point") != std::string::npos);
    CHECK(epa.out.find("[no figure: EPA trace steps are drawn for polytopes, aabbs and obbs]") != std::string::npos);
    std::filesystem::remove_all(dir);
    std::filesystem::remove_all(epa.dir);
}

TEST_CASE("check --figures: an EPA trace that breaks a rule at step k gets cdlab's EPA step k beside yours") {
    // Two cubes overlapping by 0.25 along x; your second step's support is not extreme.
    const double s = 1 / std::sqrt(3.0);
    Json line = {{"op", "penetration"},
                 {"a", {{"aabb", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}},
                 {"b", {{"aabb", {{"min", {0.75, 0, 0}}, {"max", {1.75, 1, 1}}}}}},
                 {"answer", {{"intersect", true}, {"depth", 0.25}, {"normal", {1, 0, 0}}, {"point_a", {1, 0.5, 0.5}},
                             {"point_b", {0.75, 0.5, 0.5}}}},
                 {"trace", {{"algorithm", "epa"},
                            {"steps", {{{"normal", {s, s, s}}, {"distance", 0.1}, {"support", {0.25, 1, 1}}},
                                       {{"normal", {1, 0, 0}}, {"distance", 0.25}, {"support", {0.2, 0, 0}}}}}}}};
    const FigureRun run = checkWithFigures(line.dump() + "\n", "cdlab_check_epa_figure_test");
    const std::filesystem::path& dir = run.dir;
    CHECK(run.status == 1);
    CHECK(run.out.find("trace (epa): iteration 1: different support point") != std::string::npos);
    CHECK(run.out.find("[figure " + (dir / "line_1.png").string() + "]") != std::string::npos);
    CHECK(render::readPng((dir / "line_1.png").string()).height == 640);
    std::filesystem::remove_all(dir);
}

TEST_CASE("check --figures: a closest_point_triangle line gets the triangle's regions, cdlab's answer beside yours") {
    const Json line = {{"op", "closest_point_triangle"},
                       {"point", {2, -1, 0.5}},
                       {"triangle", {{0, 0, 0}, {4, 0, 0}, {1.2, 3, 0}}},
                       {"answer", {{"point", {2, 0, 0}}, {"region", "A"}}}};
    const FigureRun run = checkWithFigures(line.dump() + "\n", "cdlab_check_region_figure_test");
    const std::filesystem::path& dir = run.dir;
    CHECK(run.status == 1);
    CHECK(run.out.find("region differs: yours A, cdlab's AB") != std::string::npos);
    CHECK(run.out.find("[figure " + (dir / "line_1.png").string() + "]") != std::string::npos);
    // Different regions are outlined: the panels differ below their headings.
    const render::Image image = render::readPng((dir / "line_1.png").string());
    REQUIRE(image.width == 1280);
    CHECK(panelDifference(image, 1) > 100);
    std::filesystem::remove_all(dir);
}

TEST_CASE("check --figures: the figure wraps its reasons, a wrong answer's broken step is the step drawn") {
    // A wrong distance and a trace whose iteration 1 keeps the wrong sub-simplex: the verdict leads
    // with the step, the figure draws iteration 1, and every word of both reasons is on it (wrapped,
    // not cut: cdlab's numbers at the ends of the long reasons included).
    const std::string line =
        R"({"op":"distance","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[2,0,0],"max":[3,1,1]}},)"
        R"("answer":{"intersect":false,"distance":1.7320508,"point_a":[1,1,1],"point_b":[2,0,0]},"trace":{"algorithm":"gjk","steps":[)"
        R"({"direction":[1,0,0],"support":[-1,1,1],"simplex":[[-1,1,1]]},)"
        R"({"direction":[1,-1,-1],"support":{"a":[1,0,0],"b":[2,1,1]},"simplex":[[-1,-1,-1]]}]}})";
    render::drawnTextLog().clear();
    const FigureRun run = checkWithFigures(line + "\n", "cdlab_check_wrapped_figure_test");
    CHECK(run.out.find("FAIL: trace: iteration 1: wrong sub-simplex kept") != std::string::npos);
    CHECK(run.out.find("distance off by") != std::string::npos);
    CHECK(run.out.find("[figure " + (run.dir / "line_1.png").string() + "]") != std::string::npos);
    std::string drawn;
    for (const std::string& s : render::drawnTextLog()) drawn += s + " ";
    CHECK(drawn.find("GJK iteration 1") != std::string::npos);
    const std::size_t from = run.out.find("trace: iteration 1"), to = run.out.find(" [figure");
    REQUIRE(from != std::string::npos);
    const std::string reasons = run.out.substr(from, to - from);  // "reason; reason"
    const std::string first = reasons.substr(0, reasons.find("; distance off"));
    const std::string rest = reasons.substr(first.size() + 2);
    const std::string second = rest.substr(0, rest.find("; "));  // the figure shows the first two reasons
    CHECK(first.size() > 150);  // over one line of the 1280-px caption: it must wrap
    CHECK_MESSAGE(drawn.find(first) != std::string::npos, drawn);
    CHECK_MESSAGE(drawn.find(second) != std::string::npos, drawn);
    std::filesystem::remove_all(run.dir);
}

TEST_CASE("check --figures: reasons are escaped on the figure as on the verdict line") {
    // A region holding newlines would put lines of its own under the figure: it is drawn as
    // printed, "\n" and all, on one caption line.
    const std::string line =
        R"({"op":"closest_point_triangle","point":[0.2,0.2,1],"triangle":[[0,0,0],[1,0,0],[0,1,0]],)"
        R"("answer":{"point":[0.2,0.2,0],"region":"X\nforged 0\nforged 1"}})";
    render::drawnTextLog().clear();
    const FigureRun run = checkWithFigures(line + "\n", "cdlab_check_escaped_figure_test");
    REQUIRE(run.out.find("[figure ") != std::string::npos);
    bool escaped = false;
    for (const std::string& s : render::drawnTextLog()) {
        CHECK(s.rfind("forged", 0) != 0);  // no drawn line starts with the forged text
        CHECK_MESSAGE(s.find('\n') == std::string::npos, s);
        escaped = escaped || s.find("X\\nforged 0\\nforged 1") != std::string::npos;
    }
    CHECK(escaped);
    std::filesystem::remove_all(run.dir);
}
