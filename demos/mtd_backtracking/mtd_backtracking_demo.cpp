// MTD correction, backtracking and conservative advancement (the course's "backtracking / minimum
// translational distance correction"; Ericson §9.5, van den Bergen 2004, Mirtich 1996 §2.3.2). All
// numbers come from core (resolution.h); this file reads the scene.
//
// Scene keys (besides the common ones in scene.h), everything in the plane z = 0:
//   "a": [[x, y], ...]                             the still body (the convex hull of the points)
//   "b": [[x, y], ...]                             the moving body in its own frame, turning about (0, 0)
//   "start": {"position": [x, y], "angle": deg}    B at t = 0
//   "motion": {"linear": [dx, dy], "angular": deg} over t in [0, 1]
//   "tolerance": number                            conservative advancement's touching distance (1e-6)
// Layers: "labels", "numbers".
#include "demos/mtd_backtracking/mtd_backtracking_demo.h"

#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/mtd_backtracking/resolution_figures.h"
#include "demos/mtd_backtracking/toi_3d_figure.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace {

const std::vector<std::string> kLayers = {"labels", "numbers"};

/// The convex hull of the scene's points, counter-clockwise; a hull with no area is an error.
std::vector<Vec2> readPolygon(const JsonNode& node) {
    if (!node.isArray() || node.size() < 3) node.fail("expected at least 3 points [[x, y], ...]");
    requireAtMost(node, double(node.size()), double(kMaxShapeVertices), "the number of points", "the limit of a shape");
    std::vector<Vec3> points;
    for (const JsonNode& item : node.items()) points.push_back(sceneVec2(item));
    const std::vector<Vec3> hull = hull2d(points);
    if (hull.size() < 3) node.fail("the points span no area");
    std::vector<Vec2> out;
    for (const Vec3& p : hull) out.emplace_back(p.x(), p.y());
    return out;
}

Quat aboutZ(double degrees) { return Quat(Eigen::AngleAxisd(degrees * M_PI / 180.0, Vec3::UnitZ())); }

class ResolutionScene final : public PreparedScene {
public:
    ResolutionScene(SceneCommon common, ResolutionInput input) : PreparedScene(std::move(common)), input_(std::move(input)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const ResolutionRun run = runResolution(input_);
        DemoOutput out;
        out.trace = resolutionJson(run);
        if (numericOnly(ctx, out)) return out;
        const int scale = figureScale(common_, ctx);
        out.frames.push_back(mtdFrame(*ctx.gl, common_, scale, input_, run));
        out.frames.push_back(backtrackFrame(*ctx.gl, common_, scale, input_, run));
        out.frames.push_back(advanceFrame(*ctx.gl, common_, scale, input_, run));
        out.frames.push_back(compareFrame(*ctx.gl, common_, scale, input_, run));
        return out;
    }

private:
    ResolutionInput input_;
};

class MtdBacktrackingDemo final : public Demo {
public:
    std::string name() const override { return "mtd_backtracking"; }
    std::string description() const override {
        return "a penetration at the end of a step corrected three ways: MTD (EPA), backtracking along the motion "
               "(linear cast), conservative advancement of a turning body";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1280, 960, 1}, {960, 720, 0, 0}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        if (auto f = r.find("figure"); f && f->asEnum({"resolution", "toi_3d"}) == "toi_3d")
            return readToi3dScene(r, std::move(common));
        ResolutionInput in;
        in.a = readPolygon(r.get("a"));
        in.b = readPolygon(r.get("b"));
        {
            ObjectReader s(r.get("start"));
            in.start.position = sceneVec2(s.get("position"));
            if (auto a = s.find("angle")) in.start.rotation = aboutZ(std::fmod(a->asNumber(), 360.0));
            s.finish();
        }
        {
            ObjectReader m(r.get("motion"));
            if (auto l = m.find("linear")) in.motion.linear = sceneVec2(*l);
            if (auto a = m.find("angular")) {
                const double deg = a->asNumber();
                if (!(std::abs(deg) <= 3600)) a->fail("expected at most 3600 degrees over the step");
                in.motion.angular = Vec3(0, 0, deg * M_PI / 180.0);
            }
            m.finish();
        }
        if (auto t = r.find("tolerance")) {
            in.tolerance = t->asNumber();
            if (!(in.tolerance > 0 && in.tolerance <= 1)) t->fail("expected a tolerance in (0, 1]");
        }
        r.finish();
        return std::make_unique<ResolutionScene>(std::move(common), std::move(in));
    }
};

}  // namespace

const Demo& mtdBacktrackingDemo() {
    static const MtdBacktrackingDemo demo;
    return demo;
}

}  // namespace cdlab::demos
