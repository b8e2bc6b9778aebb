// The moving-objects family of the primitives demo: 2D game objects (point, segment, rectangle,
// triangle, circle) moving with constant velocity against still ones — the earliest time of impact,
// the swept shape and the contact at that time (Ericson §5.5: a moving object against a still one is
// a ray cast against their Minkowski sum; core/cast/time_of_impact.h on prisms much thicker than the
// scene, so every answer lies in the plane z = 0). This file reads the 2D shapes and draws.
#include <algorithm>
#include <cmath>

#include "core/cast/time_of_impact.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace {

using namespace render;

Vec3 vec2(const JsonNode& node) { return sceneVec2(node); }

}  // namespace

Shape2d readShape2d(const JsonNode& node) {
    const char* kinds = "point, segment, rectangle, triangle or circle";
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(std::string("expected a 2D shape: an object with exactly one key (") + kinds + "), got " +
                  JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    const JsonNode body(node.raw().begin().value(), node.path() + "." + key, node.source());
    Shape2d s;
    s.kind = key;
    if (key == "point") {
        s.corners = {vec2(body)};
    } else if (key == "segment" || key == "triangle") {
        const std::size_t n = key == "segment" ? 2 : 3;
        if (!body.isArray() || body.size() != n)
            body.fail(std::string("expected ") + (n == 2 ? "[p, q]" : "[a, b, c]") + ", got " + JsonNode::describe(body.raw()));
        for (const JsonNode& item : body.items()) s.corners.push_back(vec2(item));
    } else if (key == "rectangle") {
        ObjectReader r(body);
        const Vec3 c = vec2(r.get("center"));
        JsonNode hn = r.get("half_extents");
        const Vec3 h = vec2(hn);
        if (!(h.x() >= 0 && h.y() >= 0)) hn.fail("half extents must be non-negative");
        double angle = 0;
        if (auto a = r.find("angle")) angle = std::fmod(a->asNumber(), 360.0) * M_PI / 180.0;
        r.finish();
        const Vec3 u(std::cos(angle), std::sin(angle), 0), v(-std::sin(angle), std::cos(angle), 0);
        for (const auto& [su, sv] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}})
            s.corners.push_back(c + su * h.x() * u + sv * h.y() * v);
    } else if (key == "circle") {
        ObjectReader r(body);
        s.corners = {vec2(r.get("center"))};
        s.radius = sceneSize(r.get("radius"));
        r.finish();
    } else {
        node.fail("unknown 2D shape '" + key + "' (expected " + kinds + ")");
    }
    return s;
}

namespace {

struct MovingRun {
    TimeOfImpactResult toi;
    double halfThickness = 1.0;
};

std::vector<Vec3> prism(const Shape2d& s, double half) {
    std::vector<Vec3> v;
    for (const Vec3& p : s.corners)
        for (double z : {-half, half}) v.emplace_back(p.x(), p.y(), z);
    return v;
}

MovingRun runMoving(const Moving2dInput& in) {
    MovingRun run;
    double extent = in.velocity.norm();
    for (const Shape2d* s : {&in.moving, &in.still})
        for (const Vec3& p : s->corners) extent = std::max(extent, p.norm() + s->radius);
    run.halfThickness = 10.0 * (extent + 1e-3);  // never the closest direction (see the file comment)
    // The still shape is A, the moving one B: B at its pose + t·velocity.
    run.toi = translationalTimeOfImpact(prism(in.still, run.halfThickness), in.still.radius, Vec3::Zero(),
                                        prism(in.moving, run.halfThickness), in.moving.radius, in.velocity);
    for (Vec3* p : {&run.toi.pointA, &run.toi.pointB, &run.toi.normal}) p->z() = 0.0;
    return run;
}

std::string point2(const Vec3& v) { return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ")"; }

Json vec2Json(const Vec3& v) { return Json::array({v.x() + 0.0, v.y() + 0.0}); }

Json movingJson(const Moving2dInput& in, const MovingRun& run) {
    Json j = {{"test", "moving_2d"},
              {"moving", in.moving.kind},
              {"still", in.still.kind},
              {"velocity", vec2Json(in.velocity)},
              {"hit", run.toi.hit},
              {"initially_overlapping", run.toi.initiallyOverlapping}};
    if (run.toi.hit && !run.toi.initiallyOverlapping) {
        j["t"] = run.toi.t;
        j["normal"] = vec2Json(run.toi.normal);
        j["point"] = vec2Json(run.toi.pointA);
        j["moved"] = vec2Json(run.toi.t * in.velocity);
    }
    return j;
}

/// The outline of a 2D shape moved by `offset`: its corners (a circle: 96 points on it).
std::vector<Vec3> outline(const Shape2d& s, const Vec3& offset) {
    std::vector<Vec3> out;
    if (s.radius > 0) {
        for (int k = 0; k < 96; ++k) {
            const double a = 2 * M_PI * k / 96;
            out.push_back(s.corners[0] + offset + s.radius * Vec3(std::cos(a), std::sin(a), 0));
        }
        return out;
    }
    for (const Vec3& p : s.corners) out.push_back(p + offset);
    return out;
}

void drawShape(Canvas& c, const std::vector<Vec3>& pts, Color color, bool filled, bool dashed) {
    if (pts.size() == 1) {
        c.drawPoint(pts[0], 7.0f, color);
        return;
    }
    if (filled && pts.size() >= 3) c.drawPolygon(pts, color.withAlpha(0.35f));
    LineStyle ls;
    ls.widthPx = pts.size() == 2 ? 5.0f : 3.0f;
    ls.color = color;
    ls.dashPx = dashed ? 9.0f : 0.0f;
    c.drawPolyline(pts, pts.size() > 2, ls);
}

Frame movingFrame(GlContext& gl, const SceneCommon& scene, int scale, const Moving2dInput& in, const MovingRun& run) {
    const bool labels = scene.hasLayer("labels");
    const std::vector<Vec3> start = outline(in.moving, Vec3::Zero()), end = outline(in.moving, in.velocity);
    // The swept shape: the hull of the shape at the start and at the end (its Minkowski sum with the path).
    std::vector<Vec3> both = start;
    both.insert(both.end(), end.begin(), end.end());
    const std::vector<Vec3> swept = hull2d(both);
    std::vector<Vec3> drawn = swept;
    const std::vector<Vec3> still = outline(in.still, Vec3::Zero());
    drawn.insert(drawn.end(), still.begin(), still.end());
    Eigen::AlignedBox3d box;
    for (const Vec3& p : drawn) box.extend(p);
    const int W = scene.image.width, H = scene.image.height;
    const double top = 100, bottom = 52 + 26 * 3 + 16;
    const Vec3 size = box.sizes().cwiseMax(Vec3::Constant(1e-3));
    const double s = std::min(0.86 * W / size.x(), 0.86 * (H - top - bottom) / size.y());
    const double rowMid = top + 0.5 * (H - top - bottom);
    Canvas c(gl, canvasOptions(W, H, scale));
    c.setCamera(scene.camera ? *scene.camera
                             : Camera::twoD(box.center().x(), box.center().y() - (0.5 * H - rowMid) / s, H / s));
    if (swept.size() >= 3) {
        c.drawPolygon(swept, roleColor(Role::Muted).withAlpha(0.18f));
        c.drawPolyline(swept, true, lineStyle(Role::Muted, 1.5f, true));
    }
    drawShape(c, still, roleColor(Role::ShapeA), true, false);
    drawShape(c, start, roleColor(Role::ShapeB), false, true);
    drawShape(c, end, roleColor(Role::Muted), false, true);
    const Vec3 from = in.moving.corners[0];
    c.drawArrow(from, from + in.velocity, lineStyle(Role::Ink, 2.0f, false, true));
    std::vector<std::string> lines;
    const TimeOfImpactResult& toi = run.toi;
    if (toi.hit && !toi.initiallyOverlapping) {
        drawShape(c, outline(in.moving, toi.t * in.velocity), roleColor(Role::ShapeB), true, false);
        c.drawPoint(toi.pointA, 8.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
        const double arrow = 0.12 * std::max(size.x(), size.y());
        c.drawArrow(toi.pointA, toi.pointA + arrow * toi.normal, lineStyle(Role::Direction, 3.0f, false, true));
        if (labels) {
            TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
            ts.place = true;
            ts.offsetPx = Eigen::Vector2d(40, 30);
            c.drawText(toi.pointA, "contact at t = " + formatNumber(toi.t), ts);
        }
        lines = {"first contact at t = " + formatNumber(toi.t) + ": the moving " + in.moving.kind + " has moved " +
                     point2(toi.t * in.velocity) + " of " + point2(in.velocity),
                 "contact point " + point2(toi.pointA) + ", normal " + point2(toi.normal) + " from the still " + in.still.kind +
                     " toward the moving one",
                 "one ray cast: from the origin along v against still ⊕ (−moving), the shapes' Minkowski difference"};
    } else if (toi.initiallyOverlapping) {
        lines = {"the shapes touch or overlap already at t = 0"};
    } else {
        lines = {"no contact for t in [0, 1]: the swept shape misses the still " + in.still.kind};
    }
    if (scene.hasLayer("numbers")) {
        const TextStyle ts{18.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
        double y = H - 52 - 26.0 * double(lines.size());
        for (const std::string& l : lines) {
            c.drawTextPx(20, y, l, ts);
            y += 26;
        }
    }
    drawKey(c, 20, 62,
            {{roleColor(Role::ShapeA), "still"},
             {roleColor(Role::ShapeB), "moving: at t = 0 (dashed) and at the contact"},
             {roleColor(Role::Muted), "at t = 1 (dashed), swept"},
             {roleColor(Role::Direction), "contact normal"}},
            17.0f);
    return finishedFrame(c, scene.title, scene.caption, "sweep", scene.title + (toi.hit ? ": contact at t = " + formatNumber(toi.t) : ": no contact"));
}

}  // namespace

DemoOutput runMoving2d(const SceneCommon& scene, const Moving2dInput& in, const RunContext& ctx) {
    const MovingRun run = runMoving(in);
    DemoOutput out;
    out.trace = movingJson(in, run);
    if (numericOnly(ctx, out)) return out;
    out.frames.push_back(movingFrame(*ctx.gl, scene, figureScale(scene, ctx), in, run));
    return out;
}

}  // namespace cdlab::demos
