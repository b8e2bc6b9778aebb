// The mtd_backtracking demo's frames, seen from above (everything lies in the plane z = 0): one per
// correction — the MTD, backtracking, conservative advancement step by step — and the three end poses
// compared. Numbers from resolution.h; this file only draws.
#include "demos/mtd_backtracking/resolution_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr double kTitleBand = 70;      // pixels under the top edge: the title
constexpr double kLineHeight = 26;     // the numbers block
constexpr float kNumberPx = 18.0f;

/// A 2D view framing `points` between the title and a block of `lines` lines of numbers.
Camera frameAbove(const std::vector<Vec3>& points, int W, int H, int lines) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : points) box.extend(p);
    const double bottom = 52 + kLineHeight * lines + 16;
    const double band = std::max(H - kTitleBand - bottom, 0.3 * H);
    const Vec3 size = box.sizes().cwiseMax(Vec3::Constant(1e-6));
    const double scale = std::min(0.86 * W / size.x(), 0.86 * band / size.y());
    const double rowMid = kTitleBand + 0.5 * band;
    const Vec3 c = box.center();
    return Camera::twoD(c.x(), c.y() - (0.5 * H - rowMid) / scale, H / scale);
}

void drawNumbers(Canvas& canvas, const std::vector<std::string>& lines) {
    const TextStyle ts{kNumberPx, roleColor(Role::Ink), Anchor::TopLeft, true, false};
    double y = canvas.height() - 52 - kLineHeight * double(lines.size());
    for (const std::string& l : lines) {
        canvas.drawTextPx(20, y, l, ts);
        y += kLineHeight;
    }
}

std::vector<Vec3> outlineOfA(const ResolutionInput& in) {
    std::vector<Vec3> a;
    for (const Vec2& p : in.a) a.emplace_back(p.x(), p.y(), 0.0);
    return a;
}

void drawA(Canvas& c, const ResolutionInput& in, bool labels) {
    const std::vector<Vec3> a = outlineOfA(in);
    c.drawPolygon(a, roleColor(Role::ShapeA).withAlpha(0.30f));
    c.drawPolyline(a, true, lineStyle(Role::ShapeA, 3.0f));
    if (labels) {
        Vec3 centre = Vec3::Zero();
        for (const Vec3& p : a) centre += p;
        drawBodyNameAt(c, centre / double(a.size()), "A");
    }
}

/// B at a pose: `ghost` faint and dashed (where it was, or would be), else filled with a solid outline.
void drawB(Canvas& c, const ResolutionInput& in, const Transform& pose, Color color, bool ghost) {
    const std::vector<Vec3> b = outlineAt(in.b, pose);
    if (!ghost) c.drawPolygon(b, color.withAlpha(0.35f));
    LineStyle ls;
    ls.widthPx = ghost ? 2.0f : 3.0f;
    ls.color = ghost ? color.withAlpha(0.7f) : color;
    ls.dashPx = ghost ? 8.0f : 0.0f;
    c.drawPolyline(b, true, ls);
}

TextStyle noteStyle(float size = 19.0f, bool bold = false) {
    TextStyle ts{size, roleColor(Role::Ink), Anchor::Center, true, bold};
    ts.place = true;
    return ts;
}

/// A label that names a dashed outline: placed off its anchor, with a leader line when it moves.
TextStyle awayStyle() {
    TextStyle ts = noteStyle();
    ts.offsetPx = Eigen::Vector2d(90, 50);
    return ts;
}

/// Where to name B's pose at t = 1 (a dashed outline under the frame's other poses): the point of
/// its outline (corners and edge midpoints) farthest from everything else the frame draws there,
/// `others` (the other poses' centres, a marked point): the part a reader sees (the review: "B at
/// t = 1" floated 40 px from an outline hidden under the MTD bar).
Vec3 endAnchor(const ResolutionInput& in, const ResolutionRun& run, std::initializer_list<Vec3> others) {
    const std::vector<Vec3> outline = outlineAt(in.b, run.end);
    std::vector<Vec3> candidates = outline;
    for (std::size_t i = 0; i < outline.size(); ++i) candidates.push_back(0.5 * (outline[i] + outline[(i + 1) % outline.size()]));
    Vec3 best = run.end.position;
    double bestDistance = -1;
    for (const Vec3& p : candidates) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const Vec3& o : others) nearest = std::min(nearest, (p - o).norm());
        if (nearest > bestDistance) bestDistance = nearest, best = p;
    }
    return best;
}

std::string pose(const Transform& p) {
    return "(" + formatNumber(p.position.x()) + ", " + formatNumber(p.position.y()) + ") at " +
           formatNumber(angleDegrees(p)) + "°";
}

}  // namespace

void drawBodyNameAt(Canvas& canvas, const Vec3& at, const std::string& name) {
    TextStyle ts{26.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    ts.place = true;
    canvas.drawText(at, name, ts);
}

std::vector<Vec3> framedPoints(const ResolutionInput& in, const ResolutionRun& run) {
    std::vector<Vec3> pts = outlineOfA(in);
    for (const Transform* p : {&in.start, &run.end, &run.mtd, &run.backtrack, &run.advanced}) {
        const std::vector<Vec3> b = outlineAt(in.b, *p);
        pts.insert(pts.end(), b.begin(), b.end());
    }
    return pts;
}

Frame mtdFrame(GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& in, const ResolutionRun& run) {
    const bool labels = scene.hasLayer("labels"), numbers = scene.hasLayer("numbers");
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera : frameAbove(framedPoints(in, run), scene.image.width, scene.image.height, 3));
    drawA(c, in, labels);
    std::vector<std::string> lines;
    if (run.penetrating) {
        drawB(c, in, run.mtd, roleColor(Role::ShapeB), false);
        drawB(c, in, run.end, roleColor(Role::ShapeB), true);  // dashed, over the fill: where B was
        c.drawArrow(run.pointB, run.pointB + run.depth * run.normal, lineStyle(Role::Result, 4.0f, false, true));
        c.drawPoint(run.pointB, 6.0f, roleColor(Role::Result));
        if (labels) {
            c.drawText(endAnchor(in, run, {run.mtd.position, run.pointB}), "B at t = 1", noteStyle());
            c.drawText(run.mtd.position, "B + depth·n", noteStyle(19.0f, true));
            TextStyle ts = noteStyle();
            ts.offsetPx = Eigen::Vector2d(0, 28);
            c.drawText(run.pointB + 0.5 * run.depth * run.normal, "depth·n", ts);
        }
        lines = {"EPA at t = 1: depth " + formatNumber(run.depth) + ", normal n = (" + formatNumber(run.normal.x()) + ", " +
                     formatNumber(run.normal.y()) + ") from A toward B",
                 "B moved by depth·n to " + pose(run.mtd) + ": touching, by the shortest push — across the contact, "
                 "not back along the motion",
                 "a push along n, not a step back in time: the pose need not be one B passed through"};
    } else {
        drawB(c, in, run.end, roleColor(Role::ShapeB), true);
        lines = {"at t = 1 the bodies do not overlap: nothing to correct"};
    }
    if (numbers) drawNumbers(c, lines);
    return finishedFrame(c, scene.title + ": minimum translational distance", scene.caption, "mtd",
                  run.penetrating ? "MTD: depth " + formatNumber(run.depth) : "MTD: no penetration");
}

Frame backtrackFrame(GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& in,
                     const ResolutionRun& run) {
    const bool labels = scene.hasLayer("labels"), numbers = scene.hasLayer("numbers");
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera : frameAbove(framedPoints(in, run), scene.image.width, scene.image.height, 3));
    drawA(c, in, labels);
    Transform from = run.end;
    from.position = in.start.position;
    drawB(c, in, from, roleColor(Role::Muted), true);
    drawB(c, in, run.end, roleColor(Role::ShapeB), true);
    c.drawArrow(from.position, run.end.position, lineStyle(Role::Ink, 2.0f, false, true));
    if (labels) {
        c.drawText(endAnchor(in, run, {run.backtrack.position, in.start.position, run.backtrackPoint}), "B at t = 1", noteStyle());
        c.drawText(from.position, "t = 0, turned as at t = 1", awayStyle());
    }
    std::vector<std::string> lines;
    if (run.backtrackHit && !run.backtrackAtStart) {
        drawB(c, in, run.backtrack, roleColor(Role::ShapeB), false);
        c.drawPoint(run.backtrackPoint, 7.0f, roleColor(Role::Result));
        if (labels) c.drawText(run.backtrack.position, "B at t = " + formatNumber(run.backtrackT), noteStyle(19.0f, true));
        const double back = (1.0 - run.backtrackT) * in.motion.linear.norm();
        lines = {"the linear cast along the motion (B turned as at t = 1): first contact at t = " +
                     formatNumber(run.backtrackT) + ", normal (" + formatNumber(run.backtrackNormal.x()) + ", " +
                     formatNumber(run.backtrackNormal.y()) + ")",
                 "B backed up by (1 − t)·|linear| = " + formatNumber(back) + " to " + pose(run.backtrack) +
                     ": touching, on the straight path with the turn held — not a pose B occupied while turning",
                 "the turn is held at its t = 1 value: exact for a sliding body, not for a spinning one"};
    } else if (run.backtrackAtStart) {
        lines = {"turned as at t = 1, B already overlaps A at t = 0: backtracking along the motion cannot separate them"};
    } else {
        lines = {"the linear cast meets nothing in [0, 1]"};
    }
    if (numbers) drawNumbers(c, lines);
    return finishedFrame(c, scene.title + ": backtracking along the motion (linear cast)", scene.caption, "backtrack",
                  run.backtrackHit ? "backtrack: t = " + formatNumber(run.backtrackT) : "backtrack: no contact");
}

Frame advanceFrame(GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& in,
                   const ResolutionRun& run) {
    const bool labels = scene.hasLayer("labels"), numbers = scene.hasLayer("numbers");
    const auto& steps = run.advanceTrace.steps;
    // The steps' numbers: one line each for the first few and the last, the rest summed up.
    std::vector<std::string> lines;
    const std::size_t shown = std::min<std::size_t>(steps.size(), 5);
    for (std::size_t i = 0; i < steps.size(); ++i) {
        if (i >= shown - 1 && i + 1 < steps.size()) continue;
        const AdvancementStep& s = steps[i];
        std::string l = "step " + std::to_string(i + 1) + ": t = " + formatNumber(s.t) + ", distance " + formatNumber(s.distance);
        if (s.speedBound > 0) l += ", speed bound μ = " + formatNumber(s.speedBound) + ", advance Δt = d/μ = " + formatNumber(s.step);
        else if (i + 1 == steps.size()) l += std::string(": ") + nameOf(run.advance.outcome);
        lines.push_back(l);
        if (i + 2 == shown && steps.size() > shown) lines.push_back("… " + std::to_string(steps.size() - shown) + " more steps …");
    }
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera
                             : frameAbove(framedPoints(in, run), scene.image.width, scene.image.height, int(lines.size())));
    drawA(c, in, labels);
    drawB(c, in, run.end, roleColor(Role::Muted), true);
    if (labels) c.drawText(endAnchor(in, run, {run.advanced.position, in.start.position}), "B at t = 1", noteStyle());
    // Each step's pose, fainter for the early ones, with its closest-point segment and distance.
    for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
        const Transform p = poseAt(in.start, in.motion, steps[i].t);
        drawB(c, in, p, roleColor(Role::ShapeB).withAlpha(0.35f + 0.5f * float(i) / float(steps.size())), true);
        c.drawLine(steps[i].pointA, steps[i].pointB, lineStyle(Role::Result, 2.0f, true));
        if (labels && i < 2) {  // later segments are too short to name
            TextStyle ts = noteStyle(17.0f);
            ts.offsetPx = Eigen::Vector2d(0, -18);
            c.drawText(0.5 * (steps[i].pointA + steps[i].pointB), "d" + std::to_string(i + 1), ts);
        }
    }
    drawB(c, in, run.advanced, roleColor(Role::ShapeB), false);
    if (labels) {
        c.drawText(run.advanced.position, "B at t = " + formatNumber(run.advance.t), noteStyle(19.0f, true));
        c.drawText(in.start.position, "t = 0", noteStyle());
    }
    if (numbers) drawNumbers(c, lines);
    return finishedFrame(c, scene.title + ": conservative advancement", scene.caption, "advance",
                  "advance: " + std::string(nameOf(run.advance.outcome)) + " at t = " + formatNumber(run.advance.t) + " in " +
                      std::to_string(run.advance.steps) + " steps");
}

Frame compareFrame(GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& in,
                   const ResolutionRun& run) {
    const bool labels = scene.hasLayer("labels"), numbers = scene.hasLayer("numbers");
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera : frameAbove(framedPoints(in, run), scene.image.width, scene.image.height, 4));
    drawA(c, in, labels);
    drawB(c, in, run.end, roleColor(Role::Muted), true);
    const Color colors[3] = {categorical(5), categorical(2), categorical(6)};
    const Transform* poses[3] = {&run.mtd, &run.backtrack, &run.advanced};
    const bool valid[3] = {run.penetrating, run.backtrackHit && !run.backtrackAtStart, run.advance.outcome ==
                                                                                           AdvancementResult::Outcome::Contact};
    for (int k = 0; k < 3; ++k)
        if (valid[k]) drawB(c, in, *poses[k], colors[k], false);
    drawB(c, in, run.end, roleColor(Role::Muted), true);  // dashed, over the fills
    if (labels) c.drawText(endAnchor(in, run, {run.mtd.position, run.backtrack.position, run.advanced.position}), "B at t = 1", noteStyle());
    const char* names[3] = {"MTD (EPA)", "backtracking (linear cast)", "conservative advancement"};
    std::vector<KeyItem> key;
    for (int k = 0; k < 3; ++k)  // a correction that gave no pose: its swatch greyed, the key says so
        key.push_back({valid[k] ? colors[k] : roleColor(Role::Muted), std::string(names[k]) + (valid[k] ? "" : ": none")});
    drawKey(c, 20, kTitleBand - 8, key, 18.0f);
    if (numbers) {
        std::vector<std::string> lines = {
            "MTD: " + (valid[0] ? pose(run.mtd) : std::string("none")) + ";   backtracking: " +
                (valid[1] ? pose(run.backtrack) + ", t = " + formatNumber(run.backtrackT)
                          : std::string(run.backtrackAtStart ? "none (overlapping already at t = 0)" : "none")),
            "conservative advancement: " + (valid[2] ? pose(run.advanced) + ", t = " + formatNumber(run.advance.t) : std::string("—")) +
                " (the true motion, turn included)",
            "only conservative advancement gives a pose the body really passes through when it turns;",
            "the MTD is the cheapest (one EPA) and pushes along n, whatever the path"};
        drawNumbers(c, lines);
    }
    return finishedFrame(c, scene.title + ": the three end poses", scene.caption, "compare", "the three corrections compared");
}

}  // namespace cdlab::demos
