// Internal to the space_partition demo (demos/space_partition): SpaceScene with its keys and the
// plane helpers its figures share (split colours, half-plane clipping, BSP walls and regions).
// space_partition_demo.cpp reads a scene and dispatches on its figure; each figure is drawn in its
// own file: space_partition_panels_figure.cpp, space_partition_kd_query_figure.cpp and
// space_partition_bsp_shape_figure.cpp. Everything lies in the plane z = 0 (space_partition_demo.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/demo.h"
#include "app/scene/scene_limits.h"
#include "core/base/orient.h"
#include "core/broadphase/octree.h"
#include "core/broadphase/uniform_grid.h"
#include "core/overlap/polygon_tests.h"
#include "core/spatial/bsp_tree.h"
#include "core/spatial/kd_tree.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos::spacefig {

using namespace render;

/// The BSP build's steps for trace.json: per split its node, splitter, counts and every candidate's
/// scores (space_partition_bsp_scores_figure.cpp).
Json bspStepsJson(const BspTrace& trace);

inline Vec3 P(double x, double y) { return Vec3(x, y, 0.0); }
inline Json vec2Json(const Vec3& v) { return Json::array({v.x(), v.y()}); }

// Depth colour ramp for split lines: near-black blue at the root, lighter blue deeper down
// (orange is kept for "in a pair" / "was split").
inline Color depthColor(int depth, int maxDepth) {
    const float t = maxDepth > 0 ? float(std::min(depth, maxDepth)) / float(maxDepth) : 0.0f;
    const Color blue = categorical(4);
    return blue.scaled(0.35f).mixed(blue.mixed(roleColor(Role::Background), 0.45f), t);
}
// Box colour by the octree depth it is stored at (orange excluded: it marks pairs).
inline Color octreeDepthColor(int depth) {
    static const int kIndex[6] = {6, 1, 2, 3, 4, 5};
    return categorical(kIndex[std::min(depth, 5)]);
}
inline float depthWidth(int depth) { return std::max(1.2f, 4.0f - 0.5f * float(depth)); }

// Convex polygon (xy, counter-clockwise) clipped to n . x >= d (keepFront) or <= d.
inline std::vector<Vec3> clipHalfPlane(const std::vector<Vec3>& poly, const Vec3& n, double d, bool keepFront) {
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
inline bool lineInPolygon(const std::vector<Vec3>& poly, const Vec3& n, double d, Vec3& p, Vec3& q) {
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

inline std::vector<Vec3> rectPolygon(const Aabb& r) {
    return {P(r.min.x(), r.min.y()), P(r.max.x(), r.min.y()), P(r.max.x(), r.max.y()), P(r.min.x(), r.max.y())};
}

// Vertical wall quads of a counter-clockwise xy polygon (outward normals), z in [-1, 1].
inline void addWalls(const std::vector<Vec3>& poly, std::vector<BspPolygon>& walls) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        walls.push_back(
            {{Vec3(a.x(), a.y(), -1), Vec3(b.x(), b.y(), -1), Vec3(b.x(), b.y(), 1), Vec3(a.x(), a.y(), 1)}});
    }
}

// Top view of a wall fragment: its bottom edge (z = min).
inline void fragmentSegment(const BspFragment& f, Vec3& p, Vec3& q) {
    double zmin = INFINITY;
    for (const Vec3& v : f.vertices) zmin = std::min(zmin, v.z());
    std::vector<Vec3> low;
    for (const Vec3& v : f.vertices)
        if (v.z() <= zmin + 1e-9) low.push_back(P(v.x(), v.y()));
    p = low.empty() ? P(0, 0) : low.front();
    q = low.empty() ? P(0, 0) : low.back();
}

// Region (xy polygon) of every BSP node inside `root`, by clipping with the ancestors' planes.
inline std::vector<std::vector<Vec3>> bspRegions(const BspTree& tree, const std::vector<Vec3>& root) {
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
    // bsp_scores
    int scoreFrames = 4;
    // grid_tradeoff
    std::vector<double> cellSizes;

    DemoOutput execute(const RunContext& ctx) const override {
        if (figure == "panels") return runPanels(ctx);
        if (figure == "kd_query") return runKdQuery(ctx);
        if (figure == "bsp_scores") return runBspScores(ctx);
        if (figure == "grid_tradeoff") return runGridTradeoff(ctx);
        if (figure == "grid_walk") return runGridWalk(ctx);
        if (figure == "octree_loose") return runOctreeLoose(ctx);
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
        c.drawText(topLeft, sub, TextStyle{17.0f, roleColor(Role::Ink), Anchor::BottomLeft, true, false, {0, -5}});
    }
    // A colour key just under a panel whose bottom-left corner is `bottomLeft` (world).
    static void keyBelow(Canvas& c, const Vec3& bottomLeft, const std::vector<KeyItem>& items) {
        Eigen::Vector2d px;
        if (c.project(bottomLeft, px)) drawKey(c, px.x(), px.y() + 8, items, 17.0f);  // 1.6 % of 1024 px
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
    // The wall fragments seen from the top; the pieces of walls that a plane cut in two in the
    // `cut` role (its figure's key names it; one that outlines paired boxes in the highlight
    // colour gives cut walls another).
    static void drawBspFragments(Canvas& c, const BspTree& tree, const Vec3& at, float splitWidth, float wallWidth,
                                 Role cut = Role::Highlight) {
        for (const BspFragment& f : tree.fragments()) {
            Vec3 p, q;
            fragmentSegment(f, p, q);
            c.drawLine(at + p, at + q, lineStyle(f.split ? cut : Role::Ink, f.split ? splitWidth : wallWidth, false, true));
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

    DemoOutput runPanels(const RunContext& ctx) const;

    void buildPanelStructures(PanelStructures& st) const;

    Json panelsTrace(const PanelStructures& st) const;

    Frame drawPanels(GlContext& gl, int ss, const PanelStructures& st) const;

    void drawBoxes(const PanelView& v, const Vec3& at, const std::function<Color(int)>& fill, float alpha) const;

    // 1. Uniform grid: lines every h, occupied cells shaded by their box count.
    void drawGridPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const;

    // 2. Octree (quadtree from the top): node cells, boxes coloured by the depth they sit at.
    void drawOctreePanel(const PanelView& v, const Vec3& at, const PanelStructures& st,
                         const std::string& title = "") const;

    /// The octree of the scene's boxes with looseness k (the panels' octree and octree_loose's two).
    void buildOctree(PanelStructures& st, double looseness) const;

    // octree_loose (space_partition_panels_figure.cpp): the same boxes in a tight and a loose octree.
    DemoOutput runOctreeLoose(const RunContext& ctx) const;

    // 3. k-d tree over the box centres: split lines clipped to their cells, coloured by depth.
    void drawKdPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const;

    // 4. BSP of the box walls: split lines and wall fragments. Overlapping boxes are not one
    // closed surface (walls inside other boxes), so solid / empty leaves mean little here:
    // the boxes are shaded instead (the bsp_shape figure shows solid leaves).
    void drawBspPanel(const PanelView& v, const Vec3& at, const PanelStructures& st) const;

    // kd_query (space_partition_kd_query_figure.cpp)

    DemoOutput runKdQuery(const RunContext& ctx) const;

    // bsp_shape (space_partition_bsp_shape_figure.cpp)

    DemoOutput runBspShape(const RunContext& ctx) const;

    // bsp_scores (space_partition_bsp_scores_figure.cpp): one frame per split with two or more
    // candidates, at most scoreFrames.

    DemoOutput runBspScores(const RunContext& ctx) const;

    // grid_tradeoff (space_partition_grid_figure.cpp): work of the uniform grid per cell size.
    DemoOutput runGridTradeoff(const RunContext& ctx) const;

    // grid_walk (space_partition_grid_walk_figure.cpp): a segment walking the grid cell by cell.
    DemoOutput runGridWalk(const RunContext& ctx) const;
    Frame drawBspScoreFrame(GlContext& gl, int ss, const BspTree& bt, const BspSplitStep& step) const;

    // Tree diagram: leaves evenly spaced left to right (in-order, front child first), inner
    // nodes centred over their children, one row per depth. Inner nodes name their splitter edge.
    void drawTreeDiagram(Canvas& canvas, const BspTree& bt, const Vec3& corner, double w, double h, int depth) const;
};

}  // namespace cdlab::demos::spacefig
