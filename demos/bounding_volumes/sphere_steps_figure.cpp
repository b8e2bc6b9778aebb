#include "demos/bounding_volumes/sphere_steps_figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/bounding/bounding_sphere.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr int kMaxPoints = 40;
constexpr int kColumns = 4, kRows = 3;  // twelve panels

/// One small panel: the circles it draws (dashed ones first), the points it marks, its two lines.
struct Panel {
    std::vector<Sphere> dashed, solid;
    std::vector<int> marked;   ///< ringed points (support set, starting pair)
    int hot = -1;              ///< the point this step is about
    std::vector<std::pair<Vec3, Vec3>> segments;  ///< dashed construction segments
    std::string head, sub;
};

std::string pname(int i) { return "P" + std::to_string(i); }

class SphereStepsScene final : public PreparedScene {
public:
    SphereStepsScene(SceneCommon common, std::vector<Vec3> points) : PreparedScene(std::move(common)), points_(std::move(points)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        RitterTrace rt;
        const Sphere ritter = fitSphereRitter(points_, &rt);
        WelzlTrace wt;
        const Sphere welzl = fitSphereWelzl(points_, &wt);
        DemoOutput out;
        out.trace = traceJson(ritter, rt, welzl, wt);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        out.frames.push_back(draw(*ctx.gl, ss, "ritter", ritterPanels(ritter, rt),
                                  "Ritter: r = " + formatNumber(ritter.radius) + " after " + std::to_string(rt.steps.size()) +
                                      " growth steps, " + formatNumber(100 * (ritter.radius / welzl.radius - 1)) +
                                      " % above the minimum " + formatNumber(welzl.radius)));
        out.frames.push_back(draw(*ctx.gl, ss, "welzl", welzlPanels(welzl, wt),
                                  "Each event: a point outside the circle of the points before it joins the support set; r = " +
                                      formatNumber(welzl.radius) + " (" + nameOf(wt.status) + ")"));
        return out;
    }

private:
    std::vector<Vec3> points_;

    Json traceJson(const Sphere& ritter, const RitterTrace& rt, const Sphere& welzl, const WelzlTrace& wt) const {
        const auto sphere = [](const Sphere& s) { return Json{{"center", vec3Json(s.center)}, {"radius", s.radius}}; };
        Json t = Json::object();
        Json rs = Json::array();
        for (const RitterStep& s : rt.steps)
            rs.push_back({{"point", s.pointIndex}, {"before", sphere(s.before)}, {"after", sphere(s.after)}});
        t["ritter"] = {{"initial_pair", rt.initialPair}, {"initial", sphere(rt.initial)}, {"steps", rs}, {"sphere", sphere(ritter)}};
        Json ws = Json::array();
        for (const WelzlStep& s : wt.steps)
            ws.push_back({{"point", s.pointIndex}, {"depth", s.depth}, {"support", s.support}, {"ball", sphere(s.ball)},
                          {"accepted", s.accepted}});
        t["welzl"] = {{"steps", ws}, {"final_support", wt.finalSupport}, {"status", nameOf(wt.status)}, {"sphere", sphere(welzl)}};
        return t;
    }

    std::vector<Panel> ritterPanels(const Sphere& final, const RitterTrace& rt) const {
        std::vector<Panel> panels;
        Panel start;
        start.solid = {rt.initial};
        start.marked = {rt.initialPair[0], rt.initialPair[1]};
        start.segments = {{points_[rt.initialPair[0]], points_[rt.initialPair[1]]}};
        start.head = "start: " + pname(rt.initialPair[0]) + " " + pname(rt.initialPair[1]);
        start.sub = "farthest axis-extreme pair, r " + formatNumber(rt.initial.radius);
        panels.push_back(start);
        const std::size_t shown = std::min<std::size_t>(rt.steps.size(), kColumns * kRows - 2);
        for (std::size_t k = 0; k < shown; ++k) {
            const RitterStep& s = rt.steps[k];
            Panel p;
            p.dashed = {s.before};
            p.solid = {s.after};
            p.hot = s.pointIndex;
            // The new diameter: from the old sphere's far side, through its centre, to the point.
            const Vec3 far = s.before.center - s.before.radius * (points_[s.pointIndex] - s.before.center).normalized();
            p.segments = {{far, points_[s.pointIndex]}};
            p.head = "step " + std::to_string(k + 1) + ": " + pname(s.pointIndex) + " outside";
            p.sub = "r " + formatNumber(s.before.radius) + " → " + formatNumber(s.after.radius);
            panels.push_back(p);
        }
        Panel end;
        end.solid = {final};
        end.head = "final: r " + formatNumber(final.radius);
        end.sub = rt.steps.size() > shown ? "(" + std::to_string(rt.steps.size() - shown) + " steps not drawn)" : "every point inside";
        panels.push_back(end);
        return panels;
    }

    std::vector<Panel> welzlPanels(const Sphere& final, const WelzlTrace& wt) const {
        std::vector<Panel> panels;
        const std::size_t shown = std::min<std::size_t>(wt.steps.size(), kColumns * kRows - 1);
        for (std::size_t k = 0; k < shown; ++k) {
            const WelzlStep& s = wt.steps[k];
            Panel p;
            if (s.accepted) p.solid = {s.ball};
            else p.dashed = {s.ball};
            p.marked = s.support;
            p.hot = s.pointIndex;
            std::string support;
            for (int i : s.support) support += (support.empty() ? "" : " ") + pname(i);
            p.head = std::to_string(k + 1) + ": " + pname(s.pointIndex) + (s.accepted ? " outside" : " rejected");
            p.sub = "on the circle: " + support;
            panels.push_back(p);
        }
        Panel end;
        end.solid = {final};
        end.marked = wt.finalSupport;
        end.head = "final: r " + formatNumber(final.radius);
        end.sub = wt.steps.size() > shown ? "(" + std::to_string(wt.steps.size() - shown) + " events not drawn)" : nameOf(wt.status);
        panels.push_back(end);
        return panels;
    }

    Frame draw(GlContext& gl, int ss, const std::string& name, const std::vector<Panel>& panels, const std::string& summary) const {
        const int W = common_.image.width, H = common_.image.height;
        Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
        // Every panel frames the same square: the points and every circle drawn.
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (const Vec3& p : points_) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        for (const Panel& p : panels)
            for (const auto* list : {&p.dashed, &p.solid})
                for (const Sphere& s : *list)
                    lo = lo.cwiseMin(s.center - Vec3::Constant(s.radius)), hi = hi.cwiseMax(s.center + Vec3::Constant(s.radius));
        const Vec3 mid = 0.5 * (lo + hi);
        const double side = std::max(hi.x() - lo.x(), hi.y() - lo.y()) * 1.06;
        const double top = 64, bottom = 50, pw = double(W) / kColumns, ph = (H - top - bottom) / kRows;
        const double box = std::min(pw - 24, ph - 56);
        for (std::size_t k = 0; k < panels.size(); ++k) {
            const Panel& p = panels[k];
            const double px = (k % kColumns) * pw, py = top + (k / kColumns) * ph;
            const double cx = px + 0.5 * pw, cy = py + 48 + 0.5 * box;
            const auto S = [&](const Vec3& v) {  // world (y up) to pixels (y down) in this panel, as a canvas point
                return Vec3(cx + (v.x() - mid.x()) / side * box, H - (cy - (v.y() - mid.y()) / side * box), 0);
            };
            const auto circle = [&](const Sphere& s, const LineStyle& st) {
                std::vector<Vec3> ring;
                for (int i = 0; i < 96; ++i)
                    ring.push_back(S(s.center + s.radius * Vec3(std::cos(i * M_PI / 48), std::sin(i * M_PI / 48), 0)));
                c.drawPolyline(ring, true, st);
            };
            c.drawTextPx(px + 12, py + 4, p.head, TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, true});
            c.drawTextPx(px + 12, py + 25, p.sub, TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
            for (const Sphere& s : p.dashed) circle(s, lineStyle(Role::Muted, 2.0f, true, true));
            for (const Sphere& s : p.solid) circle(s, lineStyle(Role::Simplex, 2.5f, false, true));
            for (const auto& [a, b] : p.segments) c.drawLine(S(a), S(b), lineStyle(Role::Ink, 1.2f, true, true));
            for (std::size_t i = 0; i < points_.size(); ++i) c.drawPoint(S(points_[i]), 5.0f, roleColor(Role::Ink), true);
            // The support set (or starting pair) blue, the step's point vermillion, each named.
            std::vector<int> named = p.marked;
            if (p.hot >= 0 && std::find(named.begin(), named.end(), p.hot) == named.end()) named.push_back(p.hot);
            for (int i : named) {
                const bool hot = i == p.hot;
                c.drawPoint(S(points_[i]), 11.0f, hot ? roleColor(Role::Support) : categorical(4), true, 1.5f, roleColor(Role::Ink));
                TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                ts.place = true;
                const Vec3 away = (points_[i] - mid).normalized();
                ts.offsetPx = Eigen::Vector2d(away.x(), -away.y()) * 20.0;
                c.drawText(S(points_[i]), pname(i), ts);
            }
        }
        drawTitleAndCaption(c, common_.title + (name == "ritter" ? ": Ritter's pass" : ": Welzl's recursion"), summary);
        return Frame{name, summary, c.readPixels()};
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readSphereStepsScene(ObjectReader& r, SceneCommon common) {
    const JsonNode pts = r.get("points");
    const std::vector<Vec3> points = sceneVec2List(pts, 2, kMaxPoints);
    if (std::all_of(points.begin(), points.end(), [&](const Vec3& p) { return p == points.front(); }))
        pts.fail("the points all coincide: their circle has radius 0, no step to draw");
    r.finish();
    return std::make_unique<SphereStepsScene>(std::move(common), std::move(points));
}

}  // namespace cdlab::demos
