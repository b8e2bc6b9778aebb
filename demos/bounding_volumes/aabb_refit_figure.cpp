#include "demos/bounding_volumes/aabb_refit_figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/bounding/bounding_volume_fit.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr int kMaxRefitPoints = 40, kMaxAngles = 8;

double area(const Aabb& b) { return (b.max.x() - b.min.x()) * (b.max.y() - b.min.y()); }

struct RefitCase {
    double degrees = 0;
    Transform pose;              ///< about the old box's centre
    std::vector<Vec3> points;    ///< turned
    Aabb refit, fromBox;
    std::vector<Vec3> oldBoxTurned;  ///< the old box's corners, turned
};

class AabbRefitScene final : public PreparedScene {
public:
    AabbRefitScene(SceneCommon common, std::vector<Vec3> points, std::vector<double> angles)
        : PreparedScene(std::move(common)), points_(std::move(points)), angles_(std::move(angles)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const Aabb old = fitAabb(points_);
        const Vec3 centre = 0.5 * (old.min + old.max);
        std::vector<RefitCase> cases;
        for (double deg : angles_) {
            RefitCase rc;
            rc.degrees = deg;
            const Quat q(Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitZ()));
            rc.pose = Transform{centre - q * centre, q};  // a turn about the box's centre
            for (const Vec3& p : points_) rc.points.push_back(rc.pose.apply(p));
            rc.refit = fitAabb(rc.points);
            rc.fromBox = transformAabb(old, rc.pose);
            for (int k = 0; k < 4; ++k)
                rc.oldBoxTurned.push_back(rc.pose.apply(Vec3(k == 1 || k == 2 ? old.max.x() : old.min.x(),
                                                             k >= 2 ? old.max.y() : old.min.y(), 0)));
            cases.push_back(std::move(rc));
        }
        DemoOutput out;
        Json cs = Json::array();
        for (const RefitCase& rc : cases)
            cs.push_back({{"degrees", rc.degrees},
                          {"refit", {{"min", vec3Json(rc.refit.min)}, {"max", vec3Json(rc.refit.max)}}},
                          {"from_box", {{"min", vec3Json(rc.fromBox.min)}, {"max", vec3Json(rc.fromBox.max)}}},
                          {"refit_area", area(rc.refit)},
                          {"from_box_area", area(rc.fromBox)}});
        out.trace["old_box"] = {{"min", vec3Json(old.min)}, {"max", vec3Json(old.max)}};
        out.trace["cases"] = cs;
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(draw(*ctx.gl, figureScale(common_, ctx), cases));
        return out;
    }

private:
    std::vector<Vec3> points_;
    std::vector<double> angles_;

    Frame draw(GlContext& gl, int ss, const std::vector<RefitCase>& cases) const {
        const int W = common_.image.width, H = common_.image.height;
        Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
        // Two columns up to four panels (larger ones), else four.
        const int n = int(cases.size()), cols = n <= 4 ? std::min(n, 2) : 4, rows = (n + cols - 1) / cols;
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (const RefitCase& rc : cases) lo = lo.cwiseMin(rc.fromBox.min), hi = hi.cwiseMax(rc.fromBox.max);
        const Vec3 mid = 0.5 * (lo + hi);
        const double side = std::max(hi.x() - lo.x(), hi.y() - lo.y()) * 1.08;
        const double top = 64, keyH = 40, bottom = 50, pw = double(W) / cols, ph = (H - top - keyH - bottom) / rows;
        const double box = std::min(pw - 24, ph - 60);
        for (int k = 0; k < n; ++k) {
            const RefitCase& rc = cases[k];
            const double px = (k % cols) * pw, py = top + (k / cols) * ph;
            const double cx = px + 0.5 * pw, cy = py + 52 + 0.5 * box;
            const auto S = [&](const Vec3& v) {
                return Vec3(cx + (v.x() - mid.x()) / side * box, H - (cy - (v.y() - mid.y()) / side * box), 0);
            };
            const auto rect = [&](const Aabb& b) {
                return std::vector<Vec3>{S(b.min), S(Vec3(b.max.x(), b.min.y(), 0)), S(b.max), S(Vec3(b.min.x(), b.max.y(), 0))};
            };
            std::vector<Vec3> poly, turned;
            for (const Vec3& p : rc.points) poly.push_back(S(p));
            for (const Vec3& p : rc.oldBoxTurned) turned.push_back(S(p));
            c.drawPolygon(poly, roleColor(Role::ShapeA).withAlpha(0.35f));
            c.drawPolyline(poly, true, lineStyle(Role::ShapeA, 2.0f));
            c.drawPolyline(turned, true, lineStyle(Role::Muted, 2.0f, true, true));
            c.drawPolyline(rect(rc.fromBox), true, LineStyle{2.5f, roleColor(Role::Support), 0.0f, true});
            c.drawPolyline(rect(rc.refit), true, LineStyle{2.5f, categorical(2), 0.0f, true});
            const double a1 = area(rc.refit), a2 = area(rc.fromBox);
            c.drawTextPx(px + 12, py + 4, formatNumber(rc.degrees) + "°", TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, true});
            c.drawTextPx(px + 12, py + 27, "area " + formatNumber(a1) + " vs " + formatNumber(a2) + " (+" +
                                               formatNumber(std::round(1000 * (a2 / a1 - 1)) / 10) + " %)",
                         TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        }
        drawKey(c, 20, H - bottom - keyH + 6,
                {{categorical(2), "refitted to the turned points"},
                 {roleColor(Role::Support), "AABB of the turned old box (|R| h)"},
                 {roleColor(Role::Muted), "the old box, turned", "- -"}},
                16.0f);
        drawTitleAndCaption(c, common_.title, common_.caption);
        return Frame{"refit", common_.title, c.readPixels()};
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readAabbRefitScene(ObjectReader& r, SceneCommon common) {
    const JsonNode pts = r.get("points");
    const std::vector<Vec3> points = sceneVec2List(pts, 3, kMaxRefitPoints);
    double twiceArea = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3& a = points[i];
        const Vec3& b = points[(i + 1) % points.size()];
        twiceArea += a.x() * b.y() - b.x() * a.y();
    }
    if (!(std::abs(twiceArea) > 0)) pts.fail("the polygon has no area (its boxes would have none to compare)");
    const JsonNode an = r.get("angles");
    if (an.size() < 1) an.fail("expected 1 to 8 angles in degrees");
    requireAtMost(an, double(an.size()), kMaxAngles, "the number of angles", "one panel each");
    std::vector<double> angles;
    for (const JsonNode& a : an.items()) {
        const double d = a.asNumber();
        if (!(std::abs(d) <= 360)) a.fail("expected an angle in [-360, 360] degrees");
        angles.push_back(d);
    }
    r.finish();
    return std::make_unique<AabbRefitScene>(std::move(common), std::move(points), std::move(angles));
}

}  // namespace cdlab::demos
