// The BVH demo's aabb_vs_obb figure (demos/bvh/bvh_scene.h: BvhScene and its helpers).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runAabbVsObb(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    const Bvh trees[2] = {buildChecked(m.mesh, BvKind::Aabb, build.method),
                          buildChecked(m.mesh, BvKind::Obb, build.method)};
    const int maxLevel =
        std::min(*std::max_element(levels.begin(), levels.end()) + 2, std::min(trees[0].height(), trees[1].height()));
    Json t;
    t["mesh"] = m.kind;
    t["trees"] = {treeJson(trees[0], maxLevel), treeJson(trees[1], maxLevel)};
    // The same query through both trees: mesh 1 (when given) against mesh 0.
    MeshCollisionResult q[2];
    const bool haveQuery = meshes.size() > 1;
    if (haveQuery) t["query"] = queryBothTrees(trees, q);
    out.trace = t;
    if (!ctx.gl) return;

    const MeshView mv = meshView(m.mesh, m.pose);
    Vec3 center;
    double radius;
    sphereOverTopLevel(mv, trees, m.pose, center, radius);
    out.frames.push_back(aabbVsObbLevelsFrame(*ctx.gl, mv, trees, center, radius));
    out.frames.push_back(aabbVsObbNumbersFrame(*ctx.gl, mv, trees, maxLevel, haveQuery ? q : nullptr));
}

Json BvhScene::queryBothTrees(const Bvh (&trees)[2], MeshCollisionResult (&q)[2]) const {
    const MeshSpec& m = meshes[0];
    const MeshSpec& o = meshes[1];
    const MeshCollisionResult brute = collideMeshesBruteForce(m.mesh, m.pose, o.mesh, o.pose);
    Json qj = Json::array();
    for (int k = 0; k < 2; ++k) {
        const Bvh other = buildChecked(o.mesh, trees[k].kind, build.method);
        q[k] = collideMeshes(m.mesh, trees[k], m.pose, o.mesh, other, o.pose);
        qj.push_back({{"bv", nameOf(trees[k].kind)},
                      {"bv_tests", q[k].stats.bvTests},
                      {"leaf_pairs", q[k].stats.leafVisits},
                      {"triangle_tests", q[k].stats.triangleTests},
                      {"pairs", q[k].pairs.size()},
                      {"equals_brute_force", samePairs(q[k].pairs, brute.pairs)}});
    }
    return {{"mesh", o.kind},
            {"brute_force_triangle_tests", brute.stats.triangleTests},
            {"brute_force_pairs", brute.pairs.size()},
            {"trees", qj}};
}

void BvhScene::sphereOverTopLevel(const MeshView& mv, const Bvh (&trees)[2], const Transform& pose, Vec3& center,
                                  double& radius) const {
    std::vector<Vec3> corners;
    for (int k = 0; k < 2; ++k) {
        const std::vector<Vec3> c =
            boxesCorners(trees[k], pose, levelNodes(trees[k], *std::min_element(levels.begin(), levels.end())));
        corners.insert(corners.end(), c.begin(), c.end());
    }
    meshSphere({&mv}, center, radius, corners);
}

Frame BvhScene::aabbVsObbLevelsFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], const Vec3& center,
                                     double radius) const {
    const MeshSpec& m = meshes[0];
    GridLayout L = grid(W(), H(), int(levels.size()), 2);
    const Camera cam =
        common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
    std::vector<Image> panels;
    for (int k = 0; k < 2; ++k)
        for (int level : levels) {
            const std::vector<int> nodes = levelNodes(trees[k], level);
            const double v = sumVolume(trees[k], nodes);
            panels.push_back(boxesPanel(gl, L.panelWidth(), L.panelHeight(), mv, trees[k], m.pose, nodes,
                                        k == 0 ? levelColor(0) : levelColor(1), cam,
                                        std::string(nameOf(trees[k].kind)) + " tree, level " + std::to_string(level),
                                        std::to_string(nodes.size()) + " boxes, volume " + fmt(v)));
        }
    std::vector<LegendItem> legend = {
        {LegendItem::Swatch::Fill, roleColor(Role::ShapeA).withAlpha(0.5f), "torus mesh"},
        {LegendItem::Swatch::Line, levelColor(0), "AABB (world axes)"},
        {LegendItem::Swatch::Line, levelColor(1), "OBB (covariance axes, Gottschalk 1996)"}};
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back("Same mesh (" + std::to_string(trees[0].triangleCount()) + " triangles), same split rule (" +
                      methodWords(build.method) + "), leaves of ≤ " + std::to_string(build.maxLeafTriangles) +
                      (build.maxLeafTriangles == 1 ? " triangle." : " triangles."));
    caption.push_back(
        "The OBBs turn with the tube and hug it; the AABBs keep the world axes and their corners stay empty.");
    return Frame{"levels", "AABB vs OBB boxes at equal depth",
                 composeGrid(gl, L, ss_, common_.title, panels, legend, caption)};
}

Frame BvhScene::aabbVsObbNumbersFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], int maxLevel,
                                      const MeshCollisionResult* q) const {
    const MeshSpec& m = meshes[0];
    GridLayout L = grid(W(), std::min(H(), 520), q ? 3 : 1, 1);
    L.legendBand = 0;
    std::vector<Image> panels;
    BarChartInput bc;
    bc.heading = "Total box volume per level";
    bc.sub = "sum over the boxes of the level";
    for (int k = 0; k < 2; ++k) {
        BarSeries s{nameOf(trees[k].kind), k == 0 ? levelColor(0) : levelColor(1), {}};
        for (int level = 0; level <= maxLevel; ++level)
            s.values.push_back(sumVolume(trees[k], levelNodes(trees[k], level)));
        bc.series.push_back(s);
    }
    for (int level = 0; level <= maxLevel; ++level) bc.groups.push_back(std::to_string(level));
    bc.valueFormat = "";  // too many bars for a number on each: the chart gets a value axis
    panels.push_back(drawBarChart(gl, L.panelWidth(), L.panelHeight(), ss_, bc));
    std::vector<std::string> caption;
    if (q) {
        const MeshSpec& o = meshes[1];
        const MeshView ov = meshView(o.mesh, o.pose);
        Vec3 qc;
        double qr;
        meshSphere({&mv, &ov}, qc, qr);
        Canvas c(gl, canvasOptions(L.panelWidth(), L.panelHeight(), ss_),
                 sphereCamera(qc, qr / zoom, view, L.panelWidth(), L.panelHeight()));
        drawMesh(c, mv, roleColor(Role::ShapeA).withAlpha(0.3f), 0.5f,
                 roleColor(Role::ShapeA).scaled(0.7f).withAlpha(0.5f));
        drawMesh(c, ov, roleColor(Role::ShapeB).withAlpha(0.3f), 0.5f,
                 roleColor(Role::ShapeB).scaled(0.7f).withAlpha(0.5f));
        std::vector<int> ha, hb;
        splitPairs(q[1].pairs, ha, hb);
        drawTriangleSubset(c, mv, ha, roleColor(Role::Highlight), roleColor(Role::Ink), 1.2f, false);
        drawTriangleSubset(c, ov, hb, roleColor(Role::Highlight), roleColor(Role::Ink), 1.2f, false);
        drawHeading(c, "The query: A vs B", std::to_string(q[1].pairs.size()) + " intersecting triangle pairs");
        if (common_.hasLayer("labels")) drawKey(c, 12, 56, {{roleColor(Role::Highlight), "intersecting triangles"}});
        panels.push_back(c.readPixels());
        BarChartInput cc;
        cc.heading = "Cost of the same query";
        cc.sub = "dual traversal (log scale)";
        cc.groups = {"BV tests", "leaf pairs", "triangle tests"};
        for (int k = 0; k < 2; ++k)
            cc.series.push_back(
                {nameOf(trees[k].kind),
                 k == 0 ? levelColor(0) : levelColor(1),
                 {double(q[k].stats.bvTests), double(q[k].stats.leafVisits), double(q[k].stats.triangleTests)}});
        cc.valueFormat = "%.0f";
        cc.logY = true;
        panels.push_back(drawBarChart(gl, L.panelWidth(), L.panelHeight(), ss_, cc));
        caption.push_back("Both trees report the brute-force pairs (" + std::to_string(q[0].pairs.size()) + " of " +
                          std::to_string(m.mesh.triangleCount() * o.mesh.triangleCount()) + ").");
        caption.push_back(
            "An OBB test costs more (15 axes), but the OBB tree needs " +
            pct(double(q[1].stats.bvTests) / double(std::max<long long>(1, q[0].stats.bvTests))) +
            " of the box tests and " +
            pct(double(q[1].stats.triangleTests) / double(std::max<long long>(1, q[0].stats.triangleTests))) +
            " of the triangle tests.");
    }
    std::string vols = "Summed volume AABB / OBB:";
    for (int level : levels)
        vols += "  level " + std::to_string(level) + " " + fmt(sumVolume(trees[0], levelNodes(trees[0], level))) +
                " / " + fmt(sumVolume(trees[1], levelNodes(trees[1], level)));
    caption.push_back(vols + "  (the OBB tree converges to the surface faster)");
    return Frame{"numbers", "volume per level and query cost, AABB vs OBB",
                 composeGrid(gl, L, ss_, common_.title, panels, {}, caption)};
}

}  // namespace cdlab::demos::bvhfig
