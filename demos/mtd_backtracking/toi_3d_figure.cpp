#include "demos/mtd_backtracking/toi_3d_figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/pair_scene.h"
#include "app/scene/scene_limits.h"
#include "core/cast/time_of_impact.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/draw/plot.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

struct Toi3dSettings {
    SceneShape a, b;
    Vec3 motionA = Vec3::Zero(), motionB = Vec3::Zero();
    int bisectionSteps = 12;
    Vec3 view = Vec3(1.0, -1.6, 0.9);
};

struct BisectionStep {
    double lo = 0, hi = 0, mid = 0;
    bool overlapping = false;  ///< at mid
};

struct Toi3dRun {
    TimeOfImpactResult toi;
    ConvexCastTrace cast;
    bool overlapAtEnd = false;  ///< at t = 1: bisection needs an overlapping end
    std::vector<BisectionStep> bisection;
};

/// The shape at time t: its pose moved by t · motion.
SceneShape at(const SceneShape& s, const Vec3& motion, double t) {
    SceneShape m = s;
    m.pose.position += t * motion;
    return m;
}

/// The shape as translationalTimeOfImpact takes it: core points and a radius.
void corePoints(const SceneShape& s, std::vector<Vec3>& points, double& radius) {
    if (s.kind == SceneShape::Kind::Sphere) {
        points = {s.pose.position};
        radius = s.radius;
    } else {
        points = s.worldVertices();
        radius = 0;
    }
}

bool overlapping(const Toi3dSettings& s, double t) {
    return gjkDistance(at(s.a, s.motionA, t), at(s.b, s.motionB, t)).intersect();
}

Toi3dRun solve(const Toi3dSettings& s) {
    Toi3dRun run;
    std::vector<Vec3> pa, pb;
    double ra = 0, rb = 0;
    corePoints(s.a, pa, ra);
    corePoints(s.b, pb, rb);
    run.toi = translationalTimeOfImpact(pa, ra, s.motionA, pb, rb, s.motionB, {}, &run.cast);
    // Backtracking: the step's end overlaps, its start does not; halve [lo, hi] keeping that.
    run.overlapAtEnd = overlapping(s, 1.0);
    if (run.overlapAtEnd && !overlapping(s, 0.0)) {
        double lo = 0, hi = 1;
        for (int k = 0; k < s.bisectionSteps; ++k) {
            BisectionStep b{lo, hi, 0.5 * (lo + hi), false};
            b.overlapping = overlapping(s, b.mid);
            (b.overlapping ? hi : lo) = b.mid;
            run.bisection.push_back(b);
        }
    }
    return run;
}

class Toi3dScene final : public PreparedScene {
public:
    Toi3dScene(SceneCommon common, Toi3dSettings s) : PreparedScene(std::move(common)), s_(std::move(s)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const Toi3dRun run = solve(s_);
        DemoOutput out;
        out.trace = traceJson(run);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        out.frames.push_back(drawCast(*ctx.gl, ss, run));
        if (!run.bisection.empty()) out.frames.push_back(drawBisection(*ctx.gl, ss, run));
        return out;
    }

private:
    Toi3dSettings s_;

    Json traceJson(const Toi3dRun& run) const {
        Json t = Json::object();
        t["shapes"] = {s_.a.kindName(), s_.b.kindName()};
        t["motion_a"] = vec3Json(s_.motionA);
        t["motion_b"] = vec3Json(s_.motionB);
        t["ray_direction"] = vec3Json(s_.motionA - s_.motionB);
        t["hit"] = run.toi.hit;
        t["initially_overlapping"] = run.toi.initiallyOverlapping;
        t["t"] = run.toi.t;
        t["normal"] = vec3Json(run.toi.normal);
        t["point_a"] = vec3Json(run.toi.pointA);
        t["point_b"] = vec3Json(run.toi.pointB);
        t["cast_feature_candidates"] = run.cast.candidates.size();
        t["overlap_at_end"] = run.overlapAtEnd;
        Json b = Json::array();
        for (const BisectionStep& s : run.bisection)
            b.push_back({{"lo", s.lo}, {"hi", s.hi}, {"mid", s.mid}, {"overlapping", s.overlapping}});
        t["bisection"] = b;
        return t;
    }

    Frame drawCast(GlContext& gl, int ss, const Toi3dRun& run) const {
        const TwoPanelLayout layout = twoPanelLayout(common_.image.width, common_.image.height, common_.caption);
        const CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), ss);
        const double t = run.toi.hit ? run.toi.t : 1.0;
        const bool labels = common_.hasLayer("labels");
        // World: both shapes at t = 0 (faint) and at the time of impact, the motions.
        const ConvexDrawable a0 = shapeDrawable(s_.a), b0 = shapeDrawable(s_.b);
        const ConvexDrawable a1 = shapeDrawable(at(s_.a, s_.motionA, t)), b1 = shapeDrawable(at(s_.b, s_.motionB, t));
        std::vector<Vec3> all = a0.vertices;
        for (const ConvexDrawable* d : {&b0, &a1, &b1}) all.insert(all.end(), d->vertices.begin(), d->vertices.end());
        Vec3 wc;
        double wr;
        boundingSphere(all, wc, wr);
        Canvas world(gl, po, panelCamera(false, wc, wr, s_.view, layout));
        drawBody(world, a0, roleColor(Role::ShapeA), 0.08f, roleColor(Role::ShapeA).scaled(0.8f), 1.0f, false);
        drawBody(world, b0, roleColor(Role::ShapeB), 0.08f, roleColor(Role::ShapeB).scaled(0.8f), 1.0f, false);
        drawBody(world, a1, roleColor(Role::ShapeA), 0.35f, roleColor(Role::ShapeA).scaled(0.6f), 2.0f);
        drawBody(world, b1, roleColor(Role::ShapeB), 0.35f, roleColor(Role::ShapeB).scaled(0.6f), 2.0f);
        if (s_.motionA.norm() > 0) world.drawArrow(a0.center, a0.center + s_.motionA, lineStyle(Role::ShapeA, 2.5f, true, true));
        if (s_.motionB.norm() > 0) world.drawArrow(b0.center, b0.center + s_.motionB, lineStyle(Role::ShapeB, 2.5f, true, true));
        if (run.toi.hit) {
            world.drawPoint(run.toi.pointA, 9.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
            world.drawArrow(run.toi.pointA, run.toi.pointA + 0.3 * wr * run.toi.normal, lineStyle(Role::Ink, 2.5f, false, true));
            if (labels) drawLabelAway(world, run.toi.pointA, a1.center, "contact", labelStyle(Role::Ink, 16.0f), 10.0);
        }
        if (labels) {
            drawBodyName(world, a1.center, "A", Role::ShapeA);
            drawBodyName(world, b1.center, "B", Role::ShapeB);
        }
        drawPanelHeading(world, "World space",
                         run.toi.initiallyOverlapping ? "they overlap already at t = 0"
                         : run.toi.hit ? "faint: t = 0;  solid: t = " + formatNumber(run.toi.t) + ", first contact"
                                       : "no contact in [0, 1]: solid at t = 1");
        // Configuration space: B − A and the ray from the origin along motion_A − motion_B.
        const ConvexDrawable c = minkowskiDrawable(s_.b, s_.a);
        const Vec3 dir = s_.motionA - s_.motionB;
        std::vector<Vec3> cpts = c.vertices;
        cpts.push_back(Vec3::Zero());
        cpts.push_back(dir);
        Vec3 cc;
        double cr;
        boundingSphere(cpts, cc, cr);
        Canvas cs(gl, po, panelCamera(false, cc, cr, s_.view, layout));
        drawBody(cs, c, roleColor(Role::Minkowski), 0.15f, roleColor(Role::Minkowski).scaled(0.7f), 1.2f);
        drawOrigin(cs, 0.05 * cr, false);
        cs.drawArrow(Vec3::Zero(), dir, lineStyle(Role::Direction, 2.5f, true, true));
        if (labels) drawLabelAway(cs, dir, Vec3::Zero(), "t = 1", labelStyle(Role::Ink, 16.0f), 8.0);
        if (run.toi.hit) {
            const Vec3 hit = run.toi.t * dir;
            cs.drawLine(Vec3::Zero(), hit, lineStyle(Role::Result, 4.0f, false, true));
            cs.drawPoint(hit, 10.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
            cs.drawArrow(hit, hit - 0.25 * cr * run.toi.normal, lineStyle(Role::Ink, 2.5f, false, true));
            if (labels) drawLabelAway(cs, hit, cc, "t = " + formatNumber(run.toi.t), labelStyle(Role::Ink, 17.0f), 10.0);
        }
        drawPanelHeading(cs, "Configuration space B − A", "the ray t · (m_A − m_B) from the origin meets B − A at the first contact");
        std::vector<std::string> lines;
        lines.push_back("A moves by m_A = " + formatPoint(s_.motionA) + ", B by m_B = " + formatPoint(s_.motionB) +
                        ": they touch when t (m_A − m_B) first enters B − A");
        lines.push_back(run.toi.initiallyOverlapping ? "they overlap at t = 0: no time of impact"
                        : run.toi.hit ? "ray cast: t = " + formatNumber(run.toi.t) + ", normal (A toward B) " + formatPoint(run.toi.normal) +
                                            ", contact " + formatPoint(run.toi.pointA)
                                      : "the ray leaves [0, 1] without meeting B − A: no contact during the step");
        Frame f;
        f.name = "cast";
        f.caption = run.toi.hit ? "time of impact t = " + formatNumber(run.toi.t) : "no contact";
        f.image = composeTwoPanel(gl, layout, ss, common_.title, common_.caption, world.readPixels(), cs.readPixels(), lines);
        return f;
    }

    Frame drawBisection(GlContext& gl, int ss, const Toi3dRun& run) const {
        BoundsPlot plot;
        for (std::size_t k = 0; k < run.bisection.size(); ++k) {
            const BisectionStep& b = run.bisection[k];
            plot.iterations.push_back(int(k + 1));
            plot.lower.push_back(b.overlapping ? b.lo : b.mid);
            plot.upper.push_back(b.overlapping ? b.mid : b.hi);
        }
        const BisectionStep& last = run.bisection.back();
        const double lo = last.overlapping ? last.lo : last.mid, hi = last.overlapping ? last.mid : last.hi;
        plot.xLabel = "bisection step";
        plot.yLabel = "time t in the step";
        plot.upperName = "earliest overlapping time found";
        plot.lowerName = "latest separated time found";
        plot.title = common_.title + ": backtracking by bisection";
        plot.caption = "Each step tests the midpoint with GJK and keeps the half that still changes; after " +
                       std::to_string(run.bisection.size()) + " steps t in [" + formatNumber(lo) + ", " + formatNumber(hi) +
                       "]" + (run.toi.hit ? "; the ray cast gives " + formatNumber(run.toi.t) + " at once" : "");
        return Frame{"bisection", "bisection bracket vs step",
                     drawBoundsPlot(gl, common_.image.width, common_.image.height, ss, plot)};
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readToi3dScene(ObjectReader& r, SceneCommon common) {
    Toi3dSettings s;
    const JsonNode shapes = r.get("shapes");
    if (shapes.size() != 2) shapes.fail("expected two shapes [A, B]");
    s.a = parseSceneShape(shapes.at(0), false);
    s.b = parseSceneShape(shapes.at(1), false);
    for (std::size_t i = 0; i < 2; ++i) {
        const SceneShape& sh = i == 0 ? s.a : s.b;
        if (!sh.isPolytope() && sh.kind != SceneShape::Kind::Sphere)
            shapes.at(i).fail("a time-of-impact scene takes boxes, polytopes and spheres");
    }
    ObjectReader m(r.get("motion"));
    if (auto a = m.find("a")) s.motionA = sceneVec3(*a);
    if (auto b = m.find("b")) s.motionB = sceneVec3(*b);
    m.finish();
    if (auto n = r.find("bisection_steps")) s.bisectionSteps = n->asInt(1, 40);
    if (auto v = r.find("view")) {
        s.view = sceneVec3(*v);
        if (!(s.view.norm() > 0)) v->fail("view direction must be non-zero");
    }
    r.finish();
    return std::make_unique<Toi3dScene>(std::move(common), std::move(s));
}

}  // namespace cdlab::demos
