// Internal to the BVH demo (demos/bvh): the prepared scene shared by its figure files —
// BvhScene with its keys and the helpers its figures use (meshes, world boxes, tree cuts and
// volumes, number formats). bvh_demo.cpp reads a scene and dispatches on its figure; each figure
// is drawn in its own file: bvh_levels_figure.cpp (hierarchy_levels), bvh_aabb_vs_obb_figure.cpp,
// bvh_dual_traversal_figure.cpp, bvh_refit_figure.cpp, bvh_build_methods_figure.cpp,
// bvh_sah_figure.cpp, bvh_ray_figure.cpp and dynamic_tree_figure.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/demo.h"
#include "app/scene/mesh_scene.h"
#include "app/scene/scene_limits.h"
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

namespace cdlab::demos::bvhfig {

using namespace render;
using namespace bvhdemo;

// ---- meshes

/// Flat rectangular sheet in the body xy plane (z = 0), centred at the origin: nx × ny quads, two
/// triangles each. The refit figure deforms it.
inline TriangleMesh sheetMesh(double lx, double ly, int nx, int ny) {
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

inline MeshSpec parseMesh(const JsonNode& node) {
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

inline MeshView meshView(const TriangleMesh& m, const Transform& pose) {
    MeshView v;
    for (const Vec3& p : m.vertices) v.vertices.push_back(pose.apply(p));
    for (const auto& t : m.triangles) v.triangles.emplace_back(t[0], t[1], t[2]);
    return v;
}

// The axis that separates two disjoint boxes, drawn through A's centre with both boxes'
// projections on it (Ericson §4.4.1: 15 candidate axes): the gap between the two bars is why
// the pair is pruned, even where the boxes overlap on screen. Returns the axis' name.
inline std::string drawSeparatingAxis(Canvas& c, const Obb& a, const Obb& b, bool labels) {
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

inline Obb worldBox(const Obb& b, const Transform& pose) {
    Obb w = b;
    w.center = pose.apply(b.center);
    w.axes = pose.rotation.toRotationMatrix() * b.axes;
    return w;
}

/// The cut of the tree at `level`: nodes of that depth plus the leaves above it (together they
/// cover every triangle once).
inline std::vector<int> levelNodes(const Bvh& bvh, int level) {
    std::vector<int> out;
    for (int i = 0; i < int(bvh.nodes.size()); ++i) {
        const BvhNode& n = bvh.nodes[i];
        if (n.depth == level || (n.isLeaf() && n.depth < level)) out.push_back(i);
    }
    return out;
}

inline double sumVolume(const Bvh& bvh, const std::vector<int>& nodes) {
    double v = 0;
    for (int i : nodes) v += volume(bvh.box(i));
    return v;
}

inline double totalVolume(const Bvh& bvh) {
    double v = 0;
    for (int i = 0; i < int(bvh.nodes.size()); ++i) v += volume(bvh.box(i));
    return v;
}

/// World corners of a tree's root box (for framing).
inline std::vector<Vec3> rootCorners(const Bvh& bvh, const Transform& pose) {
    if (bvh.empty()) return {};
    const auto c = boxCorners(worldBox(bvh.box(0), pose));
    return std::vector<Vec3>(c.begin(), c.end());
}

/// World corners of the boxes of `nodes` (for framing).
inline std::vector<Vec3> boxesCorners(const Bvh& bvh, const Transform& pose, const std::vector<int>& nodes) {
    std::vector<Vec3> out;
    for (int i : nodes) {
        const auto c = boxCorners(worldBox(bvh.box(i), pose));
        out.insert(out.end(), c.begin(), c.end());
    }
    return out;
}

inline std::vector<int> nodeTriangles(const Bvh& bvh, int node) {
    const BvhNode& n = bvh.nodes[node];
    return std::vector<int>(bvh.triangleOrder.begin() + n.first, bvh.triangleOrder.begin() + n.first + n.count);
}

inline TreeDiagramInput treeOf(const Bvh& bvh, int maxDepth) {
    TreeDiagramInput t;
    for (const BvhNode& n : bvh.nodes) t.children.push_back({n.left, n.right});
    t.maxDepth = maxDepth;
    return t;
}

inline std::string methodWords(BvhBuildMethod m) {
    switch (m) {
        case BvhBuildMethod::TopDownMedian: return "top-down, median split on the longest axis";
        case BvhBuildMethod::TopDownSah: return "top-down, binned SAH";
        case BvhBuildMethod::BottomUp: return "bottom-up, merge the smallest union";
    }
    return "?";
}

inline Json obbJson(const Obb& b) {
    Json axes = Json::array();
    for (int i = 0; i < 3; ++i) axes.push_back(vec3Json(b.axes.col(i)));
    return {{"center", vec3Json(b.center)}, {"half_extents", vec3Json(b.halfExtents)}, {"axes", axes}};
}

inline GridLayout grid(int width, int height, int columns, int rows) {
    GridLayout g;
    g.width = width;
    g.height = height;
    g.columns = columns;
    g.rows = rows;
    return g;
}

inline std::string fmt(double x) { return formatNumber(x); }
inline std::string pct(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f%%", 100.0 * x);
    return buf;
}

/// Whether two lists hold the same triangle pairs, in any order.
inline bool samePairs(std::vector<TrianglePair> a, std::vector<TrianglePair> b) {
    auto less = [](const TrianglePair& x, const TrianglePair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    return a == b;
}

/// The triangles of A and of B in a list of pairs, in the pairs' order.
inline void splitPairs(const std::vector<TrianglePair>& pairs, std::vector<int>& a, std::vector<int>& b) {
    for (const TrianglePair& p : pairs) {
        a.push_back(p.a);
        b.push_back(p.b);
    }
}

// ---- the scene

enum class Figure { Levels, AabbVsObb, DualTraversal, Refit, BuildMethods, DynamicTree, SahSplit, RayQuery };

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
    Ray ray{Vec3::Zero(), Vec3::UnitX()};  // ray_query

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
            case Figure::SahSplit: runSahSplit(ctx, out); break;
            case Figure::RayQuery: runRayQuery(ctx, out); break;
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

    // dynamic_tree (dynamic_tree_figure.cpp)
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

    // hierarchy_levels (bvh_levels_figure.cpp)
    void runLevels(const RunContext& ctx, DemoOutput& out) const;

    // aabb_vs_obb (bvh_aabb_vs_obb_figure.cpp)
    void runAabbVsObb(const RunContext& ctx, DemoOutput& out) const;

    /// Mesh 1 against mesh 0 through trees of each kind (q[k] with trees[k]'s kind), checked against brute force.
    Json queryBothTrees(const Bvh (&trees)[2], MeshCollisionResult (&q)[2]) const;

    /// The sphere around the mesh and both trees' boxes at the shallowest drawn level: one camera frames every panel.
    void sphereOverTopLevel(const MeshView& mv, const Bvh (&trees)[2], const Transform& pose, Vec3& center,
                            double& radius) const;

    // Frame 1: AABB row over OBB row, one column per level.
    Frame aabbVsObbLevelsFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], const Vec3& center,
                               double radius) const;

    // Frame 2: volume per level, and the query's counters (q: the query through each tree, or null when none).
    Frame aabbVsObbNumbersFrame(GlContext& gl, const MeshView& mv, const Bvh (&trees)[2], int maxLevel,
                                const MeshCollisionResult* q) const;

    // dual_traversal (bvh_dual_traversal_figure.cpp)
    struct DualStep {
        int trace = -1;  // index into the traversal trace
        BvhTraversalStep step;
        long long bvTests = 0, leafPairs = 0, triangleTests = 0, hits = 0;  // counts up to and including this step
        int pending = 0;  // node pairs left on the stack after this step
    };

    void runDual(const RunContext& ctx, DemoOutput& out) const;

    // Running counts. Every non-triangle step pops one node pair and tests its boxes; a descent
    // pushes the two pairs of the split node's children. Fills `bv` with the box-test steps and
    // returns every step as trace JSON.
    static Json countDualSteps(const BvhTraversalTrace& tr, std::vector<DualStep>& bv);

    // Frames: the given box-test steps, or the first three, the first prune and the first leaf
    // pair with a triangle hit.
    std::vector<int> chosenDualSteps(const std::vector<DualStep>& bv) const;

    // Result frame: the intersecting triangles, and the work beside brute force.
    Frame dualResultFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va, const MeshView& vb,
                          const MeshCollisionResult& r, const MeshCollisionResult& brute, bool equal,
                          const std::vector<LegendItem>& legend) const;

    Frame dualFrame(GlContext& gl, const GridLayout& L, const Camera& cam, const MeshView& va, const MeshView& vb,
                    const Bvh& ta, const Bvh& tb, const MeshSpec& ma, const MeshSpec& mb,
                    const std::vector<DualStep>& bv, int k, const BvhTraversalTrace& tr,
                    const std::vector<LegendItem>& legend) const;

    // refit (bvh_refit_figure.cpp)
    TriangleMesh deform(const MeshSpec& m, double t) const;

    void runRefit(const RunContext& ctx, DemoOutput& out) const;

    // build_methods (bvh_build_methods_figure.cpp)
    void runBuildMethods(const RunContext& ctx, DemoOutput& out) const;

    // sah_split (bvh_sah_figure.cpp)
    void runSahSplit(const RunContext& ctx, DemoOutput& out) const;

    // ray_query (bvh_ray_figure.cpp)
    void runRayQuery(const RunContext& ctx, DemoOutput& out) const;
};

}  // namespace cdlab::demos::bvhfig
