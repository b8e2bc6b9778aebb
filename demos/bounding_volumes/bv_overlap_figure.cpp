#include "demos/bounding_volumes/bv_overlap_figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/bounding/bounding_sphere.h"
#include "core/bounding/bounding_volume_fit.h"
#include "core/bounding/kdop.h"
#include "core/overlap/intersect_sphere.h"
#include "core/overlap/sat_tests.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr int kMaxOverlapPoints = 40;
/// The 18-DOP's slabs whose direction lies in the plane z = 0 (x, y, x + y, x − y: in the plane the
/// others repeat them), by index into kdopDirections<18>().
std::vector<int> planeSlabs() {
    std::vector<int> out;
    const auto dirs = kdopDirections<18>();
    for (std::size_t i = 0; i < dirs.size(); ++i)
        if (dirs[i].z() == 0) out.push_back(int(i));
    return out;
}

/// "x", "y", "x + y", "x − y": a slab direction with components in {−1, 0, 1}, z = 0.
std::string slabName(int slab) {
    const Vec3 d = kdopDirections<18>()[std::size_t(slab)];
    if (d.y() == 0) return "x";
    if (d.x() == 0) return "y";
    return d.y() > 0 ? "x + y" : "x − y";
}

struct Fits {
    Sphere sphere;
    Aabb box;
    Kdop<18> dop;
};

Fits fit(const std::vector<Vec3>& p) { return {fitSphereWelzl(p), fitAabb(p), fitKdop<18>(std::span<const Vec3>(p))}; }

/// The 8-DOP's outline in the plane: the square window clipped by its four slabs.
std::vector<Vec3> dopOutline(const Kdop<18>& d) {
    std::vector<Vec3> poly = {Vec3(-1e3, -1e3, 0), Vec3(1e3, -1e3, 0), Vec3(1e3, 1e3, 0), Vec3(-1e3, 1e3, 0)};
    for (int s : planeSlabs()) {
        const Vec3 n = kdopDirections<18>()[std::size_t(s)];
        const auto clip = [&](const Vec3& normal, double offset) {
            std::vector<Vec3> out;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const Vec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
                const double sa = normal.dot(a) - offset, sb = normal.dot(b) - offset;
                if (sa <= 0) out.push_back(a);
                if ((sa <= 0) != (sb <= 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
            }
            poly = out;
        };
        clip(n, d.max[std::size_t(s)]);
        clip(-n, -d.min[std::size_t(s)]);
    }
    return poly;
}

class BvOverlapScene final : public PreparedScene {
public:
    BvOverlapScene(SceneCommon common, std::vector<Vec3> a, std::vector<Vec3> b)
        : PreparedScene(std::move(common)), a_(std::move(a)), b_(std::move(b)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const Fits fa = fit(a_), fb = fit(b_);
        const SphereSphereResult ss = intersectSphereSphere(fa.sphere, fb.sphere);
        SatTrace boxTrace;
        const SatResult bb = testAabbAabb(fa.box, fb.box, &boxTrace);
        const KdopOverlapResult kk = testKdopKdop(fa.dop, fb.dop);
        DemoOutput out;
        const auto sphere = [](const Sphere& s) { return Json{{"center", vec3Json(s.center)}, {"radius", s.radius}}; };
        Json slabs = Json::array();
        for (int slab : planeSlabs()) {
            const std::size_t s = std::size_t(slab);
            slabs.push_back({{"slab", slab}, {"name", slabName(slab)}, {"a", {fa.dop.min[s], fa.dop.max[s]}},
                             {"b", {fb.dop.min[s], fb.dop.max[s]}}});
        }
        out.trace = {{"spheres", {sphere(fa.sphere), sphere(fb.sphere)}},
                     {"sphere_test", {{"hit", ss.hit}, {"distance", ss.distance}, {"radius_sum", fa.sphere.radius + fb.sphere.radius}}},
                     {"boxes", {{{"min", vec3Json(fa.box.min)}, {"max", vec3Json(fa.box.max)}},
                                {{"min", vec3Json(fb.box.min)}, {"max", vec3Json(fb.box.max)}}}},
                     {"box_test", {{"hit", bb.hit}}},
                     {"kdop_slabs", slabs},
                     {"kdop_test", {{"hit", kk.hit}, {"separating_slab", kk.separatingSlab}}}};
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(draw(*ctx.gl, figureScale(common_, ctx), fa, fb, ss, bb, kk));
        return out;
    }

private:
    std::vector<Vec3> a_, b_;

    Frame draw(GlContext& gl, int ss, const Fits& fa, const Fits& fb, const SphereSphereResult& sph, const SatResult& bb,
               const KdopOverlapResult& kk) const {
        const int W = common_.image.width, H = common_.image.height;
        Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
        // One world window for all three panels: both spheres (the largest volumes) with a margin.
        Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
        for (const Sphere& s : {fa.sphere, fb.sphere})
            lo = lo.cwiseMin(s.center - Vec3::Constant(s.radius)), hi = hi.cwiseMax(s.center + Vec3::Constant(s.radius));
        const Vec3 mid = 0.5 * (lo + hi);
        const double side = std::max(hi.x() - lo.x(), hi.y() - lo.y()) * 1.1;
        const double pw = W / 3.0, box = std::min(pw - 30, H - 330.0), top = 120;
        const TextStyle head{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, true};
        const TextStyle body{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false};
        const char* titles[3] = {"Spheres (minimum circles)", "AABBs", "8-DOPs (18-DOP slabs in the plane)"};
        for (int k = 0; k < 3; ++k) {
            const double px = k * pw;
            const auto S = [&](const Vec3& v) {
                return Vec3(px + 0.5 * pw + (v.x() - mid.x()) / side * box, H - (top + 0.5 * box - (v.y() - mid.y()) / side * box), 0);
            };
            const auto poly = [&](const std::vector<Vec3>& pts) {
                std::vector<Vec3> out;
                for (const Vec3& p : pts) out.push_back(S(p));
                return out;
            };
            for (int body2 = 0; body2 < 2; ++body2) {
                const std::vector<Vec3>& pts = body2 == 0 ? a_ : b_;
                const Fits& f = body2 == 0 ? fa : fb;
                const Color col = roleColor(body2 == 0 ? Role::ShapeA : Role::ShapeB);
                const std::vector<Vec3> hull = hull2d(pts);
                c.drawPolygon(poly(hull), col.withAlpha(0.55f));
                std::vector<Vec3> outline;
                if (k == 0)
                    for (int i = 0; i < 96; ++i)
                        outline.push_back(f.sphere.center + f.sphere.radius * Vec3(std::cos(i * M_PI / 48), std::sin(i * M_PI / 48), 0));
                else if (k == 1)
                    outline = {f.box.min, Vec3(f.box.max.x(), f.box.min.y(), 0), Vec3(f.box.max.x(), f.box.max.y(), 0),
                               Vec3(f.box.min.x(), f.box.max.y(), 0)};
                else outline = dopOutline(f.dop);
                c.drawPolyline(poly(outline), true, LineStyle{2.5f, col.scaled(0.6f), 0.0f, true});
            }
            const bool hit = k == 0 ? sph.hit : k == 1 ? bb.hit : kk.hit;
            c.drawTextPx(px + 14, 62, titles[k], head);
            TextStyle verdict = head;
            verdict.color = hit ? roleColor(Role::Colliding) : categorical(2).scaled(0.7f);
            c.drawTextPx(px + 14, 86, hit ? "overlap: the pair goes on" : "apart: the pair is rejected", verdict);
            double y = top + box + 20;
            const auto line = [&](const std::string& t) { c.drawTextPx(px + 14, y, t, body), y += 22; };
            if (k == 0) {
                line("|c_A − c_B| = " + formatNumber(sph.distance));
                line("r_A + r_B = " + formatNumber(fa.sphere.radius + fb.sphere.radius));
            } else if (k == 1) {
                for (int axis = 0; axis < 2; ++axis)
                    line(std::string(axis == 0 ? "x" : "y") + ": [" + formatNumber(fa.box.min[axis]) + ", " + formatNumber(fa.box.max[axis]) +
                         "] vs [" + formatNumber(fb.box.min[axis]) + ", " + formatNumber(fb.box.max[axis]) + "]");
            } else {
                for (int slab : planeSlabs()) {
                    const std::size_t i = std::size_t(slab);
                    const bool apart = fa.dop.max[i] < fb.dop.min[i] || fb.dop.max[i] < fa.dop.min[i];
                    line(slabName(slab) + ": [" + formatNumber(fa.dop.min[i]) + ", " + formatNumber(fa.dop.max[i]) + "] vs [" +
                         formatNumber(fb.dop.min[i]) + ", " + formatNumber(fb.dop.max[i]) + "]" + (apart ? "  apart" : ""));
                }
                line("(diagonal slabs widened by their rounding, ~1e-15)");
            }
        }
        drawTitleAndCaption(c, common_.title, common_.caption);
        return Frame{"overlap", common_.title, c.readPixels()};
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readBvOverlapScene(ObjectReader& r, SceneCommon common) {
    std::vector<Vec3> a = sceneVec2List(r.get("a"), 3, kMaxOverlapPoints), b = sceneVec2List(r.get("b"), 3, kMaxOverlapPoints);
    r.finish();
    return std::make_unique<BvOverlapScene>(std::move(common), std::move(a), std::move(b));
}

}  // namespace cdlab::demos
