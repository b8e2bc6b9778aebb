// The legibility rules (render/legibility.h) and the label placement step (render/label_placement.h)
// on hand-made layouts: each rule fires on the case it names and on nothing else.
#include <doctest/doctest.h>

#include "render/image.h"
#include "render/label_placement.h"
#include "render/legibility.h"

using namespace cdlab::render;
using Eigen::Vector2d;

namespace {

LayoutLabel label(const std::string& text, Box box, std::optional<Vector2d> anchor = std::nullopt,
                  double lineHeight = 20) {
    return {text, box, anchor, lineHeight};
}

int count(const std::vector<LegibilityProblem>& problems, LegibilityKind kind) {
    int n = 0;
    for (const auto& p : problems) n += p.kind == kind;
    return n;
}

}  // namespace

TEST_SUITE("legibility") {
    TEST_CASE("a clean layout has no problem") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}};
        l.labels = {label("A", {10, 10, 30, 30}, Vector2d(5, 5)), label("B", {50, 10, 70, 30})};
        l.markers = {{{0, 0, 10, 10}, 0}};
        CHECK(checkLegibility(l, 400, 300).empty());
    }

    TEST_CASE("each rule fires on its own case") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}, {200, 0, 400, 300}};
        l.labels = {label("A", {10, 10, 40, 30}), label("B", {30, 20, 60, 40}),  // overlap
                    label("q", {100, 100, 120, 120}, Vector2d(90, 90)),          // on a marker
                    label("far", {190, 50, 230, 70}, Vector2d(210, 60)),         // leaves right panel
                    label("tiny", {10, 200, 40, 204}, std::nullopt, 4)};         // 4 px < 4.5 px
        l.markers = {{{105, 105, 115, 115}, -1}};
        l.unplaced = {"lost"};
        const auto problems = checkLegibility(l, 400, 300);
        CHECK(count(problems, LegibilityKind::LabelsOverlap) == 1);
        CHECK(count(problems, LegibilityKind::LabelOnMarker) == 1);
        CHECK(count(problems, LegibilityKind::LabelOutsidePanel) == 1);
        CHECK(count(problems, LegibilityKind::TextTooSmall) == 1);
        CHECK(count(problems, LegibilityKind::Unplaced) == 1);
        CHECK(problems.front().kind == LegibilityKind::Unplaced);  // worst first
    }

    TEST_CASE("a stroke across a label, a label nearer another anchor, a font under 1.6 %") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}};
        // "axis" is crossed by a 2-px line through its middle; "v" by nothing but its own leader.
        l.labels = {label("axis", {100, 100, 160, 120}), label("v", {300, 100, 315, 120}, Vector2d(280, 140))};
        l.strokes = {{Vector2d(80, 110), Vector2d(200, 110), 2.0, -1}, {Vector2d(280, 140), Vector2d(300, 120), 1.5, 1}};
        auto problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::LabelOnStroke);
        CHECK(problems[0].text == "axis");
        CHECK(problems[0].severity == doctest::Approx(59));  // 60 px of box + half width 1 − the 1.5 px graze, both sides
        // A stroke that only grazes the box's edge (its edge 0 px inside) is no crossing.
        l.strokes[0] = {Vector2d(80, 99), Vector2d(200, 99), 2.0, -1};
        CHECK(checkLegibility(l, 400, 300).empty());
        // One that nicks its corner, under 1 px of it inside the box less the graze, neither; 2 px do.
        l.strokes[0] = {Vector2d(100, 101.6), Vector2d(101.6, 100), 2.0, -1};
        CHECK(checkLegibility(l, 400, 300).empty());
        l.strokes[0] = {Vector2d(99, 103.5), Vector2d(103.5, 99), 2.0, -1};
        CHECK(count(checkLegibility(l, 400, 300), LegibilityKind::LabelOnStroke) == 1);
        l.strokes[0] = {Vector2d(80, 99), Vector2d(200, 99), 2.0, -1};
        // The same leader line, not marked as v's own, crosses v.
        l.strokes[1].leaderOf = -1;
        l.strokes[1].b = Vector2d(310, 110);
        problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::LabelOnStroke);
        CHECK(problems[0].text == "v");
        // A body's name may cross the body's own outline (outlineOf), not another body's.
        l.strokes[1].outlineOf = 1;
        CHECK(checkLegibility(l, 400, 300).empty());
        l.strokes[1].outlineOf = 0;
        REQUIRE(checkLegibility(l, 400, 300).size() == 1);

        FigureLayout n;
        n.panels = {{0, 0, 400, 300}};
        // p's box sits on q's point, 40 px from its own.
        n.labels = {label("p", {100, 100, 120, 120}, Vector2d(60, 110)), label("q", {200, 200, 220, 220}, Vector2d(110, 110))};
        problems = checkLegibility(n, 400, 300);
        REQUIRE(count(problems, LegibilityKind::LabelNearerOther) == 1);
        CHECK(problems[0].text == "p");
        CHECK(problems[0].other == "q");  // the label placement retries first too
        // Another panel's point does not compete: q's point in a panel of its own.
        n.panels.push_back({90, 90, 130, 130});
        CHECK(count(checkLegibility(n, 400, 300), LegibilityKind::LabelNearerOther) == 0);

        FigureLayout f;
        f.panels = {{0, 0, 400, 300}};
        f.labels = {label("small", {10, 10, 60, 14.6}, std::nullopt, 4.6)};  // 1.53 %: passes 1.5 %, not 1.6 %
        problems = checkLegibility(f, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::FontBelowTarget);
    }

    TEST_CASE("a named quantity under 12 px, unless an inset draws it larger") {
        FigureLayout q;
        q.panels = {{0, 0, 400, 300}};
        q.quantities = {{"gap", 7.0}, {"depth", 30.0}};
        auto problems = checkLegibility(q, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::QuantityTooSmall);
        CHECK(problems[0].text == "gap");
        CHECK(problems[0].severity == doctest::Approx(5));
        // A zoomed inset draws the gap again at 140 px: it is seen.
        FigureLayout inset;
        inset.quantities = {{"gap", 140.0}};
        q.append(inset, 200, 150);
        CHECK(checkLegibility(q, 400, 300).empty());
        // Carried through a resize: 14 px halved is 7.
        FigureLayout r;
        r.quantities = {{"depth", 14.0}};
        CHECK(count(checkLegibility(r.scaled(0.5), 200, 150), LegibilityKind::QuantityTooSmall) == 1);
    }

    TEST_CASE("a body cut by its panel's edge, not one inside it or past it by anti-aliasing") {
        FigureLayout l;
        l.panels = {{0, 0, 400, 300}, {0, 0, 200, 300}};  // a page and its left panel
        // A's outline runs 10 px past the left panel's right edge into the other panel.
        l.bodies = {{"A", {{150, 100}, {210, 100}, {210, 200}, {150, 200}}, ""}, {"B", {{20, 20}, {60, 20}, {40, 60}}, ""}};
        auto problems = checkLegibility(l, 400, 300);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::BodyCutByPanel);
        CHECK(problems[0].text == "A");
        CHECK(problems[0].severity == doctest::Approx(10));
        l.bodies[0].outline = {{150, 100}, {201, 100}, {201, 200}, {150, 200}};  // 1 px: anti-aliasing
        CHECK(checkLegibility(l, 400, 300).empty());
    }

    TEST_CASE("a label may cover the marker it names, touching boxes are no overlap") {
        FigureLayout l;
        l.panels = {{0, 0, 100, 100}};
        l.labels = {label("p", {10, 10, 30, 30}, Vector2d(20, 20)), label("q", {30, 40, 50, 60})};
        l.markers = {{{15, 15, 25, 25}, 0}};
        CHECK(checkLegibility(l, 100, 100).empty());
    }

    TEST_CASE("labels side by side need a space between them, stacked lines may touch") {
        FigureLayout l;
        l.panels = {{0, 0, 200, 100}};
        // Line height 20: a gap under 5 px runs the two texts together.
        l.labels = {label("E = 0.764", {10, 10, 60, 30}), label("Jt = 1.17 s", {62, 12, 110, 32})};
        auto problems = checkLegibility(l, 200, 100);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].kind == LegibilityKind::LabelsRunTogether);
        l.labels[1].box = {66, 12, 114, 32};  // 6 px: a space's width
        CHECK(checkLegibility(l, 200, 100).empty());
        l.labels[1].box = {10, 30, 60, 50};  // the next line, touching: fine
        CHECK(checkLegibility(l, 200, 100).empty());
    }

    TEST_CASE("blit and downsample carry the layout") {
        Image panel(100, 50);
        panel.layout.panels = {{0, 0, 100, 50}};
        panel.layout.labels = {label("A", {10, 10, 30, 30}, Vector2d(5, 5))};
        panel.layout.markers = {{{0, 0, 10, 10}, 0}};
        Image page(300, 100);
        blit(page, panel, 200, 40);
        REQUIRE(page.layout.labels.size() == 1);
        CHECK(page.layout.labels[0].box.x0 == 210);
        CHECK(page.layout.labels[0].box.y1 == 70);
        CHECK(page.layout.panels[0].x0 == 200);
        CHECK(page.layout.markers[0].label == 0);
        blit(page, panel, 0, 0);
        CHECK(page.layout.markers[1].label == 1);  // re-based on the second label
        const Image half = downsample(page, 2);
        CHECK(half.layout.labels[0].box.x0 == 105);
        CHECK(half.layout.labels[0].lineHeight == 10);
    }
}

TEST_CASE("a picture pasted over a layout hides its strokes, labels and markers there") {
    FigureLayout l;
    l.labels = {label("under", {20, 20, 40, 30}, Vector2d(10, 10)), label("kept", {100, 0, 140, 10}, std::nullopt)};
    l.markers = {{{22, 22, 26, 26}, 0}, {{0, 0, 4, 4}, 1}};
    l.strokes = {{Vector2d(0, 25), Vector2d(100, 25), 2, -1, 1}, {Vector2d(0, 80), Vector2d(10, 80), 1}};
    l.cover({10, 10, 50, 50});
    REQUIRE(l.labels.size() == 1);
    CHECK(l.labels[0].text == "kept");
    REQUIRE(l.markers.size() == 1);
    CHECK(l.markers[0].label == 0);  // follows "kept" to its new index
    REQUIRE(l.strokes.size() == 3);  // the crossing stroke in two pieces, the other whole
    CHECK(l.strokes[0].b.x() == doctest::Approx(10));
    CHECK(l.strokes[1].a.x() == doctest::Approx(50));
    CHECK(l.strokes[0].outlineOf == 0);
    CHECK(l.strokes[2].a.y() == 80);
}

TEST_SUITE("label placement") {
    PlacementObstacles open() {
        PlacementObstacles o;
        o.panel = {0, 0, 200, 200};
        return o;
    }

    TEST_CASE("the preferred side when it is free") {
        const PlacementRequest r{Vector2d(100, 100), Vector2d(20, 10), Vector2d(1, 0), 6};
        const Placement p = placeLabel(r, open());
        REQUIRE(p.placed);
        CHECK(p.box.x0 == doctest::Approx(106));
        CHECK(p.box.center().y() == doctest::Approx(100));
        CHECK_FALSE(p.leader);
    }

    TEST_CASE("around a label in the way, never over it") {
        PlacementObstacles o = open();
        o.boxes.push_back({100, 90, 140, 110});  // right of the point
        const PlacementRequest r{Vector2d(100, 100), Vector2d(20, 10), Vector2d(1, 0), 6};
        const Placement p = placeLabel(r, o);
        REQUIRE(p.placed);
        CHECK(p.box.overlapArea(o.boxes[0]) == 0);
        CHECK(o.panel.contains(p.box));
    }

    TEST_CASE("off thick lines when it can, with a leader line when it moves out") {
        PlacementObstacles o = open();
        // A ring of boxes around the point leaves only the far positions.
        for (int k = 0; k < 8; ++k) {
            const double a = k * M_PI / 4;
            const Vector2d c = Vector2d(100, 100) + 22 * Vector2d(std::cos(a), std::sin(a));
            o.boxes.push_back({c.x() - 12, c.y() - 8, c.x() + 12, c.y() + 8});
        }
        const PlacementRequest r{Vector2d(100, 100), Vector2d(20, 10), Vector2d(1, 0), 6};
        const Placement p = placeLabel(r, o);
        REQUIRE(p.placed);
        CHECK(p.leader);
        for (const Box& b : o.boxes) CHECK(p.box.overlapArea(b) == 0);
        PlacementObstacles lines = open();
        lines.lines.push_back({Vector2d(100, 100), Vector2d(180, 100), 3});  // a thick line to the right
        const Placement q = placeLabel(r, lines);
        REQUIRE(q.placed);
        CHECK(segmentBoxDistance(lines.lines[0].a, lines.lines[0].b, q.box) >= 4);
    }

    TEST_CASE("a leader neither runs along a stroke from its point nor passes through another label") {
        // Five thin lines above, five below and five on the right, 12 px and more from the point,
        // leave a 10 px label room only on its row; with that row taken, the label goes out with
        // a leader across five lines, or left, the short way out, past what is there.
        const Vector2d at(150, 100);
        PlacementObstacles fence;
        fence.panel = {0, 0, 300, 200};
        for (int k = 0; k < 5; ++k) {
            fence.lines.push_back({Vector2d(162 + 8 * k, 20), Vector2d(162 + 8 * k, 180), 0.75, true});
            fence.lines.push_back({Vector2d(70, 88 - 8 * k), Vector2d(162, 88 - 8 * k), 0.75, true});
            fence.lines.push_back({Vector2d(70, 112 + 8 * k), Vector2d(162, 112 + 8 * k), 0.75, true});
        }
        const PlacementRequest r{at, Vector2d(20, 10), Vector2d(-1, 0), 6};
        const auto leaderOf = [&](const Placement& p) {
            return Vector2d(p.box.nearest(at) - at);
        };
        const Placement inRow = placeLabel(r, fence);
        REQUIRE(inRow.placed);
        CHECK_FALSE(inRow.leader);  // left of the point, between the lines
        // The row holds an edge leaving the point to the left: a leader along it would name its far end.
        PlacementObstacles edge = fence;
        edge.lines.push_back({at, Vector2d(70, 100), 0.75, true});
        const Placement p = placeLabel(r, edge);
        REQUIRE(p.placed);
        CHECK(p.leader);
        CHECK(std::abs(leaderOf(p).normalized().y()) > 0.34);  // not within 20 degrees of the edge
        for (const auto& l : edge.lines) CHECK(segmentBoxDistance(l.a, l.b, p.box) > l.halfWidth);
        // The row holds another label: a leader through it would name it.
        PlacementObstacles label = fence;
        label.boxes.push_back({110, 94, 146, 106});
        const Placement q = placeLabel(r, label);
        REQUIRE(q.placed);
        CHECK(q.leader);
        double t0, t1;
        CHECK_FALSE(label.boxes[0].clip(at, Vector2d(at + leaderOf(q)), t0, t1));
    }

    TEST_CASE("no room: not placed") {
        PlacementObstacles o = open();
        o.boxes.push_back({0, 0, 200, 200});
        const Placement p = placeLabel({Vector2d(100, 100), Vector2d(20, 10), Vector2d(1, 0), 6}, o);
        CHECK_FALSE(p.placed);
    }
}
