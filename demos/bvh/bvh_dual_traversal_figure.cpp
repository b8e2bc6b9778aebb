// The BVH demo's dual_traversal figure (demos/bvh/bvh_scene.h: BvhScene and its helpers).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runDual(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& ma = meshes[0];
    const MeshSpec& mb = meshes[1];
    const Bvh ta = buildChecked(ma.mesh, build.bvKind, build.method),
              tb = buildChecked(mb.mesh, build.bvKind, build.method);
    BvhTraversalTrace tr;
    const MeshCollisionResult r = collideMeshes(ma.mesh, ta, ma.pose, mb.mesh, tb, mb.pose, {}, &tr);
    const MeshCollisionResult brute = collideMeshesBruteForce(ma.mesh, ma.pose, mb.mesh, mb.pose);
    std::vector<DualStep> bv;  // the box-test steps
    const Json steps = countDualSteps(tr, bv);
    const bool equal = samePairs(r.pairs, brute.pairs);
    Json pairs = Json::array();
    for (const TrianglePair& p : r.pairs) pairs.push_back({p.a, p.b});
    out.trace = {{"trees", {treeJson(ta, 3), treeJson(tb, 3)}},
                 {"stats",
                  {{"bv_tests", r.stats.bvTests},
                   {"leaf_pairs", r.stats.leafVisits},
                   {"triangle_tests", r.stats.triangleTests}}},
                 {"pairs", pairs},
                 {"brute_force",
                  {{"triangle_tests", brute.stats.triangleTests}, {"pairs", brute.pairs.size()}, {"equal", equal}}},
                 {"steps", steps}};
    if (!ctx.gl) return;

    const MeshView va = meshView(ma.mesh, ma.pose), vb = meshView(mb.mesh, mb.pose);
    Vec3 center;
    double radius;
    meshSphere({&va, &vb}, center, radius);
    GridLayout L = grid(W(), H(), 2, 1);
    L.columnWidths = {W() - 360, 360};
    L.captionBand = 100;
    const Camera cam =
        common_.camera ? *common_.camera : sphereCamera(center, radius / zoom, view, L.panelWidth(0), L.panelHeight());
    const std::vector<LegendItem> legend = {
        {LegendItem::Swatch::Line, roleColor(Role::ShapeA), "box of A's node"},
        {LegendItem::Swatch::Line, roleColor(Role::ShapeB), "box of B's node"},
        {LegendItem::Swatch::Dashed, roleColor(Role::Muted), "disjoint: pair pruned"},
        {LegendItem::Swatch::Fill, roleColor(Role::Highlight), "intersecting triangles"}};
    for (int k : chosenDualSteps(bv)) {
        if (k < 0 || k >= int(bv.size())) continue;
        out.frames.push_back(dualFrame(*ctx.gl, L, cam, va, vb, ta, tb, ma, mb, bv, k, tr, legend));
    }
    out.frames.push_back(dualResultFrame(*ctx.gl, L, cam, va, vb, r, brute, equal, legend));
}

Json BvhScene::countDualSteps(const BvhTraversalTrace& tr, std::vector<DualStep>& bv) {
    long long bvTests = 0, leafPairs = 0, triTests = 0, hits = 0;
    int pending = 1;
    Json steps = Json::array();
    for (int i = 0; i < int(tr.steps.size()); ++i) {
        const BvhTraversalStep& s = tr.steps[i];
        if (s.action == BvhTraversalAction::TriangleTest) {
            ++triTests;
            hits += s.triangleHit;
            steps.push_back({{"action", nameOf(s.action)},
                             {"triangle_a", s.triangleA},
                             {"triangle_b", s.triangleB},
                             {"hit", s.triangleHit}});
            if (!bv.empty()) bv.back().triangleTests = triTests, bv.back().hits = hits;
            continue;
        }
        ++bvTests;
        pending -= 1;
        if (s.action == BvhTraversalAction::DescendA || s.action == BvhTraversalAction::DescendB) pending += 2;
        if (s.action == BvhTraversalAction::LeafTest) ++leafPairs;
        bv.push_back({i, s, bvTests, leafPairs, triTests, hits, pending});
        steps.push_back({{"node_a", s.nodeA},
                         {"node_b", s.nodeB},
                         {"overlap", s.overlap},
                         {"action", nameOf(s.action)},
                         {"pending", pending}});
    }
    return steps;
}

std::vector<int> BvhScene::chosenDualSteps(const std::vector<DualStep>& bv) const {
    std::vector<int> chosen = stepFrames;
    if (!chosen.empty()) return chosen;
    for (int i = 0; i < std::min<int>(3, int(bv.size())); ++i) chosen.push_back(i);
    for (int i = 0; i < int(bv.size()); ++i)
        if (bv[i].step.action == BvhTraversalAction::Prune) {
            chosen.push_back(i);
            break;
        }
    for (int i = 0; i < int(bv.size()); ++i)
        if (bv[i].step.action == BvhTraversalAction::LeafTest && bv[i].hits > (i > 0 ? bv[i - 1].hits : 0)) {
            chosen.push_back(i);
            break;
        }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    return chosen;
}

Frame BvhScene::dualResultFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va,
                                const MeshView& vb, const MeshCollisionResult& r, const MeshCollisionResult& brute,
                                bool equal, const std::vector<LegendItem>& legend) const {
    Canvas c(gl, canvasOptions(L.panelWidth(0), L.panelHeight(), ss_), cam);
    drawMesh(c, va, roleColor(Role::ShapeA).withAlpha(0.3f), 0.6f,
             roleColor(Role::ShapeA).scaled(0.7f).withAlpha(0.6f));
    drawMesh(c, vb, roleColor(Role::ShapeB).withAlpha(0.3f), 0.6f,
             roleColor(Role::ShapeB).scaled(0.7f).withAlpha(0.6f));
    std::vector<int> ha, hb;
    splitPairs(r.pairs, ha, hb);
    std::sort(ha.begin(), ha.end());
    ha.erase(std::unique(ha.begin(), ha.end()), ha.end());
    std::sort(hb.begin(), hb.end());
    hb.erase(std::unique(hb.begin(), hb.end()), hb.end());
    drawTriangleSubset(c, va, ha, roleColor(Role::Highlight), roleColor(Role::Ink), 1.5f, false);
    drawTriangleSubset(c, vb, hb, roleColor(Role::Highlight), roleColor(Role::Ink), 1.5f, false);
    drawHeading(c, "Result: " + std::to_string(r.pairs.size()) + " intersecting triangle pairs",
                std::to_string(ha.size()) + " triangles of A, " + std::to_string(hb.size()) + " of B");
    if (common_.hasLayer("labels")) drawKey(c, 12, 56, {{roleColor(Role::Highlight), "intersecting triangles"}});
    const Image main = c.readPixels();
    BarChartInput cc;
    cc.heading = "Work done";
    cc.sub = "log scale; brute force tests all " + std::to_string(brute.stats.triangleTests) + " pairs";
    cc.groups = {"BV tests", "leaf pairs", "tri tests", "brute force"};
    cc.series.push_back({"dual traversal",
                         roleColor(Role::Simplex),
                         {double(r.stats.bvTests), double(r.stats.leafVisits), double(r.stats.triangleTests),
                          double(brute.stats.triangleTests)}});
    cc.valueFormat = "%.0f";
    cc.logY = true;
    const Image chart = drawBarChart(gl, L.panelWidth(1), L.panelHeight(), ss_, cc);
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    caption.push_back(std::to_string(r.stats.bvTests) + " box tests, " + std::to_string(r.stats.leafVisits) +
                      " overlapping leaf pairs, " + std::to_string(r.stats.triangleTests) +
                      " triangle tests instead of " + std::to_string(brute.stats.triangleTests) + " (brute force)");
    caption.push_back(std::string("pairs ") + (equal ? "equal" : "DIFFER FROM") +
                      " the brute-force loop over all triangle pairs (" + std::to_string(brute.pairs.size()) + ")");
    return Frame{"result",
                 "result: " + std::to_string(r.pairs.size()) + " triangle pairs, " +
                     std::to_string(r.stats.triangleTests) + " triangle tests",
                 composeGrid(gl, L, ss_, common_.title, {main, chart}, legend, caption)};
}

Frame BvhScene::dualFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va, const MeshView& vb,
                          const Bvh& ta, const Bvh& tb, const MeshSpec& ma, const MeshSpec& mb,
                          const std::vector<DualStep>& bv, int k, const BvhTraversalTrace& tr,
                          const std::vector<LegendItem>& legend) const {
    const DualStep& d = bv[k];
    const BvhTraversalStep& s = d.step;
    Canvas c(gl, canvasOptions(L.panelWidth(0), L.panelHeight(), ss_));
    c.setCamera(cam);
    drawMesh(c, va, roleColor(Role::ShapeA).withAlpha(0.18f), 0.5f,
             roleColor(Role::ShapeA).scaled(0.7f).withAlpha(0.35f));
    drawMesh(c, vb, roleColor(Role::ShapeB).withAlpha(0.18f), 0.5f,
             roleColor(Role::ShapeB).scaled(0.7f).withAlpha(0.35f));
    // The triangles under the two nodes, and their boxes.
    drawTriangleSubset(c, va, nodeTriangles(ta, s.nodeA), roleColor(Role::ShapeA).withAlpha(0.55f),
                       roleColor(Role::ShapeA).scaled(0.6f), 0.8f);
    drawTriangleSubset(c, vb, nodeTriangles(tb, s.nodeB), roleColor(Role::ShapeB).withAlpha(0.55f),
                       roleColor(Role::ShapeB).scaled(0.6f), 0.8f);
    const bool leafTest = s.action == BvhTraversalAction::LeafTest;
    for (int side = 0; side < 2; ++side) {
        const Obb b = side == 0 ? worldBox(ta.box(s.nodeA), ma.pose) : worldBox(tb.box(s.nodeB), mb.pose);
        const Role role = side == 0 ? Role::ShapeA : Role::ShapeB;
        drawBoxFill(c, b, roleColor(role).withAlpha(0.07f));
        drawBoxWire(c, b, lineStyle(role, 3.0f, !s.overlap, true));
    }
    std::string axisName;
    if (!s.overlap)
        axisName =
            drawSeparatingAxis(c, worldBox(ta.box(s.nodeA), ma.pose), worldBox(tb.box(s.nodeB), mb.pose), labels());
    // A leaf pair: its triangle tests follow in the trace; the hits highlighted.
    std::string triNote;
    if (leafTest) {
        std::vector<int> ha, hb;
        int tests = 0, hit = 0;
        for (int i = d.trace + 1; i < int(tr.steps.size()) && tr.steps[i].action == BvhTraversalAction::TriangleTest;
             ++i) {
            ++tests;
            if (tr.steps[i].triangleHit) {
                ++hit;
                ha.push_back(tr.steps[i].triangleA);
                hb.push_back(tr.steps[i].triangleB);
            }
        }
        drawTriangleSubset(c, va, ha, roleColor(Role::Highlight), roleColor(Role::Ink), 1.5f, false);
        drawTriangleSubset(c, vb, hb, roleColor(Role::Highlight), roleColor(Role::Ink), 1.5f, false);
        triNote = std::to_string(tests) + " triangle test" + (tests == 1 ? "" : "s") + ", " + std::to_string(hit) +
                  (hit == 1 ? " hit" : " hits");
    }
    const std::string pair = "pair (A" + std::to_string(s.nodeA) + ", B" + std::to_string(s.nodeB) + ")";
    // Steps count from 0, as in the trace, the scene's step_frames and the file names (step_04).
    drawHeading(c, "Step " + std::to_string(k) + " (of 0–" + std::to_string(bv.size() - 1) + "): " + pair,
                std::string(s.overlap          ? "boxes overlap"
                            : axisName.empty() ? "boxes disjoint"
                                               : "boxes disjoint along " + axisName) +
                    " → " + nameOf(s.action) + (triNote.empty() ? "" : ": " + triNote));
    if (labels()) {
        drawFooter(c,
                   {"pending pairs on the stack: " + std::to_string(d.pending),
                    "so far: " + std::to_string(d.bvTests) + " box tests, " + std::to_string(d.leafPairs) +
                        " leaf pairs, " + std::to_string(d.triangleTests) + " triangle tests, " +
                        std::to_string(d.hits) + (d.hits == 1 ? " hit" : " hits")},
                   roleColor(Role::Ink));
    }
    const Image main = c.readPixels();

    // The two trees: visited nodes tinted, the current one ringed.
    auto treeImage = [&](const Bvh& t, int current, bool isA) {
        TreeDiagramInput tin = treeOf(t, treeDepth);
        const Color base = roleColor(isA ? Role::ShapeA : Role::ShapeB);
        std::vector<char> seen(t.nodes.size(), 0);
        for (int i = 0; i <= k; ++i) seen[isA ? bv[i].step.nodeA : bv[i].step.nodeB] = 1;
        for (std::size_t i = 0; i < t.nodes.size(); ++i)
            tin.look.push_back(seen[i] ? TreeNodeLook{base.mixed(roleColor(Role::Background), 0.35f), 4.0f, false}
                                       : TreeNodeLook{roleColor(Role::Muted), 2.5f, false});
        tin.look[current] = TreeNodeLook{base, 7.0f, true};
        for (int n = current; n > 0; n = t.nodes[n].parent) tin.litEdges.push_back(n);
        tin.heading = std::string("Tree of ") + (isA ? "A" : "B") + " (" + nameOf(t.kind) + ", " +
                      std::to_string(t.nodes.size()) + " nodes)";
        tin.sub =
            "node " + std::to_string(current) + (t.nodes[current].isLeaf() ? " (leaf)" : "") + "; tinted: visited";
        tin.levelLabels = false;
        const int h = L.panelHeight() / 2;
        return drawTreeDiagram(gl, L.panelWidth(1), isA ? h : L.panelHeight() - h, ss_, tin);
    };
    const Image trees = stackVertically(treeImage(ta, s.nodeA, true), treeImage(tb, s.nodeB, false));
    std::vector<std::string> caption;
    if (!common_.caption.empty()) caption.push_back(common_.caption);
    std::string rule;
    if (s.action == BvhTraversalAction::DescendA)
        rule =
            "descend A: B is a leaf or A's box is at least as large (Ericson's \"descend larger\") → push (A.left, "
            "B), (A.right, B)";
    if (s.action == BvhTraversalAction::DescendB)
        rule = "descend B: B's box is larger and not a leaf → push (A, B.left), (A, B.right)";
    if (s.action == BvhTraversalAction::Prune)
        rule = "prune: no triangle under A's node can touch one under B's node; the pair is dropped";
    if (s.action == BvhTraversalAction::LeafTest)
        rule = "leaf pair: test every triangle of A's leaf against every triangle of B's leaf (exact test)";
    caption.push_back(rule);
    return Frame{stepFrameName(k), "step " + std::to_string(k) + ": " + pair + " " + nameOf(s.action),
                 composeGrid(gl, L, ss_, common_.title, {main, trees}, legend, caption)};
}

}  // namespace cdlab::demos::bvhfig
