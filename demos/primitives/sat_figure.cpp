// The separating-axis family of the primitives demo: box-box (15 axes, Ericson §4.4.1),
// segment-box (6, §5.3.3) and triangle-AABB (13, §5.2.9 after Akenine-Möller 2001). Every axis
// core tested is listed with the two projected intervals and the gap between them; the test stops
// at the first separating axis, so the rest are listed as not tested. When nothing separates, the
// axis of least overlap is the one a contact generator would take. Numbers: core/overlap/sat_tests.h.
#include <algorithm>
#include <cmath>

#include "core/overlap/sat_tests.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/zoom_inset.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

namespace {

using namespace render;
using K = PrimitiveShape::Kind;

bool isBox(const PrimitiveShape& s) { return s.kind == K::Aabb || s.kind == K::Obb; }

/// The pair as core sees it: `box` is core's A (projections are measured from its centre).
struct SatPair {
    const PrimitiveShape* box = nullptr;
    const PrimitiveShape* other = nullptr;  // the second box, the segment or the triangle
    bool boxIsA = true;                 // the scene's "a" is the box
    std::string boxName, otherName;     // as written in the figure
};

SatPair pairOf(const SatInput& in) {
    SatPair p;
    p.boxIsA = isBox(in.a);
    p.box = p.boxIsA ? &in.a : &in.b;
    p.other = p.boxIsA ? &in.b : &in.a;
    if (isBox(*p.other)) {
        p.boxName = "A";
        p.otherName = "B";
    } else {
        p.boxName = "box";
        p.otherName = p.other->kind == K::Segment ? "segment" : "triangle";
    }
    return p;
}

/// Every candidate axis's name in core's order (tested or not).
std::vector<std::string> axisNames(const SatPair& p) {
    std::vector<std::string> names;
    if (p.other->kind == K::Obb || p.other->kind == K::Aabb) {
        for (int i = 1; i <= 3; ++i) names.push_back("A" + std::to_string(i) + " (face of A)");
        for (int j = 1; j <= 3; ++j) names.push_back("B" + std::to_string(j) + " (face of B)");
        for (int i = 1; i <= 3; ++i)
            for (int j = 1; j <= 3; ++j) names.push_back("A" + std::to_string(i) + " × B" + std::to_string(j));
    } else if (p.other->kind == K::Segment) {
        for (int i = 1; i <= 3; ++i) names.push_back("box axis " + std::to_string(i));
        for (int i = 1; i <= 3; ++i) names.push_back("box axis " + std::to_string(i) + " × segment");
    } else {
        const char* axis[3] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) names.push_back(std::string(axis[i]) + " × edge " + std::to_string(j + 1));
        for (int i = 0; i < 3; ++i) names.push_back(std::string(axis[i]) + " (box face)");
        names.push_back("triangle normal");
    }
    return names;
}

/// One tested axis in length units: intervals along the unit axis from the box's centre.
struct AxisRow {
    std::string name;
    Vec3 unit = Vec3::Zero();
    bool zero = false;  // parallel edges: the cross product vanishes, the axis cannot separate
    double boxLo = 0, boxHi = 0, otherLo = 0, otherHi = 0;
    double gap = 0;  // > 0: the intervals are apart by gap; <= 0: they overlap by -gap
    bool separating = false;
};

struct SatRun {
    SatPair pair;
    SatResult result;
    std::vector<std::string> names;
    std::vector<AxisRow> rows;  // the tested axes, in order
    int leastOverlap = -1;      // when nothing separates: the row of least depth (the first of equals; not a zero axis)
};

SatRun runSatTest(const SatInput& in) {
    SatRun run;
    run.pair = pairOf(in);
    run.names = axisNames(run.pair);
    const PrimitiveShape& box = *run.pair.box;
    const PrimitiveShape& other = *run.pair.other;
    SatTrace trace;
    if (isBox(other)) run.result = testObbObb(box.box, other.box, &trace);
    else if (other.kind == K::Segment) run.result = testSegmentObb({other.vertices[0], other.vertices[1]}, box.box, &trace);
    else run.result = testTriangleAabb({other.vertices[0], other.vertices[1], other.vertices[2]}, box.aabb(), &trace);
    for (std::size_t k = 0; k < trace.steps.size(); ++k) {
        const SatAxisStep& s = trace.steps[k];
        AxisRow row;
        row.name = k < run.names.size() ? run.names[k] : "axis " + std::to_string(k + 1);
        row.separating = s.separating;
        const double len = s.axis.norm();
        // A cross product of (nearly) parallel directions: its intervals are rounding, not lengths.
        row.zero = !(len > 1e-12);
        if (!row.zero) {
            row.unit = s.axis / len;
            row.boxLo = s.minA / len;
            row.boxHi = s.maxA / len;
            row.otherLo = s.minB / len;
            row.otherHi = s.maxB / len;
            row.gap = std::max(row.otherLo - row.boxHi, row.boxLo - row.otherHi);
        }
        run.rows.push_back(row);
    }
    if (run.result.hit)
        for (std::size_t k = 0; k < run.rows.size(); ++k)
            if (!run.rows[k].zero && (run.leastOverlap < 0 || run.rows[k].gap > run.rows[std::size_t(run.leastOverlap)].gap))
                run.leastOverlap = int(k);
    return run;
}


Json satJson(const SatInput& in, const SatRun& run) {
    Json axes = Json::array();
    for (const AxisRow& r : run.rows) {
        Json a = {{"name", r.name}, {"zero_axis", r.zero}, {"separating", r.separating}};
        if (!r.zero) {
            a["axis"] = vec3Json(r.unit);
            a[run.pair.boxName] = {r.boxLo, r.boxHi};
            a[run.pair.otherName] = {r.otherLo, r.otherHi};
            a["gap"] = r.gap;
        }
        axes.push_back(a);
    }
    Json j = {{"test", "sat"},
              {"a", nameOf(in.a.kind)},
              {"b", nameOf(in.b.kind)},
              {"intersect", run.result.hit},
              {"candidate_axes", run.names.size()},
              {"tested_axes", run.rows.size()},
              {"axes", axes}};
    if (!run.result.hit) j["separating_axis"] = run.rows.back().name;
    if (run.leastOverlap >= 0) j["least_overlap_axis"] = run.rows[std::size_t(run.leastOverlap)].name;
    return j;
}

// -------------------------------------------------------------------------------------- picture

void drawShape(Canvas& c, const PrimitiveShape& s, Role role) {
    if (isBox(s)) {
        drawBody(c, boxDrawable(s.box), roleColor(role), 0.22f, roleColor(role).scaled(0.7f), 3.0f);
    } else if (s.kind == K::Segment) {
        c.drawLine(s.vertices[0], s.vertices[1], lineStyle(role, 6.0f));
        for (const Vec3& v : s.vertices) c.drawPoint(v, 6.0f, roleColor(role));
    } else {
        c.drawPolygon(s.vertices, roleColor(role).withAlpha(0.3f), true);
        c.drawPolyline(s.vertices, true, lineStyle(role, 3.0f));
    }
}

Vec3 centreOf(const PrimitiveShape& s) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : s.vertices) c += v;
    return c / double(s.vertices.size());
}

/// Where the deciding axis is drawn: a line along it beside the shapes (offset across it on the
/// screen, below or left of them), on which each shape's projection is an interval.
struct AxisLine {
    Vec3 base = Vec3::Zero();  // the box's centre moved off the shapes; interval k lies at base + k * unit
    Vec3 across = Vec3::Zero();  // unit, across the axis: the two intervals sit either side of the line
    double lo = 0, hi = 0;     // the drawn stretch of k
};

AxisLine placeAxisLine(const AxisRow& row, const Vec3& origin, const std::vector<Vec3>& vertices, const Vec3& view,
                       const Vec3& up, double size) {
    const Vec3 back = view.normalized();
    const Vec3 screenUp = (up - up.dot(back) * back).normalized();
    const Vec3 right = screenUp.cross(back);
    // Across the axis on the screen, pointing down (or left when the axis lies across the screen).
    Eigen::Vector2d s(row.unit.dot(right), row.unit.dot(screenUp));
    Eigen::Vector2d across = s.norm() > 1e-9 ? Eigen::Vector2d(-s.y(), s.x()).normalized() : Eigen::Vector2d(0, -1);
    if (across.y() > 0.2 || (std::abs(across.y()) <= 0.2 && across.x() > 0)) across = -across;
    Vec3 off = across.x() * right + across.y() * screenUp;
    off -= off.dot(row.unit) * row.unit;  // move across the axis only: the intervals stay where they are
    off = off.norm() > 1e-12 ? Vec3(off.normalized()) : row.unit.unitOrthogonal();
    double reach = 0;
    for (const Vec3& v : vertices) reach = std::max(reach, (v - origin).dot(off));
    AxisLine line;
    line.base = origin + off * (reach + 0.3 * size);
    line.across = off;
    const double lo = std::min(row.boxLo, row.otherLo), hi = std::max(row.boxHi, row.otherHi);
    const double pad = 0.2 * std::max(hi - lo, 1e-3 * size);
    line.lo = lo - pad;
    line.hi = hi + pad;
    return line;
}

Image satPicture(GlContext& gl, const SceneCommon& scene, int scale, int height, const SatInput& in, const SatRun& run) {
    std::vector<Vec3> vertices;
    for (const PrimitiveShape* s : {&in.a, &in.b}) vertices.insert(vertices.end(), s->vertices.begin(), s->vertices.end());
    Eigen::AlignedBox3d frame;
    for (const Vec3& v : vertices) frame.extend(v);
    const double size = frame.diagonal().norm();
    // The axis drawn beside the shapes: the row that decides (separating, or least depth).
    const AxisRow* shown = !run.result.hit ? &run.rows.back()
                           : run.leastOverlap >= 0 ? &run.rows[std::size_t(run.leastOverlap)]
                                                   : nullptr;
    if (shown && shown->zero) shown = nullptr;
    // Seen across that axis (it lies in the picture's plane), a gap along it shows as a gap.
    const Vec3 view = shown ? viewAcross(Vec3(1.0, 0.8, 1.7), shown->unit) : Vec3(1.0, 0.8, 1.7);
    const Vec3 origin = run.pair.box->box.center;  // core measures the projections from the box's centre
    AxisLine line;
    std::vector<Vec3> drawn = vertices;
    if (shown) {
        line = placeAxisLine(*shown, origin, vertices, view, Vec3::UnitY(), size);
        drawn.push_back(line.base + line.lo * shown->unit);
        drawn.push_back(line.base + line.hi * shown->unit);
    }
    Camera cam = viewAbove(drawn, view, Vec3::UnitY(), 1.0, scene.image.width, height);
    if (scene.camera) cam = *scene.camera;
    Canvas c(gl, canvasOptions(scene.image.width, height, scale));
    c.setCamera(cam);
    const Role roleOf[2] = {Role::ShapeA, Role::ShapeB};
    const std::string nameA = run.pair.boxIsA ? run.pair.boxName : run.pair.otherName;
    const std::string nameB = run.pair.boxIsA ? run.pair.otherName : run.pair.boxName;
    const auto at = [&](double k) { return Vec3(line.base + k * shown->unit); };
    // The shapes, the axis, the dashed projections and the two intervals: the picture, and again
    // in the inset that magnifies a gap or depth drawn under 12 px.
    const auto drawGeometry = [&](Canvas& on) {
        on.setStrokeOwner(bodyOwner(nameA));
        drawShape(on, in.a, roleOf[0]);
        on.setStrokeOwner(bodyOwner(nameB));
        drawShape(on, in.b, roleOf[1]);
        on.setStrokeOwner(0);
        if (!shown) return;
        on.drawArrow(at(line.lo), at(line.hi), lineStyle(Role::Muted, 2.0f, false, true));
        // Each interval's ends come from a shape's extreme points along the axis: dashed lines show which.
        for (const PrimitiveShape* s : {&in.a, &in.b}) {
            const Vec3* lo = &s->vertices.front();
            const Vec3* hi = lo;
            for (const Vec3& v : s->vertices) {
                if (v.dot(shown->unit) < lo->dot(shown->unit)) lo = &v;
                if (v.dot(shown->unit) > hi->dot(shown->unit)) hi = &v;
            }
            for (const Vec3* v : {lo, hi})
                on.drawLine(*v, at((*v - origin).dot(shown->unit)), lineStyle(Role::Muted, 1.5f, true));
        }
        const Role boxRole = run.pair.boxIsA ? roleOf[0] : roleOf[1];
        const Role otherRole = run.pair.boxIsA ? roleOf[1] : roleOf[0];
        // Side by side across the line, so that an overlap shows both bars.
        const Vec3 apart = 0.012 * size * line.across;
        on.drawLine(at(shown->boxLo) - apart, at(shown->boxHi) - apart, lineStyle(boxRole, 8.0f, false, true));
        on.drawLine(at(shown->otherLo) + apart, at(shown->otherHi) + apart, lineStyle(otherRole, 8.0f, false, true));
    };
    drawGeometry(c);
    const bool labels = scene.hasLayer("labels");
    if (labels) {
        // Two boxes deep in each other: the larger one's name moves onto a part the other leaves free.
        std::pair<Vec3, Vec3> names{centreOf(in.a), centreOf(in.b)};
        if (isBox(in.a) && isBox(in.b)) names = bodyNamePoints(boxDrawable(in.a.box), boxDrawable(in.b.box));
        drawBodyName(c, names.first, nameA, Role::Ink);
        drawBodyName(c, names.second, nameB, Role::Ink);
        // A triangle's edges numbered as the table's axes name them (core: edge j + 1 runs from
        // vertex j to vertex j + 1), outside the triangle at each edge's middle.
        for (const PrimitiveShape* s : {&in.a, &in.b}) {
            if (s->kind != K::Triangle) continue;
            const Vec3 centroid = (s->vertices[0] + s->vertices[1] + s->vertices[2]) / 3.0;
            for (int j = 0; j < 3; ++j) {
                const Vec3 mid = 0.5 * (s->vertices[std::size_t(j)] + s->vertices[std::size_t((j + 1) % 3)]);
                drawLabelAway(c, mid, centroid, "edge " + std::to_string(j + 1), labelStyle(Role::Ink, 18.0f, false),
                              8.0);
            }
        }
    }
    if (!shown) {
        drawTitleAndCaption(c, scene.title, "");
        return c.readPixels();
    }
    // The gap (or the depth, the shorter push) the frame names, between the bars' ends.
    ZoomTarget quantity;
    quantity.name = shown->gap > 0 ? "gap" : "depth";
    quantity.heading = quantity.name + " " + formatNumber(std::abs(shown->gap));
    if (shown->otherLo - shown->boxHi >= shown->boxLo - shown->otherHi) quantity.p = at(shown->boxHi), quantity.q = at(shown->otherLo);
    else quantity.p = at(shown->otherHi), quantity.q = at(shown->boxLo);
    quantity.draw = drawGeometry;
    c.noteQuantity(quantity.name, quantity.p, quantity.q);
    if (labels) {
        // Past the axis's arrowhead, along it (on the axis's middle it crossed the axis and the
        // dashed projection lines).
        TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
        Eigen::Vector2d lo2, hi2, along(0, 1);
        if (c.project(at(line.lo), lo2) && c.project(at(line.hi), hi2) && (hi2 - lo2).norm() > 1)
            along = (hi2 - lo2).normalized();
        ts.offsetPx = 24.0 * along;
        ts.place = true;
        const std::string what = !run.result.hit ? "separating axis " + shown->name + ": gap " + formatNumber(shown->gap)
                                                 : "least depth: " + shown->name + ", depth " + formatNumber(-shown->gap);
        c.drawText(at(line.hi), what, ts);
    }
    drawTitleAndCaption(c, scene.title, "");
    return readPixelsZoomed(gl, c, scale, quantity, Box{14.0, 60.0, scene.image.width - 14.0, height - 14.0});
}

// ---------------------------------------------------------------------------------------- table

/// One row per candidate axis: its name, the two intervals to scale (each row its own scale, the
/// union of the two intervals), the gap or the overlap; rows after the separating axis not tested.
Image satTable(GlContext& gl, const SceneCommon& scene, int scale, int height, const SatRun& run) {
    const int W = scene.image.width, H = height;
    Canvas c(gl, canvasOptions(W, H, scale), Camera::pixels(W, H));  // world = pixels, y up
    auto P = [](double x, double y) { return Vec3(x, y, 0); };
    const double rowH = 27, top = H - 20;
    const double nameX = 20, barX0 = 330, barX1 = 700, textX = 730;
    const TextStyle ink{18.0f, roleColor(Role::Ink), Anchor::Left, true, false};
    TextStyle bold = ink;
    bold.bold = true;
    TextStyle muted = ink;
    muted.color = roleColor(Role::Muted).scaled(0.8f);
    const Role boxRole = run.pair.boxIsA ? Role::ShapeA : Role::ShapeB;
    const Role otherRole = run.pair.boxIsA ? Role::ShapeB : Role::ShapeA;
    const Color deciding = roleColor(Role::Background).mixed(roleColor(Role::Highlight), 0.25f);  // a light band
    c.drawText(P(nameX, top - 0.5 * rowH), "candidate axis", bold);
    c.drawText(P(barX0, top - 0.5 * rowH), "projections on the axis", bold);
    c.drawText(P(textX, top - 0.5 * rowH), "gap, or depth to push them apart", bold);
    for (std::size_t k = 0; k < run.names.size(); ++k) {
        const double y = top - rowH * (double(k) + 1.5);
        if (k >= run.rows.size()) {
            c.drawText(P(nameX, y), run.names[k], muted);
            c.drawText(P(barX0, y), "not tested: an earlier axis separates", muted);
            continue;
        }
        const AxisRow& r = run.rows[k];
        const bool decisive = r.separating || int(k) == run.leastOverlap;
        if (decisive) {
            LineStyle band = lineStyle(Role::Highlight, float(rowH - 4));
            band.color = deciding;
            c.drawLine(P(nameX - 10, y), P(W - 20, y), band);
        }
        c.drawText(P(nameX, y), r.name, decisive ? bold : ink);
        if (r.zero) {
            c.drawText(P(barX0, y), "zero axis (parallel edges): cannot separate", ink);
            continue;
        }
        const double lo = std::min(r.boxLo, r.otherLo), hi = std::max(r.boxHi, r.otherHi);
        const double span = hi > lo ? hi - lo : 1.0;
        auto X = [&](double v) { return barX0 + (v - lo) / span * (barX1 - barX0); };
        c.drawLine(P(X(r.boxLo), y + 5), P(std::max(X(r.boxHi), X(r.boxLo) + 2), y + 5), lineStyle(boxRole, 7.0f));
        c.drawLine(P(X(r.otherLo), y - 5), P(std::max(X(r.otherHi), X(r.otherLo) + 2), y - 5), lineStyle(otherRole, 7.0f));
        // -gap is the shorter push that separates the intervals (not their common length when one holds the other).
        std::string text = r.gap > 0 ? "gap " + formatNumber(r.gap) : "depth " + formatNumber(-r.gap);
        if (r.separating) text += ": separates, stop";
        else if (int(k) == run.leastOverlap) text += ": the least depth (first of equals)";
        c.drawText(P(textX, y), text, decisive ? bold : ink);
    }
    drawKey(c, nameX, H - (top - rowH * (double(run.names.size()) + 1.2)),
            {{roleColor(boxRole), run.pair.boxName + "'s interval (upper bar)"},
             {roleColor(otherRole), run.pair.otherName + "'s interval (lower bar)"},
             {deciding, "the deciding axis"}},
            18.0f);
    drawTitleAndCaption(c, "", scene.caption);
    return c.readPixels();
}

}  // namespace

DemoOutput runSat(const SceneCommon& scene, const SatInput& in, const RunContext& ctx) {
    const SatRun run = runSatTest(in);
    DemoOutput out;
    out.trace = satJson(in, run);
    if (numericOnly(ctx, out)) return out;
    const int scale = figureScale(scene, ctx);
    Frame f;
    f.name = "axes";
    f.caption = scene.title + ": " +
                (run.result.hit ? "no axis separates (" + std::to_string(run.rows.size()) + " tested)"
                                : "separated on " + run.rows.back().name);
    if (!scene.hasLayer("numbers")) {
        f.image = satPicture(*ctx.gl, scene, scale, scene.image.height, in, run);
    } else {
        const int tableH = int(27 * (double(run.names.size()) + 2.2) + 20 + 70);
        f.image = stackVertically(satPicture(*ctx.gl, scene, scale, scene.image.height - tableH, in, run),
                                  satTable(*ctx.gl, scene, scale, tableH, run));
    }
    out.frames.push_back(std::move(f));
    return out;
}

}  // namespace cdlab::demos
