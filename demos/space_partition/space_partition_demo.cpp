// Space partitioning, drawn from above (Ericson, Real-Time Collision Detection ch. 7-8): the same
// boxes under a uniform grid (core/broadphase/uniform_grid.h), an octree (core/broadphase/octree.h), a k-d tree over
// the box centres (core/spatial/kd_tree.h) and a solid-leaf BSP tree of the boxes' walls
// (core/spatial/bsp_tree.h); k-d nearest / range queries; a BSP of a non-convex polygon with point
// classification, a segment query and the tree diagram. All numbers come from core; this file
// only draws.
//
// Everything lies in the plane z = 0 (boxes are flat, points have z = 0, BSP walls are vertical
// quads over z in [-1, 1]), so each 3D structure is seen exactly from the top: the octree never
// cuts at z (its root spans z in [0, S] and the boxes touch only z = 0), so it acts as a
// quadtree; BSP planes are vertical and show as lines.
//
// Scene keys (besides the common ones): see docs/scenes.md, section space_partition.
#include "demos/space_partition/space_partition_demo.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>

#include "core/base/orient.h"
#include "core/broadphase/octree.h"
#include "core/broadphase/uniform_grid.h"
#include "core/overlap/polygon_tests.h"
#include "core/spatial/bsp_tree.h"
#include "core/spatial/kd_tree.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"objects", "cells", "splits", "labels", "queries", "tree"};

Vec3 P(double x, double y) { return Vec3(x, y, 0.0); }
Json vec2Json(const Vec3& v) { return Json::array({v.x(), v.y()}); }

// mt19937's output sequence is fixed by the standard (unlike the distributions): uniform doubles
// from it keep scenes identical on every platform.
struct SceneRng {
    std::mt19937 engine;
    explicit SceneRng(unsigned seed) : engine(seed) {}
    double uniform(double a, double b) { return a + (b - a) * (double(engine()) / 4294967296.0); }
};

// Depth colour ramp for split lines: near-black blue at the root, lighter blue deeper down
// (orange is kept for "in a pair" / "was split").
Color depthColor(int depth, int maxDepth) {
    const float t = maxDepth > 0 ? float(std::min(depth, maxDepth)) / float(maxDepth) : 0.0f;
    const Color blue = categorical(4);
    return blue.scaled(0.35f).mixed(blue.mixed(roleColor(Role::Background), 0.45f), t);
}
// Box colour by the octree depth it is stored at (orange excluded: it marks pairs).
Color octreeDepthColor(int depth) {
    static const int kIndex[6] = {6, 1, 2, 3, 4, 5};
    return categorical(kIndex[std::min(depth, 5)]);
}
float depthWidth(int depth) { return std::max(1.2f, 4.0f - 0.5f * float(depth)); }

// Convex polygon (xy, counter-clockwise) clipped to n . x >= d (keepFront) or <= d.
std::vector<Vec3> clipHalfPlane(const std::vector<Vec3>& poly, const Vec3& n, double d, bool keepFront) {
    std::vector<Vec3> out;
    const double sign = keepFront ? 1.0 : -1.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        const double sa = sign * (n.dot(a) - d), sb = sign * (n.dot(b) - d);
        if (sa >= 0) out.push_back(a);
        if ((sa >= 0) != (sb >= 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    return out;
}

// The part of the line n . x = d inside a convex polygon: its two crossing points (false if none).
bool lineInPolygon(const std::vector<Vec3>& poly, const Vec3& n, double d, Vec3& p, Vec3& q) {
    std::vector<Vec3> hits;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        const double sa = n.dot(a) - d, sb = n.dot(b) - d;
        if ((sa <= 0 && sb > 0) || (sa > 0 && sb <= 0)) hits.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    if (hits.size() < 2) return false;
    p = hits[0];
    q = hits[1];
    return true;
}

std::vector<Vec3> rectPolygon(const Aabb& r) {
    return {P(r.min.x(), r.min.y()), P(r.max.x(), r.min.y()), P(r.max.x(), r.max.y()), P(r.min.x(), r.max.y())};
}

// Vertical wall quads of a counter-clockwise xy polygon (outward normals), z in [-1, 1].
void addWalls(const std::vector<Vec3>& poly, std::vector<BspPolygon>& walls) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        walls.push_back(
            {{Vec3(a.x(), a.y(), -1), Vec3(b.x(), b.y(), -1), Vec3(b.x(), b.y(), 1), Vec3(a.x(), a.y(), 1)}});
    }
}

// Top view of a wall fragment: its bottom edge (z = min).
void fragmentSegment(const BspFragment& f, Vec3& p, Vec3& q) {
    double zmin = INFINITY;
    for (const Vec3& v : f.vertices) zmin = std::min(zmin, v.z());
    std::vector<Vec3> low;
    for (const Vec3& v : f.vertices)
        if (v.z() <= zmin + 1e-9) low.push_back(P(v.x(), v.y()));
    p = low.empty() ? P(0, 0) : low.front();
    q = low.empty() ? P(0, 0) : low.back();
}

// Region (xy polygon) of every BSP node inside `root`, by clipping with the ancestors' planes.
std::vector<std::vector<Vec3>> bspRegions(const BspTree& tree, const std::vector<Vec3>& root) {
    std::vector<std::vector<Vec3>> regions(tree.nodes().size());
    if (tree.nodes().empty()) return regions;
    regions[0] = root;
    for (std::size_t i = 0; i < tree.nodes().size(); ++i) {  // parents come before children
        const BspNode& n = tree.nodes()[i];
        if (n.kind != BspNodeKind::Inner) continue;
        const Vec3 nrm = P(n.plane.normal.x(), n.plane.normal.y());
        regions[std::size_t(n.front)] = clipHalfPlane(regions[i], nrm, n.plane.offset, true);
        regions[std::size_t(n.back)] = clipHalfPlane(regions[i], nrm, n.plane.offset, false);
    }
    return regions;
}

struct OctreeParams {
    int maxDepth = 5;
    int leaf = 2;
    double looseness = 1.0;
};
struct KdParams {
    KdSplitRule rule = KdSplitRule::Cycle;
    int leaf = 1;
};

// ---------------------------------------------------------------------------------------------

class SpaceScene final : public PreparedScene {
public:
    explicit SpaceScene(SceneCommon common) : PreparedScene(std::move(common)) {}

    std::string figure = "panels";
    // panels
    std::vector<Aabb> boxes;
    Aabb region{P(0, 0), P(16, 16)};
    double gridCell = 2.0;
    OctreeParams octree;
    KdParams kd;
    BspOptions bsp;
    // kd_query
    std::vector<Vec3> points;
    Vec3 query = P(0, 0);
    Aabb range{P(0, 0), P(0, 0)};
    // bsp_shape
    std::vector<Vec3> polygon;
    std::vector<Vec3> queries;
    Segment segment{P(0, 0), P(0, 0)};
    bool hasSegment = false;

    DemoOutput execute(const RunContext& ctx) const override {
        if (figure == "panels") return runPanels(ctx);
        if (figure == "kd_query") return runKdQuery(ctx);
        return runBspShape(ctx);
    }

private:
    static void outlineRect(Canvas& c, const Aabb& r, const Vec3& at, const LineStyle& s) {
        std::vector<Vec3> poly = rectPolygon(r);
        for (Vec3& v : poly) v += at;
        c.drawPolyline(poly, true, s);
    }
    static void fillRect(Canvas& c, const Aabb& r, const Vec3& at, const Color& color) {
        std::vector<Vec3> poly = rectPolygon(r);
        for (Vec3& v : poly) v += at;
        c.drawPolygon(poly, color);
    }
    static std::vector<Vec3> shifted(std::vector<Vec3> poly, const Vec3& at) {
        for (Vec3& v : poly) v += at;
        return poly;
    }
    // Heading above a panel whose top-left corner is `topLeft` (world).
    static void heading(Canvas& c, const Vec3& topLeft, const std::string& text, const std::string& sub) {
        c.drawText(topLeft, text, TextStyle{20.0f, roleColor(Role::Ink), Anchor::BottomLeft, true, true, {0, -24}});
        c.drawText(topLeft, sub, TextStyle{16.0f, roleColor(Role::Ink), Anchor::BottomLeft, true, false, {0, -5}});
    }
    // A colour key just under a panel whose bottom-left corner is `bottomLeft` (world).
    static void keyBelow(Canvas& c, const Vec3& bottomLeft, const std::vector<KeyItem>& items) {
        Eigen::Vector2d px;
        if (c.project(bottomLeft, px)) drawKey(c, px.x(), px.y() + 8, items);
    }
    // The title and caption drawn over a finished figure, which is named `name` and captioned by the title.
    Frame titledFrame(Canvas& canvas, const std::string& name) const {
        drawTitleAndCaption(canvas, common_.title, common_.caption);
        return Frame{name, common_.title, canvas.readPixels()};
    }
    // Cell of k-d node `id`: the root's cell is the points' bounds, so the sides a cell shares with
    // the root reach out to the frame.
    static Aabb kdCellInFrame(const KdTree& tree, int id, const Aabb& frame) {
        const auto& nodes = tree.nodes();
        Aabb c = nodes[std::size_t(id)].cell;
        for (int a = 0; a < 2; ++a) {
            if (c.min[a] == nodes[0].cell.min[a]) c.min[a] = frame.min[a];
            if (c.max[a] == nodes[0].cell.max[a]) c.max[a] = frame.max[a];
        }
        return c;
    }
    // The split line of an inner k-d node across its cell.
    static void drawKdSplit(Canvas& c, const KdNode& node, const Aabb& cell, const Vec3& at, const LineStyle& s) {
        if (node.axis == 0) c.drawLine(at + P(node.split, cell.min.y()), at + P(node.split, cell.max.y()), s);
        else c.drawLine(at + P(cell.min.x(), node.split), at + P(cell.max.x(), node.split), s);
    }
    // Every BSP plane as the part of its line inside the node's region, by depth (width scaled by `widthScale`).
    static void drawBspSplits(Canvas& c, const BspTree& tree, const std::vector<std::vector<Vec3>>& regions,
                              const Vec3& at, float widthScale) {
        const int maxDepth = tree.stats().depth;
        for (std::size_t i = 0; i < tree.nodes().size(); ++i) {
            const BspNode& node = tree.nodes()[i];
            Vec3 p, q;
            if (node.kind == BspNodeKind::Inner &&
                lineInPolygon(regions[i], P(node.plane.normal.x(), node.plane.normal.y()), node.plane.offset, p, q))
                c.drawLine(at + p, at + q,
                           LineStyle{widthScale * depthWidth(node.depth), depthColor(node.depth, maxDepth)});
        }
    }
    // The wall fragments seen from the top; the pieces of walls that a plane cut in two are highlighted.
    static void drawBspFragments(Canvas& c, const BspTree& tree, const Vec3& at, float splitWidth, float wallWidth) {
        for (const BspFragment& f : tree.fragments()) {
            Vec3 p, q;
            fragmentSegment(f, p, q);
            c.drawLine(at + p, at + q,
                       lineStyle(f.split ? Role::Highlight : Role::Ink, f.split ? splitWidth : wallWidth, false, true));
        }
    }

    // ------------------------------------------------------------------------------- panels

    // The four structures of the panels figure, each built over the same boxes.
    struct PanelStructures {
        UniformGridResult grid;
        Octree octree;
        std::int64_t octreeTests = 0;
        std::vector<std::pair<int, int>> octreePairs;
        OctreeStats octreeStats;
        std::vector<Vec3> centres;
        KdTree kdTree;
        std::vector<BspPolygon> walls;
        BspTree bspTree;
        BspStats bspStats;
    };

    // What the four panels share: the canvas, the region's square frame (side W), which boxes are in
    // a pair (the same for every structure: each is exact) and the layers asked for.
    struct PanelView {
        Canvas& canvas;
        Aabb frame;
        double W;
        std::vector<bool> paired;
        bool drawObjects, cells, splits;
    };

    DemoOutput runPanels(const RunContext& ctx) const {
        DemoOutput out;
        PanelStructures st;
        buildPanelStructures(st);
        out.trace = panelsTrace(st);
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(drawPanels(*ctx.gl, figureScale(common_, ctx), st));
        return out;
    }

    void buildPanelStructures(PanelStructures& st) const {
        // Uniform grid (Ericson §7.1).
        UniformGrid grid;
        UniformGridOptions go;
        go.cellSize = gridCell;
        st.grid = grid.build(boxes, go);
        // Octree, root = the square region x [0, S] in z (boxes touch z = 0 only: a quadtree).
        const double S = (region.max - region.min).head<2>().maxCoeff();
        OctreeOptions oo;
        oo.maxDepth = octree.maxDepth;
        oo.maxObjectsPerLeaf = octree.leaf;
        oo.looseness = octree.looseness;
        oo.useRootBounds = true;
        oo.rootBounds = {Vec3(region.min.x(), region.min.y(), 0.0), Vec3(region.min.x() + S, region.min.y() + S, S)};
        st.octree.build(boxes, oo);
        st.octreePairs = st.octree.overlappingPairs(&st.octreeTests);
        st.octreeStats = st.octree.stats();
        // k-d tree over the box centres.
        for (const Aabb& b : boxes) st.centres.push_back(0.5 * (b.min + b.max));
        st.kdTree.build(st.centres, {kd.rule, kd.leaf});
        // BSP tree of the boxes' walls.
        for (const Aabb& b : boxes) addWalls(rectPolygon(b), st.walls);
        BspTrace btrace;
        st.bspTree.build(st.walls, bsp, &btrace);
        st.bspStats = st.bspTree.stats();
    }

    Json panelsTrace(const PanelStructures& st) const {
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

    Frame drawPanels(GlContext& gl, int ss, const PanelStructures& st) const {
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

    void drawBoxes(const PanelView& v, const Vec3& at, const std::function<Color(int)>& fill, float alpha) const {
        if (!v.drawObjects) return;
        for (int i = 0; i < int(boxes.size()); ++i) {
            fillRect(v.canvas, boxes[std::size_t(i)], at, fill(i).withAlpha(alpha));
            outlineRect(v.canvas, boxes[std::size_t(i)], at,
                        lineStyle(v.paired[std::size_t(i)] ? Role::Highlight : Role::Ink,
                                  v.paired[std::size_t(i)] ? 2.2f : 1.4f));
        }
    }

    // 1. Uniform grid: lines every h, occupied cells shaded by their box count.
    void drawGridPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
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
                std::to_string(st.grid.entries) + " box-cell entries, " + std::to_string(st.grid.pairTests) +
                    " tests, " + std::to_string(st.grid.pairs) + " pairs");
    }

    // 2. Octree (quadtree from the top): node cells, boxes coloured by the depth they sit at.
    void drawOctreePanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
        Canvas& canvas = v.canvas;
        const Aabb& frame = v.frame;
        const Octree& ot = st.octree;
        const OctreeStats& os = st.octreeStats;
        if (v.cells)
            for (const OctreeNode& node : ot.nodes())
                outlineRect(canvas, node.cell, at,
                            LineStyle{depthWidth(node.depth), depthColor(node.depth, os.maxDepthReached)});
        drawBoxes(
            v, at, [&](int i) { return octreeDepthColor(ot.nodes()[std::size_t(ot.nodeOf(i))].depth); }, 0.45f);
        outlineRect(canvas, frame, at, lineStyle(Role::Ink, 1.5f));
        heading(canvas, at + P(frame.min.x(), frame.max.y()),
                "Octree (seen as a quadtree), " + std::to_string(os.nodeCount) + " nodes",
                std::to_string(st.octreeTests) + " tests, " + std::to_string(st.octreePairs.size()) + " pairs; " +
                    std::to_string(os.objectsAtRoot) + " boxes on the root's split lines");
        if (common_.hasLayer("labels")) {
            // Legend: box colour = depth of the node that stores it.
            for (int d = 0; d <= os.maxDepthReached; ++d) {
                const Vec3 p = at + P(frame.max.x(), frame.max.y()) + P(0.02 * v.W, -0.045 * v.W * (d + 0.5));
                canvas.drawPoint(p, 6.0f, octreeDepthColor(d).withAlpha(0.8f));
                canvas.drawText(
                    p,
                    (d == 0 ? "root" : "d" + std::to_string(d)) + ": " +
                        std::to_string(d < int(os.objectsPerDepth.size()) ? os.objectsPerDepth[std::size_t(d)] : 0),
                    TextStyle{16.0f, roleColor(Role::Ink), Anchor::Left, true, false, {9, 0}});
            }
        }
    }

    // 3. k-d tree over the box centres: split lines clipped to their cells, coloured by depth.
    void drawKdPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
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

    // 4. BSP of the box walls: split lines and wall fragments. Overlapping boxes are not one
    // closed surface (walls inside other boxes), so solid / empty leaves mean little here:
    // the boxes are shaded instead (the bsp_shape figure shows solid leaves).
    void drawBspPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const {
        Canvas& canvas = v.canvas;
        const BspTree& bt = st.bspTree;
        const BspStats& bs = st.bspStats;
        const auto regions = bspRegions(bt, rectPolygon(v.frame));
        if (v.drawObjects)
            for (const Aabb& b : boxes) fillRect(canvas, b, at, roleColor(Role::ShapeA).withAlpha(0.30f));
        if (v.splits) drawBspSplits(canvas, bt, regions, at, 0.6f);
        if (v.drawObjects) drawBspFragments(canvas, bt, at, 3.5f, 2.5f);
        outlineRect(canvas, v.frame, at, lineStyle(Role::Ink, 1.5f));
        heading(canvas, at + P(v.frame.min.x(), v.frame.max.y()),
                "BSP tree of the box walls, depth " + std::to_string(bs.depth),
                std::to_string(bs.innerCount) + " planes, " + std::to_string(bs.splits) + " walls cut in two");
        if (common_.hasLayer("labels"))
            keyBelow(canvas, at + v.frame.min, {{roleColor(Role::Highlight), "a wall cut in two"}});
    }

    // ----------------------------------------------------------------------------- kd_query

    DemoOutput runKdQuery(const RunContext& ctx) const {
        DemoOutput out;
        KdTree kt;
        kt.build(points, {kd.rule, kd.leaf});
        KdQueryTrace nt, rt;
        const KdNearestResult nearest = kt.nearest(query, &nt);
        const std::vector<int> hits = kt.rangeQuery(range, &rt);
        out.trace["points"] = int(points.size());
        out.trace["nodes"] = int(kt.nodes().size());
        out.trace["depth"] = kt.depth();
        out.trace["nearest"] = {{"query", vec2Json(query)},
                                {"index", nearest.index},
                                {"distance", std::sqrt(nearest.distanceSquared)},
                                {"distance_tests", nt.distanceTests},
                                {"nodes_visited", int(nt.visited.size())},
                                {"subtrees_pruned", int(nt.pruned.size())},
                                {"best_so_far", nt.bestSoFar}};
        out.trace["range"] = {{"box", {vec2Json(range.min), vec2Json(range.max)}},
                              {"hits", hits},
                              {"point_tests", rt.distanceTests},
                              {"nodes_visited", int(rt.visited.size())},
                              {"subtrees_pruned", int(rt.pruned.size())}};
        if (numericOnly(ctx, out)) return out;
        Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        const Vec3 size = region.max - region.min;
        const double W = std::max(size.x(), size.y());
        const double gap = 0.12 * W;
        const Vec3 offsets[2] = {P(0, 0), P(W + gap, 0)};
        const Vec3 middle = region.min + P(0.5 * (2 * W + gap), 0.5 * W);
        const double aspect = double(common_.image.width) / double(common_.image.height);
        canvas.setCamera(
            Camera::twoD(middle.x(), middle.y() + 0.03 * W, std::max(W * 1.45, (2 * W + gap) * 1.05 / aspect)));
        const Aabb frame{region.min, region.min + P(W, W)};
        const auto& nodes = kt.nodes();

        auto cellOf = [&](int id) { return kdCellInFrame(kt, id, frame); };
        auto drawTree = [&](const Vec3& at, const KdQueryTrace& t) {
            if (common_.hasLayer("cells")) {
                for (int id : t.pruned) fillRect(canvas, cellOf(id), at, roleColor(Role::Muted).withAlpha(0.30f));
                for (int id : t.visited)
                    if (nodes[std::size_t(id)].isLeaf())
                        fillRect(canvas, cellOf(id), at, roleColor(Role::Highlight).withAlpha(0.22f));
            }
            if (common_.hasLayer("splits"))
                for (std::size_t id = 0; id < nodes.size(); ++id) {
                    const KdNode& node = nodes[id];
                    if (node.isLeaf()) continue;
                    drawKdSplit(canvas, node, cellOf(int(id)), at,
                                LineStyle{depthWidth(node.depth), depthColor(node.depth, kt.depth())});
                }
            if (common_.hasLayer("objects"))
                for (const Vec3& p : points) canvas.drawPoint(at + p, 4.0f, roleColor(Role::Ink), true, 0.0f);
            outlineRect(canvas, frame, at, lineStyle(Role::Ink, 1.5f));
        };

        // Left: nearest neighbour.
        drawTree(offsets[0], nt);
        if (common_.hasLayer("queries") && nearest.index >= 0) {
            const Vec3 at = offsets[0];
            const double r = std::sqrt(nearest.distanceSquared);
            std::vector<Vec3> circle;
            for (int k = 0; k < 96; ++k)
                circle.push_back(at + query + r * P(std::cos(2 * M_PI * k / 96), std::sin(2 * M_PI * k / 96)));
            canvas.drawPolyline(circle, true, lineStyle(Role::Result, 2.0f, true, true));
            // Improvements of the best point, in order: the search narrows.
            for (std::size_t k = 0; k + 1 < nt.bestSoFar.size(); ++k)
                canvas.drawPoint(at + points[std::size_t(nt.bestSoFar[k])], 7.0f, roleColor(Role::Simplex), true, 1.5f);
            canvas.drawLine(at + query, at + points[std::size_t(nearest.index)],
                            lineStyle(Role::Result, 3.0f, false, true));
            canvas.drawPoint(at + points[std::size_t(nearest.index)], 8.0f, roleColor(Role::Result), true, 2.0f);
            canvas.drawPoint(at + query, 9.0f, roleColor(Role::Query), true, 2.0f);
            if (common_.hasLayer("labels"))
                canvas.drawText(at + query, "q",
                                TextStyle{20.0f, roleColor(Role::Ink), Anchor::Left, true, true, {10, 0}});
        }
        heading(canvas, offsets[0] + P(frame.min.x(), frame.max.y()), "Nearest neighbour of q",
                std::to_string(nt.distanceTests) + " of " + std::to_string(points.size()) + " points tested, " +
                    std::to_string(nt.pruned.size()) + " subtrees pruned");
        // Under each panel: the two cell tints drawTree paints, then what the query's points mean.
        const auto keyWith = [&](const KeyItem& points) {
            return std::vector<KeyItem>{
                {roleColor(Role::Highlight).mixed(roleColor(Role::Background), 0.6f), "leaf searched"},
                {roleColor(Role::Muted), "subtree pruned"},
                points};
        };
        if (common_.hasLayer("labels"))
            keyBelow(canvas, offsets[0] + frame.min, keyWith({roleColor(Role::Simplex), "earlier best"}));
        // Right: range query.
        drawTree(offsets[1], rt);
        if (common_.hasLayer("queries")) {
            const Vec3 at = offsets[1];
            fillRect(canvas, range, at, roleColor(Role::Simplex).withAlpha(0.25f));
            outlineRect(canvas, range, at, lineStyle(Role::Simplex, 3.0f, false, true));
            for (int i : hits) canvas.drawPoint(at + points[std::size_t(i)], 7.0f, roleColor(Role::Result), true, 1.5f);
        }
        heading(canvas, offsets[1] + P(frame.min.x(), frame.max.y()), "Range query (box)",
                std::to_string(hits.size()) + " hits, " + std::to_string(rt.distanceTests) + " points tested, " +
                    std::to_string(rt.pruned.size()) + " subtrees pruned");
        if (common_.hasLayer("labels"))
            keyBelow(canvas, offsets[1] + frame.min, keyWith({roleColor(Role::Result), "hit"}));
        out.frames.push_back(titledFrame(canvas, "kd_query"));
        return out;
    }

    // ---------------------------------------------------------------------------- bsp_shape

    DemoOutput runBspShape(const RunContext& ctx) const {
        DemoOutput out;
        std::vector<BspPolygon> walls;
        addWalls(polygon, walls);
        BspTree bt;
        BspTrace trace;
        bt.build(walls, bsp, &trace);
        const BspStats bs = bt.stats();
        static const char* kClass[3] = {"inside", "outside", "on"};
        std::vector<BspPointClass> classes;
        for (const Vec3& q : queries) classes.push_back(bt.classifyPoint(q));
        BspRayResult ray;
        if (hasSegment) ray = bt.segmentQuery(segment);
        out.trace["edges"] = int(polygon.size());
        out.trace["nodes"] = bs.nodeCount;
        out.trace["inner"] = bs.innerCount;
        out.trace["solid_leaves"] = bs.solidLeaves;
        out.trace["empty_leaves"] = bs.emptyLeaves;
        out.trace["depth"] = bs.depth;
        out.trace["splits"] = bs.splits;
        out.trace["fragments"] = bs.fragmentCount;
        Json steps = Json::array();
        for (const BspSplitStep& s : trace.steps)
            steps.push_back({{"node", s.node},
                             {"depth", s.depth},
                             {"splitter", s.splitter},
                             {"front", s.front},
                             {"back", s.back},
                             {"coplanar", s.coplanar},
                             {"straddling", s.straddling},
                             {"score", s.score}});
        out.trace["steps"] = steps;
        Json qs = Json::array();
        for (std::size_t i = 0; i < queries.size(); ++i)
            qs.push_back({{"point", vec2Json(queries[i])}, {"class", kClass[int(classes[i])]}});
        out.trace["queries"] = qs;
        if (hasSegment)
            out.trace["segment"] = {{"from", vec2Json(segment.a)},
                                    {"to", vec2Json(segment.b)},
                                    {"hit", ray.hit},
                                    {"t", ray.t},
                                    {"point", vec2Json(ray.point)}};
        if (numericOnly(ctx, out)) return out;
        Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        // Shape panel on the left (square), tree diagram on the right.
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (const Vec3& v : polygon) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        const double W = (hi - lo).head<2>().maxCoeff() * 1.25;
        const Vec3 c = 0.5 * (lo + hi);
        const Aabb frame{P(c.x() - 0.5 * W, c.y() - 0.5 * W), P(c.x() + 0.5 * W, c.y() + 0.5 * W)};
        const double treeW = 0.85 * W, gap = 0.08 * W;
        const double aspect = double(common_.image.width) / double(common_.image.height);
        const double viewH = std::max(W * 1.32, (W + gap + treeW) * 1.04 / aspect);
        canvas.setCamera(Camera::twoD(frame.min.x() + 0.5 * (W + gap + treeW), c.y() + 0.02 * W, viewH));
        const auto regions = bspRegions(bt, rectPolygon(frame));
        const auto& nodes = bt.nodes();
        if (common_.hasLayer("cells"))
            for (std::size_t i = 0; i < nodes.size(); ++i) {
                if (nodes[i].kind == BspNodeKind::Inner || regions[i].size() < 3) continue;
                const bool solid = nodes[i].kind == BspNodeKind::SolidLeaf;
                canvas.drawPolygon(regions[i],
                                   solid ? roleColor(Role::ShapeA).withAlpha(0.38f) : roleColor(Role::Background));
            }
        if (common_.hasLayer("splits")) drawBspSplits(canvas, bt, regions, Vec3::Zero(), 1.0f);
        if (common_.hasLayer("objects")) drawBspFragments(canvas, bt, Vec3::Zero(), 4.0f, 4.0f);
        outlineRect(canvas, frame, Vec3::Zero(), lineStyle(Role::Ink, 1.5f));
        const bool labels = common_.hasLayer("labels");
        if (labels)  // edge names e0, e1, ... at the midpoints, pushed outwards
            for (std::size_t i = 0; i < polygon.size(); ++i) {
                const Vec3 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
                const Vec3 out2 = Vec3(b.y() - a.y(), a.x() - b.x(), 0).normalized();
                TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                ts.place = true;  // outside the edge's midpoint, off the query points
                ts.offsetPx = Eigen::Vector2d(out2.x(), -out2.y()) * 18.0;
                canvas.drawText(0.5 * (a + b), "e" + std::to_string(i), ts);
            }
        if (common_.hasLayer("queries")) {
            for (std::size_t i = 0; i < queries.size(); ++i) {
                const Role role = classes[i] == BspPointClass::Inside    ? Role::Result
                                  : classes[i] == BspPointClass::Outside ? Role::Query
                                                                         : Role::Simplex;
                canvas.drawPoint(queries[i], 8.0f, roleColor(role), true, 2.0f);
                if (labels)
                    canvas.drawText(queries[i], kClass[int(classes[i])],
                                    TextStyle{15.0f, roleColor(Role::Ink), Anchor::Left, true, false, {10, 0}});
            }
            if (hasSegment) {
                canvas.drawArrow(segment.a, segment.b, lineStyle(Role::Direction, 2.5f, true, true));
                if (ray.hit) {
                    canvas.drawPoint(ray.point, 9.0f, roleColor(Role::Support), true, 2.0f);
                    if (labels)
                        canvas.drawText(ray.point, "first hit, t = " + formatNumber(ray.t),
                                        TextStyle{15.0f, roleColor(Role::Ink), Anchor::TopRight, true, true, {-12, 6}});
                }
            }
        }
        heading(canvas, P(frame.min.x(), frame.max.y()), "Splits and leaf regions (top view)",
                std::to_string(bs.innerCount) + " planes, " + std::to_string(bs.splits) +
                    (bs.splits == 1 ? " edge" : " edges") + " cut");
        if (common_.hasLayer("labels"))
            keyBelow(canvas, frame.min, {{roleColor(Role::Highlight), "an edge cut in two"}});
        if (common_.hasLayer("tree"))
            drawTreeDiagram(canvas, bt, P(frame.max.x() + gap, frame.min.y()), treeW, W, bs.depth);
        out.frames.push_back(titledFrame(canvas, "bsp_shape"));
        return out;
    }

    // Tree diagram: leaves evenly spaced left to right (in-order, front child first), inner
    // nodes centred over their children, one row per depth. Inner nodes name their splitter edge.
    void drawTreeDiagram(Canvas& canvas, const BspTree& bt, const Vec3& corner, double w, double h, int depth) const {
        const auto& nodes = bt.nodes();
        std::vector<double> x(nodes.size(), 0.0);
        int leafCount = 0;
        for (const BspNode& n : nodes) leafCount += n.kind != BspNodeKind::Inner;
        int next = 0;
        std::function<double(int)> place = [&](int id) -> double {
            const BspNode& n = nodes[std::size_t(id)];
            if (n.kind != BspNodeKind::Inner) return x[std::size_t(id)] = (next++ + 0.5) / double(leafCount);
            const double a = place(n.front), b = place(n.back);
            return x[std::size_t(id)] = 0.5 * (a + b);
        };
        place(0);
        const double rowH = h / double(depth + 1);
        auto pos = [&](int id) -> Vec3 {
            return corner + P(x[std::size_t(id)] * w, h - (nodes[std::size_t(id)].depth + 0.5) * rowH);
        };
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const BspNode& n = nodes[i];
            if (n.kind != BspNodeKind::Inner) continue;
            canvas.drawLine(pos(int(i)), pos(n.front), lineStyle(Role::Muted, 1.8f));
            canvas.drawLine(pos(int(i)), pos(n.back), lineStyle(Role::Ink, 1.8f, true));
        }
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const BspNode& n = nodes[i];
            const Vec3 p = pos(int(i));
            if (n.kind == BspNodeKind::Inner) {
                canvas.drawPoint(p, 11.0f, depthColor(n.depth, depth).mixed(roleColor(Role::Background), 0.35f), true,
                                 1.5f);
                canvas.drawText(p, "e" + std::to_string(n.splitter),
                                TextStyle{12.0f, roleColor(Role::Ink), Anchor::Center, false, true});
            } else {
                const bool solid = n.kind == BspNodeKind::SolidLeaf;
                canvas.drawPoint(p, 6.0f, solid ? roleColor(Role::ShapeA) : roleColor(Role::Muted), true, 1.5f);
            }
        }
        Eigen::Vector2d px;
        if (canvas.project(corner, px))
            drawKey(
                canvas, px.x(), px.y() - 18,
                {{roleColor(Role::ShapeA), "solid leaf (inside)"}, {roleColor(Role::Muted), "empty leaf (outside)"}});
        heading(canvas, corner + P(0, h), "The tree", "edge name = splitting line; solid: front child, dashed: back");
    }
};

// ---------------------------------------------------------------------------------------------

// bsp_shape's polygon: simple and counter-clockwise. Its walls face outward only in that order (the
// BSP classifies by the side of them: a clockwise square put (1, 1) outside and far points inside),
// and a self-crossing outline bounds no solid. Exact: consecutive vertices differ, two edges that
// are not neighbours share no point, neighbours share only their vertex (no fold back), and the
// turn at the lowest-leftmost vertex (a convex corner of a simple polygon) is counter-clockwise.
// O(n²) segment tests, n <= kMaxBspEdges. Test: "hostile scenes" / "bsp_shape polygons".
void requireSimpleCounterClockwise(const JsonNode& node, const std::vector<Vec3>& polygon) {
    const std::size_t n = polygon.size();
    const auto v = [&](std::size_t i) { return Vec2(polygon[i % n].x(), polygon[i % n].y()); };
    const auto edge = [&](std::size_t i) {
        return "the edge from vertex " + std::to_string(i) + " to " + std::to_string((i + 1) % n);
    };
    for (std::size_t i = 0; i < n; ++i)
        if (v(i) == v(i + 1)) node.at((i + 1) % n).fail("repeats the vertex before it (an edge of zero length)");
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = v(i), b = v(i + 1), c = v(i + 2);
        if (orient2d(a, b, c) == 0 && (a - b).dot(c - b) > 0)
            node.fail(edge(i) + " and " + edge((i + 1) % n) +
                      " overlap: the polygon folds back on itself (it must be simple)");
        for (std::size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;  // neighbours through vertex 0
            if (segmentsIntersect2d(a, b, v(j), v(j + 1)))
                node.fail(edge(i) + " and " + edge(j) + " meet: the polygon crosses itself (it must be simple)");
        }
    }
    std::size_t low = 0;
    for (std::size_t i = 1; i < n; ++i)
        if (std::pair(v(i).x(), v(i).y()) < std::pair(v(low).x(), v(low).y())) low = i;
    if (orient2d(v(low + n - 1), v(low), v(low + 1)) < 0) {
        double area = 0;
        for (std::size_t i = 0; i < n; ++i) area += v(i).x() * v(i + 1).y() - v(i + 1).x() * v(i).y();
        node.fail("the polygon is clockwise (signed area " + formatNumber(0.5 * area) +
                  "); give its vertices counter-clockwise");
    }
}

Aabb readRect(const JsonNode& node) {
    if (node.size() != 4) node.fail("expected [x0, y0, x1, y1]");
    const double x0 = sceneCoordinate(node.at(0)), y0 = sceneCoordinate(node.at(1)), x1 = sceneCoordinate(node.at(2)),
                 y1 = sceneCoordinate(node.at(3));
    if (x0 > x1 || y0 > y1) node.fail("expected x0 <= x1 and y0 <= y1");
    return {P(x0, y0), P(x1, y1)};
}
Vec3 readPoint2(const JsonNode& node) {
    if (node.size() != 2) node.fail("expected [x, y]");
    return P(sceneCoordinate(node.at(0)), sceneCoordinate(node.at(1)));
}

class SpacePartitionDemo final : public Demo {
public:
    std::string name() const override { return "space_partition"; }
    std::string description() const override {
        return "uniform grid, octree, k-d tree and BSP tree on the same boxes (top views); k-d queries; solid-leaf BSP";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        auto s = std::make_unique<SpaceScene>(std::move(common));
        s->figure = r.get("figure").asEnum({"panels", "kd_query", "bsp_shape"});
        if (auto g = r.find("region")) s->region = readRect(*g);
        // Random boxes / points: {"count", "seed", "size": [min, max]} inside the region.
        unsigned seed = 1;
        int count = 0;
        double sizeLo = 0.5, sizeHi = 2.0;
        if (auto g = r.find("random")) {
            ObjectReader gr(*g);
            count = gr.get("count").asInt(1, 2000);
            if (auto v = gr.find("seed")) seed = unsigned(v->asInt(0, 1 << 30));
            if (auto v = gr.find("size")) {
                if (v->size() != 2) v->fail("expected [min, max]");
                sizeLo = v->at(0).asNonNegative();
                sizeHi = v->at(1).asNonNegative();
                requireAtMost(*v, sizeHi, kMaxSceneCoordinate, "the largest size", "figures are drawn in float32");
                if (sizeLo > sizeHi) v->fail("expected min <= max");
            }
            gr.finish();
        }
        SceneRng rng(seed);
        if (auto o = r.find("octree")) {
            ObjectReader orr(*o);
            if (auto v = orr.find("max_depth")) s->octree.maxDepth = v->asInt(0, 12);
            if (auto v = orr.find("leaf")) s->octree.leaf = v->asInt(0, 1000);
            if (auto v = orr.find("looseness")) s->octree.looseness = v->asNumber();
            if (!(s->octree.looseness >= 1.0 && s->octree.looseness <= 4.0)) o->fail("looseness must be in [1, 4]");
            orr.finish();
        }
        if (auto k = r.find("kd")) {
            ObjectReader kr(*k);
            if (auto v = kr.find("rule"))
                s->kd.rule = v->asEnum({"cycle", "widest"}) == "cycle" ? KdSplitRule::Cycle : KdSplitRule::WidestAxis;
            if (auto v = kr.find("leaf")) s->kd.leaf = v->asInt(1, 1000);
            kr.finish();
        }
        if (auto b = r.find("bsp")) {
            ObjectReader br(*b);
            if (auto v = br.find("split_weight")) {
                s->bsp.splitWeight = v->asNumber();
                if (s->bsp.splitWeight < 0 || s->bsp.splitWeight > 1) v->fail("expected a number in [0, 1]");
            }
            br.finish();
        }
        if (s->figure == "panels") {
            if (auto b = r.find("boxes")) {
                requireAtMost(*b, double(b->size()), kMaxPartitionItems, "the number of boxes", "one drawn box each");
                for (const JsonNode& item : b->items()) s->boxes.push_back(readRect(item));
            }
            for (int i = 0; i < count; ++i) {
                const double w = rng.uniform(sizeLo, sizeHi), h = rng.uniform(sizeLo, sizeHi);
                const double x = rng.uniform(s->region.min.x(), s->region.max.x() - w);
                const double y = rng.uniform(s->region.min.y(), s->region.max.y() - h);
                s->boxes.push_back({P(x, y), P(x + w, y + h)});
            }
            if (s->boxes.empty()) r.node().fail("panels: expected 'boxes' or 'random'");
            const auto g = r.find("grid_cell");
            if (g) s->gridCell = g->asPositive();
            // The grid panel draws one line per cell row and column over the region and the boxes,
            // and the hashed grid visits every cell a box covers: their cell count is the cost.
            Aabb all = s->region;
            for (const Aabb& b : s->boxes) all.min = all.min.cwiseMin(b.min), all.max = all.max.cwiseMax(b.max);
            const Vec3 extent = all.max - all.min;
            const double cells =
                (std::floor(extent.x() / s->gridCell) + 2) * (std::floor(extent.y() / s->gridCell) + 2);
            requireAtMost(g ? *g : r.node(), cells, kMaxGridCells,
                          "the number of grid cells over the region and the boxes",
                          "the grid panel draws every cell row and column");
        } else if (s->figure == "kd_query") {
            if (auto p = r.find("points")) {
                requireAtMost(*p, double(p->size()), kMaxPartitionItems, "the number of points",
                              "one drawn point each");
                for (const JsonNode& item : p->items()) s->points.push_back(readPoint2(item));
            }
            for (int i = 0; i < count; ++i)
                s->points.push_back(P(rng.uniform(s->region.min.x(), s->region.max.x()),
                                      rng.uniform(s->region.min.y(), s->region.max.y())));
            if (s->points.empty()) r.node().fail("kd_query: expected 'points' or 'random'");
            s->query = readPoint2(r.get("query"));
            s->range = readRect(r.get("range"));
        } else {
            const JsonNode polygon = r.get("polygon");
            // The BSP autopartition splits every edge by every splitter: quadratic in the edges.
            requireAtMost(polygon, double(polygon.size()), kMaxBspEdges, "the number of polygon edges",
                          "the BSP autopartition is quadratic in the edges");
            for (const JsonNode& item : polygon.items()) s->polygon.push_back(readPoint2(item));
            if (s->polygon.size() < 3) polygon.fail("expected at least 3 vertices (counter-clockwise)");
            requireSimpleCounterClockwise(polygon, s->polygon);
            if (auto q = r.find("queries")) {
                requireAtMost(*q, double(q->size()), kMaxPartitionItems, "the number of query points",
                              "one drawn point each");
                for (const JsonNode& item : q->items()) s->queries.push_back(readPoint2(item));
            }
            if (auto g = r.find("segment")) {
                if (g->size() != 2) g->fail("expected [[x, y], [x, y]]");
                s->segment = {readPoint2(g->at(0)), readPoint2(g->at(1))};
                s->hasSegment = true;
            }
        }
        r.finish();
        return s;
    }
};

}  // namespace

const Demo& spacePartitionDemo() {
    static const SpacePartitionDemo demo;
    return demo;
}

}  // namespace cdlab::demos
