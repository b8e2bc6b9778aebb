// Bounding-volume hierarchies over triangle meshes, as teaching figures. Every tree, box, volume,
// counter and triangle pair comes from core (core/bvh/bvh.h: buildBvh with its BvhBuildTrace,
// refitBvh, traverseBvhPair; core/bvh/mesh_collision.h: collideMeshes with its BvhTraversalTrace;
// core/bounding/bounding_volume_fit.h: volume). This file only chooses what to draw, counts trace steps
// and moves boxes into the world for drawing.
//
// Sources: C. Ericson, "Real-Time Collision Detection" (2005) ch. 6 (§6.2 construction, §6.3.2
// dual traversal, "descend larger"); S. Gottschalk, M. Lin, D. Manocha, "OBBTree: A Hierarchical
// Structure for Rapid Interference Detection", SIGGRAPH 1996 (AABB vs OBB trees on a torus);
// G. van den Bergen, "Efficient collision detection of complex deformable models using AABB
// trees", JGT 2(4) 1997 (refitting).
//
// Figures ("figure" key): hierarchy_levels, aabb_vs_obb, dual_traversal, refit, build_methods,
// dynamic_tree (demos/bvh/dynamic_tree_figure.h: core/broadphase/dynamic_tree.h step by step).
// Scene keys: docs/scenes.md, "bvh".
#include "demos/bvh/bvh_demo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/bounding/bounding_volume_fit.h"
#include "core/bvh/bvh.h"
#include "core/bvh/mesh_collision.h"
#include "core/geometry/triangle_mesh.h"
#include "core/overlap/sat_tests.h"
#include "demos/bvh/bvh_draw.h"
#include "demos/bvh/dynamic_tree_figure.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/step_frames.h"
#include "app/scene/mesh_scene.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace {

using namespace render;
using namespace bvhdemo;

const std::vector<std::string> kLayers = {"mesh", "boxes", "tree", "labels"};

// ---- meshes

/// Flat rectangular sheet in the body xy plane (z = 0), centred at the origin: nx × ny quads, two
/// triangles each. The refit figure deforms it.
TriangleMesh sheetMesh(double lx, double ly, int nx, int ny) {
    TriangleMesh m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            m.vertices.emplace_back(lx * (double(i) / nx - 0.5), ly * (double(j) / ny - 0.5), 0.0);
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

struct MeshSpec {
    std::string kind;  // "torus", "ellipsoid", "blob", "sheet"
    TriangleMesh mesh;
    Transform pose;
    double sheetLength = 0;  // sheet: length along x (the deformations use it)
};

MeshSpec parseMesh(const JsonNode& node) {
    // {"torus": {...}, "position": [x, y, z], "rotation": [w, x, y, z]}: one mesh key and the pose.
    if (!node.isObject()) node.fail("expected an object with one of the keys torus, ellipsoid, blob, sheet");
    MeshSpec s;
    for (auto it = node.raw().begin(); it != node.raw().end(); ++it) {
        if (it.key() == "position" || it.key() == "rotation") continue;
        if (!s.kind.empty()) node.fail("two meshes in one object ('" + s.kind + "', '" + it.key() + "')");
        s.kind = it.key();
    }
    if (s.kind.empty()) node.fail("expected one of the keys torus, ellipsoid, blob, sheet");
    ObjectReader outer(node);
    if (auto p = outer.find("position")) s.pose.position = sceneVec3(*p);
    if (auto q = outer.find("rotation")) s.pose.rotation = q->asQuat();
    JsonNode body = outer.get(s.kind);
    outer.finish();
    ObjectReader r(body);
    if (readMeshGenerator(s.kind, body, r, MeshTessellation{24, 12, 16, 8}, s.mesh)) {
        // torus, ellipsoid or blob
    } else if (s.kind == "sheet") {
        Vec3 size(3, 1, 0);
        if (auto v = r.find("size")) {
            if (!v->isArray() || v->size() != 2) v->fail("expected [length_x, width_y]");
            size = Vec3(sceneSize(v->at(0)), sceneSize(v->at(1)), 0);
        }
        int nx = 24, ny = 6;
        if (auto v = r.find("segments")) {
            if (!v->isArray() || v->size() != 2) v->fail("expected [nx, ny]");
            nx = v->at(0).asInt(1, 256);
            ny = v->at(1).asInt(1, 256);
        }
        s.mesh = sheetMesh(size.x(), size.y(), nx, ny);
        s.sheetLength = size.x();
    } else {
        node.fail("unknown mesh '" + s.kind + "' (torus, ellipsoid, blob, sheet)");
    }
    r.finish();
    return s;
}

MeshView meshView(const TriangleMesh& m, const Transform& pose) {
    MeshView v;
    for (const Vec3& p : m.vertices) v.vertices.push_back(pose.apply(p));
    for (const auto& t : m.triangles) v.triangles.emplace_back(t[0], t[1], t[2]);
    return v;
}

// The axis that separates two disjoint boxes, drawn through A's centre with both boxes'
// projections on it (Ericson §4.4.1: 15 candidate axes): the gap between the two bars is why
// the pair is pruned, even where the boxes overlap on screen. Returns the axis' name.
std::string drawSeparatingAxis(Canvas& c, const Obb& a, const Obb& b, bool labels) {
    const SatResult sat = testObbObb(a, b);
    if (sat.hit) return "";
    const SatAxisStep& s = sat.separatingAxis;
    const double len = s.axis.norm();
    if (!(len > 0)) return "";
    const Vec3 u = s.axis / len;
    const auto at = [&](double t) { return Vec3(a.center + u * (t / len)); };
    const double lo = std::min(s.minA, s.minB), hi = std::max(s.maxA, s.maxB), pad = 0.1 * (hi - lo);
    c.drawLine(at(lo - pad), at(hi + pad), lineStyle(Role::Ink, 1.5f, true, true));
    c.drawLine(at(s.minA), at(s.maxA), lineStyle(Role::ShapeA, 6.0f, false, true));
    c.drawLine(at(s.minB), at(s.maxB), lineStyle(Role::ShapeB, 6.0f, false, true));
    const std::string name = s.kind == SatAxisKind::FaceA   ? "a face normal of A's box"
                             : s.kind == SatAxisKind::FaceB ? "a face normal of B's box"
                                                            : "an edge of A's box × an edge of B's";
    if (labels) {
        TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, false};
        drawLabelAway(c, at(s.maxA < s.minB ? 0.5 * (s.maxA + s.minB) : 0.5 * (s.maxB + s.minA)), a.center,
                      "gap on the separating axis", ts, 14.0);
    }
    return name;
}

Obb worldBox(const Obb& b, const Transform& pose) {
    Obb w = b;
    w.center = pose.apply(b.center);
    w.axes = pose.rotation.toRotationMatrix() * b.axes;
    return w;
}

/// The cut of the tree at `level`: nodes of that depth plus the leaves above it (together they
/// cover every triangle once).
std::vector<int> levelNodes(const Bvh& bvh, int level) {
    std::vector<int> out;
    for (int i = 0; i < int(bvh.nodes.size()); ++i) {
        const BvhNode& n = bvh.nodes[i];
        if (n.depth == level || (n.isLeaf() && n.depth < level)) out.push_back(i);
    }
    return out;
}

double sumVolume(const Bvh& bvh, const std::vector<int>& nodes) {
    double v = 0;
    for (int i : nodes) v += volume(bvh.box(i));
    return v;
}

double totalVolume(const Bvh& bvh) {
    double v = 0;
    for (int i = 0; i < int(bvh.nodes.size()); ++i) v += volume(bvh.box(i));
    return v;
}

/// World corners of a tree's root box (for framing).
std::vector<Vec3> rootCorners(const Bvh& bvh, const Transform& pose) {
    if (bvh.empty()) return {};
    const auto c = boxCorners(worldBox(bvh.box(0), pose));
    return std::vector<Vec3>(c.begin(), c.end());
}

/// World corners of the boxes of `nodes` (for framing).
std::vector<Vec3> boxesCorners(const Bvh& bvh, const Transform& pose, const std::vector<int>& nodes) {
    std::vector<Vec3> out;
    for (int i : nodes) {
        const auto c = boxCorners(worldBox(bvh.box(i), pose));
        out.insert(out.end(), c.begin(), c.end());
    }
    return out;
}

std::vector<int> nodeTriangles(const Bvh& bvh, int node) {
    const BvhNode& n = bvh.nodes[node];
    return std::vector<int>(bvh.triangleOrder.begin() + n.first, bvh.triangleOrder.begin() + n.first + n.count);
}

TreeDiagramInput treeOf(const Bvh& bvh, int maxDepth) {
    TreeDiagramInput t;
    for (const BvhNode& n : bvh.nodes) t.children.push_back({n.left, n.right});
    t.maxDepth = maxDepth;
    return t;
}

std::string methodWords(BvhBuildMethod m) {
    switch (m) {
        case BvhBuildMethod::TopDownMedian: return "top-down, median split on the longest axis";
        case BvhBuildMethod::TopDownSah: return "top-down, binned SAH";
        case BvhBuildMethod::BottomUp: return "bottom-up, merge the smallest union";
    }
    return "?";
}

Json obbJson(const Obb& b) {
    Json axes = Json::array();
    for (int i = 0; i < 3; ++i) axes.push_back(vec3Json(b.axes.col(i)));
    return {{"center", vec3Json(b.center)}, {"half_extents", vec3Json(b.halfExtents)}, {"axes", axes}};
}

GridLayout grid(int width, int height, int columns, int rows) {
    GridLayout g;
    g.width = width;
    g.height = height;
    g.columns = columns;
    g.rows = rows;
    return g;
}

std::string fmt(double x) { return formatNumber(x); }
std::string pct(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f%%", 100.0 * x);
    return buf;
}

/// Whether two lists hold the same triangle pairs, in any order.
bool samePairs(std::vector<TrianglePair> a, std::vector<TrianglePair> b) {
    auto less = [](const TrianglePair& x, const TrianglePair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    return a == b;
}

/// The triangles of A and of B in a list of pairs, in the pairs' order.
void splitPairs(const std::vector<TrianglePair>& pairs, std::vector<int>& a, std::vector<int>& b) {
    for (const TrianglePair& p : pairs) {
        a.push_back(p.a);
        b.push_back(p.b);
    }
}

// ---- the scene

enum class Figure { Levels, AabbVsObb, DualTraversal, Refit, BuildMethods, DynamicTree };

enum class Deformation { Roll, Twist };

class BvhScene final : public PreparedScene {
public:
    explicit BvhScene(SceneCommon common) : PreparedScene(std::move(common)) {}

    Figure figure = Figure::Levels;
    std::vector<MeshSpec> meshes;
    BvhBuildOptions build;
    std::vector<int> levels = {0, 1, 2, 3, 4};
    Vec3 view{1.0, -1.5, 1.1};
    double zoom = 1.0;            // > 1 frames the scene closer
    std::vector<int> stepFrames;  // dual traversal: BV step indices to draw (empty: chosen)
    int treeDepth = 5;            // tree diagram depth
    Deformation deformation = Deformation::Roll;
    double deformAngle = 270.0;  // degrees at t = 1
    std::vector<double> times = {0.33, 0.67, 1.0};
    DynamicTreeSpec dynamicTree;

    DemoOutput execute(const RunContext& ctx) const override {
        DemoOutput out;
        ss_ = figureScale(common_, ctx);
        switch (figure) {
            case Figure::Levels: runLevels(ctx, out); break;
            case Figure::AabbVsObb: runAabbVsObb(ctx, out); break;
            case Figure::DualTraversal: runDual(ctx, out); break;
            case Figure::Refit: runRefit(ctx, out); break;
            case Figure::BuildMethods: runBuildMethods(ctx, out); break;
            case Figure::DynamicTree: runDynamicTree(ctx, out); break;
        }
        numericOnly(ctx, out);  // records that nothing was drawn
        return out;
    }

private:
    mutable int ss_ = 1;

    int W() const { return common_.image.width; }
    int H() const { return common_.image.height; }
    bool labels() const { return common_.hasLayer("labels"); }

    Bvh buildChecked(const TriangleMesh& mesh, BvKind kind, BvhBuildMethod method,
                     BvhBuildTrace* trace = nullptr) const {
        BvhBuildOptions o = build;
        o.bvKind = kind;
        o.method = method;
        Bvh b = buildBvh(mesh, o, trace);
        if (b.status != BvhStatus::Ok)
            throw InputError(common_.file + ": building the " + std::string(nameOf(kind)) +
                             " tree failed: " + nameOf(b.status));
        return b;
    }

    Json treeJson(const Bvh& bvh, int maxLevel) const {
        Json lv = Json::array();
        for (int L = 0; L <= std::min(maxLevel, bvh.height()); ++L) {
            const std::vector<int> nodes = levelNodes(bvh, L);
            lv.push_back({{"level", L}, {"nodes", nodes.size()}, {"volume", sumVolume(bvh, nodes)}});
        }
        return {{"bv", nameOf(bvh.kind)},
                {"method", nameOf(bvh.method)},
                {"nodes", bvh.nodes.size()},
                {"height", bvh.height()},
                {"triangles", bvh.triangleCount()},
                {"total_volume", totalVolume(bvh)},
                {"levels", lv}};
    }

    /// One 3D panel: the mesh (translucent) and the boxes of `nodes` coloured by `color`.
    Image boxesPanel(GlContext& gl, int w, int h, const MeshView& mesh, const Bvh& bvh, const Transform& pose,
                     const std::vector<int>& nodes, const Color& color, const Camera& cam, const std::string& heading,
                     const std::string& sub, const std::vector<std::string>& footer = {}) const {
        Canvas c(gl, canvasOptions(w, h, ss_));
        c.setCamera(cam);
        if (common_.hasLayer("mesh"))
            drawMesh(c, mesh, roleColor(Role::ShapeA).withAlpha(0.35f), 0.6f,
                     roleColor(Role::ShapeA).scaled(0.7f).withAlpha(0.6f));
        if (common_.hasLayer("boxes"))
            for (int i : nodes) {
                const Obb b = worldBox(bvh.box(i), pose);
                drawBoxFill(c, b, color.withAlpha(0.08f));
                drawBoxWire(c, b, lineStyle(Role::Ink, 2.0f));
            }
        // The boxes' colour: re-stroke the wires in the level colour over the ink (thin ink rim).
        if (common_.hasLayer("boxes"))
            for (int i : nodes) {
                LineStyle s;
                s.widthPx = 1.6f;
                s.color = color;
                drawBoxWire(c, worldBox(bvh.box(i), pose), s);
            }
        drawHeading(c, heading, sub);
        if (!footer.empty()) drawFooter(c, footer, roleColor(Role::Ink));
        return c.readPixels();
    }

    // ---- hierarchy_levels -----------------------------------------------------------------
    void runDynamicTree(const RunContext& ctx, DemoOutput& out) const {
        DynamicTreeDrawing d;
        d.gl = ctx.gl;
        d.width = W();
        d.height = H();
        d.scale = ss_;
        d.title = common_.title;
        d.caption = common_.caption;
        d.labels = labels();
        d.treePanel = common_.hasLayer("tree");
        out.trace = runDynamicTreeFigure(dynamicTree, d, out.frames);
    }

    void runLevels(const RunContext& ctx, DemoOutput& out) const {
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
        const Camera cam = common_.camera ? *common_.camera
                                          : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
        const double rootVolume = volume(bvh.box(0));
        std::vector<Image> panels;
        for (int level : levels) {
            const std::vector<int> nodes = levelNodes(bvh, level);
            const double v = sumVolume(bvh, nodes);
            panels.push_back(boxesPanel(*ctx.gl, L.panelWidth(), L.panelHeight(), mv, bvh, m.pose, nodes,
                                        levelColor(level), cam,
                                        "Level " + std::to_string(level) + ": " + std::to_string(nodes.size()) +
                                            " box" + (nodes.size() == 1 ? "" : "es"),
                                        "total volume " + fmt(v) + " (" + pct(v / rootVolume) + " of the root)"));
        }
        while (int(panels.size()) < L.columns * L.rows - 1)
            panels.push_back(Image::blank(L.panelWidth(), L.panelHeight(), ss_));
        if (common_.hasLayer("tree")) {
            TreeDiagramInput tin = treeOf(bvh, treeDepth);
            tin.heading = "The tree (" + std::to_string(bvh.nodes.size()) + " nodes, height " +
                          std::to_string(bvh.height()) + ")";
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
                          std::to_string(build.maxLeafTriangles) + " triangle" +
                          (build.maxLeafTriangles == 1 ? "" : "s") + "; " + std::to_string(bvh.triangleCount()) +
                          " triangles, " + std::to_string(bvh.nodes.size()) + " nodes, height " +
                          std::to_string(bvh.height()));
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

    // ---- aabb_vs_obb --------------------------------------------------------------------------
    void runAabbVsObb(const RunContext& ctx, DemoOutput& out) const {
        const MeshSpec& m = meshes[0];
        const Bvh trees[2] = {buildChecked(m.mesh, BvKind::Aabb, build.method),
                              buildChecked(m.mesh, BvKind::Obb, build.method)};
        const int maxLevel = std::min(*std::max_element(levels.begin(), levels.end()) + 2,
                                      std::min(trees[0].height(), trees[1].height()));
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

    /// Mesh 1 against mesh 0 through trees of each kind (q[k] with trees[k]'s kind), checked against brute force.
    Json queryBothTrees(const Bvh (&trees)[2], MeshCollisionResult (&q)[2]) const {
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

    /// The sphere around the mesh and both trees' boxes at the shallowest drawn level: one camera frames every panel.
    void sphereOverTopLevel(const MeshView& mv, const Bvh (&trees)[2], const Transform& pose, Vec3& center,
                            double& radius) const {
        std::vector<Vec3> corners;
        for (int k = 0; k < 2; ++k) {
            const std::vector<Vec3> c =
                boxesCorners(trees[k], pose, levelNodes(trees[k], *std::min_element(levels.begin(), levels.end())));
            corners.insert(corners.end(), c.begin(), c.end());
        }
        meshSphere({&mv}, center, radius, corners);
    }

    // Frame 1: AABB row over OBB row, one column per level.
    Frame aabbVsObbLevelsFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], const Vec3& center,
                               double radius) const {
        const MeshSpec& m = meshes[0];
        GridLayout L = grid(W(), H(), int(levels.size()), 2);
        const Camera cam = common_.camera ? *common_.camera
                                          : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
        std::vector<Image> panels;
        for (int k = 0; k < 2; ++k)
            for (int level : levels) {
                const std::vector<int> nodes = levelNodes(trees[k], level);
                const double v = sumVolume(trees[k], nodes);
                panels.push_back(
                    boxesPanel(gl, L.panelWidth(), L.panelHeight(), mv, trees[k], m.pose, nodes,
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

    // Frame 2: volume per level, and the query's counters (q: the query through each tree, or null when none).
    Frame aabbVsObbNumbersFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], int maxLevel,
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

    // ---- dual_traversal -----------------------------------------------------------------------
    struct DualStep {
        int trace = -1;  // index into the traversal trace
        BvhTraversalStep step;
        long long bvTests = 0, leafPairs = 0, triangleTests = 0, hits = 0;  // counts up to and including this step
        int pending = 0;  // node pairs left on the stack after this step
    };

    void runDual(const RunContext& ctx, DemoOutput& out) const {
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
        const Camera cam = common_.camera ? *common_.camera
                                          : sphereCamera(center, radius / zoom, view, L.panelWidth(0), L.panelHeight());
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

    // Running counts. Every non-triangle step pops one node pair and tests its boxes; a descent
    // pushes the two pairs of the split node's children. Fills `bv` with the box-test steps and
    // returns every step as trace JSON.
    static Json countDualSteps(const BvhTraversalTrace& tr, std::vector<DualStep>& bv) {
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

    // Frames: the given box-test steps, or the first three, the first prune and the first leaf
    // pair with a triangle hit.
    std::vector<int> chosenDualSteps(const std::vector<DualStep>& bv) const {
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

    // Result frame: the intersecting triangles, and the work beside brute force.
    Frame dualResultFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va, const MeshView& vb,
                          const MeshCollisionResult& r, const MeshCollisionResult& brute, bool equal,
                          const std::vector<LegendItem>& legend) const {
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

    Frame dualFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va, const MeshView& vb,
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
            axisName = drawSeparatingAxis(c, worldBox(ta.box(s.nodeA), ma.pose), worldBox(tb.box(s.nodeB), mb.pose),
                                          labels());
        // A leaf pair: its triangle tests follow in the trace; the hits highlighted.
        std::string triNote;
        if (leafTest) {
            std::vector<int> ha, hb;
            int tests = 0, hit = 0;
            for (int i = d.trace + 1;
                 i < int(tr.steps.size()) && tr.steps[i].action == BvhTraversalAction::TriangleTest; ++i) {
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
                    std::string(s.overlap             ? "boxes overlap"
                                : axisName.empty() ? "boxes disjoint"
                                                   : "boxes disjoint along " + axisName) +
                        " → " + nameOf(s.action) +
                        (triNote.empty() ? "" : ": " + triNote));
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

    // ---- refit ----------------------------------------------------------------------------------
    TriangleMesh deform(const MeshSpec& m, double t) const {
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

    void runRefit(const RunContext& ctx, DemoOutput& out) const {
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
        const Camera cam = common_.camera ? *common_.camera
                                          : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
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
                BarSeries s{std::string(nameOf(kinds[kk])) + (row == 0 ? " refitted" : " rebuilt"),
                            (kk == 0 ? levelColor(0) : levelColor(2))
                                .mixed(roleColor(Role::Background), row == 0 ? 0.0f : 0.45f),
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
            "AABB refit: union of the children's boxes, exact for the old groups: refitted / rebuilt volume " +
                fmt(lo[0]) + " .. " + fmt(hi[0]) + ".",
            "OBB refit: the flat sheet's axes, new extents: refitted / rebuilt " + fmt(lo[1]) + " .. " + fmt(hi[1]) +
                ". Refitting is one bottom-up pass; rebuilding a full build per frame."};
        out.frames.push_back(
            Frame{"volume", "total box volume, refitted vs rebuilt",
                  composeGrid(*ctx.gl, C, ss_, common_.title,
                              {drawBarChart(*ctx.gl, C.panelWidth(), C.panelHeight(), ss_, bc)}, {}, cap2)});
    }

    // ---- build_methods --------------------------------------------------------------------------
    void runBuildMethods(const RunContext& ctx, DemoOutput& out) const {
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
        const Camera cam = common_.camera ? *common_.camera
                                          : sphereCamera(center, radius / zoom, view, L.panelWidth(), L.panelHeight());
        std::vector<Image> panels;
        for (int k = 0; k < 2; ++k) {
            for (int level : levels) {
                const std::vector<int> nodes = levelNodes(trees[k], level);
                panels.push_back(
                    boxesPanel(*ctx.gl, L.panelWidth(), L.panelHeight(), mv, trees[k], m.pose, nodes, levelColor(level),
                               cam, std::string(k == 0 ? "Top-down" : "Bottom-up") + ", level " + std::to_string(level),
                               std::to_string(nodes.size()) + " boxes, volume " + fmt(sumVolume(trees[k], nodes))));
            }
            TreeDiagramInput tin = treeOf(trees[k], treeDepth);
            tin.heading =
                std::string(k == 0 ? "Top-down" : "Bottom-up") + " tree, height " + std::to_string(trees[k].height());
            tin.sub = std::to_string(trees[k].nodes.size()) + " nodes, total volume " + fmt(totalVolume(trees[k]));
            tin.levelLabels = false;
            for (const BvhNode& n : trees[k].nodes) {
                const bool shown = std::find(levels.begin(), levels.end(), n.depth) != levels.end();
                tin.look.push_back(shown ? TreeNodeLook{levelColor(n.depth), 4.0f, false}
                                         : TreeNodeLook{roleColor(Role::Muted), 2.5f, false});
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
};

// The dynamic_tree figure's keys: boxes [{min, max}] (2 to 16, inserted in order), margin, moves
// [{box: index, by: [dx, dy, dz]}] (up to 8), view.
void readDynamicTree(ObjectReader& r, DynamicTreeSpec& spec) {
    JsonNode bs = r.get("boxes");
    if (!bs.isArray() || bs.size() < 2 || bs.size() > 16) bs.fail("expected 2 to 16 boxes [{\"min\": [x,y,z], \"max\": [x,y,z]}]");
    for (const JsonNode& b : bs.items()) {
        ObjectReader br(b);
        const Aabb box{sceneVec3(br.get("min")), sceneVec3(br.get("max"))};
        br.finish();
        if (!(box.min.array() <= box.max.array()).all()) b.fail("min must not exceed max on any axis");
        spec.boxes.push_back(box);
    }
    if (auto m = r.find("margin")) {
        spec.margin = m->asNonNegative();
        if (spec.margin > 1e6) m->fail("expected a margin in [0, 1e6]");
    }
    if (auto ms = r.find("moves")) {
        if (!ms->isArray() || ms->size() > 8) ms->fail("expected up to 8 moves [{\"box\": i, \"by\": [dx,dy,dz]}]");
        for (const JsonNode& m : ms->items()) {
            ObjectReader mr(m);
            DynamicTreeSpec::Move mv;
            mv.box = mr.get("box").asInt(0, static_cast<int>(spec.boxes.size()) - 1);
            mv.by = sceneVec3(mr.get("by"));
            mr.finish();
            spec.moves.push_back(mv);
        }
    }
    if (auto v = r.find("view")) spec.view = sceneVec3(*v);
}

class BvhDemo final : public Demo {
public:
    std::string name() const override { return "bvh"; }
    std::string description() const override {
        return "bounding-volume hierarchies: levels and tree, AABB vs OBB trees on a torus, dual traversal step by "
               "step, refitting";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {480, 360}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        auto s = std::make_unique<BvhScene>(std::move(common));
        const std::string fig = r.get("figure").asEnum(
            {"hierarchy_levels", "aabb_vs_obb", "dual_traversal", "refit", "build_methods", "dynamic_tree"});
        if (fig == "dynamic_tree") {
            s->figure = Figure::DynamicTree;
            readDynamicTree(r, s->dynamicTree);
            r.finish();
            return s;
        }
        s->figure = fig == "hierarchy_levels" ? Figure::Levels
                    : fig == "aabb_vs_obb"    ? Figure::AabbVsObb
                    : fig == "dual_traversal" ? Figure::DualTraversal
                    : fig == "refit"          ? Figure::Refit
                                              : Figure::BuildMethods;
        JsonNode ms = r.get("meshes");
        if (!ms.isArray() || ms.size() < 1 || ms.size() > 2) ms.fail("expected [mesh] or [meshA, meshB]");
        for (const JsonNode& m : ms.items()) s->meshes.push_back(parseMesh(m));
        if (s->figure == Figure::DualTraversal && s->meshes.size() != 2) ms.fail("dual_traversal needs two meshes");
        if (s->figure == Figure::Refit && s->meshes[0].kind != "sheet")
            ms.fail("refit deforms a sheet: use {\"sheet\": {...}}");
        for (std::size_t i = 0; i < s->meshes.size(); ++i)
            if (s->meshes[i].mesh.triangleCount() > 20000) ms.at(i).fail("at most 20000 triangles in a figure");
        if (auto b = r.find("bv")) s->build.bvKind = b->asEnum({"aabb", "obb"}) == "aabb" ? BvKind::Aabb : BvKind::Obb;
        if (auto m = r.find("method")) {
            const std::string v = m->asEnum({"top_down_median", "top_down_sah", "bottom_up"});
            s->build.method = v == "top_down_median" ? BvhBuildMethod::TopDownMedian
                              : v == "top_down_sah"  ? BvhBuildMethod::TopDownSah
                                                     : BvhBuildMethod::BottomUp;
        }
        if (auto n = r.find("max_leaf_triangles")) s->build.maxLeafTriangles = n->asInt(1, 64);
        if (auto l = r.find("levels")) {
            s->levels.clear();
            for (const JsonNode& v : l->items()) s->levels.push_back(v.asInt(0, 30));
            if (s->levels.empty() || s->levels.size() > 5) l->fail("expected 1 to 5 levels");
        }
        if (auto v = r.find("view")) s->view = sceneVec3(*v);
        if (auto z = r.find("zoom")) {
            s->zoom = z->asPositive();
            if (s->zoom < 0.01 || s->zoom > 100) z->fail("expected a zoom in [0.01, 100]");
        }
        if (auto d = r.find("tree_depth")) s->treeDepth = d->asInt(1, 8);
        if (auto f = r.find("step_frames")) {
            for (const JsonNode& v : f->items()) s->stepFrames.push_back(v.asInt(0, 100000));
            if (s->stepFrames.size() > 12) f->fail("at most 12 step frames");
        }
        if (auto d = r.find("deformation")) {
            ObjectReader dr(*d);
            s->deformation =
                dr.get("kind").asEnum({"roll", "twist"}) == "roll" ? Deformation::Roll : Deformation::Twist;
            if (auto a = dr.find("angle")) {
                s->deformAngle = a->asNumber();
                if (std::abs(s->deformAngle) > 3600) a->fail("expected an angle in [-3600, 3600] degrees");
            }
            if (auto t = dr.find("times")) {
                s->times.clear();
                for (const JsonNode& v : t->items()) {
                    s->times.push_back(v.asNonNegative());
                    if (s->times.back() > 1e3) v.fail("expected a time in [0, 1000]");
                }
                if (s->times.empty() || s->times.size() > 4) t->fail("expected 1 to 4 times");
            }
            dr.finish();
        }
        r.finish();
        return s;
    }
};

}  // namespace

const Demo& bvhDemo() {
    static const BvhDemo demo;
    return demo;
}

}  // namespace cdlab::demos
