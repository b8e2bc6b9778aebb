// The sphere family of the primitives demo: a sphere against a sphere (Ericson §4.3.1), an AABB or
// OBB (§5.2.5, §5.2.6: the centre clamped to the box on each axis) or a triangle (§5.2.7: the closest
// point of the triangle and its Voronoi region) — every test compares the distance from the centre
// to the other shape's closest point with the radius. Numbers from core; this file draws them.
#include <algorithm>
#include <cmath>

#include "core/closest/closest_point.h"
#include "core/closest/closest_point_box.h"
#include "core/overlap/intersect_sphere.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/zoom_inset.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"
#include "app/scene/json_reader.h"
#include "app/scene/pair_scene.h"

namespace cdlab::demos {

namespace {

using namespace render;
using K = PrimitiveShape::Kind;

struct SphereRun {
    bool hit = false;
    Vec3 closest = Vec3::Zero();  // the other shape's point nearest the centre (sphere: its surface point)
    double distance = 0.0;        // centre to `closest` (sphere–sphere: centre to centre)
    double reach = 0.0;           // what the distance is compared with: r (or r_a + r_b)
    BoxRegionResult box;          // aabb / obb: the clamping, axis by axis
    std::string region;           // triangle: the closest point's region
};

SphereRun runSphere(const SphereOverlapInput& in) {
    SphereRun run;
    const Sphere s{in.sphere.vertices[0], in.sphere.radius};
    const PrimitiveShape& o = in.other;
    if (o.kind == K::Sphere) {
        const SphereSphereResult r = intersectSphereSphere(s, {o.vertices[0], o.radius});
        run.hit = r.hit;
        run.distance = r.distance;
        run.reach = s.radius + o.radius;
        run.closest = o.vertices[0] - o.radius * r.normal;
        return run;
    }
    run.reach = s.radius;
    if (o.kind == K::Triangle) {
        const Triangle t{o.vertices[0], o.vertices[1], o.vertices[2]};
        const SphereShapeResult r = intersectSphereTriangle(s, t);
        run.hit = r.hit;
        run.closest = r.closestPoint;
        run.distance = std::sqrt(r.distanceSquared);
        run.region = nameOf(closestPointOnTriangle(s.center, t).region);
        return run;
    }
    // An aabb by its exact min and max, an obb in its own frame.
    const SphereShapeResult r = o.kind == K::Aabb ? intersectSphereAabb(s, o.aabb())
                                                  : intersectSphereObb(s, o.box);
    run.hit = r.hit;
    run.closest = r.closestPoint;
    run.distance = std::sqrt(r.distanceSquared);
    run.box = closestPointOnBox(s.center, o.box);  // the same clamping, with its per-axis tests for the figure
    return run;
}


Json sphereJson(const SphereOverlapInput& in, const SphereRun& run) {
    Json j = {{"test", "sphere_overlap"},
              {"shape", nameOf(in.other.kind)},
              {"hit", run.hit},
              {"closest", vec3Json(run.closest)},
              {"distance", run.distance},
              {"reach", run.reach},
              {"gap", run.distance - run.reach}};
    if (!run.region.empty()) j["region"] = run.region;
    if (run.box.valid) {
        Json axes = Json::array();
        for (const BoxAxisTest& t : run.box.tests)
            axes.push_back({{"coordinate", t.coordinate}, {"half_extent", t.halfExtent}, {"side", t.side}});
        j["clamp"] = axes;
        j["region"] = regionName(run.box);
    }
    return j;
}

void drawOther(Canvas& c, const PrimitiveShape& o, bool labels) {
    const Color color = roleColor(Role::ShapeB);
    if (o.kind == K::Sphere) {
        SceneShape s;
        s.kind = SceneShape::Kind::Sphere;
        s.radius = o.radius;
        s.pose.position = o.vertices[0];
        drawBody(c, shapeDrawable(s), color, 0.25f, color.scaled(0.7f), 1.5f);
    } else if (o.kind == K::Triangle) {
        c.drawPolygon(o.vertices, color.withAlpha(0.35f), true);
        c.drawPolyline(o.vertices, true, lineStyle(Role::ShapeB, 3.0f));
        // The vertices named A, B, C, as the region the caption names (Ericson §5.1.5's).
        if (labels) {
            const Vec3 centroid = (o.vertices[0] + o.vertices[1] + o.vertices[2]) / 3.0;
            for (int i = 0; i < 3; ++i)
                drawLabelAway(c, o.vertices[std::size_t(i)], centroid, std::string(1, char('A' + i)),
                              labelStyle(Role::Ink, 18.0f));
        }
    } else {
        drawBody(c, boxDrawable(o.box), color, 0.25f, color.scaled(0.7f), 3.0f);
        // The box's axes u_x, u_y, u_z from its centre to its faces: the frame's text clamps the
        // sphere's centre along them (the review: the axes the footer names were not drawn).
        if (labels)
            for (int i = 0; i < 3; ++i) {
                const Vec3 tip = o.box.center + o.box.halfExtents[i] * o.box.axes.col(i);
                c.drawArrow(o.box.center, tip, lineStyle(Role::Ink, 2.0f, false, true));
                drawLabelAway(c, tip, o.box.center, std::string("u_") + "xyz"[i], labelStyle(Role::Ink, 17.0f), 6.0);
            }
    }
}

std::vector<std::string> numberLines(const SphereOverlapInput& in, const SphereRun& run) {
    std::vector<std::string> lines;
    const std::string verdict = run.hit ? "overlap (depth " + formatNumber(run.reach - run.distance) + ")"
                                        : "apart (gap " + formatNumber(run.distance - run.reach) + ")";
    if (in.other.kind == K::Sphere) {
        lines.push_back("|c_b − c_a| = " + formatNumber(run.distance) + " against r_a + r_b = " + formatNumber(run.reach) +
                        " (compared squared, no square root): " + verdict);
        return lines;
    }
    if (run.box.valid) {
        std::string clamp = "the centre clamped to the box, axis by axis:";
        const char* axes = "xyz";
        for (int i = 0; i < 3; ++i) {
            const BoxAxisTest& t = run.box.tests[std::size_t(i)];
            clamp += std::string(i ? ";  " : " ") + "u_" + axes[i] + " = " + formatNumber(t.coordinate) + " → " +
                     formatNumber(std::clamp(t.coordinate, -t.halfExtent, t.halfExtent));
        }
        lines.push_back(clamp);
        lines.push_back("the closest point " + formatPoint(run.closest) + " lies in region " + regionName(run.box));
    } else {
        lines.push_back("the triangle's closest point to the centre, " + formatPoint(run.closest) + ", in region " + run.region +
                        " (Ericson §5.1.5)");
    }
    lines.push_back("|c − closest| = " + formatNumber(run.distance) + " against r = " + formatNumber(run.reach) + ": " + verdict);
    return lines;
}

// A cap of the sphere (centre c, radius r) about direction `dir`, `halfAngle` radians across,
// as a 128 x 128 grid of triangles: the sphere where a zoomed inset looks (its 900-sample hull's
// facets are seen there).
std::pair<std::vector<Vec3>, std::vector<Eigen::Vector3i>> sphereCap(const Vec3& c, double r, const Vec3& dir, double halfAngle) {
    constexpr int n = 128;
    const Vec3 e1 = dir.unitOrthogonal(), e2 = dir.cross(e1);
    const double t = std::tan(std::min(halfAngle, 1.2));
    std::vector<Vec3> vertices;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double a = t * (2.0 * i / n - 1), b = t * (2.0 * j / n - 1);
            vertices.push_back(c + r * (dir + a * e1 + b * e2).normalized());
        }
    std::vector<Eigen::Vector3i> triangles;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int k = i * (n + 1) + j;
            triangles.emplace_back(k, k + n + 1, k + 1);
            triangles.emplace_back(k + 1, k + n + 1, k + n + 2);
        }
    return {vertices, triangles};
}

Frame sphereFrame(GlContext& gl, const SceneCommon& scene, int scale, const SphereOverlapInput& in, const SphereRun& run) {
    const Vec3 c0 = in.sphere.vertices[0];
    const bool twoSpheres = in.other.kind == K::Sphere;
    const double r = in.sphere.radius;
    std::vector<Vec3> drawn = in.other.vertices;
    for (int i = 0; i < 3; ++i) {
        drawn.push_back(c0 + r * Vec3::Unit(i));
        drawn.push_back(c0 - r * Vec3::Unit(i));
        if (twoSpheres) {
            drawn.push_back(in.other.vertices[0] + in.other.radius * Vec3::Unit(i));
            drawn.push_back(in.other.vertices[0] - in.other.radius * Vec3::Unit(i));
        }
    }
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera
                             : viewAbove(drawn, viewAcross(Vec3(1.0, 0.8, 1.7), run.closest - c0), Vec3::UnitY(), 0.72,
                                         scene.image.width, scene.image.height));
    SceneShape s;
    s.kind = SceneShape::Kind::Sphere;
    s.radius = r;
    s.pose.position = c0;
    // The bodies and the centre line: the picture, and again in the inset that magnifies an
    // overlap or gap drawn under 12 px (names only on the picture). There the sphere's 900-sample
    // hull would show its facets: a fine cap about `capAt` replaces it.
    const auto drawGeometry = [&](Canvas& on, bool labels, const Vec3* capAt) {
        drawOther(on, in.other, labels);
        const Color fill = roleColor(Role::ShapeA);
        const float alpha = run.hit ? 0.35f : 0.25f;
        if (capAt) {
            const auto [vertices, triangles] = sphereCap(c0, r, *capAt, 25.0 * std::abs(run.reach - run.distance) / r);
            on.drawMesh(vertices, triangles, fill.withAlpha(alpha), true);
        } else {
            drawBody(on, shapeDrawable(s), fill, alpha, fill.scaled(0.7f), 1.5f);
        }
        on.drawPoint(c0, 6.0f, roleColor(Role::Ink));
        // Two spheres: the centre line c_a → c_b, the quantity compared with r_a + r_b; else the line
        // to the other shape's closest point.
        const Vec3 end = twoSpheres ? in.other.vertices[0] : run.closest;
        on.drawLine(c0, end, lineStyle(Role::Result, 3.0f, false, true));
        if (twoSpheres) on.drawPoint(end, 6.0f, roleColor(Role::Ink));
        else on.drawPoint(end, 8.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
    };
    drawGeometry(c, scene.hasLayer("labels"), nullptr);
    // The overlap or the gap the frame names: along the centre line, between the sphere's surface
    // and the closest point (the other sphere's surface).
    ZoomTarget quantity;
    if ((run.closest - c0).norm() > 0) {
        const Vec3 dir = (run.closest - c0).normalized();
        quantity = {run.hit ? "overlap" : "gap", (run.hit ? "overlap " : "gap ") + formatNumber(std::abs(run.reach - run.distance)),
                    c0 + r * dir, run.closest - (run.reach - r) * dir, [&, dir](Canvas& on) { drawGeometry(on, false, &dir); }};
        c.noteQuantity(quantity.name, quantity.p, quantity.q);
    }
    if (scene.hasLayer("labels")) {
        TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
        ts.place = true;
        ts.offsetPx = Eigen::Vector2d(0, -24);
        c.drawText(c0, twoSpheres ? "c_a" : "c", ts);
        ts.offsetPx = Eigen::Vector2d(0, 28);
        c.drawText(twoSpheres ? in.other.vertices[0] : run.closest, twoSpheres ? "c_b" : "closest point", ts);
    }
    drawKey(c, 20, 62,
            {{roleColor(Role::ShapeA), twoSpheres ? "sphere a" : "the sphere"},
             {roleColor(Role::ShapeB), twoSpheres ? "sphere b" : std::string("the ") + nameOf(in.other.kind)},
             {roleColor(Role::Result), twoSpheres ? "centre to centre" : "centre to closest point"}},
            17.0f);
    if (scene.hasLayer("numbers")) drawNumberBlock(c, numberLines(in, run), 52);
    drawTitleAndCaption(c, scene.title, scene.caption);
    const Box within{14.0, 90.0, scene.image.width - 14.0, scene.image.height - 130.0};
    return Frame{"test", scene.title + (run.hit ? ": overlap" : ": apart"),
                 quantity.draw ? readPixelsZoomed(gl, c, scale, quantity, within) : c.readPixels()};
}

}  // namespace

DemoOutput runSphereOverlap(const SceneCommon& scene, const SphereOverlapInput& in, const RunContext& ctx) {
    const SphereRun run = runSphere(in);
    DemoOutput out;
    out.trace = sphereJson(in, run);
    if (numericOnly(ctx, out)) return out;
    out.frames.push_back(sphereFrame(*ctx.gl, scene, figureScale(scene, ctx), in, run));
    return out;
}

}  // namespace cdlab::demos
