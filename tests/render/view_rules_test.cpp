// The legibility rules about views and plots (render/legibility.h): a planted layout per rule that
// the check must fail, and the neighbouring case it must pass. The Canvas half (what noteFeature,
// noteBody, noteAxis and noteSeries record from a camera) is checked against hand-computed angles;
// StepFeatureFaded (checkFigure) against planted pixels and a drawn translucent face.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "render/canvas.h"
#include "render/legibility.h"
#include "tests/gl_test_context.h"

using namespace cdlab::render;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

int countOf(const std::vector<LegibilityProblem>& problems, LegibilityKind kind) {
    int n = 0;
    for (const auto& p : problems) n += p.kind == kind;
    return n;
}

LayoutLabel numberLabel(const std::string& text, Box box) { return {text, box, std::nullopt, 20}; }

}  // namespace

TEST_SUITE("legibility") {
    TEST_CASE("separated bodies overlapping on the picture, not touching ones or ones not known apart") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}};
        l.bodies = {{"A", {{10, 10}, {110, 10}, {110, 110}, {10, 110}}, "B"},
                    {"B", {{100, 50}, {200, 50}, {200, 150}, {100, 150}}, ""}};  // 10 px deep into A
        auto problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::SeparatedBodiesOverlap);
        CHECK(problems[0].text == "A");
        CHECK(problems[0].severity == doctest::Approx(10));
        l.bodies[1].outline = {{111, 50}, {200, 50}, {200, 150}, {111, 150}};  // a 1-px gap
        CHECK(checkLegibility(l, 400, 300).empty());
        l.bodies[1].outline = {{100, 50}, {200, 50}, {200, 150}, {100, 150}};
        l.bodies[0].apartFrom = "";  // overlapping bodies in contact are drawn overlapping
        CHECK(checkLegibility(l, 400, 300).empty());
        // Two panels (one body in each, side by side on the page) never overlap each other's.
        l.panels = {{0, 0, 400, 300}, {0, 0, 105, 300}, {105, 0, 400, 300}};
        l.bodies[0].apartFrom = "B";
        l.bodies[0].outline = {{10, 10}, {100, 10}, {100, 110}, {10, 110}};
        l.bodies[1].outline = {{106, 50}, {200, 50}, {200, 150}, {106, 150}};
        CHECK(checkLegibility(l, 400, 300).empty());
    }

    TEST_CASE("a highlighted feature edge-on, the step's from behind, a hidden one filled") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}};
        // A face at 80 degrees from the view, front side: edge-on only.
        l.features = {{"F1 (A)", 2, std::cos(80 * M_PI / 180), std::cos(80 * M_PI / 180), true, true, {50, 50}}};
        auto problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::FeatureEdgeOn);
        CHECK(problems[0].detail.find("80 deg") != std::string::npos);
        // Turned away at 40 degrees, filled, the step's: from behind and hidden-filled, not edge-on.
        const double away = -std::cos(40 * M_PI / 180);
        l.features = {{"F2 (B)", 2, away, -away, true, true, {50, 50}}};
        problems = checkLegibility(l, 400, 300);
        CHECK(problems.size() == 2);
        CHECK(countOf(problems, LegibilityKind::FeatureFromBehind) == 1);
        CHECK(countOf(problems, LegibilityKind::HiddenFilled) == 1);
        // The same face hollow and not the step's (the other body's current feature): fine.
        l.features[0].filled = false, l.features[0].step = false;
        CHECK(checkLegibility(l, 400, 300).empty());
        // An edge seen end-on (10 degrees off its direction): edge-on; a vertex never is.
        l.features = {{"E4 (A)", 1, 0.5, std::sin(10 * M_PI / 180), false, true, {50, 50}},
                      {"V0 (B)", 0, 0.5, 1.0, false, false, {80, 50}}};
        problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::FeatureEdgeOn);
        CHECK(problems[0].text == "E4 (A)");
    }

    TEST_CASE("a log axis needs numbers beside it, two named series need two colours") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}, {0, 0, 200, 300}, {200, 0, 400, 300}};
        l.axes = {{{60, 20}, {60, 280}, true}};
        l.labels = {numberLabel("1e3", {20, 30, 55, 50}), numberLabel("log scale", {80, 0, 160, 20})};
        auto problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::LogAxisWithoutValues);
        CHECK(problems[0].detail.find("1 numbers") != std::string::npos);
        l.labels.push_back(numberLabel("1e5", {20, 200, 55, 220}));  // a second value: read
        CHECK(checkLegibility(l, 400, 300).empty());
        l.labels.back().box = {300, 200, 335, 220};  // a number far from the axis is no value of it
        CHECK(countOf(checkLegibility(l, 400, 300), LegibilityKind::LogAxisWithoutValues) == 1);
        l.axes[0].log = false;  // a linear axis may leave its values to the bars
        CHECK(checkLegibility(l, 400, 300).empty());

        l.series = {{"Johnson median", 0x0072B2, {50, 50}}, {"signed volumes median", 0x0075B0, {50, 60}}};
        problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::SeriesShareColour);
        l.series[1].rgb = 0xD55E00;
        CHECK(checkLegibility(l, 400, 300).empty());
        l.series[1] = {"Johnson median", 0x0072B2, {60, 60}};  // one thing drawn twice (a line and its markers)
        CHECK(checkLegibility(l, 400, 300).empty());
        l.series[1] = {"signed volumes median", 0x0072B2, {300, 60}};  // the same colour in another plot
        CHECK(checkLegibility(l, 400, 300).empty());
    }
}

TEST_SUITE("canvas") {
    TEST_CASE("noteFeature measures a face's and an edge's angle to the view, noteBody keeps apart_from") {
        Camera cam;
        cam.projection = Camera::Projection::Orthographic;
        cam.eye = {0, 0, 5}, cam.target = {0, 0, 0}, cam.up = {0, 1, 0};
        cam.viewHeight = 4;
        Canvas c(cdlab::test::glContext(), CanvasOptions{200, 200, 1, 1, 1, true}, cam);
        const double a = 80 * M_PI / 180;  // the face's normal 80 degrees from the view (+z)
        c.noteFeature({"F", {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}}, {{std::sin(a), 0, std::cos(a)}}, true, true});
        c.noteFeature({"back", {{0, 0, -1}}, {{0, 0, -1}, {0, 1, -1}}, false, false});  // a vertex behind
        c.noteFeature({"E", {{0, 0, 0}, {0.1, 0, 1}}, {{0, 1, 0}, {1, 0, 0}}, false, true});  // nearly end-on
        c.noteBody("A", {{-1, -1, 0}, {0, -1, 0}, {0, 0, 0}}, "B");
        const FigureLayout l = c.layout();
        REQUIRE(l.features.size() == 3);
        CHECK(l.features[0].dimension == 2);
        CHECK(l.features[0].facing == doctest::Approx(std::cos(a)));
        CHECK(l.features[0].foreshortening == doctest::Approx(std::cos(a)));
        CHECK(l.features[0].at.x() == doctest::Approx(100 + 50.0 / 3));  // 50 px a unit: 4 units on 200 px
        CHECK(l.features[1].dimension == 0);
        CHECK(l.features[1].facing == doctest::Approx(-std::sqrt(0.5)));  // the better of its faces' -1 and -0.71
        CHECK(l.features[2].dimension == 1);
        CHECK(l.features[2].foreshortening == doctest::Approx(0.1 / std::sqrt(1.01)));
        REQUIRE(l.bodies.size() == 1);
        CHECK(l.bodies[0].apartFrom == "B");
        const auto problems = checkLegibility(l, 200, 200);
        CHECK(countOf(problems, LegibilityKind::FeatureEdgeOn) == 2);  // the face and the edge
        CHECK(countOf(problems, LegibilityKind::FeatureFromBehind) == 0);  // the vertex behind is no step's
    }

    TEST_CASE("the step's feature must show its colour: olive fails, its own colour or a zoomed copy passes") {
        // A 100 x 100 picture: the left half the face's yellow, the right half olive.
        Image im(100, 100);
        for (int y = 0; y < 100; ++y)
            for (int x = 0; x < 100; ++x) {
                std::uint8_t* p = &im.rgba[(std::size_t(y) * 100 + std::size_t(x)) * 4];
                const bool left = x < 50;
                p[0] = left ? 0xF0 : 0x80, p[1] = left ? 0xE4 : 0x89, p[2] = left ? 0x42 : 0x4B, p[3] = 255;
            }
        LayoutFeature olive{"closest face", 2, 1, 1, true, true, {75, 50}};
        olive.rgb = 0xF0E442;
        olive.samples = {{75, 50}, {70, 30}, {80, 70}};
        im.layout.panels = {{0, 0, 100, 100}};
        im.layout.features = {olive};
        auto problems = checkFigure(im);
        REQUIRE(countOf(problems, LegibilityKind::StepFeatureFaded) == 1);
        CHECK(problems[0].text == "closest face");
        CHECK(problems[0].severity == doctest::Approx(0xF0 - 0x80));

        // One point in the face's colour of three is not most of them; two are.
        im.layout.features[0].samples = {{75, 50}, {70, 30}, {20, 70}};
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 1);
        im.layout.features[0].samples = {{75, 50}, {10, 30}, {20, 70}};
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 0);

        // Under a label (with its 3-px halo) nothing is judged; a feature no step changed, a vertex
        // (a marker over everything), a hidden or hollow face are not judged.
        im.layout.features[0] = olive;
        im.layout.labels = {{"closest", {60, 20, 95, 82}, std::nullopt, 16}};
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 0);
        im.layout.labels[0].box = {60, 20, 95, 66};  // (80, 70) is 4 px below it: judged
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 1);
        im.layout.labels.clear();
        for (auto change : {+[](LayoutFeature& f) { f.step = false; }, +[](LayoutFeature& f) { f.dimension = 0; },
                            +[](LayoutFeature& f) { f.facing = -0.2; }, +[](LayoutFeature& f) { f.filled = false; },
                            +[](LayoutFeature& f) { f.rgb = -1; }}) {
            im.layout.features[0] = olive;
            change(im.layout.features[0]);
            CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 0);
        }

        // A face's sample on a stroke (an arrow across it) is not judged; an edge's is its own stroke.
        im.layout.features[0] = olive;
        im.layout.strokes = {{{60, 30}, {90, 30}, 3}, {{75, 40}, {75, 60}, 3}};
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 1);  // (80, 70) alone: olive, 0 of 1
        im.layout.features[0].samples.pop_back();
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 0);  // nothing left to judge
        im.layout.features[0].dimension = 1;
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 1);
        im.layout.strokes.clear();

        // The same feature shown in its colour in a zoomed inset is enough.
        LayoutFeature zoomed = olive;
        zoomed.samples = {{20, 50}, {25, 40}};
        im.layout.features = {olive, zoomed};
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 0);
        im.layout.features[1].name = "another face";
        CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == 1);
    }

    TEST_CASE("a drawn translucent step face over another colour fails, drawn opaque passes") {
        Camera cam;
        cam.projection = Camera::Projection::Orthographic;
        cam.eye = {0, 0, 5}, cam.target = {0, 0, 0}, cam.up = {0, 1, 0};
        cam.viewHeight = 4;
        const Color yellow{0.94f, 0.894f, 0.259f, 1.0f}, teal{0.0f, 0.5f, 0.45f, 1.0f};
        const std::vector<Vector3d> face{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
        const std::vector<Vector3d> behind{{-1.5, -1.5, -1}, {1.5, -1.5, -1}, {1.5, 1.5, -1}, {-1.5, 1.5, -1}};
        for (const float alpha : {0.6f, 1.0f}) {
            CAPTURE(alpha);
            Canvas c(cdlab::test::glContext(), CanvasOptions{200, 200, 1, 1, 1, true}, cam);
            c.drawPolygon(behind, teal);
            c.drawPolygon(face, yellow.withAlpha(alpha));
            // A point off the picture records no sample: a quad's centre and 4 halfway points, one lost.
            std::vector<Vector3d> pts = face;
            pts[2] = {7, 7, 0};
            c.noteFeature({"off", pts, {{0, 0, 1}}, true, false, yellow});
            c.noteFeature({"closest face", face, {{0, 0, 1}}, true, true, yellow});
            const Image im = c.readPixels();
            REQUIRE(im.layout.features.size() == 2);
            CHECK(im.layout.features[0].samples.size() == 4);
            CHECK(im.layout.features[1].samples.size() == 5);
            CHECK(im.layout.features[1].rgb == 0xF0E442);
            CHECK(countOf(checkFigure(im), LegibilityKind::StepFeatureFaded) == (alpha < 1 ? 1 : 0));
        }
    }
}
