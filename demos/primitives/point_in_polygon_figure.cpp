// The point-in-polygon family of the primitives demo: the same polygon and points through the three
// tests of core/overlap/point_in_polygon.h, side by side — same side of every edge (cheap, convex
// only), angle summation (n atan2, counts windings: the nonzero rule) and the crossing number
// (n cheap edge tests, any polygon: the even-odd rule) — with each test's own numbers per point.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/overlap/point_in_polygon.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"

namespace cdlab::demos {

namespace {

using namespace render;

struct PointRun {
    EdgeSideResult sides;
    AngleSumResult angles;
    CrossingNumberResult crossing;
};

std::vector<PointRun> runTests(const PointInPolygonInput& in) {
    std::vector<PointRun> runs;
    for (const Vec2& q : in.queries)
        runs.push_back({sameSideOfEveryEdge(in.polygon, q), angleSummation(in.polygon, q), crossingNumber(in.polygon, q)});
    return runs;
}

Json pointJson(const Vec2& q, const PointRun& r) {
    Json angles = Json::array();
    for (double a : r.angles.angles) angles.push_back(a);
    return {{"point", {q.x(), q.y()}},
            {"same_side", {{"inside", r.sides.inside},
                           {"on_boundary", r.sides.onBoundary},
                           {"orientation", r.sides.orientation},
                           {"sides", r.sides.sides},
                           {"first_outer_edge", r.sides.firstOuterEdge}}},
            {"angle_sum", {{"inside", r.angles.inside},
                           {"on_boundary", r.angles.onBoundary},
                           {"angles", angles},
                           {"total", r.angles.total},
                           {"winding", r.angles.winding}}},
            {"crossing_number", {{"inside", r.crossing.inside},
                                 {"on_boundary", r.crossing.onBoundary},
                                 {"edges", r.crossing.crossingEdges},
                                 {"x", r.crossing.crossingX}}}};
}

std::string inOut(bool inside, bool boundary) { return boundary ? "on the boundary" : inside ? "in" : "out"; }

std::string sideText(const PointRun& r) {
    if (r.sides.orientation == 0) return "zero area: out";
    if (r.sides.firstOuterEdge >= 0) return "outside edge " + std::to_string(r.sides.firstOuterEdge + 1) + ": out";
    return inOut(true, r.sides.onBoundary);
}

std::string angleText(const PointRun& r) {
    if (r.angles.onBoundary) return "on the boundary";
    // Off the boundary the sum is a whole number of turns up to rounding: three decimals show it.
    const double turns = std::round(r.angles.total / (2 * std::numbers::pi) * 1000.0) / 1000.0;
    return "sum " + formatNumber(turns) + "·2π: winding " +
           std::to_string(r.angles.winding) + ", " + inOut(r.angles.inside, false);
}

std::string crossingText(const PointRun& r) {
    if (r.crossing.onBoundary) return "on the boundary";
    const std::size_t n = r.crossing.crossingEdges.size();
    return std::to_string(n) + (n == 1 ? " crossing: " : " crossings: ") + inOut(r.crossing.inside, false);
}

/// The three panels' placement: one world-to-pixel scale, the polygon's copy k shifted by offset(k).
struct PanelLayout {
    double scale = 1;        // pixels per world unit
    Vec2 polygonCentre;      // of the polygon's bounding box
    double panelWidth = 0;   // pixels
    double pictureTop = 0, pictureBottom = 0;  // pixel rows (from the top) of the drawing area
    Camera camera;
    Vec3 offset(int k) const { return Vec3(panelWidth * k / scale, 0, 0); }
};

PanelLayout layoutPanels(const PointInPolygonInput& in, int W, int H, double numbersHeight) {
    PanelLayout L;
    Vec2 lo = in.polygon[0], hi = in.polygon[0];
    for (const Vec2& v : in.polygon) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    for (const Vec2& q : in.queries) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const Vec2 size = (hi - lo).cwiseMax(Vec2::Constant(1e-3 * std::max(1.0, (hi - lo).maxCoeff())));
    L.polygonCentre = 0.5 * (lo + hi);
    L.panelWidth = W / 3.0;
    L.pictureTop = 150;
    L.pictureBottom = H - numbersHeight - 60;
    const double ph = L.pictureBottom - L.pictureTop;
    // The crossing-number rays leave the polygon to the right: room for them inside the panel.
    L.scale = std::min(0.78 * L.panelWidth / size.x(), 0.9 * ph / size.y());
    const double viewHeight = H / L.scale;
    // Panel 0's polygon centre at pixel (panelWidth / 2, middle of the picture area).
    const double cx = L.polygonCentre.x() + (W / 2.0 - L.panelWidth / 2.0) / L.scale;
    const double cy = L.polygonCentre.y() - (H / 2.0 - 0.5 * (L.pictureTop + L.pictureBottom)) / L.scale;
    L.camera = Camera::twoD(cx, cy, viewHeight);
    return L;
}

Vec3 at(const Vec2& p, const Vec3& offset) { return Vec3(p.x(), p.y(), 0) + offset; }

Frame drawFigure(GlContext& gl, const SceneCommon& scene, int scale, const PointInPolygonInput& in,
                 const std::vector<PointRun>& runs) {
    const int W = scene.image.width, H = scene.image.height;
    const bool numbers = scene.hasLayer("numbers"), labels = scene.hasLayer("labels");
    const double numbersHeight = numbers ? kNumberLineHeight * double(in.queries.size()) + 20 : 0;
    const PanelLayout L = layoutPanels(in, W, H, numbersHeight);
    Canvas c(gl, canvasOptions(W, H, scale));
    c.setCamera(L.camera);
    const char* headings[3] = {"same side of every edge", "angle summation", "crossing number"};
    const char* costs[3] = {"n orientation tests; right for convex only", "n atan2; nonzero rule (windings)",
                            "n edge tests, ray to +x; even-odd rule"};
    const TextStyle head{21.0f, roleColor(Role::Ink), Anchor::Top, true, true};
    const TextStyle sub{17.0f, roleColor(Role::Ink), Anchor::Top, true, false};
    const double rayEnd = L.polygonCentre.x() + 0.39 * L.panelWidth / L.scale;
    for (int k = 0; k < 3; ++k) {
        const Vec3 off = L.offset(k);
        c.drawTextPx(L.panelWidth * (k + 0.5), 70, headings[k], head);
        c.drawTextPx(L.panelWidth * (k + 0.5), 100, costs[k], sub);
        std::vector<Vec3> outline;
        for (const Vec2& v : in.polygon) outline.push_back(at(v, off));
        c.drawPolyline(outline, true, lineStyle(Role::ShapeA, 3.0f));
        // The edges' direction (the sides and the angles' signs depend on it): a head mid-edge.
        for (std::size_t e = 0; e < outline.size(); ++e) {
            const Vec3 &p = outline[e], &q = outline[(e + 1) % outline.size()];
            const Vec3 mid = 0.5 * (p + q), half = 11.0 / L.scale * (q - p).normalized();  // 22 px long
            c.drawArrow(mid - half, mid + half, lineStyle(Role::ShapeA, 3.0f));
        }
        if (labels)
            for (std::size_t e = 0; e < in.polygon.size() && k == 0; ++e) {
                // Edge numbers in the first panel: the edge-side test names the edge that rejects.
                const Vec3 mid = 0.5 * (outline[e] + outline[(e + 1) % outline.size()]);
                TextStyle ts{18.0f, roleColor(Role::ShapeA).scaled(0.6f), Anchor::Center, true, true};
                ts.place = true;
                c.drawText(mid, std::to_string(e + 1), ts);
            }
        for (std::size_t i = 0; i < in.queries.size(); ++i) {
            const PointRun& r = runs[i];
            const Vec3 q = at(in.queries[i], off);
            if (k == 2 && !r.crossing.onBoundary) {
                const double end = std::max(rayEnd + off.x(), q.x() + 0.06 * L.panelWidth / L.scale);
                c.drawLine(q, Vec3(end, q.y(), 0), lineStyle(Role::Direction, 1.5f));
                for (double x : r.crossing.crossingX)
                    c.drawPoint(Vec3(x + off.x(), q.y(), 0), 4.5f, roleColor(Role::Direction));
            }
            const bool inside = k == 0 ? r.sides.inside : k == 1 ? r.angles.inside : r.crossing.inside;
            c.drawPoint(q, 8.0f, roleColor(inside ? Role::Result : Role::Muted), true, 2.0f, roleColor(Role::Ink));
            if (labels) {
                TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                ts.offsetPx = Eigen::Vector2d(-22, -16);
                ts.place = true;
                c.drawText(q, "q" + std::to_string(i + 1), ts);
            }
        }
    }
    drawKey(c, 20, L.pictureBottom + 8, {{roleColor(Role::Result), "the test says inside"}, {roleColor(Role::Muted), "outside"}},
            16.0f);
    if (numbers) {
        std::vector<std::string> lines;
        for (std::size_t i = 0; i < in.queries.size(); ++i)
            lines.push_back("q" + std::to_string(i + 1) + " (" + formatNumber(in.queries[i].x()) + ", " +
                            formatNumber(in.queries[i].y()) + "):  same side: " + sideText(runs[i]) +
                            ";  angles: " + angleText(runs[i]) + ";  " + crossingText(runs[i]));
        drawNumberBlock(c, lines, 52);
    }
    return finishedFrame(c, scene.title, scene.caption, "tests", scene.title);
}

}  // namespace

DemoOutput runPointInPolygon(const SceneCommon& scene, const PointInPolygonInput& in, const RunContext& ctx) {
    const std::vector<PointRun> runs = runTests(in);
    DemoOutput out;
    Json points = Json::array();
    for (std::size_t i = 0; i < in.queries.size(); ++i) points.push_back(pointJson(in.queries[i], runs[i]));
    Json polygon = Json::array();
    for (const Vec2& v : in.polygon) polygon.push_back({v.x(), v.y()});
    out.trace = {{"test", "point_in_polygon"}, {"polygon", polygon}, {"queries", points}};
    if (numericOnly(ctx, out)) return out;
    out.frames.push_back(drawFigure(*ctx.gl, scene, figureScale(scene, ctx), in, runs));
    return out;
}

}  // namespace cdlab::demos
