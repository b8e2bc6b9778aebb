// The BVH demo's refit figure (demos/bvh/bvh_scene.h: BvhScene and its helpers).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

TriangleMesh BvhScene::deform(const MeshSpec& m, double t) const {
    TriangleMesh d = m.mesh;
    const double angle = deformAngle * M_PI / 180.0 * t;
    const double len = m.sheetLength > 0 ? m.sheetLength : 2.0;
    for (Vec3& p : d.vertices) {
        if (deformation == Deformation::Roll) {
            // Bend the x axis onto a circle arc of total angle `angle` (length kept), curling up in z.
            if (angle <= 0) continue;
            const double k = angle / len;  // curvature
            const double a = k * (p.x() + 0.5 * len) - 0.5 * angle;
            p = Vec3(std::sin(a) / k, p.y(), (1 - std::cos(a)) / k + p.z());
        } else {
            // Twist about the x axis, linear in x: the ends turn by ±angle/2.
            const double a = angle * p.x() / len;
            p = Vec3(p.x(), std::cos(a) * p.y() - std::sin(a) * p.z(), std::sin(a) * p.y() + std::cos(a) * p.z());
        }
    }
    return d;
}

void BvhScene::runRefit(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    // Trees built on the rest shape, refitted to each deformed shape, against trees rebuilt there.
    const BvKind kinds[2] = {BvKind::Aabb, BvKind::Obb};
    Json rows = Json::array();
    std::vector<TriangleMesh> shapes;
    std::vector<std::array<Bvh, 2>> refit, rebuilt;  // per time, per kind
    for (double t : times) {
        shapes.push_back(deform(m, t));
        std::array<Bvh, 2> rf, rb;
        Json perKind = Json::array();
        for (int k = 0; k < 2; ++k) {
            rf[k] = buildChecked(m.mesh, kinds[k], build.method);
            const BvhStatus st = refitBvh(rf[k], shapes.back());
            if (st != BvhStatus::Ok) throw InputError(common_.file + ": refit failed: " + nameOf(st));
            rb[k] = buildChecked(shapes.back(), kinds[k], build.method);
            const std::vector<int> lr = levelNodes(rf[k], levels.front()), lb = levelNodes(rb[k], levels.front());
            perKind.push_back({{"bv", nameOf(kinds[k])},
                               {"refit_total_volume", totalVolume(rf[k])},
                               {"rebuilt_total_volume", totalVolume(rb[k])},
                               {"refit_level_volume", sumVolume(rf[k], lr)},
                               {"rebuilt_level_volume", sumVolume(rb[k], lb)},
                               {"refit_root", obbJson(rf[k].box(0))},
                               {"rebuilt_root", obbJson(rb[k].box(0))}});
        }
        rows.push_back({{"t", t}, {"angle_degrees", deformAngle * t}, {"trees", perKind}});
        refit.push_back(std::move(rf));
        rebuilt.push_back(std::move(rb));
    }
    out.trace = {{"mesh", m.kind},
                 {"triangles", m.mesh.triangleCount()},
                 {"deformation", deformation == Deformation::Roll ? "roll" : "twist"},
                 {"level", levels.front()},
                 {"frames", rows}};
    if (!ctx.gl) return;

    const int k = build.bvKind == BvKind::Aabb ? 0 : 1;  // the kind drawn in the grid
    const int level = levels.front();
    GridLayout L = grid(W(), H(), int(times.size()), 2);
    std::vector<MeshView> views;
    for (const TriangleMesh& s : shapes) views.push_back(meshView(s, m.pose));
    std::vector<const MeshView*> all;
    for (const MeshView& v : views) all.push_back(&v);
    Vec3 center;
    double radius;
    meshSphere(all, center, radius);
    const Camera cam =
        common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
    std::vector<Image> panels;
    for (int row = 0; row < 2; ++row)
        for (std::size_t i = 0; i < times.size(); ++i) {
            const Bvh& b = row == 0 ? refit[i][k] : rebuilt[i][k];
            const std::vector<int> nodes = levelNodes(b, level);
            char head[96];
            std::snprintf(head, sizeof head, "%s, %s%.0f°", row == 0 ? "Refitted" : "Rebuilt",
                          deformation == Deformation::Roll ? "rolled " : "twisted ", deformAngle * times[i]);
            const double ratio = totalVolume(refit[i][k]) / totalVolume(rebuilt[i][k]);
            panels.push_back(boxesPanel(
                *ctx.gl, L.panelWidth(), L.panelHeight(), views[i], b, m.pose, nodes,
                row == 0 ? levelColor(0) : levelColor(1), cam, head,
                "all nodes: volume " + fmt(totalVolume(b)) + (row == 0 ? " (" + fmt(ratio) + "× rebuilt)" : "")));
        }
    std::vector<LegendItem> legend = {
        {LegendItem::Swatch::Fill, roleColor(Role::ShapeA).withAlpha(0.5f), "deformed mesh"},
        {LegendItem::Swatch::Line, levelColor(0),
         std::string("refitted ") + nameOf(kinds[k]) + "s (topology of the rest shape)"},
        {LegendItem::Swatch::Line, levelColor(1), "rebuilt from scratch"}};
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back("Level " + std::to_string(level) +
                      " boxes drawn. Refit (van den Bergen 1997) keeps the tree built on the flat sheet: " +
                      (k == 0 ? "each AABB is exact for its triangles, but the groups no longer fit the shape."
                              : "the OBB axes stay those of the rest shape."));
    out.frames.push_back(Frame{"refit", "refitted vs rebuilt boxes",
                               composeGrid(*ctx.gl, L, ss_, common_.title, panels, legend, caption)});

    // Volume chart for both kinds.
    GridLayout C = grid(W(), std::min(H(), 460), 1, 1);
    C.legendBand = 0;
    BarChartInput bc;
    bc.heading = "Total volume of all boxes (sum over every node)";
    bc.sub = "refitted vs rebuilt, AABB and OBB trees";
    for (double t : times) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.0f°", deformAngle * t);
        bc.groups.push_back(buf);
    }
    for (int kk = 0; kk < 2; ++kk)
        for (int row = 0; row < 2; ++row) {
            BarSeries s{
                std::string(nameOf(kinds[kk])) + (row == 0 ? " refitted" : " rebuilt"),
                (kk == 0 ? levelColor(0) : levelColor(2)).mixed(roleColor(Role::Background), row == 0 ? 0.0f : 0.45f),
                {}};
            for (std::size_t i = 0; i < times.size(); ++i)
                s.values.push_back(totalVolume(row == 0 ? refit[i][kk] : rebuilt[i][kk]));
            bc.series.push_back(s);
        }
    // Refitted / rebuilt volume ratio per kind, smallest and largest over the times.
    double lo[2] = {1e300, 1e300}, hi[2] = {0, 0};
    for (std::size_t i = 0; i < times.size(); ++i)
        for (int kk = 0; kk < 2; ++kk) {
            const double r = totalVolume(refit[i][kk]) / totalVolume(rebuilt[i][kk]);
            lo[kk] = std::min(lo[kk], r);
            hi[kk] = std::max(hi[kk], r);
        }
    std::vector<std::string> cap2 = {
        "AABB refit: union of the children's boxes, exact for the old groups: refitted / rebuilt volume " + fmt(lo[0]) +
            " .. " + fmt(hi[0]) + ".",
        "OBB refit: the flat sheet's axes, new extents: refitted / rebuilt " + fmt(lo[1]) + " .. " + fmt(hi[1]) +
            ". Refitting is one bottom-up pass; rebuilding a full build per frame."};
    out.frames.push_back(
        Frame{"volume", "total box volume, refitted vs rebuilt",
              composeGrid(*ctx.gl, C, ss_, common_.title,
                          {drawBarChart(*ctx.gl, C.panelWidth(), C.panelHeight(), ss_, bc)}, {}, cap2)});
}

}  // namespace cdlab::demos::bvhfig
