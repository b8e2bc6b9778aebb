// The BVH demo's hierarchy_levels figure (demos/bvh/bvh_scene.h: BvhScene and its helpers).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runLevels(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    BvhBuildTrace bt;
    const Bvh bvh = buildChecked(m.mesh, build.bvKind, build.method, &bt);
    const int maxLevel = *std::max_element(levels.begin(), levels.end());
    Json t = treeJson(bvh, bvh.height());
    t["mesh"] = m.kind;
    // The build trace of the drawn levels: each node's range and split.
    Json steps = Json::array();
    for (const BvhBuildStep& s : bt.steps)
        if (s.depth <= maxLevel)
            steps.push_back({{"node", s.node},
                             {"depth", s.depth},
                             {"first", s.first},
                             {"count", s.count},
                             {"split_axis", s.splitAxis},
                             {"split_position", s.splitPosition},
                             {"box", obbJson(s.box)}});
    t["build_steps"] = steps;
    out.trace = t;
    if (!ctx.gl) return;

    GridLayout L = grid(W(), H(), 3, 2);
    L.captionBand = 100;
    const MeshView mv = meshView(m.mesh, m.pose);
    Vec3 center;
    double radius;
    meshSphere({&mv}, center, radius, rootCorners(bvh, m.pose));
    const Camera cam =
        common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
    const double rootVolume = volume(bvh.box(0));
    std::vector<Image> panels;
    for (int level : levels) {
        const std::vector<int> nodes = levelNodes(bvh, level);
        const double v = sumVolume(bvh, nodes);
        panels.push_back(boxesPanel(*ctx.gl, L.panelWidth(), L.panelHeight(), mv, bvh, m.pose, nodes, levelColor(level),
                                    cam,
                                    "Level " + std::to_string(level) + ": " + std::to_string(nodes.size()) + " box" +
                                        (nodes.size() == 1 ? "" : "es"),
                                    "total volume " + fmt(v) + " (" + pct(v / rootVolume) + " of the root)"));
    }
    while (int(panels.size()) < L.columns * L.rows - 1)
        panels.push_back(Image::blank(L.panelWidth(), L.panelHeight(), ss_));
    if (common_.hasLayer("tree")) {
        TreeDiagramInput tin = treeOf(bvh, treeDepth);
        tin.heading =
            "The tree (" + std::to_string(bvh.nodes.size()) + " nodes, height " + std::to_string(bvh.height()) + ")";
        tin.sub = "binary; drawn to level " + std::to_string(treeDepth) + ", dashed: more below";
        for (const BvhNode& n : bvh.nodes) {
            const bool shown = std::find(levels.begin(), levels.end(), n.depth) != levels.end();
            tin.look.push_back(shown ? TreeNodeLook{levelColor(n.depth), n.depth <= 3 ? 5.0f : 3.5f, false}
                                     : TreeNodeLook{roleColor(Role::Muted), 2.5f, false});
        }
        tin.litLevels = levels;
        panels.push_back(drawTreeDiagram(*ctx.gl, L.panelWidth(), L.panelHeight(), ss_, tin));
    }
    std::vector<LegendItem> legend = {{LegendItem::Swatch::Fill, roleColor(Role::ShapeA).withAlpha(0.5f), "mesh"}};
    for (int level : levels)
        legend.push_back({LegendItem::Swatch::Line, levelColor(level), "level " + std::to_string(level)});
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back(std::string(nameOf(bvh.kind)) + " tree, " + methodWords(bvh.method) + ", leaves of ≤ " +
                      std::to_string(build.maxLeafTriangles) + " triangle" + (build.maxLeafTriangles == 1 ? "" : "s") +
                      "; " + std::to_string(bvh.triangleCount()) + " triangles, " + std::to_string(bvh.nodes.size()) +
                      " nodes, height " + std::to_string(bvh.height()));
    std::string vols = "Summed box volume, levels 0.." + std::to_string(bvh.height()) + ":";
    for (int level = 0; level <= bvh.height(); ++level) vols += " " + fmt(sumVolume(bvh, levelNodes(bvh, level)));
    caption.push_back(vols + ". Boxes of one level overlap, and on a closed");
    caption.push_back(
        "surface the sum only falls once the boxes are thinner than the shape: the tree pays off at the deep "
        "levels.");
    out.frames.push_back(Frame{"levels",
                               "levels " + std::to_string(levels.front()) + ".." + std::to_string(maxLevel) +
                                   " of the " + nameOf(bvh.kind) + " tree",
                               composeGrid(*ctx.gl, L, ss_, common_.title, panels, legend, caption)});
}

}  // namespace cdlab::demos::bvhfig
