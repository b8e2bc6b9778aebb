// The space_partition demo's panels figure (demos/space_partition/space_partition_scene.h: SpaceScene
// and its helpers).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos::spacefig {

DemoOutput SpaceScene::runPanels(const RunContext& ctx) const {
    DemoOutput out;
    PanelStructures st;
    buildPanelStructures(st);
    out.trace = panelsTrace(st);
    if (numericOnly(ctx, out)) return out;
    out.frames.push_back(drawPanels(*ctx.gl, figureScale(common_, ctx), st));
    return out;
}

void SpaceScene::buildOctree(PanelStructures& st, double looseness) const {
    // Octree, root = the square region x [0, S] in z (boxes touch z = 0 only: a quadtree).
    const double S = (region.max - region.min).head<2>().maxCoeff();
    OctreeOptions oo;
    oo.maxDepth = octree.maxDepth;
    oo.maxObjectsPerLeaf = octree.leaf;
    oo.looseness = looseness;
    oo.useRootBounds = true;
    oo.rootBounds = {Vec3(region.min.x(), region.min.y(), 0.0), Vec3(region.min.x() + S, region.min.y() + S, S)};
    st.octree.build(boxes, oo);
    st.octreePairs = st.octree.overlappingPairs(&st.octreeTests);
    st.octreeStats = st.octree.stats();
}

void SpaceScene::buildPanelStructures(PanelStructures& st) const {
    // Uniform grid (Ericson §7.1).
    UniformGrid grid;
    UniformGridOptions go;
    go.cellSize = gridCell;
    st.grid = grid.build(boxes, go);
    buildOctree(st, octree.looseness);
    // k-d tree over the box centres.
    for (const Aabb& b : boxes) st.centres.push_back(0.5 * (b.min + b.max));
    st.kdTree.build(st.centres, {kd.rule, kd.leaf});
    // BSP tree of the boxes' walls.
    for (const Aabb& b : boxes) addWalls(rectPolygon(b), st.walls);
    BspTrace btrace;
    st.bspTree.build(st.walls, bsp, &btrace);
    st.bspStats = st.bspTree.stats();
}

Json SpaceScene::panelsTrace(const PanelStructures& st) const {
    const int n = int(boxes.size());
    const UniformGridResult& gr = st.grid;
    const OctreeStats& os = st.octreeStats;
    const KdTree& kt = st.kdTree;
    const BspStats& bs = st.bspStats;
    Json t = Json::object();
    t["objects"] = n;
    t["brute_force_tests"] = std::int64_t(n) * (n - 1) / 2;
    t["grid"] = {{"cell_size", gridCell},
                 {"status", int(gr.status)},
                 {"entries", gr.entries},
                 {"pair_tests", gr.pairTests},
                 {"pairs", gr.pairs}};
    Json depthCounts = Json::array();
    for (int c : os.objectsPerDepth) depthCounts.push_back(c);
    t["octree"] = {{"nodes", os.nodeCount},
                   {"leaves", os.leafCount},
                   {"depth", os.maxDepthReached},
                   {"objects_at_root", os.objectsAtRoot},
                   {"objects_per_depth", depthCounts},
                   {"pair_tests", st.octreeTests},
                   {"pairs", int(st.octreePairs.size())}};
    t["kd_tree"] = {{"nodes", int(kt.nodes().size())}, {"leaves", kt.leafCount()}, {"depth", kt.depth()}};
    t["bsp"] = {{"polygons", int(st.walls.size())},
                {"nodes", bs.nodeCount},
                {"inner", bs.innerCount},
                {"solid_leaves", bs.solidLeaves},
                {"empty_leaves", bs.emptyLeaves},
                {"depth", bs.depth},
                {"splits", bs.splits},
                {"fragments", bs.fragmentCount}};
    return t;
}

Frame SpaceScene::drawPanels(GlContext& gl, int ss, const PanelStructures& st) const {
    Canvas canvas(gl, sceneCanvasOptions(common_, ss));
    const Vec3 size = region.max - region.min;
    const double W = std::max(size.x(), size.y());
    const double gap = 0.16 * W;
    const Vec3 offsets[4] = {P(0, 0), P(W + gap, 0), P(0, -(W + gap)), P(W + gap, -(W + gap))};
    const Vec3 middle = region.min + P(0.5 * (2 * W + gap), 0.5 * W - 0.5 * (W + gap));
    // Room above for the title and two heading lines per row, below for the caption.
    canvas.setCamera(Camera::twoD(middle.x(), middle.y() + 0.02 * W, (2 * W + gap) * 1.26));
    PanelView v{canvas,
                Aabb{region.min, region.min + P(W, W)},
                W,
                std::vector<bool>(boxes.size(), false),
                common_.hasLayer("objects"),
                common_.hasLayer("cells"),
                common_.hasLayer("splits")};
    for (const auto& p : st.octreePairs) v.paired[std::size_t(p.first)] = v.paired[std::size_t(p.second)] = true;
    drawGridPanel(v, offsets[0], st);
    drawOctreePanel(v, offsets[1], st);
    drawKdPanel(v, offsets[2], st);
    drawBspPanel(v, offsets[3], st);
    return titledFrame(canvas, "panels");
}

void SpaceScene::drawBoxes(const PanelView& v, const Vec3& at, const std::function<Color(int)>& fill,
                           float alpha) const {
    if (!v.drawObjects) return;
    for (int i = 0; i < int(boxes.size()); ++i) {
        fillRect(v.canvas, boxes[std::size_t(i)], at, fill(i).withAlpha(alpha));
        outlineRect(
            v.canvas, boxes[std::size_t(i)], at,
            lineStyle(v.paired[std::size_t(i)] ? Role::Highlight : Role::Ink, v.paired[std::size_t(i)] ? 2.2f : 1.4f));
    }
}

void SpaceScene::drawGridPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
    Canvas& canvas = v.canvas;
    const Aabb& frame = v.frame;
    if (v.cells) {
        std::map<std::pair<std::int64_t, std::int64_t>, int> occupancy;
        for (const Aabb& b : boxes) {
            const auto lo = UniformGrid::cellOf(b.min, gridCell), hi = UniformGrid::cellOf(b.max, gridCell);
            for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
                for (std::int64_t y = lo[1]; y <= hi[1]; ++y) ++occupancy[{x, y}];
        }
        for (const auto& [cell, count] : occupancy) {
            const Aabb r{P(double(cell.first) * gridCell, double(cell.second) * gridCell),
                         P(double(cell.first + 1) * gridCell, double(cell.second + 1) * gridCell)};
            fillRect(canvas, r, at, roleColor(Role::Muted).withAlpha(std::min(0.55f, 0.12f * float(count))));
        }
        const LineStyle gl = lineStyle(Role::Muted, 1.2f);
        for (double x = std::ceil(frame.min.x() / gridCell) * gridCell; x <= frame.max.x(); x += gridCell)
            canvas.drawLine(at + P(x, frame.min.y()), at + P(x, frame.max.y()), gl);
        for (double y = std::ceil(frame.min.y() / gridCell) * gridCell; y <= frame.max.y(); y += gridCell)
            canvas.drawLine(at + P(frame.min.x(), y), at + P(frame.max.x(), y), gl);
    }
    drawBoxes(
        v, at, [](int) { return roleColor(Role::ShapeA); }, 0.30f);
    outlineRect(canvas, frame, at, lineStyle(Role::Ink, 1.5f));
    heading(canvas, at + P(frame.min.x(), frame.max.y()), "Uniform grid, cell h = " + formatNumber(gridCell),
            std::to_string(st.grid.entries) + " box-cell entries, " + std::to_string(st.grid.pairTests) + " tests, " +
                std::to_string(st.grid.pairs) + " pairs");
}

void SpaceScene::drawOctreePanel(const PanelView& v, const Vec3& at, const PanelStructures& st,
                                 const std::string& title) const {
    Canvas& canvas = v.canvas;
    const Aabb& frame = v.frame;
    const Octree& ot = st.octree;
    const OctreeStats& os = st.octreeStats;
    if (v.cells)
        for (const OctreeNode& node : ot.nodes()) {
            outlineRect(canvas, node.cell, at,
                        LineStyle{depthWidth(node.depth), depthColor(node.depth, os.maxDepthReached)});
            // A loose octree: the enlarged cell its objects fit in, dashed, where it stores any; drawn
            // within the root's square (nothing lies outside it, and beyond it the dashes crossed the
            // headings).
            if (!node.objects.empty() && !(node.looseCell.min == node.cell.min && node.looseCell.max == node.cell.max)) {
                const Aabb shown{node.looseCell.min.cwiseMax(frame.min), node.looseCell.max.cwiseMin(frame.max)};
                outlineRect(canvas, shown, at, LineStyle{1.2f, octreeDepthColor(node.depth).scaled(0.7f), 6.0f, false});
            }
        }
    drawBoxes(
        v, at, [&](int i) { return octreeDepthColor(ot.nodes()[std::size_t(ot.nodeOf(i))].depth); }, 0.45f);
    outlineRect(canvas, frame, at, lineStyle(Role::Ink, 1.5f));
    heading(canvas, at + P(frame.min.x(), frame.max.y()),
            (title.empty() ? "Octree (seen as a quadtree), " : title + ", ") + std::to_string(os.nodeCount) + " nodes",
            std::to_string(st.octreeTests) + " tests, " + std::to_string(st.octreePairs.size()) + " pairs; " +
                std::to_string(os.objectsAtRoot) + " boxes on the root's split lines");
    if (common_.hasLayer("labels")) {
        // Legend: box colour = depth of the node that stores it.
        // Rows 22 px apart whatever the zoom (world units per pixel from the camera).
        Eigen::Vector2d p0, p1;
        double rowWorld = 0.045 * v.W;
        if (canvas.project(at, p0) && canvas.project(at + P(0, 1), p1) && (p1 - p0).norm() > 0)
            rowWorld = std::max(rowWorld, 22.0 / (p1 - p0).norm());
        for (int d = 0; d <= os.maxDepthReached; ++d) {
            const Vec3 p = at + P(frame.max.x(), frame.max.y()) + P(0.02 * v.W, -rowWorld * (d + 0.5));
            canvas.drawPoint(p, 6.0f, octreeDepthColor(d).withAlpha(0.8f));
            canvas.drawText(
                p,
                (d == 0 ? "root" : "d" + std::to_string(d)) + ": " +
                    std::to_string(d < int(os.objectsPerDepth.size()) ? os.objectsPerDepth[std::size_t(d)] : 0),
                TextStyle{17.0f, roleColor(Role::Ink), Anchor::Left, true, false, {9, 0}});
        }
    }
}

void SpaceScene::drawKdPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
    Canvas& canvas = v.canvas;
    const KdTree& kt = st.kdTree;
    drawBoxes(
        v, at, [](int) { return roleColor(Role::Muted); }, 0.18f);
    if (v.splits)
        for (std::size_t id = 0; id < kt.nodes().size(); ++id) {
            const KdNode& node = kt.nodes()[id];
            if (node.isLeaf()) continue;
            const LineStyle s{depthWidth(node.depth), depthColor(node.depth, kt.depth()), 0.0f, true};
            drawKdSplit(canvas, node, kdCellInFrame(kt, int(id), v.frame), at, s);
        }
    if (v.drawObjects)
        for (const Vec3& c : st.centres)
            canvas.drawPoint(at + c, 4.5f, roleColor(Role::Query), true, 1.0f, roleColor(Role::Ink));
    outlineRect(canvas, v.frame, at, lineStyle(Role::Ink, 1.5f));
    heading(canvas, at + P(v.frame.min.x(), v.frame.max.y()),
            "k-d tree of the box centres, depth " + std::to_string(kt.depth()),
            std::to_string(kt.nodes().size()) + " nodes; median splits " +
                (kd.rule == KdSplitRule::Cycle ? "cycling x, y" : "on the widest axis") + " (root: darkest)");
}

void SpaceScene::drawBspPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
    Canvas& canvas = v.canvas;
    const BspTree& bt = st.bspTree;
    const BspStats& bs = st.bspStats;
    const auto regions = bspRegions(bt, rectPolygon(v.frame));
    if (v.drawObjects)
        for (const Aabb& b : boxes) fillRect(canvas, b, at, roleColor(Role::ShapeA).withAlpha(0.30f));
    if (v.splits) drawBspSplits(canvas, bt, regions, at, 0.6f);
    // Cut walls in the direction colour: the highlight colour outlines a box in a pair in every
    // panel (the review: orange meant two things).
    if (v.drawObjects) drawBspFragments(canvas, bt, at, 3.5f, 2.5f, Role::Direction);
    outlineRect(canvas, v.frame, at, lineStyle(Role::Ink, 1.5f));
    heading(canvas, at + P(v.frame.min.x(), v.frame.max.y()),
            "BSP tree of the box walls, depth " + std::to_string(bs.depth),
            std::to_string(bs.innerCount) + " planes, " + std::to_string(bs.splits) + " walls cut in two");
    if (common_.hasLayer("labels"))
        keyBelow(canvas, at + v.frame.min, {{roleColor(Role::Direction), "a wall cut in two"}});
}

}  // namespace cdlab::demos::spacefig

namespace cdlab::demos::spacefig {

DemoOutput SpaceScene::runOctreeLoose(const RunContext& ctx) const {
    // The same boxes in a tight octree and a loose one (looseness k: each cell enlarged k times
    // about its centre; Ulrich, "Loose Octrees", Game Programming Gems 2000; Ericson §7.3.6).
    const double k = octree.looseness > 1 ? octree.looseness : 2.0;
    PanelStructures tight, loose;
    buildOctree(tight, 1.0);
    buildOctree(loose, k);
    DemoOutput out;
    const auto stats = [](const PanelStructures& st) {
        const OctreeStats& os = st.octreeStats;
        return Json{{"nodes", os.nodeCount}, {"depth", os.maxDepthReached}, {"objects_at_root", os.objectsAtRoot},
                    {"objects_per_depth", os.objectsPerDepth}, {"pair_tests", st.octreeTests},
                    {"pairs", int(st.octreePairs.size())}};
    };
    Json depthOf = Json::array();
    for (std::size_t i = 0; i < boxes.size(); ++i)
        depthOf.push_back({tight.octree.nodes()[std::size_t(tight.octree.nodeOf(int(i)))].depth,
                           loose.octree.nodes()[std::size_t(loose.octree.nodeOf(int(i)))].depth});
    Json list = Json::array();
    for (const Aabb& b : boxes) list.push_back({b.min.x(), b.min.y(), b.max.x(), b.max.y()});
    out.trace = {{"looseness", k}, {"tight", stats(tight)}, {"loose", stats(loose)}, {"box_depths", depthOf},
                 {"box_list", list}, {"root_side", (region.max - region.min).head<2>().maxCoeff()}};
    if (numericOnly(ctx, out)) return out;
    Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
    const Vec3 size = region.max - region.min;
    const double W = std::max(size.x(), size.y()), gap = 0.3 * W;
    const Vec3 middle = region.min + P(0.5 * (2 * W + gap), 0.5 * W);
    canvas.setCamera(Camera::twoD(middle.x() + 0.05 * W, middle.y() + 0.02 * W, (2 * W + gap) * 0.9));
    PanelView v{canvas, Aabb{region.min, region.min + P(W, W)}, W, std::vector<bool>(boxes.size(), false),
                common_.hasLayer("objects"), common_.hasLayer("cells"), common_.hasLayer("splits")};
    for (const auto& p : tight.octreePairs) v.paired[std::size_t(p.first)] = v.paired[std::size_t(p.second)] = true;
    drawOctreePanel(v, P(0, 0), tight, "Tight octree");
    drawOctreePanel(v, P(W + gap, 0), loose, "Loose octree, k = " + formatNumber(k));
    out.frames.push_back(titledFrame(canvas, "loose"));
    return out;
}

}  // namespace cdlab::demos::spacefig
