// Bounding-volume hierarchies over triangle meshes, as teaching figures. Every tree, box, volume,
// counter and triangle pair comes from core (core/bvh/bvh.h: buildBvh with its BvhBuildTrace,
// refitBvh, traverseBvhPair; core/bvh/mesh_collision.h: collideMeshes with its BvhTraversalTrace;
// core/bounding/bounding_volume_fit.h: volume). The figure files (demos/bvh/bvh_scene.h) only
// choose what to draw, count trace steps and move boxes into the world for drawing; this file
// reads a scene and dispatches on its figure.
//
// Sources: C. Ericson, "Real-Time Collision Detection" (2005) ch. 6 (§6.2 construction, §6.3.2
// dual traversal, "descend larger"); S. Gottschalk, M. Lin, D. Manocha, "OBBTree: A Hierarchical
// Structure for Rapid Interference Detection", SIGGRAPH 1996 (AABB vs OBB trees on a torus);
// G. van den Bergen, "Efficient collision detection of complex deformable models using AABB
// trees", JGT 2(4) 1997 (refitting).
//
// Figures ("figure" key): hierarchy_levels, aabb_vs_obb, dual_traversal, refit, build_methods,
// sah_split, ray_query, dynamic_tree (demos/bvh/dynamic_tree_figure.h: core/broadphase/dynamic_tree.h step by step).
// Scene keys: docs/scenes.md, "bvh".
#include "demos/bvh/bvh_demo.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/base/aabb_ops.h"
#include "demos/bvh/bvh_scene.h"
#include "demos/bvh/dynamic_tree_figure.h"

namespace cdlab::demos {

namespace {

using namespace render;
using namespace bvhdemo;
using namespace bvhfig;

const std::vector<std::string> kLayers = {"mesh", "boxes", "tree", "labels"};

// The dynamic_tree figure's keys: boxes [{min, max}] (2 to 16, inserted in order), margin, moves
// [{box: index, by: [dx, dy, dz]}] (up to 8), view.
void readDynamicTree(ObjectReader& r, DynamicTreeSpec& spec) {
    JsonNode bs = r.get("boxes");
    if (!bs.isArray() || bs.size() < 2 || bs.size() > 16)
        bs.fail("expected 2 to 16 boxes [{\"min\": [x,y,z], \"max\": [x,y,z]}]");
    for (const JsonNode& b : bs.items()) {
        ObjectReader br(b);
        const Aabb box{sceneVec3(br.get("min")), sceneVec3(br.get("max"))};
        br.finish();
        if (!isValidBox(box)) b.fail("min must not exceed max on any axis");  // coordinates are finite (sceneVec3)
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
            {"hierarchy_levels", "aabb_vs_obb", "dual_traversal", "refit", "build_methods", "dynamic_tree", "sah_split",
             "ray_query"});
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
                    : fig == "sah_split"      ? Figure::SahSplit
                    : fig == "ray_query"      ? Figure::RayQuery
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
        if (auto n = r.find("sah_bins")) s->build.sahBins = n->asInt(2, 64);
        if (s->figure == Figure::SahSplit && s->meshes[0].mesh.triangleCount() <= s->build.maxLeafTriangles)
            ms.at(0).fail("sah_split needs more triangles than max_leaf_triangles: the root would not split");
        if (s->figure == Figure::RayQuery) {
            ObjectReader rr(r.get("ray"));
            s->ray.origin = sceneVec3(rr.get("origin"));
            const JsonNode d = rr.get("direction");
            s->ray.direction = sceneVec3(d);
            if (!(s->ray.direction.norm() > 0)) d.fail("a ray direction must be non-zero");
            rr.finish();
        }
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