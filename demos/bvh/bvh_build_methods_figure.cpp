// The BVH demo's build_methods figure (demos/bvh/bvh_scene.h: BvhScene and its helpers).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runBuildMethods(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    const BvhBuildMethod methods[2] = {BvhBuildMethod::TopDownMedian, BvhBuildMethod::BottomUp};
    const Bvh trees[2] = {buildChecked(m.mesh, build.bvKind, methods[0]),
                          buildChecked(m.mesh, build.bvKind, methods[1])};
    const int maxLevel = *std::max_element(levels.begin(), levels.end());
    out.trace = {{"mesh", m.kind}, {"trees", {treeJson(trees[0], maxLevel + 2), treeJson(trees[1], maxLevel + 2)}}};
    if (!ctx.gl) return;
    GridLayout L = grid(W(), H(), int(levels.size()) + 1, 2);
    L.captionBand = 100;
    const MeshView mv = meshView(m.mesh, m.pose);
    Vec3 center;
    double radius;
    sphereOverTopLevel(mv, trees, m.pose, center, radius);
    const Camera cam =
        common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
    std::vector<Image> panels;
    for (int k = 0; k < 2; ++k) {
        for (int level : levels) {
            const std::vector<int> nodes = levelNodes(trees[k], level);
            panels.push_back(
                boxesPanel(*ctx.gl, L.panelWidth(), L.panelHeight(), mv, trees[k], m.pose, nodes, levelColor(level),
                           cam, std::string(k == 0 ? "Top-down" : "Bottom-up") + ", level " + std::to_string(level),
                           std::to_string(nodes.size()) + " boxes, volume " + fmt(sumVolume(trees[k], nodes))));
        }
        // The whole tree, every leaf at its real depth: drawn only to level 5 both are complete
        // binary trees (the review: "balanced vs greedy" not visible); the top-down tree's leaves
        // end on one level, the bottom-up one's spread over several.
        TreeDiagramInput tin = treeOf(trees[k], trees[k].height());
        tin.heading =
            std::string(k == 0 ? "Top-down" : "Bottom-up") + " tree, height " + std::to_string(trees[k].height());
        tin.sub = std::to_string(trees[k].nodes.size()) + " nodes, total volume " + fmt(totalVolume(trees[k]));
        tin.levelLabels = false;
        for (const BvhNode& n : trees[k].nodes) {
            const bool shown = std::find(levels.begin(), levels.end(), n.depth) != levels.end();
            tin.look.push_back(shown                       ? TreeNodeLook{levelColor(n.depth), 4.0f, false}
                               : n.depth <= levels.back() ? TreeNodeLook{roleColor(Role::Muted), 2.5f, false}
                                                          : TreeNodeLook{roleColor(Role::Muted), 1.0f, false});
        }
        panels.push_back(drawTreeDiagram(*ctx.gl, L.panelWidth(), L.panelHeight(), ss_, tin));
    }
    std::vector<LegendItem> legend;
    for (int level : levels)
        legend.push_back({LegendItem::Swatch::Line, levelColor(level), "level " + std::to_string(level)});
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back(
        "Top-down splits at the median centroid on the longest axis; bottom-up merges the pair with the smallest "
        "union box (Walter et al. 2008).");
    std::string vols = "Summed volume top-down / bottom-up:";
    for (int level : levels)
        vols += "  level " + std::to_string(level) + " " + fmt(sumVolume(trees[0], levelNodes(trees[0], level))) +
                " / " + fmt(sumVolume(trees[1], levelNodes(trees[1], level)));
    caption.push_back(vols + ";  all nodes " + fmt(totalVolume(trees[0])) + " / " + fmt(totalVolume(trees[1])));
    out.frames.push_back(Frame{"methods", "top-down vs bottom-up",
                               composeGrid(*ctx.gl, L, ss_, common_.title, panels, legend, caption)});
}

}  // namespace cdlab::demos::bvhfig
