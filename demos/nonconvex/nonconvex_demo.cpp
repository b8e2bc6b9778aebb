// Non-convex bodies as unions of convex pieces (the course's "convex decomposition of non-convex
// polyhedra"): each closed mesh split into the solid cells of its BSP tree
// (core/spatial/convex_decomposition.h — why those cells and not cuts at reflex edges is said
// there), a box per piece and per body (a two-level bounding hierarchy), and the body pair answered
// as pairs of pieces: the bodies' boxes first, then for intersection every piece pair whose boxes
// overlap goes to GJK/EPA, and for distance the piece pairs in order of their boxes' distance until
// that bound passes the best distance found (branch and bound). The closest pair and the deepest
// pair are highlighted; the deepest pair's depth is not the union's true depth (a body can be deeper
// in the union than in any one piece), as docs/query.md says for `cdlab query`'s compounds.
//
// Scene keys (besides the common ones in scene.h):
//   "a", "b": a body — {"prism": {"outline": [[x, y], ...], "height": h}} (a simple polygon extruded
//             along z, non-convex allowed) or {"mesh": {"vertices": [...], "triangles": [[i, j, k], ...]}}
//             (closed, outward or inward facing), each with "position" and "rotation" beside it
//   "view": [x, y, z]   the direction the camera looks from (default [0.35, -0.55, 1.6]: mostly down z)
// Layers: "labels", "boxes", "numbers".
#include "demos/nonconvex/nonconvex_demo.h"

#include "demos/nonconvex/decomposition_figure.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/shapes.h"
#include "core/geometry/solid_mesh.h"
#include "core/geometry/triangle_mesh.h"
#include "core/gjk_epa/epa.h"
#include "core/spatial/convex_decomposition.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"labels", "boxes", "numbers"};

struct Body {
    TriangleMesh mesh;                      // world frame, outward-facing
    DecompositionTrace decomposition;       // world frame cells
    std::vector<std::vector<Vec3>> pieces;  // world frame
    std::vector<Eigen::AlignedBox3d> boxes;
    Eigen::AlignedBox3d box;
};

/// One piece pair: what the hierarchy did with it and, when tested, GJK/EPA's answer.
struct PiecePair {
    int a = 0, b = 0;
    double boxDistance = 0.0;  // 0 when the boxes overlap
    std::string action;        // "tested", "culled: boxes apart", "pruned: box bound >= best"
    bool intersect = false;
    double distance = 0.0, depth = 0.0;
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero(), normal = Vec3::Zero();
};

struct PairRun {
    bool intersect = false;
    std::vector<PiecePair> pairs;
    int closest = -1, deepest = -1;  // indices into pairs
    int tested = 0;
};

double boxDistance(const Eigen::AlignedBox3d& x, const Eigen::AlignedBox3d& y) {
    const Vec3 gap = (x.min() - y.max()).cwiseMax(y.min() - x.max()).cwiseMax(Vec3::Zero());
    return gap.norm();
}

/// Intersection: the box-overlapping piece pairs, each through GJK/EPA (penetration() gives the
/// depth, or the distance when apart). Distance (when no pair meets): branch and bound on the boxes.
PairRun runPairs(const Body& A, const Body& B) {
    PairRun run;
    for (std::size_t i = 0; i < A.pieces.size(); ++i)
        for (std::size_t j = 0; j < B.pieces.size(); ++j)
            run.pairs.push_back({int(i), int(j), boxDistance(A.boxes[i], B.boxes[j]), "", false, 0, 0, {}, {}, {}});
    std::stable_sort(run.pairs.begin(), run.pairs.end(),
                     [](const PiecePair& x, const PiecePair& y) { return x.boxDistance < y.boxDistance; });
    const auto test = [&](PiecePair& p) {
        const EpaResult e = penetration(PolytopeShape(A.pieces[std::size_t(p.a)]), PolytopeShape(B.pieces[std::size_t(p.b)]));
        p.action = "tested";
        ++run.tested;
        p.intersect = e.status == EpaStatus::Penetrating || e.status == EpaStatus::Touching;
        p.depth = p.intersect ? e.depth : 0.0;
        p.pointA = e.pointA;
        p.pointB = e.pointB;
        p.normal = e.normal;
        p.distance = p.intersect ? 0.0 : (e.pointB - e.pointA).norm();
    };
    // Intersection pass: only pairs whose boxes overlap can meet.
    for (PiecePair& p : run.pairs) {
        if (p.boxDistance > 0) break;
        test(p);
        run.intersect = run.intersect || p.intersect;
    }
    if (!run.intersect) {
        // Distance: boxes in order of their distance; stop when the next box distance is no better.
        double best = INFINITY;
        for (PiecePair& p : run.pairs) {
            if (!p.action.empty()) {
                best = std::min(best, p.distance);
                continue;
            }
            if (p.boxDistance >= best) {
                p.action = "pruned: box bound >= best";
                continue;
            }
            test(p);
            best = std::min(best, p.distance);
        }
    } else {
        for (PiecePair& p : run.pairs)
            if (p.action.empty()) p.action = "culled: boxes apart";
    }
    for (std::size_t k = 0; k < run.pairs.size(); ++k) {
        const PiecePair& p = run.pairs[k];
        if (p.action != "tested") continue;
        if (p.intersect && (run.deepest < 0 || p.depth > run.pairs[std::size_t(run.deepest)].depth)) run.deepest = int(k);
        if (!p.intersect && (run.closest < 0 || p.distance < run.pairs[std::size_t(run.closest)].distance)) run.closest = int(k);
    }
    return run;
}


Json pairsJson(const Body& A, const Body& B, const PairRun& run) {
    Json pairs = Json::array();
    for (const PiecePair& p : run.pairs) {
        Json j = {{"a", p.a}, {"b", p.b}, {"box_distance", p.boxDistance}, {"action", p.action}};
        if (p.action == "tested") {
            j["intersect"] = p.intersect;
            if (p.intersect) j["depth"] = p.depth;
            else j["distance"] = p.distance;
        }
        pairs.push_back(j);
    }
    Json j = {{"pieces_a", A.pieces.size()}, {"pieces_b", B.pieces.size()}, {"intersect", run.intersect},
              {"pairs", pairs}, {"tested", run.tested}};
    if (run.deepest >= 0) {
        const PiecePair& p = run.pairs[std::size_t(run.deepest)];
        j["deepest"] = {{"a", p.a}, {"b", p.b}, {"depth", p.depth}, {"normal", vec3Json(p.normal)}};
    }
    if (run.closest >= 0 && !run.intersect) {
        const PiecePair& p = run.pairs[std::size_t(run.closest)];
        j["closest"] = {{"a", p.a}, {"b", p.b}, {"distance", p.distance}, {"point_a", vec3Json(p.pointA)},
                        {"point_b", vec3Json(p.pointB)}};
    }
    return j;
}

// ------------------------------------------------------------------------------------- scene

Body readBody(const JsonNode& node) {
    ObjectReader r(node);
    Body body;
    TriangleMesh local;
    if (r.has("prism") == r.has("mesh")) node.fail("expected exactly one of 'prism' or 'mesh'");
    if (auto p = r.find("prism")) {
        ObjectReader pr(*p);
        JsonNode on = pr.get("outline");
        if (!on.isArray() || on.size() < 3) on.fail("expected at least 3 corners [[x, y], ...]");
        requireAtMost(on, double(on.size()), 64, "the number of corners", "the limit of a drawn outline");
        std::vector<Vec2> outline;
        for (const JsonNode& item : on.items()) outline.push_back(sceneVec2(item).head<2>());
        const double height = sceneSize(pr.get("height"));
        pr.finish();
        local = prismMesh(outline, height);
        if (local.triangles.empty()) on.fail("the outline is not a simple polygon (its edges cross or it has no area)");
    } else {
        JsonNode mn = r.get("mesh");
        ObjectReader mr(mn);
        local.vertices = sceneVec3List(mr.get("vertices"), 4, 400);
        JsonNode tn = mr.get("triangles");
        requireAtMost(tn, double(tn.size()), 800, "the number of triangles", "the limit of a drawn mesh");
        const int last = int(local.vertices.size()) - 1;
        for (const JsonNode& t : tn.items()) {
            if (!t.isArray() || t.size() != 3) t.fail("expected [i, j, k]");
            local.triangles.push_back({t.at(0).asInt(0, last), t.at(1).asInt(0, last), t.at(2).asInt(0, last)});
        }
        mr.finish();
        const SolidMeshCheck check = checkSolidMesh(local);
        if (check.status != SolidMeshStatus::Closed)
            tn.fail(std::string("the mesh does not bound a solid: ") + nameOf(check.status) +
                    (check.triangle >= 0 ? " at triangle " + std::to_string(check.triangle) : ""));
        const double volume = signedVolume(local);
        if (volume == 0) tn.fail("the mesh encloses no volume");
        if (volume < 0)
            for (auto& t : local.triangles) std::swap(t[1], t[2]);  // inward-facing: the same solid, turned out
    }
    Transform pose;
    if (auto p = r.find("position")) pose.position = sceneVec3(*p);
    if (auto q = r.find("rotation")) pose.rotation = q->asQuat();
    r.finish();
    body.mesh = local;
    for (Vec3& v : body.mesh.vertices) v = pose.apply(v);
    const ConvexDecomposition d = decomposeIntoConvexPieces(local, {}, &body.decomposition);
    for (DecompositionStep& st : body.decomposition.steps)
        for (Vec3& v : st.cell) v = pose.apply(v);
    if (d.pieces.empty()) node.fail("the body could not be split into convex pieces");
    for (const std::vector<Vec3>& piece : d.pieces) {
        std::vector<Vec3> world;
        Eigen::AlignedBox3d box;
        for (const Vec3& v : piece) {
            world.push_back(pose.apply(v));
            box.extend(world.back());
        }
        body.pieces.push_back(world);
        body.boxes.push_back(box);
        body.box.extend(box);
    }
    return body;
}

// ------------------------------------------------------------------------------------ figures

ConvexDrawable pieceDrawable(const std::vector<Vec3>& corners) {
    SceneShape s;
    s.kind = SceneShape::Kind::Polytope;
    s.polytope = PolytopeShape(corners);
    return shapeDrawable(s);
}

void drawBoxOutline(Canvas& c, const Eigen::AlignedBox3d& box, const LineStyle& style) {
    for (int k = 0; k < 8; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            if (k & (1 << axis)) continue;
            const Vec3 p = box.corner(Eigen::AlignedBox3d::CornerType(k)),
                       q = box.corner(Eigen::AlignedBox3d::CornerType(k | (1 << axis)));
            c.drawLine(p, q, style);
        }
}

class NonconvexScene final : public PreparedScene {
public:
    NonconvexScene(SceneCommon common, Body a, Body b, Vec3 view)
        : PreparedScene(std::move(common)), a_(std::move(a)), b_(std::move(b)), view_(view) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const PairRun run = runPairs(a_, b_);
        DemoOutput out;
        out.trace = pairsJson(a_, b_, run);
        out.trace["decomposition_a"] = decompositionJson(a_.decomposition);
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(drawFrame(*ctx.gl, ctx, run, false));
        out.frames.push_back(drawFrame(*ctx.gl, ctx, run, true));
        out.frames.push_back(Frame{"decomposition", common_.title + " — A's decomposition",
                                   drawDecomposition(*ctx.gl, common_.image.width, common_.image.height,
                                                     figureScale(common_, ctx), common_.title, "A", a_.decomposition,
                                                     a_.mesh, view_)});
        return out;
    }

private:
    Body a_, b_;
    Vec3 view_;

    Frame drawFrame(GlContext& gl, const RunContext& ctx, const PairRun& run, bool pairsFrame) const {
        Canvas c(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        Eigen::AlignedBox3d all = a_.box;
        all.extend(b_.box);
        // Room under the bodies for the numbers block.
        const double radius = 0.5 * all.diagonal().norm();
        Camera cam = framingCamera(all.center(), radius * 1.12, view_, Vec3::UnitY(), true);
        c.setCamera(common_.camera ? *common_.camera : cam);
        const bool labels = common_.hasLayer("labels");
        const PiecePair* focus = run.deepest >= 0 ? &run.pairs[std::size_t(run.deepest)]
                                 : run.closest >= 0 ? &run.pairs[std::size_t(run.closest)]
                                                    : nullptr;
        // Pieces: each its own colour in the pieces frame; in the pairs frame the focused pair's two
        // pieces in the bodies' colours, the rest faint.
        for (int k = 0; k < 2; ++k) {
            const Body& body = k == 0 ? a_ : b_;
            for (std::size_t i = 0; i < body.pieces.size(); ++i) {
                // One hue per body in both frames (A's, B's), its pieces told apart by shade.
                const Color base = roleColor(k == 0 ? Role::ShapeA : Role::ShapeB);
                Color fill = i % 2 ? base.mixed(roleColor(Role::Background), 0.45f) : base.scaled(1.0f - 0.12f * float(i / 2));
                float alpha = 0.45f;
                if (pairsFrame) {
                    const bool mine = focus && (k == 0 ? focus->a : focus->b) == int(i);
                    fill = mine ? roleColor(k == 0 ? Role::ShapeA : Role::ShapeB) : roleColor(Role::Muted);
                    alpha = mine ? 0.55f : 0.15f;
                }
                drawBody(c, pieceDrawable(body.pieces[i]), fill, alpha, base.scaled(0.6f), 1.5f);
                if (labels) {  // named in both frames: the pairs frame's text names pieces
                    Vec3 centre = Vec3::Zero();
                    for (const Vec3& v : body.pieces[i]) centre += v;
                    TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                    ts.place = true;
                    c.drawText(centre / double(body.pieces[i].size()), std::string(k == 0 ? "A" : "B") + std::to_string(i + 1), ts);
                }
            }
        }
        if (common_.hasLayer("boxes") && !pairsFrame) {
            for (const Body* body : {&a_, &b_}) {
                drawBoxOutline(c, body->box, lineStyle(Role::Ink, 1.5f, true));
                for (const auto& box : body->boxes) drawBoxOutline(c, box, lineStyle(Role::Muted, 1.0f, true));
            }
        }
        if (pairsFrame && focus) {
            if (focus->intersect) {
                c.drawArrow(focus->pointB, focus->pointB + focus->depth * focus->normal, lineStyle(Role::Result, 4.0f, false, true));
            } else {
                c.drawLine(focus->pointA, focus->pointB, lineStyle(Role::Result, 3.0f, true, true));
                c.drawPoint(focus->pointA, 7.0f, roleColor(Role::Result));
                c.drawPoint(focus->pointB, 7.0f, roleColor(Role::Result));
                if (labels) {
                    TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                    ts.offsetPx = Eigen::Vector2d(0, -30);
                    ts.place = true;
                    c.drawText(0.5 * (focus->pointA + focus->pointB), "distance " + formatNumber(focus->distance), ts);
                }
            }
        }
        std::vector<std::string> lines;
        int culled = 0, pruned = 0;
        for (const PiecePair& p : run.pairs) {
            culled += p.action.rfind("culled", 0) == 0;
            pruned += p.action.rfind("pruned", 0) == 0;
        }
        lines.push_back("A: " + std::to_string(a_.pieces.size()) + " convex pieces, B: " + std::to_string(b_.pieces.size()) +
                        " (the solid cells of each body's BSP tree);  " + std::to_string(run.pairs.size()) + " piece pairs: " +
                        std::to_string(run.tested) + " tested by GJK/EPA, " + std::to_string(culled) + " culled (boxes apart), " +
                        std::to_string(pruned) + " pruned (box distance ≥ the best distance found)");
        if (focus && focus->intersect)
            lines.push_back("they intersect; the deepest pair A" + std::to_string(focus->a + 1) + "–B" + std::to_string(focus->b + 1) +
                            ": depth " + formatNumber(focus->depth) + " along " + formatPoint(focus->normal) +
                            " (a pair's depth, not the union's: pushing out of one piece can push into another)");
        else if (focus)
            lines.push_back("apart; the closest pair A" + std::to_string(focus->a + 1) + "–B" + std::to_string(focus->b + 1) +
                            ": distance " + formatNumber(focus->distance) + " — the bodies' distance");
        // The order the caption teaches, pair by pair (the review: 0.316, 0.6, 1.4, 2.1 not drawn).
        if (pairsFrame && !run.pairs.empty()) {
            std::string order = "pairs by box distance:";
            const std::size_t shown = std::min<std::size_t>(run.pairs.size(), 6);
            for (std::size_t i = 0; i < shown; ++i) {
                const PiecePair& p = run.pairs[i];
                order += std::string(i ? ";  " : "  ") + "A" + std::to_string(p.a + 1) + "–B" + std::to_string(p.b + 1) +
                         " " + formatNumber(p.boxDistance) + " " + p.action.substr(0, p.action.find(':'));
            }
            if (run.pairs.size() > shown) order += ";  … " + std::to_string(run.pairs.size() - shown) + " more";
            lines.push_back(order);
        }
        if (common_.hasLayer("numbers")) {
            const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
            std::vector<std::string> wrapped;
            for (const std::string& l : lines)  // a line breaks only between its ";  " phrases
                for (const std::string& w : wrapAtSeparator(c, l, ";  ", ts, c.width() - 40.0)) wrapped.push_back(w);
            double y = c.height() - 48 - 24.0 * double(wrapped.size());
            for (const std::string& l : wrapped) {
                c.drawTextPx(20, y, l, ts);
                y += 24;
            }
        }
        if (!pairsFrame && common_.hasLayer("boxes"))
            drawKey(c, 20, 62,
                    {{roleColor(Role::ShapeA), "A's pieces"}, {roleColor(Role::ShapeB), "B's pieces"},
                     {roleColor(Role::Ink), "a body's box (dashed)"}, {roleColor(Role::Muted), "a piece's box (dashed)"}},
                    17.0f);
        if (pairsFrame)
            drawKey(c, 20, 62,
                    {{roleColor(Role::ShapeA), "A's piece"}, {roleColor(Role::ShapeB), "B's piece"},
                     {roleColor(Role::Result), focus && focus->intersect ? "depth·n of the deepest pair" : "closest points"}},
                    17.0f);
        drawTitleAndCaption(c, common_.title + (pairsFrame ? ": the pairs" : ": convex pieces"), common_.caption);
        Frame f;
        f.name = pairsFrame ? "pairs" : "pieces";
        f.caption = common_.title + (pairsFrame ? " — pairs" : " — pieces");
        f.image = c.readPixels();
        return f;
    }
};

class NonconvexDemo final : public Demo {
public:
    std::string name() const override { return "nonconvex"; }
    std::string description() const override {
        return "non-convex bodies split into convex pieces (solid BSP cells), collided as pairs of pieces with a "
               "box hierarchy: culled, pruned and tested pairs, the closest and the deepest pair";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1280, 960, 1}, {960, 720, 0, 0}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        Body a = readBody(r.get("a"));
        Body b = readBody(r.get("b"));
        Vec3 view(0.35, -0.55, 1.6);  // mostly down the extrusion axis: prisms read as their outlines
        if (auto v = r.find("view")) {
            view = sceneVec3(*v);
            if (view.isZero(0.0)) v->fail("the view direction must be non-zero");
        }
        r.finish();
        return std::make_unique<NonconvexScene>(std::move(common), std::move(a), std::move(b), view);
    }
};

}  // namespace

const Demo& nonconvexDemo() {
    static const NonconvexDemo demo;
    return demo;
}

}  // namespace cdlab::demos
