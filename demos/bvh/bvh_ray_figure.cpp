// The BVH demo's ray_query figure (demos/bvh/bvh_scene.h: BvhScene and its helpers): one ray walking
// a tree (core's queryBvhRay with its BvhTraversalTrace). Left: the mesh, the ray, every box the walk
// tested — entered (solid, in its level's colour) or pruned (dashed grey) — and the triangles the
// leaves tested, the ones hit highlighted with the first hit marked. Right: the tree with the
// entered nodes lit along their edges and the pruned ones ringed grey. The counts beside brute force
// (one test per triangle). Test: tests/demos/bvh/bvh_ray_test.cpp.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runRayQuery(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    const Bvh tree = buildChecked(m.mesh, build.bvKind, build.method);
    BvhTraversalTrace trace;
    const BvhQueryResult r = queryBvhRay(tree, m.mesh, m.pose, ray, &trace);
    std::vector<int> entered, pruned, tested;
    Json steps = Json::array();
    for (const BvhTraversalStep& s : trace.steps) {
        steps.push_back({{"node", s.nodeA}, {"action", nameOf(s.action)}, {"overlap", s.overlap}, {"triangle", s.triangleA},
                         {"hit", s.triangleHit}});
        if (s.action == BvhTraversalAction::Prune) pruned.push_back(s.nodeA);
        else if (s.action == BvhTraversalAction::TriangleTest) tested.push_back(s.triangleA);
        else entered.push_back(s.nodeA);
    }
    out.trace = {{"mesh", m.kind},
                 {"tree", treeJson(tree, 0)},
                 {"ray", {{"origin", vec3Json(ray.origin)}, {"direction", vec3Json(ray.direction)}}},
                 {"steps", steps},
                 {"box_tests", r.stats.bvTests},
                 {"leaf_visits", r.stats.leafVisits},
                 {"triangle_tests", r.stats.triangleTests},
                 {"hits", r.hits},
                 {"first_t", r.firstT},
                 {"first_triangle", r.firstTriangle}};
    if (!ctx.gl) return;
    GridLayout L = grid(W(), H(), 2, 1);
    L.captionBand = 100;
    const MeshView mv = meshView(m.mesh, m.pose);
    Vec3 center;
    double radius;
    meshSphere({&mv}, center, radius, {ray.origin});
    const Camera cam = common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
    // Left: the walk in 3D.
    Canvas c(*ctx.gl, canvasOptions(L.panelWidth(), L.panelHeight(), ss_));
    c.setCamera(cam);
    if (common_.hasLayer("mesh"))
        drawMesh(c, mv, roleColor(Role::ShapeA).withAlpha(0.25f), 0.5f, roleColor(Role::ShapeA).scaled(0.7f).withAlpha(0.5f));
    drawTriangleSubset(c, mv, tested, roleColor(Role::Muted).withAlpha(0.9f), roleColor(Role::Ink), 1.0f);
    drawTriangleSubset(c, mv, r.hits, roleColor(Role::Highlight), roleColor(Role::Ink), 1.5f);
    // Boxes: the top levels' (entered solid, pruned dashed) and the leaves entered; the tree on the
    // right has every node (dozens of nested wireframes hid the torus).
    constexpr int kDrawnDepth = 2;
    if (common_.hasLayer("boxes")) {
        for (int i : pruned)
            if (tree.nodes[std::size_t(i)].depth <= kDrawnDepth + 1)
                drawBoxWire(c, worldBox(tree.box(i), m.pose), lineStyle(Role::Muted, 1.5f, true));
        for (int i : entered) {
            const BvhNode& n = tree.nodes[std::size_t(i)];
            const bool leaf = n.left < 0;
            if (n.depth > kDrawnDepth && !leaf) continue;
            LineStyle s = lineStyle(Role::Ink, leaf ? 2.5f : 2.0f);
            s.color = levelColor(n.depth);
            drawBoxWire(c, worldBox(tree.box(i), m.pose), s);
        }
    }
    const double reach = r.firstTriangle >= 0 ? std::max(r.firstT * 1.6, 2.2 * radius / ray.direction.norm())
                                              : 2.2 * radius / ray.direction.norm();
    c.drawArrow(ray.origin, ray.at(reach), lineStyle(Role::Ink, 3.0f, false, true));  // not a level colour
    if (r.firstTriangle >= 0) c.drawPoint(ray.at(r.firstT), 10.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
    drawHeading(c, "The walk", std::to_string(entered.size()) + " boxes entered, " + std::to_string(pruned.size()) +
                                   " pruned (drawn: levels 0 to " + std::to_string(kDrawnDepth + 1) + " and the leaves entered)");
    // Right: the tree, entered nodes lit by level, pruned ones grey.
    TreeDiagramInput tin = treeOf(tree, treeDepth);
    tin.heading = "The tree (" + std::to_string(tree.nodes.size()) + " nodes)";
    tin.sub = "lit: entered; grey ring: pruned; the rest never reached";
    tin.look.assign(tree.nodes.size(), TreeNodeLook{roleColor(Role::Muted).withAlpha(0.5f), 2.0f, false});
    for (int i : pruned) tin.look[std::size_t(i)] = TreeNodeLook{roleColor(Role::Muted), 4.0f, true};
    for (int i : entered) {
        tin.look[std::size_t(i)] = TreeNodeLook{levelColor(tree.nodes[std::size_t(i)].depth), 5.0f, false};
        tin.litEdges.push_back(i);
    }
    const std::vector<Image> panels = {c.readPixels(), drawTreeDiagram(*ctx.gl, L.panelWidth(), L.panelHeight(), ss_, tin)};
    const std::vector<LegendItem> legend = {{LegendItem::Swatch::Line, levelColor(1), "box entered (its level's colour)"},
                                            {LegendItem::Swatch::Dashed, roleColor(Role::Muted), "box pruned"},
                                            {LegendItem::Swatch::Fill, roleColor(Role::Muted), "triangle tested"},
                                            {LegendItem::Swatch::Fill, roleColor(Role::Highlight), "triangle hit"}};
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back(std::to_string(r.stats.bvTests) + " box tests, " + std::to_string(r.stats.leafVisits) + " leaves, " +
                      std::to_string(r.stats.triangleTests) + " triangle tests against " +
                      std::to_string(m.mesh.triangleCount()) + " by brute force; " + std::to_string(r.hits.size()) + " hit" +
                      (r.firstTriangle >= 0 ? ", the first at t = " + fmt(r.firstT) + " (triangle " + std::to_string(r.firstTriangle) + ")"
                                            : ""));
    out.frames.push_back(Frame{"walk", "a ray walking the tree", composeGrid(*ctx.gl, L, ss_, common_.title, panels, legend, caption)});
}

}  // namespace cdlab::demos::bvhfig
