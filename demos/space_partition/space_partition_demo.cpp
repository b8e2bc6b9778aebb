// Space partitioning, drawn from above (Ericson, Real-Time Collision Detection ch. 7-8): the same
// boxes under a uniform grid (core/broadphase/uniform_grid.h), an octree (core/broadphase/octree.h), a k-d tree over
// the box centres (core/spatial/kd_tree.h) and a solid-leaf BSP tree of the boxes' walls
// (core/spatial/bsp_tree.h); k-d nearest / range queries; a BSP of a non-convex polygon with point
// classification, a segment query and the tree diagram. All numbers come from core; the figure
// files (demos/space_partition/space_partition_scene.h) only draw, and this file reads a scene and
// dispatches on its figure.
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
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/base/orient.h"
#include "core/overlap/polygon_tests.h"
#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos {

namespace {

using namespace render;
using namespace spacefig;

const std::vector<std::string> kLayers = {"objects", "cells", "splits", "labels", "queries", "tree"};

// mt19937's output sequence is fixed by the standard (unlike the distributions): uniform doubles
// from it keep scenes identical on every platform.
struct SceneRng {
    std::mt19937 engine;
    explicit SceneRng(unsigned seed) : engine(seed) {}
    double uniform(double a, double b) { return a + (b - a) * (double(engine()) / 4294967296.0); }
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

/// grid_walk's segment, and its box count bounded (each drawn, the visited cells labelled among them).
void readWalkSegment(ObjectReader& r, SpaceScene& s) {
    requireAtMost(r.node(), double(s.boxes.size()), 200, "the number of boxes",
                  "grid_walk labels each visited cell among them");
    const JsonNode g = r.get("segment");
    if (g.size() != 2) g.fail("expected [[x, y], [x, y]]");
    s.segment = {readPoint2(g.at(0)), readPoint2(g.at(1))};
    s.hasSegment = true;
}

/// grid_tradeoff's cell sizes, each bounded by the grid entries the scene's boxes make at it.
void readCellSizes(const JsonNode& cs, SpaceScene& s) {
    if (cs.size() < 2 || cs.size() > 16) cs.fail("expected 2 to 16 cell sizes");
    for (const JsonNode& h : cs.items()) {
        s.cellSizes.push_back(h.asPositive());
        requireAtMost(h, s.cellSizes.back(), kMaxSceneCoordinate, "a cell size", "figures are drawn in float32");
        // Every box enters each cell it touches (nothing is drawn per cell).
        double entries = 0;
        for (const Aabb& b : s.boxes)
            entries += (std::floor((b.max.x() - b.min.x()) / s.cellSizes.back()) + 2) *
                       (std::floor((b.max.y() - b.min.y()) / s.cellSizes.back()) + 2);
        requireAtMost(h, entries, 2e6, "the grid entries the boxes make at this cell size",
                      "every box enters each cell it touches");
    }
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
        s->figure = r.get("figure").asEnum({"panels", "kd_query", "bsp_shape", "bsp_scores", "grid_tradeoff", "grid_walk",
                                             "octree_loose"});
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
        if (s->figure == "panels" || s->figure == "grid_tradeoff" || s->figure == "grid_walk" ||
            s->figure == "octree_loose") {
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
            if (s->boxes.empty()) r.node().fail(s->figure + ": expected 'boxes' or 'random'");
            if (s->figure == "grid_tradeoff") {
                readCellSizes(r.get("cell_sizes"), *s);
                r.finish();
                return s;
            }
            if (s->figure == "grid_walk") readWalkSegment(r, *s);
            const auto g = r.find("grid_cell");
            if (g) s->gridCell = g->asPositive();
            if (g) requireAtMost(*g, s->gridCell, kMaxSceneCoordinate, "the cell size", "figures are drawn in float32");
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
            if (s->figure == "bsp_scores") {
                // Every candidate is a row of the table, 15 px text at the least: 24 fit (and each of
                // the frames' nodes scores them all, quadratic in the edges).
                requireAtMost(polygon, double(polygon.size()), 24, "the number of polygon edges",
                              "bsp_scores lists every candidate edge in its table");
                if (auto f = r.find("frames")) s->scoreFrames = f->asInt(1, 8);
            } else if (auto q = r.find("queries")) {
                requireAtMost(*q, double(q->size()), kMaxPartitionItems, "the number of query points",
                              "one drawn point each");
                for (const JsonNode& item : q->items()) s->queries.push_back(readPoint2(item));
            }
            if (auto g = s->figure == "bsp_shape" ? r.find("segment") : std::nullopt) {
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