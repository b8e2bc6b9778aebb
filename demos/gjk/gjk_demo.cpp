// GJK step-through (Gilbert, Johnson, Keerthi 1988, as in van den Bergen, "Collision Detection in
// Interactive 3D Environments" §4.3, and Ericson, Real-Time Collision Detection §9.5). Every number
// drawn comes from core's GjkTrace (core/gjk_epa/gjk.h): this file computes only drawing geometry (the hull
// of A − B, cameras).
//
// Scene keys (besides the common ones in scene.h and the pair keys of scene/pair_scene.h):
//   "method": {"solver": "signed_volumes" | "johnson", "tolerance": eps_rel, "max_iterations": n}
// Layers: "minkowski" (A − B), "simplex", "direction", "support", "witness", "labels".
// Frames: step_NN (one per traced iteration, at most max_step_frames), "result", "bounds" (runs of 10
// iterations or more), and with "steps" a contact sheet; plus animation.gif (files) and the JSON trace.
#include "demos/gjk/gjk_demo.h"

#include "demos/gjk/gjk_closest_set_frame.h"
#include "demos/gjk/gjk_regions_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/gjk_epa/gjk.h"
#include "demos/draw/contact_sheet.h"
#include "demos/draw/plot.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/draw/step_frames.h"
#include "demos/draw/zoom_inset.h"
#include "app/scene/pair_scene.h"
#include "render/canvas.h"
#include "render/legibility.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"minkowski", "simplex", "direction", "support", "witness", "labels"};

// What a kept sub-simplex of `letters` vertices is; a full simplex (dimension + 1 vertices) only
// survives the reduction when it holds the origin.
std::string regionKind(std::size_t letters, int dimension) {
    if (int(letters) == dimension + 1) return dimension == 2 ? "triangle: origin inside" : "tetrahedron: origin inside";
    static const char* kKind[4] = {"", "vertex", "edge", "face"};
    return kKind[std::min<std::size_t>(letters, 3)];
}

Json vertexJson(const GjkVertex& v) { return {{"w", vec3Json(v.w)}, {"a", vec3Json(v.a)}, {"b", vec3Json(v.b)}}; }

// The kept slots' indices, ascending (0b1011 -> 0, 1, 3).
std::vector<int> keptSlotIndices(std::uint8_t slots) {
    std::vector<int> out;
    for (int i = 0; i < 4; ++i)
        if (slots & (1u << i)) out.push_back(i);
    return out;
}

// The figures name the simplex vertices by their slot, w0..w3 (A and B are the bodies); trace.json's
// "region" spells the same kept slots as letters A..D = w0..w3 (slotLetters: "AC" is w0w2).
std::string slotName(int slot) { return "w" + std::to_string(slot); }

// The kept slots as the figures name them: 0b1011 -> "w0w1w3" (a region of the simplex).
std::string slotNames(std::uint8_t slots) {
    std::string names;
    for (int i : keptSlotIndices(slots)) names += slotName(i);
    return names;
}

class GjkScene final : public PreparedScene {
public:
    GjkScene(SceneCommon common, PairScene pair, GjkOptions options)
        : PreparedScene(std::move(common)), pair_(std::move(pair)), options_(options) {}

    DemoOutput execute(const RunContext& ctx) const override {
        GjkTrace trace;
        const GjkResult r = gjkDistance(pair_.a, pair_.b, options_, &trace);
        const int dropping = firstDroppingStep(trace.steps);
        const ClosestSet closestSet = gjkClosestSet(pair_, r);
        DemoOutput out;
        out.trace = traceJson(r, trace, dropping, closestSet);
        if (numericOnly(ctx, out)) return out;

        // Configuration-space framing: A − B (or the simplices, without it) and the origin.
        std::vector<Vec3> cpts;
        for (const GjkTraceStep& s : trace.steps) {
            for (int i = 0; i < s.simplexCount; ++i) cpts.push_back(s.simplex[i].w);
            cpts.push_back(s.support.w);
        }
        const Drawing d = makePairDrawing(pair_, common_.hasLayer("minkowski"), std::move(cpts), out.skipped);

        const int scale = figureScale(common_, ctx);
        const std::vector<int> framed = framedSteps(int(trace.steps.size()), pair_.maxStepFrames);
        if (common_.steps || ctx.stepsOverride)  // "steps": false draws the result frame only
            for (int i : framed) out.frames.push_back(drawStep(*ctx.gl, scale, d, trace, i, r));
        else out.skipped.push_back("step frames (\"steps\": false)");
        out.frames.push_back(drawStep(*ctx.gl, scale, d, trace, -1, r));
        // Parallel closest features: the whole set of closest pairs beside GJK's one.
        if (closestSet.onA.size() >= 2)
            out.frames.push_back(Frame{"closest_set", "the closest pairs are not unique",
                                       drawClosestSet(*ctx.gl, common_, scale, pair_, d, r, closestSet)});
        // The first reduction that drops a vertex, in the simplex's plane with its Voronoi regions.
        if (dropping >= 0)
            out.frames.push_back(Frame{"regions", "the Voronoi regions of the simplex at iteration " +
                                                      std::to_string(trace.steps[std::size_t(dropping)].iteration),
                                       drawReductionRegions(*ctx.gl, common_.image.width, common_.image.height, scale,
                                                            common_.title, trace.steps[std::size_t(dropping)])});
        // The long runs (curved shapes: each support only approaches A − B's boundary) get the two
        // bounds closing on the distance, per iteration (gjk_demo_test "bounds").
        if (trace.steps.size() >= kBoundsPlotSteps) out.frames.push_back(boundsFrame(*ctx.gl, scale, trace, r));
        addAnimationAndSheet(*ctx.gl, common_, ctx, pair_.gif, "GJK", int(trace.steps.size()), framed, out);
        return out;
    }

    static constexpr std::size_t kBoundsPlotSteps = 10;

    Frame boundsFrame(GlContext& gl, int scale, const GjkTrace& trace, const GjkResult& r) const {
        BoundsPlot plot;
        for (const GjkTraceStep& s : trace.steps) {
            plot.iterations.push_back(s.iteration);
            plot.lower.push_back(s.lowerBound);
            plot.upper.push_back(s.upperBound);
        }
        plot.xLabel = "GJK iteration";
        plot.yLabel = "distance bounds";
        plot.upperName = "upper bound |v| (before the step)";
        plot.lowerName = "lower bound: max v·w / |v| so far";
        plot.title = common_.title + ": distance bounds per iteration";
        // The gap's decay, which the linear axis flattens after the first few iterations.
        const auto gapAt = [&](std::size_t i) {
            const GjkTraceStep& s = trace.steps[i];
            return formatNumber(s.upperBound - s.lowerBound) + " at " + std::to_string(s.iteration);
        };
        plot.caption = "gap upper − lower: " + gapAt(0) + ", " + gapAt(trace.steps.size() / 2) + ", " +
                       gapAt(trace.steps.size() - 1) + ";  distance " + formatNumber(r.distance) + " (" +
                       nameOf(r.termination) + ")";
        return Frame{"bounds", "distance bounds vs iteration",
                     drawBoundsPlot(gl, common_.image.width, common_.image.height, scale, plot)};
    }

private:
    PairScene pair_;
    GjkOptions options_;

    using Drawing = PairDrawing;

    /// `dropping`: firstDroppingStep of the trace; `closestSet`: gjkClosestSet of the answer.
    Json traceJson(const GjkResult& r, const GjkTrace& trace, int dropping, const ClosestSet& closestSet) const {
        Json t;
        t["dimension"] = pair_.dimension;
        t["shapes"] = {pair_.a.kindName(), pair_.b.kindName()};
        t["solver"] = nameOf(options_.solver);
        t["status"] = nameOf(r.status);
        t["termination"] = nameOf(r.termination);
        t["distance"] = r.distance;
        t["point_a"] = vec3Json(r.pointA);
        t["point_b"] = vec3Json(r.pointB);
        t["separating_axis"] = vec3Json(r.separatingAxis);
        t["iterations"] = r.iterations;
        t["lower_bound"] = r.lowerBound;
        t["upper_bound"] = r.upperBound;
        Json fs = Json::array();
        for (int i = 0; i < r.simplex.count; ++i) fs.push_back(vertexJson(r.simplex.vertex[i]));
        t["final_simplex"] = fs;
        Json steps = Json::array();
        for (const GjkTraceStep& s : trace.steps) {
            Json simplex = Json::array();
            for (int i = 0; i < s.simplexCount; ++i) simplex.push_back(vertexJson(s.simplex[i]));
            Json lambda = Json::array();
            for (int k = 0; k < s.keptCount(); ++k) lambda.push_back(s.lambda[k]);
            steps.push_back({{"iteration", s.iteration},
                             {"simplex", simplex},
                             {"direction", vec3Json(s.direction)},
                             {"support", vertexJson(s.support)},
                             {"region", slotLetters(s.keptSlots)},
                             {"lambda", lambda},
                             {"v", vec3Json(s.v)},
                             {"point_a", vec3Json(s.pointA)},
                             {"point_b", vec3Json(s.pointB)},
                             {"lower_bound", s.lowerBound},
                             {"upper_bound", s.upperBound},
                             {"gap_test", s.gapTest},
                             {"terminated", s.terminated}});
        }
        t["steps"] = steps;
        if (dropping >= 0) t["regions"] = reductionRegionsJson(trace.steps[std::size_t(dropping)]);
        if (closestSet.onA.size() >= 2) t["closest_set"] = closestSetJson(closestSet);
        return t;
    }

    Frame drawStep(GlContext& gl, int scale, const Drawing& d, const GjkTrace& trace, int index,
                   const GjkResult& r) const {
        const TwoPanelLayout layout = twoPanelLayout(common_.image.width, common_.image.height, common_.caption);
        const CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), scale);
        const GjkTraceStep* s = index >= 0 ? &trace.steps[index] : nullptr;
        const Image world = worldPanel(gl, po, layout, d, s, r);
        const Image configuration = configurationPanel(gl, po, layout, d, trace, s, r);
        Frame f;
        const std::vector<std::string> lines = captionLines(trace, s, r, f);
        f.image = composeTwoPanel(gl, layout, scale, common_.title, common_.caption, world, configuration, lines);
        return f;
    }

    // World space: the bodies, the witness points of the kept simplex, the support points.
    Image worldPanel(GlContext& gl, const CanvasOptions& po, const TwoPanelLayout& layout, const Drawing& d,
                     const GjkTraceStep* s, const GjkResult& r) const {
        const bool labels = common_.hasLayer("labels");
        // A separated pair seen across its gap where the scene's view would overlap the bodies.
        const Camera camera = panelCamera(d.planar, d.wCenter, d.wRadius, pair_.view, layout);
        Canvas world(gl, po,
                     r.status == GjkStatus::Separated ? acrossGapCamera(gl, po, camera, d, r.pointA, r.pointB) : camera);
        // Outlined as colliding when they intersect; noted as apart when the result separates them.
        drawPairBodies(world, d, 0.45f, r.status == GjkStatus::Intersecting, labels, r.status == GjkStatus::Separated);
        const Vec3 pa = s ? s->pointA : r.pointA, pb = s ? s->pointB : r.pointB;
        if (common_.hasLayer("witness")) {
            world.drawLine(pa, pb, lineStyle(Role::Result, 3.0f, false, true));
            // The result's distance is what the frame names: drawn at 12 px, or again in the inset.
            if (!s && r.status != GjkStatus::Intersecting) world.noteQuantity(kDistanceQuantity, pa, pb);
            world.drawPoint(pa, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            world.drawPoint(pb, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            if (labels) {
                TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                const bool apart = (pa - pb).norm() > 1e-3 * d.wRadius;
                if (!s && r.status == GjkStatus::Intersecting) {
                    // No closest points: the result's pointA ~ pointB is one common point.
                    drawLabelAway(world, pa, d.a.center, "common point", ts);
                } else if (Eigen::Vector2d qa, qb; !s && r.status == GjkStatus::Separated && world.project(pa, qa) &&
                                                    world.project(pb, qb) && (qa - qb).norm() < render::kMinQuantityPx) {
                    // One spot on the picture (the inset draws them apart): one label, not two
                    // that each may land on the other's body (gjk/sliver's result had p_A on B).
                    drawLabelAway(world, 0.5 * (pa + pb), d.a.center, "p_A, p_B", ts);
                } else {
                    drawLabelAway(world, pa, apart ? pb : d.a.center, "p_A", ts);
                    drawLabelAway(world, pb, apart ? pa : d.b.center, "p_B", ts);
                }
            }
        }
        if (s && common_.hasLayer("support")) {
            drawSupportPoint(world, d.a, s->support.a, 6.0f);
            drawSupportPoint(world, d.b, s->support.b, 6.0f);
            if (labels) {
                TextStyle ts{16.0f, roleColor(Role::Support).scaled(0.7f), Anchor::Center, true, true};
                drawLabelAway(world, s->support.a, d.a.center, "s_A(d)", ts);
                drawLabelAway(world, s->support.b, d.b.center, "s_B(−d)", ts);
            }
        }
        drawPanelHeading(world, "World space",
                         s                                     ? "witness points of the kept simplex"
                         : r.status == GjkStatus::Intersecting ? "intersecting: a common point, no closest points"
                                                               : "closest points");
        // The result's gap, magnified when the panel draws it under 12 px (gjk/sliver: 0.0048).
        if (s || r.status == GjkStatus::Intersecting || !common_.hasLayer("witness")) return world.readPixels();
        ZoomTarget gap{kDistanceQuantity, "gap " + formatNumber((pa - pb).norm()), pa, pb, [&](Canvas& c) {
                           drawPairBodies(c, d, 0.45f, false, false);
                           c.drawPoint(pa, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                           c.drawPoint(pb, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                           // The bodies' centres lie far outside the inset: each name points away from the other point.
                           const TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                           drawLabelAway(c, pa, pb, "p_A", ts);
                           drawLabelAway(c, pb, pa, "p_B", ts);
                       }};
        const Image image = readPixelsZoomed(gl, world, po.scale, gap,
                                             Box{14.0, 70.0, layout.panelWidth() - 14.0, layout.panelHeight() - 14.0});
        return image;
    }

    // Configuration space: A − B, the origin, the simplex, the direction, the support point, v.
    Image configurationPanel(GlContext& gl, const CanvasOptions& po, const TwoPanelLayout& layout, const Drawing& d,
                             const GjkTrace& trace, const GjkTraceStep* s, const GjkResult& r) const {
        const bool labels = common_.hasLayer("labels");
        const bool touching = r.status == GjkStatus::Intersecting;
        // A step whose simplex, O, w and v span under a third of A − B (a curved body's simplex
        // shrinks onto its boundary: sphere_box's within 25 px) is framed on them, the zoom named
        // in the heading (issue 42 §3: the camera zooms on a change too small to see).
        Vec3 viewCenter = d.cCenter;
        double viewRadius = d.cRadius;
        if (s && !(common_.camera && !d.planar)) {
            std::vector<Vec3> around{Vec3::Zero(), s->support.w, s->v};
            for (int i = 0; i < s->simplexCount; ++i) around.push_back(s->simplex[i].w);
            Vec3 c;
            double radius = 0;
            boundingSphere(around, c, radius);
            if (radius > 1e-6 * d.cRadius && radius < 0.35 * d.cRadius) viewCenter = c, viewRadius = 2 * radius;
        }
        Canvas cs(gl, po,
                  common_.camera && !d.planar ? *common_.camera
                                              : panelCamera(d.planar, viewCenter, viewRadius, pair_.view, layout));
        if (d.c.valid)
            drawBody(cs, d.c, roleColor(Role::Minkowski), d.planar ? 0.22f : 0.18f,
                     roleColor(Role::Minkowski).scaled(0.7f), 1.2f, false);
        drawOrigin(cs, 0.06 * viewRadius, d.planar);

        // The simplex: W ∪ {w} dashed, the kept sub-simplex solid and filled.
        std::vector<Vec3> w;
        std::vector<int> kept;
        std::vector<std::string> names;
        if (s) {
            // A vertex the reduction moved to another slot says so: the previous step's w2 is this
            // step's w1 once w0 is dropped (the review read the renaming as a new point).
            const GjkTraceStep* previous = s == trace.steps.data() ? nullptr : s - 1;
            for (int i = 0; i < s->simplexCount; ++i) {
                w.push_back(s->simplex[i].w);
                names.push_back(slotName(i));
                for (int j = 0; previous && j < previous->simplexCount; ++j)
                    if (j != i && previous->simplex[j].w == s->simplex[i].w) names.back() += " (was " + slotName(j) + ")";
            }
            kept = keptSlotIndices(s->keptSlots);
        } else {
            // The result's simplex is compacted: name each vertex by its slot in the last step.
            const GjkTraceStep* last = trace.steps.empty() ? nullptr : &trace.steps.back();
            for (int i = 0; i < r.simplex.count; ++i) {
                w.push_back(r.simplex.vertex[i].w);
                kept.push_back(i);
                int slot = i;
                for (int j = 0; last && j < last->simplexCount; ++j)
                    if (last->simplex[j].w == r.simplex.vertex[i].w) slot = j;
                names.push_back(slotName(slot));
            }
        }
        if (common_.hasLayer("simplex")) drawSimplex(cs, d, s, w, names, kept, labels);
        const double arrowLen = 0.35 * viewRadius;
        const int index = s ? int(s - trace.steps.data()) : -1;
        for (const GjkDrawnVector& dv : s ? gjkStepVectors(trace.steps, index) : std::vector<GjkDrawnVector>{}) {
            if (!dv.arrow || !common_.hasLayer("direction") || !(dv.vector.norm() > 0)) continue;
            const Vec3 tip = dv.vector.normalized() * arrowLen;
            cs.drawArrow(Vec3::Zero(), tip, lineStyle(Role::Direction, 3.0f, false, true));
            if (labels) {
                TextStyle ts{18.0f, roleColor(Role::Direction).scaled(0.8f), Anchor::Center, true, true};
                drawLabelAway(cs, tip, Vec3::Zero(), dv.label, ts, 8.0);
            }
        }
        if (s && common_.hasLayer("support")) {
            cs.drawPoint(s->support.w, 10.0f, roleColor(Role::Support), true, 2.0f, roleColor(Role::Ink));
            // A loop that stops before adding w (converged) leaves it out of the simplex: named here,
            // as the simplex names it otherwise ("w2 = w"; the review: box_box step 3's unnamed dot).
            const bool inSimplex = std::any_of(s->simplex, s->simplex + s->simplexCount,
                                               [&](const GjkVertex& v) { return v.w == s->support.w; });
            if (labels && !inSimplex)
                drawLabelAway(cs, s->support.w, d.cCenter, "w", TextStyle{20.0f, roleColor(Role::Ink), Anchor::Center, true, true},
                              12.0);
        }
        // v: the closest point of the kept simplex (after this iteration's reduction).
        const Vec3 v = s ? s->v : Vec3(r.pointA - r.pointB);
        if (common_.hasLayer("witness") && v.norm() > 1e-12 * d.cRadius) {
            cs.drawLine(Vec3::Zero(), v, lineStyle(Role::Result, 2.5f, false, true));
            cs.drawPoint(v, 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            if (labels) {
                TextStyle ts{18.0f, roleColor(Role::Result).scaled(0.7f), Anchor::Center, true, true};
                drawLabelAway(cs, v, d.cCenter, s ? gjkStepVectors(trace.steps, index).back().label : "v", ts, 10.0);
            }
        }
        std::string sub;
        if (s) {
            sub = "kept: region " + slotNames(s->keptSlots) + " (" +
                  regionKind(std::size_t(s->keptCount()), pair_.dimension) + ")";
            // Converged / duplicate support: the loop stopped before reducing W ∪ {w}.
            if (s->terminated && trace.termination != GjkTermination::OriginInSimplex)
                sub = std::string("loop ends here (") + nameOf(trace.termination) + "): simplex not reduced";
        } else {
            sub = touching ? "origin inside the simplex: intersecting" : "final simplex";
        }
        char zoom[32] = "";
        if (viewRadius < d.cRadius) std::snprintf(zoom, sizeof zoom, ", zoom ×%.2g", d.cRadius / viewRadius);
        drawPanelHeading(
            cs, std::string("Configuration space A − B") + (d.c.valid && !d.exact ? " (sampled hull)" : "") + zoom,
            sub);

        return cs.readPixels();
    }

    // The simplex: W ∪ {w} dashed, the kept sub-simplex solid and filled, the vertices named.
    void drawSimplex(Canvas& cs, const Drawing& d, const GjkTraceStep* s, const std::vector<Vec3>& w,
                     const std::vector<std::string>& names, const std::vector<int>& kept, bool labels) const {
        for (std::size_t i = 0; i < w.size(); ++i)
            for (std::size_t j = i + 1; j < w.size(); ++j)
                cs.drawLine(w[i], w[j], lineStyle(Role::Muted, 2.0f, true, true));
        std::vector<Vec3> kv;
        for (int k : kept) kv.push_back(w[k]);
        if (kv.size() == 3) cs.drawPolygon(kv, roleColor(Role::Simplex).withAlpha(0.35f));
        if (kv.size() == 4)
            cs.drawMesh(kv, kTetrahedronFaces, roleColor(Role::Simplex).withAlpha(0.3f), true);
        // A kept tetrahedron's edges behind it dashed and faded, so whether O is inside reads (the
        // review: gjk/deep_penetration's final tetrahedron all solid).
        const LineStyle edge = lineStyle(Role::Simplex, 4.0f, false, true);
        if (kv.size() == 4) drawConvexMeshEdges(cs, kv, kTetrahedronFaces, edge);
        else
            for (std::size_t i = 0; i < kv.size(); ++i)
                for (std::size_t j = i + 1; j < kv.size(); ++j) cs.drawLine(kv[i], kv[j], edge);
        for (std::size_t i = 0; i < w.size(); ++i) {
            const bool isKept = std::find(kept.begin(), kept.end(), int(i)) != kept.end();
            cs.drawPoint(w[i], isKept ? 8.0f : 6.0f, isKept ? roleColor(Role::Simplex) : roleColor(Role::Muted), true,
                         1.5f, roleColor(Role::Ink));
            if (labels) {
                TextStyle ts{20.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                const bool isNew = s && int(i) + 1 == s->simplexCount && s->simplex[i].w == s->support.w;
                drawLabelAway(cs, w[i], d.cCenter, names[i] + (isNew ? " = w" : ""), ts, 12.0);
            }
        }
    }

    // The text under the panels, and the frame's name and caption.
    std::vector<std::string> captionLines(const GjkTrace& trace, const GjkTraceStep* s, const GjkResult& r,
                                          Frame& f) const {
        const bool touching = r.status == GjkStatus::Intersecting;
        std::vector<std::string> lines;
        if (s) {
            const double vv = s->upperBound * s->upperBound;
            std::string stop = s->terminated ? std::string("stop: ") + nameOf(trace.termination) : "continue";
            lines.push_back("Iteration " + std::to_string(s->iteration) +
                            ": w = s_A(d) − s_B(−d) = " + formatPoint(s->support.w) + ", simplex {" +
                            slotNames(std::uint8_t((1u << s->simplexCount) - 1)) + "} → region " +
                            slotNames(s->keptSlots) + ", |v" + subscriptNumber(s->iteration) +
                            "| = " + formatNumber(s->v.norm()));
            const std::string previousV =
                s == trace.steps.data() ? std::string("|w0|") : "|v" + subscriptNumber(s[-1].iteration) + "|";
            lines.push_back("bounds " + formatNumber(s->lowerBound) + " ≤ distance ≤ " + previousV + " = " +
                            formatNumber(s->upperBound) +
                            ";  test |v|² − v·w = " + formatNumber(s->gapTest) +
                            (s->gapTest <= options_.relativeTolerance * vv ? " ≤ " : " > ") +
                            "ε|v|² = " + formatNumber(options_.relativeTolerance * vv) + ":  " + stop);
            f.name = stepFrameName(s->iteration);
            f.caption = "it " + std::to_string(s->iteration) + ": region " + slotNames(s->keptSlots) + ", |v| " +
                        formatNumber(s->v.norm()) + (s->terminated ? " (stop)" : "");
        } else {
            lines.push_back(std::string("Result: ") + nameOf(r.status) + " after " + std::to_string(r.iterations) +
                            " iterations (" + nameOf(r.termination) + "), distance " + formatNumber(r.distance));
            lines.push_back(
                touching ? "the terminal simplex contains the origin: feed it to EPA for the penetration depth"
                         : "p_A = " + formatPoint(r.pointA) + ",  p_B = " + formatPoint(r.pointB) + ",  bounds " +
                               formatNumber(r.lowerBound) + " ≤ d ≤ " + formatNumber(r.upperBound));
            f.name = "result";
            f.caption = std::string("result: ") + nameOf(r.status) + ", distance " + formatNumber(r.distance);
        }
        return lines;
    }
};

class GjkDemo final : public Demo {
public:
    std::string name() const override { return "gjk"; }
    std::string description() const override {
        return "GJK step by step: world space and configuration space (A − B, simplex, direction, support point), 3D "
               "and 2D";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1280, 640}, {320, 240}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        PairScene pair = readPairScene(r);
        GjkOptions options;
        if (auto m = r.find("method")) {
            ObjectReader mr(*m);
            if (auto s = mr.find("solver"))
                options.solver = s->asEnum({"signed_volumes", "johnson"}) == "johnson" ? SimplexSolver::Johnson
                                                                                       : SimplexSolver::SignedVolumes;
            if (auto t = mr.find("tolerance")) options.relativeTolerance = t->asPositive();
            if (auto n = mr.find("max_iterations")) options.maxIterations = n->asInt(1, 1000);
            mr.finish();
        }
        r.finish();
        // The result; with steps at most max_step_frames steps and the contact sheet.
        common.frames = {1, pair.maxStepFrames + 4, 0};
        return std::make_unique<GjkScene>(std::move(common), std::move(pair), options);
    }
};

}  // namespace

std::string subscriptNumber(int n) {
    static const char* kDigit[10] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
    std::string out;
    for (char c : std::to_string(n)) out += c == '-' ? "₋" : kDigit[c - '0'];
    return out;
}

std::vector<GjkDrawnVector> gjkStepVectors(const std::vector<GjkTraceStep>& steps, int index) {
    if (index < 0 || index >= int(steps.size())) return {};
    const GjkTraceStep& s = steps[std::size_t(index)];
    std::vector<GjkDrawnVector> out;
    out.push_back({index == 0 ? std::string("d (start)")
                              : "d = −v" + subscriptNumber(steps[std::size_t(index) - 1].iteration),
                   s.direction, true});
    out.push_back({"v" + subscriptNumber(s.iteration), s.v, false});
    return out;
}

const Demo& gjkDemo() {
    static const GjkDemo demo;
    return demo;
}

}  // namespace cdlab::demos
