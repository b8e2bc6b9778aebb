// EPA step-through. Numbers come from core (gjkDistance + epaPenetration with their traces) or, for
// planar scenes, from epaPenetration2d (core/gjk_epa/epa_2d.h: core's 3D EPA reports flat input as
// touching). This file converts both traces into one drawable form and draws them.
//
// Scene keys (besides the common ones and the pair keys of scene/pair_scene.h):
//   "method": {"tolerance": eps_rel (EPA), "max_iterations": n (EPA), "gjk_tolerance": eps_rel}
// Layers: "minkowski", "polytope", "closest", "support", "horizon", "witness", "labels", "plot".
// Frames: "gjk" (GJK's final simplex), "blow_up" (3D: a point, segment or triangle from GJK grown
// toward a tetrahedron), step_NN (per EPA iteration, at most max_step_frames), "witness" (3D: the
// barycentric witness step), "result" (penetration vector), "bounds" (plot), with "steps" a
// contact sheet; animation.gif. Test: tests/demos/epa/epa_demo_test.cpp.
#include "demos/epa/epa_demo.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/contact_sheet.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/draw/plot.h"
#include "demos/draw/step_frames.h"
#include "demos/draw/zoom_inset.h"
#include "core/gjk_epa/epa_2d.h"
#include "app/scene/pair_scene.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

// The closest face / edge and its closest point: yellow, distinct from the support colour (vermillion)
// that marks w and the faces it removes.
Color closestColor() { return categorical(3); }

// The quantity a step's frame names last: how far w lies beyond the closest face's plane.
const std::string kTestQuantity = "n·w − d";

const std::vector<std::string> kLayers = {"minkowski", "polytope", "closest", "support",
                                          "horizon",   "witness",  "labels",  "plot"};

/// One EPA iteration in a dimension-free form: faces are vertex-id lists (3 in 3D, 2 in 2D).
struct PolyStep {
    int iteration = 0;
    std::vector<Vec3> vertices;
    std::vector<std::vector<int>> faces;
    int closestFace = -1;
    Vec3 normal = Vec3::Zero(), closestPoint = Vec3::Zero();
    double distance = 0.0;
    Vec3 support = Vec3::Zero(), supportA = Vec3::Zero(), supportB = Vec3::Zero();
    std::vector<int> removed;                      // indices into faces
    std::vector<std::array<int, 2>> horizonEdges;  // 3D: vertex-id edges
    std::vector<int> horizonVertices;              // 2D: the two kept ends
    double lower = 0.0, upper = 0.0;
    bool terminated = false;
};

struct EpaRun {
    GjkResult gjk;
    EpaStatus status = EpaStatus::InvalidInput;
    EpaTermination termination = EpaTermination::InvalidInput;
    double depth = 0.0, lower = 0.0, upper = 0.0;
    Vec3 normal = Vec3::UnitX(), pointA = Vec3::Zero(), pointB = Vec3::Zero();
    int iterations = 0;
    std::string start;
    std::vector<PolyStep> steps;
    std::vector<Vec3> blowUpDirections, blowUpPoints;  // 3D: EpaTrace's
    EpaWitnessStep witness;                            // 3D: EpaTrace's
};

// Frame indices of drawFrame besides the steps (0, 1, ...).
constexpr int kResultFrame = -1, kGjkFrame = -2, kBlowUpFrame = -3, kWitnessFrame = -4;

/// "a₀ = a₂"-style names of the three points, coincident ones named together, each group once:
/// (point, name) pairs.
std::vector<std::pair<Vec3, std::string>> groupedNames(const std::array<Vec3, 3>& p, const std::string& letter) {
    static const char* kSub[3] = {"₀", "₁", "₂"};
    std::vector<std::pair<Vec3, std::string>> out;
    for (int i = 0; i < 3; ++i) {
        bool seen = false;
        for (int j = 0; j < i; ++j) seen |= p[j] == p[i];
        if (seen) continue;
        std::string name;
        for (int j = i; j < 3; ++j)
            if (p[j] == p[i]) name += (name.empty() ? "" : " = ") + letter + kSub[j];
        out.emplace_back(p[i], name);
    }
    return out;
}

std::string weightList(const std::array<double, 3>& l) {
    return "(" + formatNumber(l[0]) + ", " + formatNumber(l[1]) + ", " + formatNumber(l[2]) + ")";
}

std::vector<std::vector<int>> faceList(const std::vector<std::array<int, 3>>& f) {
    std::vector<std::vector<int>> out;
    for (const auto& t : f) out.push_back({t[0], t[1], t[2]});
    return out;
}

class EpaScene final : public PreparedScene {
public:
    EpaScene(SceneCommon common, PairScene pair, EpaOptions options)
        : PreparedScene(std::move(common)), pair_(std::move(pair)), options_(options) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const EpaRun run = compute();
        DemoOutput out;
        out.trace = traceJson(run);
        if (numericOnly(ctx, out)) return out;

        std::vector<Vec3> cpts;
        for (const PolyStep& s : run.steps) {
            cpts.insert(cpts.end(), s.vertices.begin(), s.vertices.end());
            cpts.push_back(s.support);
        }
        for (int i = 0; i < run.gjk.simplex.count; ++i) cpts.push_back(run.gjk.simplex.vertex[i].w);
        const Drawing d = makePairDrawing(pair_, common_.hasLayer("minkowski"), std::move(cpts), out.skipped);

        const int ss = figureScale(common_, ctx);
        out.frames.push_back(drawFrame(*ctx.gl, ss, d, run, kGjkFrame));
        if (!run.blowUpDirections.empty()) out.frames.push_back(drawFrame(*ctx.gl, ss, d, run, kBlowUpFrame));
        const std::vector<int> framed = framedSteps(int(run.steps.size()), pair_.maxStepFrames);
        if (common_.steps || ctx.stepsOverride)  // "steps": false: GJK's simplex, the result, the bounds
            for (int i : framed) out.frames.push_back(drawFrame(*ctx.gl, ss, d, run, i));
        else out.skipped.push_back("step frames (\"steps\": false)");
        if (run.witness.recorded && common_.hasLayer("witness"))
            out.frames.push_back(drawFrame(*ctx.gl, ss, d, run, kWitnessFrame));
        out.frames.push_back(drawFrame(*ctx.gl, ss, d, run, kResultFrame));
        if (common_.hasLayer("plot") && !run.steps.empty()) out.frames.push_back(drawPlot(*ctx.gl, ss, run));
        addAnimationAndSheet(*ctx.gl, common_, ctx, pair_.gif, "EPA", int(run.steps.size()), framed, out);
        return out;
    }

private:
    PairScene pair_;
    EpaOptions options_;

    using Drawing = PairDrawing;

    EpaRun compute() const {
        EpaRun run;
        run.gjk = gjkDistance(pair_.a, pair_.b, options_.gjk);
        if (run.gjk.status == GjkStatus::InvalidInput) return run;
        if (!run.gjk.intersect()) {
            run.status = EpaStatus::Separated;
            run.termination = EpaTermination::NotIntersecting;
            run.normal = run.gjk.separatingAxis;
            run.pointA = run.gjk.pointA;
            run.pointB = run.gjk.pointB;
            return run;
        }
        // The 3D and the 2D EPA record the same fields of a step...
        const auto commonStep = [](const auto& s) {
            PolyStep p;
            p.iteration = s.iteration;
            p.vertices = s.vertices;
            p.normal = s.closestNormal;
            p.closestPoint = s.closestPoint;
            p.distance = s.closestDistance;
            p.support = s.support;
            p.supportA = s.supportA;
            p.supportB = s.supportB;
            p.lower = s.lowerBound;
            p.upper = s.upperBound;
            p.terminated = s.terminated;
            return p;
        };
        // ...and of the outcome.
        const auto copyOutcome = [](EpaRun& out, const auto& r, const std::string& start) {
            out.status = r.status;
            out.termination = r.termination;
            out.depth = r.depth;
            out.lower = r.lowerBound;
            out.upper = r.upperBound;
            out.normal = r.normal;
            out.pointA = r.pointA;
            out.pointB = r.pointB;
            out.iterations = r.iterations;
            out.start = start;
        };
        if (pair_.dimension == 3) {
            EpaTrace t;
            const EpaResult r = epaPenetration(pair_.a, pair_.b, run.gjk.simplex, options_, &t);
            copyOutcome(run, r, t.start);
            run.blowUpDirections = t.blowUpDirections;
            run.blowUpPoints = t.blowUpPoints;
            run.witness = t.witness;
            for (const EpaTraceStep& s : t.steps) {
                PolyStep p = commonStep(s);
                p.faces = faceList(s.faces);
                p.closestFace = s.closestFace;
                // Removed faces come as vertex triples: find them among the live faces.
                for (const auto& rf : s.removedFaces)
                    for (std::size_t k = 0; k < s.faces.size(); ++k)
                        if (s.faces[k] == rf) p.removed.push_back(int(k));
                p.horizonEdges = s.horizon;
                run.steps.push_back(std::move(p));
            }
        } else {
            Epa2dTrace t;
            const Epa2dResult r = epaPenetration2d(pair_.a, pair_.b, run.gjk.simplex, options_, &t);
            copyOutcome(run, r, t.start);
            for (const Epa2dStep& s : t.steps) {
                PolyStep p = commonStep(s);
                const int n = int(s.vertices.size());
                for (int i = 0; i < n; ++i) p.faces.push_back({i, (i + 1) % n});
                p.closestFace = s.closestEdge;
                p.removed = s.removedEdges;
                if (s.horizon[0] >= 0) p.horizonVertices = {s.horizon[0], s.horizon[1]};
                run.steps.push_back(std::move(p));
            }
        }
        return run;
    }

    Json traceJson(const EpaRun& run) const {
        Json t;
        t["dimension"] = pair_.dimension;
        t["shapes"] = {pair_.a.kindName(), pair_.b.kindName()};
        t["method"] = pair_.dimension == 3 ? "core epaPenetration (3D)" : "epaPenetration2d (expanding polygon)";
        Json gs = Json::array();
        for (int i = 0; i < run.gjk.simplex.count; ++i) gs.push_back(vec3Json(run.gjk.simplex.vertex[i].w));
        t["gjk"] = {{"status", nameOf(run.gjk.status)},
                    {"termination", nameOf(run.gjk.termination)},
                    {"iterations", run.gjk.iterations},
                    {"distance", run.gjk.distance},
                    {"simplex", gs}};
        t["status"] = nameOf(run.status);
        t["termination"] = nameOf(run.termination);
        t["start"] = run.start;
        t["depth"] = run.depth;
        t["normal"] = vec3Json(run.normal);
        t["point_a"] = vec3Json(run.pointA);
        t["point_b"] = vec3Json(run.pointB);
        t["iterations"] = run.iterations;
        t["lower_bound"] = run.lower;
        t["upper_bound"] = run.upper;
        Json steps = Json::array();
        for (const PolyStep& s : run.steps) {
            Json verts = Json::array();
            for (const Vec3& v : s.vertices) verts.push_back(vec3Json(v));
            Json horizon = Json::array();
            for (const auto& e : s.horizonEdges) horizon.push_back({e[0], e[1]});
            for (int v : s.horizonVertices) horizon.push_back(v);
            steps.push_back({{"iteration", s.iteration},
                             {"vertices", verts},
                             {"faces", s.faces},
                             {"closest_face", s.closestFace},
                             {"closest_normal", vec3Json(s.normal)},
                             {"closest_distance", s.distance},
                             {"closest_point", vec3Json(s.closestPoint)},
                             {"support", vec3Json(s.support)},
                             {"support_a", vec3Json(s.supportA)},
                             {"support_b", vec3Json(s.supportB)},
                             {"removed_faces", s.removed},
                             {"horizon", horizon},
                             {"lower_bound", s.lower},
                             {"upper_bound", s.upper},
                             {"terminated", s.terminated}});
        }
        t["steps"] = steps;
        if (!run.blowUpDirections.empty()) {
            Json blow = Json::array();
            for (std::size_t k = 0; k < run.blowUpDirections.size(); ++k)
                blow.push_back({{"direction", vec3Json(run.blowUpDirections[k])},
                                {"support", vec3Json(run.blowUpPoints[k])},
                                {"support_value", run.blowUpDirections[k].dot(run.blowUpPoints[k])}});
            t["blow_up"] = blow;
        }
        if (run.witness.recorded) {
            const auto face = [](const EpaWitnessFace& f) {
                Json w = Json::array(), a = Json::array(), b = Json::array();
                for (int k = 0; k < 3; ++k) w.push_back(vec3Json(f.w[k])), a.push_back(vec3Json(f.a[k])), b.push_back(vec3Json(f.b[k]));
                return Json{{"w", w}, {"a", a}, {"b", b}, {"weights", f.weights}};
            };
            t["witness"] = {{"projection", vec3Json(run.witness.projection)},
                            {"nearest_face", face(run.witness.nearest)},
                            {"covered", run.witness.covered},
                            {"used_face", face(run.witness.used)},
                            {"point_a", vec3Json(run.witness.pointA)},
                            {"point_b", vec3Json(run.witness.pointB)}};
        }
        return t;
    }

    // Polytope of a step: faces shaded, removed ones in the support colour, the closest highlighted.
    // `inset`: drawn in a zoomed inset, where only w is named (the closest point and n are named
    // on the picture it magnifies).
    void drawPolytope(Canvas& cs, const Drawing& d, const PolyStep& s, bool showStep, bool inset = false) const {
        const bool labels = common_.hasLayer("labels");
        std::vector<bool> removed(s.faces.size(), false);
        if (showStep)
            for (int k : s.removed) removed[k] = true;
        if (d.planar) {
            cs.drawPolygon(s.vertices, roleColor(Role::Simplex).withAlpha(0.30f));
            for (std::size_t k = 0; k < s.faces.size(); ++k) {
                const Vec3 &p = s.vertices[s.faces[k][0]], &q = s.vertices[s.faces[k][1]];
                if (showStep && int(k) == s.closestFace && common_.hasLayer("closest")) {
                    LineStyle ls = lineStyle(Role::Ink, 7.0f, false, true);
                    ls.color = closestColor().scaled(0.85f);
                    cs.drawLine(p, q, ls);
                } else if (removed[k] && common_.hasLayer("horizon"))
                    cs.drawLine(p, q, lineStyle(Role::Support, 4.0f, true, true));
                else cs.drawLine(p, q, lineStyle(Role::Simplex, 3.0f, false, true));
                if (removed[k] && int(k) == s.closestFace && common_.hasLayer("horizon"))
                    cs.drawLine(p, q, lineStyle(Role::Support, 2.0f, true, true));
            }
            if (showStep && common_.hasLayer("horizon"))
                for (int v : s.horizonVertices) {
                    cs.drawLine(s.vertices[v], s.support, lineStyle(Role::Direction, 2.5f, true, true));
                    cs.drawPoint(s.vertices[v], 9.0f, roleColor(Role::Direction), true, 2.0f, roleColor(Role::Ink));
                }
        } else {
            std::vector<Eigen::Vector3i> live, gone, closest;
            // The closest face and the removed ones are filled only where they face the eye; on the
            // polytope's far side they are outlined dashed (hidden geometry is never filled: the view
            // rules HiddenFilled and FeatureFromBehind, render/legibility.h).
            const Camera& cam = cs.camera();
            const auto outward = [&](const auto& f) {  // a face's normal away from the origin it holds
                const Vec3 &a = s.vertices[f[0]], &b = s.vertices[f[1]], &c = s.vertices[f[2]];
                const Vec3 n = (b - a).cross(c - a);
                return n.dot(a + b + c) < 0 ? Vec3(-n) : n;
            };
            for (std::size_t k = 0; k < s.faces.size(); ++k) {
                Eigen::Vector3i t(s.faces[k][0], s.faces[k][1], s.faces[k][2]);
                const bool isClosest = showStep && int(k) == s.closestFace && common_.hasLayer("closest");
                const bool isGone = !isClosest && removed[k] && common_.hasLayer("horizon");
                if (!isClosest && !isGone) {
                    live.push_back(t);
                    continue;
                }
                const std::vector<Vec3> pts{s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]};
                const Vec3 centre = (pts[0] + pts[1] + pts[2]) / 3.0, n = outward(s.faces[k]);
                const bool hidden = !facesCamera(cam, centre, n);
                cs.noteFeature({isClosest ? "closest face" : "removed face", pts, {n}, !hidden, isClosest,
                                isClosest ? closestColor() : roleColor(Role::Support)});
                if (hidden) {
                    LineStyle ls = lineStyle(isClosest ? Role::Ink : Role::Support, 3.0f, true, true);
                    if (isClosest) ls.color = closestColor().scaled(0.7f);
                    cs.drawPolyline(pts, true, ls);
                    live.push_back(t);  // shaded as the rest of the polytope, seen through it
                } else (isClosest ? closest : gone).push_back(t);
            }
            // What the step changed is saturated, the rest faded (issue 42 §3): the closest and the
            // removed faces opaque and unlit, in their legend colours (StepFeatureFaded: blended over
            // the polytope at 0.8 alpha the closest face read olive), the polytope light behind them.
            cs.drawMesh(s.vertices, live, roleColor(Role::Simplex).withAlpha(showStep ? 0.2f : 0.3f), true);
            if (!gone.empty()) cs.drawMesh(s.vertices, gone, roleColor(Role::Support), false);
            if (!closest.empty()) cs.drawMesh(s.vertices, closest, closestColor(), false);
            LineStyle edge = lineStyle(Role::Simplex, 1.5f);
            edge.color = roleColor(Role::Simplex).scaled(showStep ? 0.75f : 0.6f);
            // Each edge once, dashed and faded where both its faces look away from the camera
            // (the review: a 26-face polytope with every edge solid does not read as a solid).
            std::vector<Eigen::Vector3i> all;
            for (const auto& f : s.faces) all.emplace_back(f[0], f[1], f[2]);
            drawConvexMeshEdges(cs, s.vertices, all, edge);
            // A horizon edge on the polytope's far side (both its faces turned away) dashed and
            // faded, as hidden edges are: drawn solid it crossed the closest face (the review).
            if (showStep && common_.hasLayer("horizon"))
                for (const auto& e : s.horizonEdges) {
                    std::vector<Vec3> normals;
                    for (const auto& f : s.faces)
                        if (std::count(f.begin(), f.end(), e[0]) && std::count(f.begin(), f.end(), e[1]))
                            normals.push_back(outward(f));
                    const Vec3 p = s.vertices[e[0]], q = s.vertices[e[1]];
                    const LineStyle solid = lineStyle(Role::Direction, 5.0f, false, true);
                    cs.drawLine(p, q, normals.size() == 2 ? edgeStyleSeen(cam, 0.5 * (p + q), normals[0], normals[1], solid)
                                                          : solid);
                }
        }
        if (showStep && common_.hasLayer("closest")) {
            cs.drawLine(Vec3::Zero(), s.closestPoint, lineStyle(Role::Ink, 2.0f, true, true));
            cs.drawPoint(s.closestPoint, 7.0f, closestColor(), true, 1.5f, roleColor(Role::Ink));
            if (labels && !inset)
                drawLabelAway(cs, s.closestPoint, Vec3::Zero(), "closest",
                              TextStyle{16.0f, roleColor(Role::Ink), Anchor::Center, true, true}, 10.0);
        }
        if (showStep && common_.hasLayer("support")) {
            const double h = s.normal.dot(s.support);
            if (const auto gap = testGap(d, s)) cs.noteQuantity(kTestQuantity, gap->from, gap->to);
            const Vec3 tip = s.closestPoint + s.normal * std::max(h - s.distance, 0.25 * d.cRadius);
            // The search normal in ink and named: the horizon has the direction colour (the review:
            // an unlabelled arrow in the horizon's pink).
            cs.drawArrow(s.closestPoint, tip, lineStyle(Role::Ink, 3.0f, false, true));
            cs.drawPoint(s.support, 10.0f, roleColor(Role::Support), true, 2.0f, roleColor(Role::Ink));
            if (labels) {
                if (!inset) drawLabelAway(cs, tip, s.closestPoint, "n", labelStyle(Role::Ink, 18.0f), 8.0);
                drawLabelAway(cs, s.support, d.cCenter, "w", labelStyle(Role::Ink, 20.0f), 10.0);
            }
        }
    }

    Frame drawFrame(GlContext& gl, int ss, const Drawing& d, const EpaRun& run, int index) const {
        const TwoPanelLayout layout = twoPanelLayout(common_.image.width, common_.image.height, common_.caption);
        const CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), ss);
        const bool isGjk = index == kGjkFrame, isResult = index == kResultFrame;
        const PolyStep* s = index >= 0 ? &run.steps[index] : nullptr;
        Canvas world(gl, po, panelCamera(d.planar, d.wCenter, d.wRadius, pair_.view, layout));
        if (index == kWitnessFrame) drawWitnessWorld(world, d, run);
        else drawWorldPanel(world, d, run, s, isResult);
        // A step's closest face seen from its front, its normal within 49° of the configuration
        // space's view (turned to it where needed; at 60° the labels at its closest point crowd).
        const Vec3 csView = s && !d.planar && common_.hasLayer("closest") ? viewTowards(pair_.view, s->normal, 0.65) : pair_.view;
        Canvas cs(gl, po,
                  common_.camera && !d.planar ? *common_.camera
                                              : panelCamera(d.planar, d.cCenter, d.cRadius, csView, layout));
        Frame f;
        std::vector<std::string> lines;
        if (index == kBlowUpFrame) lines = drawBlowUp(cs, d, run, f);
        else if (index == kWitnessFrame) lines = drawWitnessConfiguration(cs, d, run, f);
        else {
            drawConfigurationPanel(cs, d, run, s, isGjk);
            lines = describeFrame(d, run, s, isGjk, f);
        }
        f.image = composeTwoPanel(gl, layout, ss, common_.title, common_.caption, world.readPixels(),
                                  configurationPixels(gl, cs, po.scale, layout, d, s), lines);
        return f;
    }

    // The step's test n·w − d as the segment from the closest face's plane to w (a converged step
    // draws it a pixel or two long: the frame notes it, QuantityTooSmall, and zooms on it; issue 42
    // §3); none under 1e-4 of A − B, where w is on the face: no picture shows it, the text prints it.
    struct TestGap {
        double length;
        Vec3 from, to;
    };
    static std::optional<TestGap> testGap(const Drawing& d, const PolyStep& s) {
        const double gap = s.normal.dot(s.support) - s.distance;
        if (!(gap > 1e-4 * d.cRadius)) return std::nullopt;
        return TestGap{gap, s.support - gap * s.normal, s.support};
    }

    // The configuration space's picture, with the step's test n·w − d magnified where it is drawn
    // under 12 px (zoom_inset.h): the closest face, w and the gap between them.
    Image configurationPixels(GlContext& gl, Canvas& cs, int scale, const TwoPanelLayout& layout, const Drawing& d,
                              const PolyStep* s) const {
        const auto gap = s && common_.hasLayer("support") ? testGap(d, *s) : std::nullopt;
        if (!gap) return cs.readPixels();
        const ZoomTarget test{kTestQuantity, "gap " + formatNumber(gap->length), gap->from, gap->to,
                              [&](Canvas& c) { drawPolytope(c, d, *s, true, true); }};
        return readPixelsZoomed(gl, cs, scale, test,
                                Box{14.0, 70.0, layout.panelWidth() - 14.0, layout.panelHeight() - 40.0});
    }

    // World space: the bodies, this step's support points or the result's witness points.
    void drawWorldPanel(Canvas& world, const Drawing& d, const EpaRun& run, const PolyStep* s, bool isResult) const {
        const bool labels = common_.hasLayer("labels");
        const bool penetrating = run.status == EpaStatus::Penetrating || run.status == EpaStatus::Touching;
        // Outlined as colliding when they intersect; noted as apart when GJK found them separated.
        drawPairBodies(world, d, 0.4f, penetrating, labels, run.status == EpaStatus::Separated);
        if (s && common_.hasLayer("support")) {
            drawSupportPoint(world, d.a, s->supportA, 7.0f);
            drawSupportPoint(world, d.b, s->supportB, 7.0f);
            if (labels) {
                TextStyle ts{16.0f, roleColor(Role::Support).scaled(0.7f), Anchor::Center, true, true};
                drawLabelAway(world, s->supportA, d.a.center, "s_A(n)", ts);
                drawLabelAway(world, s->supportB, d.b.center, "s_B(−n)", ts);
            }
        }
        if (isResult && common_.hasLayer("witness")) {
            world.drawPoint(run.pointA, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            world.drawPoint(run.pointB, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            if (penetrating && run.depth > 0) {
                world.drawArrow(run.pointB, run.pointA, lineStyle(Role::Result, 3.5f, false, true));
                world.noteQuantity("depth", run.pointB, run.pointA);
            }
            else if (penetrating)
                world.drawArrow(run.pointA, run.pointA + run.normal * 0.3 * d.wRadius,
                                lineStyle(Role::Direction, 3.0f, false, true));
            if (labels) {
                TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                const bool apart = (run.pointA - run.pointB).norm() > 1e-3 * d.wRadius;
                drawLabelAway(world, run.pointA, apart ? run.pointB : d.a.center, "p_A", ts);
                drawLabelAway(world, run.pointB, apart ? run.pointA : d.b.center, "p_B", ts);
            }
        }
        drawPanelHeading(world, "World space",
                         isResult ? (run.status == EpaStatus::Separated ? "separated: closest points"
                                                                        : "witness points, p_A − p_B = depth · n")
                         : s      ? "support points of the new vertex"
                                  : "");
    }

    // Configuration space: A − B with GJK's simplex, this step's polytope or the penetration vector.
    void drawConfigurationPanel(Canvas& cs, const Drawing& d, const EpaRun& run, const PolyStep* s, bool isGjk) const {
        const bool labels = common_.hasLayer("labels");
        const bool penetrating = run.status == EpaStatus::Penetrating || run.status == EpaStatus::Touching;
        if (d.c.valid)
            drawBody(cs, d.c, roleColor(Role::Minkowski), d.planar ? 0.18f : 0.12f,
                     roleColor(Role::Minkowski).scaled(0.75f), 1.0f, false);
        drawOrigin(cs, 0.06 * d.cRadius, d.planar);
        std::string sub;
        if (isGjk) {
            std::vector<Vec3> w;
            for (int i = 0; i < run.gjk.simplex.count; ++i) w.push_back(run.gjk.simplex.vertex[i].w);
            if (w.size() == 3) cs.drawPolygon(w, roleColor(Role::Simplex).withAlpha(0.35f));
            if (w.size() == 4)
                cs.drawMesh(w, kTetrahedronFaces, roleColor(Role::Simplex).withAlpha(0.3f), true);
            for (std::size_t i = 0; i < w.size(); ++i) {
                for (std::size_t j = i + 1; j < w.size(); ++j)
                    cs.drawLine(w[i], w[j], lineStyle(Role::Simplex, 4.0f, false, true));
                cs.drawPoint(w[i], 8.0f, roleColor(Role::Simplex), true, 1.5f, roleColor(Role::Ink));
                if (labels)
                    drawLabelAway(cs, w[i], d.cCenter, "w" + std::to_string(i), labelStyle(Role::Ink, 20.0f), 12.0);
            }
            sub = "GJK's terminal simplex (" + std::to_string(w.size()) + " vertices): " + nameOf(run.gjk.status);
        } else if (s) {
            drawPolytope(cs, d, *s, true);
            sub = "closest " + std::string(d.planar ? "edge" : "face") + " at distance " + formatNumber(s->distance) +
                  "; " + std::to_string(s->removed.size()) + (d.planar ? " edge(s)" : " face(s)") + " visible from w";
            if (common_.hasLayer("labels"))
                drawKey(cs, 14, cs.height() - 28,  // at the bottom: the polytope fills the top
                        {{closestColor(), std::string("closest ") + (d.planar ? "edge" : "face")},
                         {roleColor(Role::Support), "visible from w (removed)"},
                         {roleColor(Role::Direction),
                          d.planar ? "horizon (dashed: its new edges to w)" : "horizon"}});  // the 2D drawing dashes them
            if (s->terminated)
                sub = "converged: the closest " + std::string(d.planar ? "edge" : "face") + " is on the boundary";
        } else {
            if (!run.steps.empty()) drawPolytope(cs, d, run.steps.back(), false);
            if (penetrating && run.depth > 0) {
                const Vec3 pv = run.depth * run.normal;
                cs.drawArrow(Vec3::Zero(), pv, lineStyle(Role::Result, 4.0f, false, true));
                cs.noteQuantity("depth", Vec3::Zero(), pv);
                if (labels)
                    drawLabelAway(cs, pv, Vec3::Zero(), "depth · n",
                                  TextStyle{18.0f, roleColor(Role::Result).scaled(0.7f), Anchor::Center, true, true},
                                  8.0);
            } else if (penetrating) {
                cs.drawArrow(Vec3::Zero(), run.normal * 0.3 * d.cRadius, lineStyle(Role::Direction, 3.0f, false, true));
            }
            sub = run.status == EpaStatus::Separated ? "GJK: the origin is outside A − B (no penetration)"
                  : run.depth > 0                    ? "penetration vector: origin to the nearest boundary point"
                                                     : "origin on the boundary: depth 0, contact normal n";
        }
        drawPanelHeading(
            cs, std::string("Configuration space A − B") + (d.c.valid && !d.exact ? " (sampled hull)" : ""), sub);
    }

    // The caption lines under the panels; names the frame.
    std::vector<std::string> describeFrame(const Drawing& d, const EpaRun& run, const PolyStep* s, bool isGjk,
                                           Frame& f) const {
        std::vector<std::string> lines;
        if (isGjk) {
            lines.push_back("GJK: " + std::string(nameOf(run.gjk.status)) + " after " +
                            std::to_string(run.gjk.iterations) + " iterations (" + nameOf(run.gjk.termination) + ")" +
                            (run.gjk.intersect() ? "; EPA starts from this simplex (" + run.start + ")"
                                                 : ", distance " + formatNumber(run.gjk.distance)));
            lines.push_back(
                "EPA grows a polytope inside A − B around the origin until its face nearest the origin lies on the "
                "boundary.");
            f.name = "gjk";
            f.caption = std::string("GJK: ") + nameOf(run.gjk.status) + ", " + std::to_string(run.gjk.simplex.count) +
                        "-vertex simplex";
        } else if (s) {
            const double h = s->normal.dot(s->support);
            lines.push_back("EPA iteration " + std::to_string(s->iteration) + ": " + std::to_string(s->faces.size()) +
                            (d.planar ? " edges" : " faces") + ", closest at distance " + formatNumber(s->distance) +
                            ", n = " + formatPoint(s->normal) + ", w = s_C(n) = " + formatPoint(s->support));
            lines.push_back("bounds " + formatNumber(s->lower) + " ≤ depth ≤ " + formatNumber(s->upper) +
                            ";  test n·w − d = " + formatNumber(h - s->distance) +
                            (s->terminated ? "  → stop: " + std::string(nameOf(run.termination))
                                           : "  → remove the visible " + std::string(d.planar ? "edges" : "faces") +
                                                 ", connect the horizon to w"));
            f.name = stepFrameName(s->iteration);
            f.caption = "it " + std::to_string(s->iteration) + ": d = " + formatNumber(s->distance) + ", gap " +
                        formatNumber(h - s->distance) + (s->terminated ? " (stop)" : "");
        } else {
            // Where the bounds have not met (a curved A − B stops at its tolerance or the cap), the
            // depth is the interval, not its lower end (the review: 0.551 printed, 0.5560 exact).
            const bool open = run.upper - run.lower > 1e-4 * std::abs(run.upper);
            const std::string depth = open ? "depth in [" + formatNumber(run.lower) + ", " + formatNumber(run.upper) + "]"
                                           : "depth " + formatNumber(run.depth);
            lines.push_back(std::string("Result: ") + nameOf(run.status) + " (" + nameOf(run.termination) + ") after " +
                            std::to_string(run.iterations) + " EPA iterations: " + depth + ", normal " +
                            formatPoint(run.normal));
            lines.push_back("p_A = " + formatPoint(run.pointA) + ",  p_B = " + formatPoint(run.pointB) + ";  bounds " +
                            formatNumber(run.lower) + " ≤ depth ≤ " + formatNumber(run.upper));
            f.name = "result";
            f.caption = std::string("result: ") + nameOf(run.status) + ", " + depth;
        }
        return lines;
    }

    // GJK's point, segment or triangle and the supports that blow it up: each direction d from the
    // origin (orthogonal to the simplex's hull), the support s_C(d) it gave and d · s_C(d), the test:
    // at 0 the whole of A − B lies behind the plane through the origin orthogonal to d (touching).
    std::vector<std::string> drawBlowUp(Canvas& cs, const Drawing& d, const EpaRun& run, Frame& f) const {
        const bool labels = common_.hasLayer("labels");
        if (d.c.valid) drawBody(cs, d.c, roleColor(Role::Minkowski), 0.12f, roleColor(Role::Minkowski).scaled(0.75f), 1.0f, false);
        drawOrigin(cs, 0.06 * d.cRadius, d.planar);
        std::vector<Vec3> w;
        for (int i = 0; i < run.gjk.simplex.count; ++i) w.push_back(run.gjk.simplex.vertex[i].w);
        if (w.size() == 3) cs.drawPolygon(w, roleColor(Role::Simplex).withAlpha(0.35f));
        for (std::size_t i = 0; i < w.size(); ++i)
            for (std::size_t j = i + 1; j < w.size(); ++j) cs.drawLine(w[i], w[j], lineStyle(Role::Simplex, 4.0f, false, true));
        const std::size_t n = run.blowUpDirections.size();
        std::vector<std::string> lines;
        std::string tests;
        for (std::size_t k = 0; k < n; ++k) {
            const Vec3 dir = run.blowUpDirections[k], p = run.blowUpPoints[k];
            const double h = dir.dot(p);
            const Vec3 tip = dir * (0.45 * d.cRadius);
            cs.drawArrow(Vec3::Zero(), tip, lineStyle(Role::Direction, 3.0f, false, true));
            cs.drawPoint(p, 10.0f, roleColor(Role::Support), true, 2.0f, roleColor(Role::Ink));
            const std::string idx = std::to_string(w.size() + k);
            if (labels) {
                drawLabelAway(cs, tip, Vec3::Zero(), "d", labelStyle(Role::Ink, 18.0f), 8.0);
                drawLabelAway(cs, p, d.cCenter, "w" + idx + " = s_C(d)", labelStyle(Role::Ink, 18.0f), 10.0);
            }
            tests += (tests.empty() ? "" : "; ") + std::string("d = ") + formatPoint(dir) + ", d · w" + idx + " = " + formatNumber(h);
        }
        for (std::size_t i = 0; i < w.size(); ++i)
            if (labels) drawLabelAway(cs, w[i], d.cCenter, "w" + std::to_string(i), labelStyle(Role::Ink, 18.0f), 12.0);
        const bool touching = run.termination == EpaTermination::Touching;
        drawPanelHeading(cs, "Configuration space A − B",
                         "blow-up of GJK's " + std::to_string(w.size()) + "-vertex simplex: support along its normal d");
        lines.push_back("EPA needs a tetrahedron around the origin; GJK ended on a " + run.start.substr(0, run.start.find(' ')) +
                        ". Support along d orthogonal to its hull: " + tests);
        lines.push_back(touching ? "d · s_C(d) = 0: all of A − B lies behind the plane through the origin orthogonal to d: the "
                                   "origin is on the boundary: touching, depth 0, normal d"
                                 : "d · s_C(d) > 0: the new point lies beyond the origin's plane, and the tetrahedron "
                                   "holds the origin; EPA's loop starts from it");
        f.name = "blow_up";
        f.caption = "blow-up: " + run.start + (touching ? ", touching" : "");
        return lines;
    }

    // The barycentric witness step (3D): the nearest face of the final polytope, the origin's
    // projection p = depth · n on it and its weights; the same weights on the faces' points of A and B
    // give the witness points (world panel, drawWitnessWorld).
    std::vector<std::string> drawWitnessConfiguration(Canvas& cs, const Drawing& d, const EpaRun& run, Frame& f) const {
        const bool labels = common_.hasLayer("labels");
        const EpaWitnessStep& ws = run.witness;
        if (d.c.valid) drawBody(cs, d.c, roleColor(Role::Minkowski), 0.10f, roleColor(Role::Minkowski).scaled(0.75f), 1.0f, false);
        drawOrigin(cs, 0.06 * d.cRadius, d.planar);
        const std::vector<Vec3> nearest(ws.nearest.w.begin(), ws.nearest.w.end());
        const std::vector<Vec3> used(ws.used.w.begin(), ws.used.w.end());
        if (ws.covered) {
            LineStyle dashed = lineStyle(Role::Ink, 2.5f, true, true);
            dashed.color = closestColor().scaled(0.7f);
            cs.drawPolyline(nearest, true, dashed);
        }
        cs.drawMesh(used, {Eigen::Vector3i(0, 1, 2)}, closestColor(), false);
        cs.drawPolyline(used, true, lineStyle(Role::Ink, 1.5f, false, true));
        cs.drawLine(Vec3::Zero(), ws.projection, lineStyle(Role::Ink, 2.0f, true, true));
        cs.drawPoint(ws.projection, 9.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
        if (labels) {
            // The vertices named w₀ w₁ w₂ (their weights are on the caption's second line).
            for (const auto& [p, name] : groupedNames(ws.used.w, "w"))
                drawLabelAway(cs, p, ws.projection, name, labelStyle(Role::Ink, 17.0f), 10.0);
            drawLabelAway(cs, ws.projection, Vec3::Zero(), "p", labelStyle(Role::Ink, 18.0f), 10.0);
        }
        drawPanelHeading(cs, "Configuration space A − B",
                         ws.covered ? "p is outside the nearest face (dashed): the coplanar face holding it gives λ"
                                    : "p = λ₀w₀ + λ₁w₁ + λ₂w₂ on the nearest face");
        std::vector<std::string> lines;
        lines.push_back("p = depth · n = " + formatPoint(ws.projection) + ": weights on the nearest face " +
                        weightList(ws.nearest.weights) +
                        (ws.covered ? ", one negative: p is outside it" : ", all ≥ 0: p is on it"));
        lines.push_back("λ = " + weightList(ws.used.weights) + " at w₀, w₁, w₂:  p_A = λ₀a₀ + λ₁a₁ + λ₂a₂ = " + formatPoint(ws.pointA) +
                        ",  p_B = λ₀b₀ + λ₁b₁ + λ₂b₂ = " + formatPoint(ws.pointB) +
                        (run.pointA == ws.pointA && run.pointB == ws.pointB ? "" : " (then refined)"));
        f.name = "witness";
        f.caption = "witness: λ = " + weightList(ws.used.weights) + (ws.covered ? " (coplanar face)" : "");
        return lines;
    }

    // The witness step in world space: the used face's points of A and B and the witnesses they give.
    void drawWitnessWorld(Canvas& world, const Drawing& d, const EpaRun& run) const {
        const bool labels = common_.hasLayer("labels");
        const EpaWitnessStep& ws = run.witness;
        drawPairBodies(world, d, 0.3f, true, labels, false);
        for (const auto* pts : {&ws.used.a, &ws.used.b}) {
            const std::vector<Vec3> tri(pts->begin(), pts->end());
            world.drawPolyline(tri, true, lineStyle(Role::Result, 2.0f, true, true));
            for (const Vec3& p : tri) world.drawPoint(p, 6.0f, roleColor(Role::Support), true, 1.5f, roleColor(Role::Ink));
        }
        world.drawPoint(ws.pointA, 9.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
        world.drawPoint(ws.pointB, 9.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
        if (labels) {
            // The face's points named on polytopes; on curved shapes they crowd on the surface, and
            // the caption's sums name them.
            // A face point at its witness (a weight of 1, or all three points one) is named by the
            // witness's label alone (two labels on one point crowded the sliver's slab).
            const TextStyle small = labelStyle(Role::Ink, 15.0f);
            const auto points = [&](const std::array<Vec3, 3>& pts, const char* letter, const Vec3& witness,
                                    const Vec3& centre) {
                for (const auto& [p, name] : groupedNames(pts, letter))
                    if (p != witness && d.exact) drawLabelAway(world, p, centre, name, small, 8.0);
            };
            points(ws.used.a, "a", ws.pointA, d.a.center);
            points(ws.used.b, "b", ws.pointB, d.b.center);
            const TextStyle big{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
            // Each pushed away from the other witness (they are depth apart), else from its body's centre.
            const bool apart = (ws.pointA - ws.pointB).norm() > 1e-3 * d.wRadius;
            drawLabelAway(world, ws.pointA, apart ? ws.pointB : d.a.center, "p_A", big, 10.0);
            drawLabelAway(world, ws.pointB, apart ? ws.pointA : d.b.center, "p_B", big, 10.0);
        }
        drawPanelHeading(world, "World space", "the same weights on the face's points of A and of B");
    }

    // Lower and upper depth bounds against the iteration (demos/draw/plot.h).
    Frame drawPlot(GlContext& gl, int ss, const EpaRun& run) const {
        BoundsPlot plot;
        for (const PolyStep& s : run.steps) {
            plot.iterations.push_back(s.iteration);
            plot.lower.push_back(s.lower);
            plot.upper.push_back(s.upper);
        }
        plot.xLabel = "EPA iteration";
        plot.yLabel = "penetration depth bounds";
        plot.upperName = "upper bound min n·s_C(n)";
        plot.lowerName = "lower bound: closest face distance";
        plot.title = common_.title + ": depth bounds per iteration";
        plot.caption = "final depth " + formatNumber(run.depth) + " (" + nameOf(run.termination) +
                       "); the gap closes as the polytope reaches the boundary of A − B";
        return Frame{"bounds", "depth bounds vs iteration",
                     drawBoundsPlot(gl, common_.image.width, common_.image.height, ss, plot)};
    }
};

class EpaDemo final : public Demo {
public:
    std::string name() const override { return "epa"; }
    std::string description() const override {
        return "EPA step by step after GJK: expanding polytope, closest face, horizon, penetration vector, depth "
               "bounds; 3D and 2D";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1280, 640}, {320, 240}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        PairScene pair = readPairScene(r);
        EpaOptions options;
        if (auto m = r.find("method")) {
            ObjectReader mr(*m);
            if (auto t = mr.find("tolerance")) options.relativeTolerance = t->asPositive();
            if (auto n = mr.find("max_iterations")) options.maxIterations = n->asInt(1, 120);
            if (auto g = mr.find("gjk_tolerance")) options.gjk.relativeTolerance = g->asPositive();
            mr.finish();
        }
        r.finish();
        // GJK's simplex, the result and the plot; with steps at most max_step_frames steps and the sheet.
        common.frames = {3, pair.maxStepFrames + 6, 0};
        return std::make_unique<EpaScene>(std::move(common), std::move(pair), options);
    }
};

}  // namespace

const Demo& epaDemo() {
    static const EpaDemo demo;
    return demo;
}

}  // namespace cdlab::demos
