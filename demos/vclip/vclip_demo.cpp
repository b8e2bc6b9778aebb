// V-Clip step-through (Mirtich, "V-Clip: Fast and Robust Polyhedral Collision Detection", ACM TOG
// 17(3) 1998 / MERL TR-97-05). Runs core's vclip() once per scene (or once per frame of a motion
// sequence, warm-started through VClipCache) and draws its VClipTrace: every number drawn comes from
// the trace or the result; this file adds only drawing geometry, the Theorem-1 check of the final
// pair (closest points re-tested against the stored region planes) and a GJK cross-check.
//
// Scene keys (besides the common ones in scene.h; docs/scenes.md, "vclip"):
//   "bodies": [A, B]            {"icosahedron": {"radius", "position", "rotation"}}, box, prism, disk, ...
//   "seed": ["V0", "F3"]        first feature pair (default: vertex 0 of each, the cold start)
//   "view": [x, y, z]           view direction of the 3D panel
//   "max_step_frames": n        with "steps": at most n step frames (the first ones and the last)
//   "motion": {...}             a coherent sequence: B orbits a centre, one warm-started call per frame
//   "gif": bool
// Layers: "planes", "clip", "derivative", "update", "closest", "labels", "diagram", "plot".
#include "demos/vclip/vclip_demo.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/feature_walk/vclip.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/contact_sheet.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/feature_walk_figure.h"
#include "demos/draw/feature_walk_trace_json.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/draw/step_frames.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;
using namespace walkfigure;

const std::vector<std::string> kLayers = {"planes",  "clip",   "derivative", "update",
                                          "closest", "labels", "diagram",    "plot"};

/// A coherent motion: B's pose at call k is its scene pose turned by k * orbitDegrees about the
/// axis through `center` and spun by k * spinDegrees about its own body axis.
struct Motion {
    int calls = 24;
    Vec3 center = Vec3::Zero();
    Vec3 orbitAxis = Vec3::UnitY();
    double orbitDegrees = 6.0;
    Vec3 spinAxis = Vec3::UnitX();
    double spinDegrees = 0.0;
    int drawnFrames = 8;
};

struct Settings {
    Body a, b;
    std::optional<VClipCache> seed;
    Vec3 view = Vec3(1.0, 0.8, 1.7);
    int maxStepFrames = 12;
    bool gif = true;
    std::optional<Motion> motion;
};

/// One vclip() call and what is drawn from it.
struct Call {
    Transform poseB;
    VClipCache seed;  // the pair it started from
    VClipResult result;
    VClipTrace trace;
    GjkResult gjk;
};

// The calls of a coherent sequence that get a frame, at most m, in call order: the first (the cold
// start), then the calls whose walk updated features — the most updates first — then evenly
// spaced others to fill m (figure review 2026-11-29: five 0-update calls were drawn while calls 27,
// 33 and 37 changed features).
std::vector<int> motionCallsToDraw(const std::vector<Call>& calls, int m) {
    const int n = int(calls.size());
    m = std::min(n, m);
    std::vector<int> chosen;
    if (m <= 0) return chosen;
    chosen.push_back(0);
    std::vector<int> updating;
    for (int k = 1; k < n; ++k)
        if (calls[std::size_t(k)].result.steps > 0) updating.push_back(k);
    std::stable_sort(updating.begin(), updating.end(), [&](int a, int b) {
        return calls[std::size_t(a)].result.steps > calls[std::size_t(b)].result.steps;
    });
    for (int k : updating)
        if (int(chosen.size()) < m) chosen.push_back(k);
    for (int j = 1; int(chosen.size()) < m && j < m; ++j) {  // fill: evenly spaced, unused
        int k = int(std::lround(double(j) * (n - 1) / (m - 1)));
        while (k < n && std::find(chosen.begin(), chosen.end(), k) != chosen.end()) ++k;
        if (k < n) chosen.push_back(k);
    }
    for (int k = 1; int(chosen.size()) < m && k < n; ++k)
        if (std::find(chosen.begin(), chosen.end(), k) == chosen.end()) chosen.push_back(k);
    std::sort(chosen.begin(), chosen.end());
    return chosen;
}

// The sheet's title: which calls it shows and how many of them updated features.
std::string motionSheetTitle(const std::vector<Call>& calls, const std::vector<int>& drawn) {
    int updating = 0, shown = 0;
    for (std::size_t k = 1; k < calls.size(); ++k) updating += calls[k].result.steps > 0;
    for (int k : drawn) shown += k > 0 && calls[std::size_t(k)].result.steps > 0;
    return "The first call and " + std::to_string(shown) + " of the " + std::to_string(updating) +
           " that updated (of " + std::to_string(calls.size()) + ")";
}

int stateIndex(VClipState s) { return static_cast<int>(s); }

GjkResult gjkOf(const Body& a, const Body& b, const Transform& poseB) {
    const Transformed<PolytopeShape> sa{PolytopeShape(a.regions.mesh()), a.pose};
    const Transformed<PolytopeShape> sb{PolytopeShape(b.regions.mesh()), poseB};
    return gjkDistance(sa, sb);
}

Transform motionPose(const Transform& base, const Motion& m, int k) {
    const Quat orbit(Eigen::AngleAxisd(k * m.orbitDegrees * M_PI / 180.0, m.orbitAxis.normalized()));
    const Quat spin(Eigen::AngleAxisd(k * m.spinDegrees * M_PI / 180.0, m.spinAxis.normalized()));
    Transform t;
    t.position = m.center + orbit * (base.position - m.center);
    t.rotation = (orbit * base.rotation * spin).normalized();
    return t;
}

std::string signName(int s) { return s == 2 ? "·" : s > 0 ? "+" : s < 0 ? "−" : "0"; }

class VclipScene final : public PreparedScene {
public:
    VclipScene(SceneCommon common, Settings s) : PreparedScene(std::move(common)), s_(std::move(s)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        std::vector<Call> calls = compute();
        DemoOutput out;
        out.trace = traceJson(calls);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        // Framing: every pose of B with A.
        std::vector<Vec3> pts;
        for (const Vec3& p : s_.a.regions.mesh().positions()) pts.push_back(s_.a.pose.apply(p));
        for (const Call& c : calls)
            for (const Vec3& p : s_.b.regions.mesh().positions()) pts.push_back(c.poseB.apply(p));
        boundingSphere(pts, center_, radius_);

        std::vector<const Frame*> animated;
        std::vector<int> drawnCalls, framed;
        if (s_.motion) {
            drawnCalls = motionCallsToDraw(calls, s_.motion->drawnFrames);
            for (int k : drawnCalls) out.frames.push_back(drawMotionFrame(*ctx.gl, ss, calls, k));
        } else {
            const Call& c = calls.front();
            framed = framedSteps(int(c.trace.steps.size()), s_.maxStepFrames);
            if (common_.steps || ctx.stepsOverride)
                for (int i : framed) out.frames.push_back(drawStepFrame(*ctx.gl, ss, c, i));
            out.frames.push_back(drawStepFrame(*ctx.gl, ss, c, -1));
        }
        for (const Frame& f : out.frames) animated.push_back(&f);
        if (s_.gif && animated.size() > 1) addGif(out, animated, 2);
        else if (s_.gif) out.skipped.push_back("animation.gif (a single frame)");
        if ((common_.steps || ctx.stepsOverride) && animated.size() > 1) {
            // At most 1024 x 768: 3 columns of quarter-size frames, or 4 of fifth-size beyond six frames.
            ContactSheetOptions o;
            o.caption = common_.caption;
            o.title = s_.motion ? motionSheetTitle(calls, drawnCalls)
                                : "V-Clip: " + iterationCoverage(int(calls.front().trace.steps.size()), framed, "step", 0);
            const bool many = animated.size() > 6;
            o.cellWidth = common_.image.width / (many ? 5 : 4) + 1;
            o.columns = many ? 4 : 3;
            Frame sheet = contactSheetFrame(*ctx.gl, animated, common_.title, o);
            out.frames.push_back(std::move(sheet));
        }
        return out;
    }

private:
    Settings s_;
    mutable Vec3 center_ = Vec3::Zero();
    mutable double radius_ = 1.0;

    std::vector<Call> compute() const {
        std::vector<Call> calls;
        VClipCache cache;
        if (s_.seed) cache = *s_.seed;
        else cache = VClipCache{VClipFeature::vertex(0), VClipFeature::vertex(0)};
        const int n = s_.motion ? s_.motion->calls : 1;
        for (int k = 0; k < n; ++k) {
            Call c;
            c.poseB = s_.motion ? motionPose(s_.b.pose, *s_.motion, k) : s_.b.pose;
            c.seed = cache;
            c.result = vclip(s_.a.regions, s_.a.pose, s_.b.regions, c.poseB, &cache, VClipOptions{}, &c.trace);
            c.gjk = gjkOf(s_.a, s_.b, c.poseB);
            calls.push_back(std::move(c));
        }
        return calls;
    }

    // ------------------------------------------------------------------------------- trace JSON

    Json stepJson(const VClipTraceStep& st) const {
        Json clips = Json::array();
        for (const VClipClip& c : st.clips)
            clips.push_back({{"edge_body", c.edgeBody},
                             {"edge", featureJson(c.edge)},
                             {"region", featureJson(c.region)},
                             {"lambda_min", c.lambdaMin},
                             {"lambda_max", c.lambdaMax},
                             {"n_min", featureJson(c.neighborMin)},
                             {"n_max", featureJson(c.neighborMax)},
                             {"simply_excluded", c.simplyExcluded},
                             {"compound_excluded", c.compoundExcluded},
                             {"excluded_by", featureJson(c.excludedBy)},
                             {"derivative_min", c.derivativeMin},
                             {"derivative_max", c.derivativeMax},
                             {"tail", vec3Json(c.tail)},
                             {"head", vec3Json(c.head)}});
        Json j = walkStepJson(st);
        j["clips"] = clips;
        return j;
    }

    Json resultJson(const Call& c) const {
        Json j = walkResultJson(c.result);
        j["seed"] = {featureJson(c.seed.a), featureJson(c.seed.b)};
        j["gjk_distance"] = c.gjk.distance;
        j["gjk_intersect"] = c.gjk.intersect();
        if (c.result.status == VClipStatus::Separated) {
            j["theorem1_a_in_region_b"] = checkInRegion(s_.b, c.poseB, c.result.featureB, c.result.pointA).minDistance;
            j["theorem1_b_in_region_a"] =
                checkInRegion(s_.a, s_.a.pose, c.result.featureA, c.result.pointB).minDistance;
        }
        return j;
    }

    Json traceJson(const std::vector<Call>& calls) const {
        Json t;
        t["bodies"] = {{{"kind", s_.a.kind},
                        {"vertices", s_.a.regions.mesh().vertexCount()},
                        {"edges", s_.a.regions.mesh().edgeCount()},
                        {"faces", s_.a.regions.mesh().faceCount()}},
                       {{"kind", s_.b.kind},
                        {"vertices", s_.b.regions.mesh().vertexCount()},
                        {"edges", s_.b.regions.mesh().edgeCount()},
                        {"faces", s_.b.regions.mesh().faceCount()}}};
        if (!s_.motion) {
            const Call& c = calls.front();
            t["result"] = resultJson(c);
            Json steps = Json::array();
            for (const VClipTraceStep& st : c.trace.steps) steps.push_back(stepJson(st));
            t["steps"] = steps;
        } else {
            Json cs = Json::array();
            for (std::size_t k = 0; k < calls.size(); ++k) {
                Json j = resultJson(calls[k]);
                j["call"] = k;
                j["position_b"] = vec3Json(calls[k].poseB.position);
                Json states = Json::array();
                for (const VClipTraceStep& st : calls[k].trace.steps) states.push_back(nameOf(st.state));
                j["states"] = states;
                cs.push_back(j);
            }
            t["calls"] = cs;
        }
        return t;
    }

    // ---------------------------------------------------------------------------------- frames

    Layout layout() const { return Layout{common_.image.width, common_.image.height}; }

    CanvasOptions mainOptions(int ss) const {
        const Layout L = layout();
        return canvasOptions(L.mainWidth(), L.panelHeight(), ss);
    }

    /// `view`: the scene's, or the walk's (chooseWalkView). Framed a little low so
    /// that the panel heading stays clear of the bodies, and pulled back until both bodies (B at
    /// `poseB`) and the points `alsoInside` (a step's plane patches) are whole `top` px below the
    /// panel's top (BodyCutByPanel; a step frame's plane key ends at 86 px, the gate found B's edges
    /// through it; the review found violated planes cut by the panel's bottom).
    void setupMain(Canvas& c, const Vec3& view, const Transform& poseB, double top = 48.0,
                   const std::vector<Vec3>& alsoInside = {}) const {
        if (common_.camera) {
            c.setCamera(*common_.camera);
            return;
        }
        const std::vector<Vec3> a = worldVertices(s_.a, s_.a.pose), b = worldVertices(s_.b, poseB);
        double zoom = 0.92;
        for (int k = 0; k < 16; ++k, zoom *= 1.04) {
            Camera cam = framingCamera(center_, radius_ * zoom, view, Vec3::UnitY(), true);
            const Vec3 forward = (cam.target - cam.eye).normalized();
            const Vec3 screenUp = (Vec3::UnitY() - Vec3::UnitY().dot(forward) * forward).normalized();
            cam.eye += screenUp * 0.12 * radius_;
            cam.target += screenUp * 0.12 * radius_;
            c.setCamera(cam);
            if (verticesInside(c, a, top) && verticesInside(c, b, top) && verticesInside(c, alsoInside, top)) break;
        }
    }

    const Body& body(int i) const { return i == 0 ? s_.a : s_.b; }

    /// The call's bodies (B at `poseB`), apart when the call found them separated.
    WalkBodies walkBodies(const Call& call) const {
        return {&s_.a, s_.a.pose, &s_.b, call.poseB, call.result.status == VClipStatus::Separated};
    }

    Vec3 centroidA() const { return s_.a.pose.apply(s_.a.regions.mesh().centroid()); }
    Vec3 centroidB(const Transform& poseB) const { return poseB.apply(s_.b.regions.mesh().centroid()); }

    Color featureColor(int bodyIndex) const {
        return roleColor(bodyIndex == 0 ? Role::ShapeA : Role::ShapeB).scaled(0.8f);
    }

    void drawClosest(Canvas& c, const Vec3& pa, const Vec3& pb, bool named) const {
        drawClosestPoints(c, pa, pb, named && common_.hasLayer("labels"), radius_);
    }

    void drawClip(Canvas& c, const VClipClip& cl, bool derivative) const {
        const bool excluded = cl.simplyExcluded || cl.compoundExcluded;
        LineStyle dashed = lineStyle(Role::Ink, 3.0f, true, true);
        dashed.color = excluded ? violatedColor() : roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.4f);
        c.drawLine(cl.tail, cl.head, dashed);
        const bool labels = common_.hasLayer("labels");
        if (excluded) {
            for (int end = 0; cl.compoundExcluded && end < 2; ++end) {  // the crossed ends: λmax before λmin
                c.drawPoint(end == 0 ? cl.clippedTail : cl.clippedHead, 8.0f, violatedColor(), true, 1.5f, roleColor(Role::Ink));
                if (labels) drawLabelAway(c, end == 0 ? cl.clippedTail : cl.clippedHead, center_, end == 0 ? "λmin" : "λmax",
                                          TextStyle{15.0f, violatedColor().scaled(0.8f), Anchor::Center, true, true}, 8.0);
            }
            if (labels && cl.simplyExcluded)  // a compound one is named by its λmin, λmax and the caption
                drawLabelAway(c, 0.5 * (cl.tail + cl.head), center_, "simply excluded",
                              TextStyle{15.0f, violatedColor().scaled(0.8f), Anchor::Center, true, true}, 10.0);
            return;
        }
        LineStyle solid = lineStyle(Role::Ink, 6.0f, false, true);
        solid.color = clipColor();
        c.drawLine(cl.clippedTail, cl.clippedHead, solid);
        for (int end = 0; end < 2; ++end) {
            const Vec3& p = end == 0 ? cl.clippedTail : cl.clippedHead;
            const double lambda = end == 0 ? cl.lambdaMin : cl.lambdaMax;
            const bool clipped = end == 0 ? lambda > 0 : lambda < 1;
            if (clipped) c.drawPoint(p, 5.0f, clipColor(), true, 1.2f, roleColor(Role::Ink));
            const int sign = end == 0 ? cl.derivativeMin : cl.derivativeMax;
            if (derivative && sign != 2) {
                // The distance decreases against the sign of D'(λ) along e(λ) = tail + λ (head − tail).
                const Vec3 dir = (cl.head - cl.tail).normalized();
                if (sign != 0) {
                    const Vec3 tip = p - double(sign) * dir * 0.22 * radius_;
                    c.drawArrow(p, tip, lineStyle(Role::Support, 3.0f, false, true));
                    if (labels)
                        drawLabelAway(
                            c, tip, p, std::string("D′") + (sign > 0 ? " > 0" : " < 0"),
                            TextStyle{14.0f, roleColor(Role::Support).scaled(0.75f), Anchor::Center, true, true}, 6.0);
                } else {
                    c.drawPoint(p, 7.0f, roleColor(Role::Support), true, 1.2f, roleColor(Role::Ink));
                }
            }
        }
    }

    std::string updateText(const VClipTraceStep& st) const {
        return std::string(st.updatedBody == 0 ? "A" : "B") + ": " + nameOf(st.from) + " → " + nameOf(st.to);
    }

    Frame drawStepFrame(GlContext& gl, int ss, const Call& call, int index) const {
        const Layout L = layout();
        const bool labels = common_.hasLayer("labels");
        const VClipTraceStep* st = index >= 0 ? &call.trace.steps[index] : nullptr;
        Canvas c(gl, mainOptions(ss));
        // One view for the walk's frames, near the scene's; a step whose new feature it shows from
        // behind swings round to it (demos/draw/feature_walk_figure.h, chooseWalkView).
        const WalkBodies w = walkBodies(call);
        std::vector<WalkStepFeatures> steps;
        for (const VClipTraceStep& t : call.trace.steps)
            steps.push_back({t.featureA, t.featureB, t.kind == VClipStepKind::Update ? t.updatedBody : -1, t.to});
        Vec3 view = chooseWalkView(w, s_.view, steps, 180.0);
        if (st) view = stepView(w, view, steps[std::size_t(index)]);
        const std::vector<Vec3> patches =
            st && common_.hasLayer("planes") ? drawnPatchPoints(w, st->planes, radius_) : std::vector<Vec3>{};
        setupMain(c, view, call.poseB, 92.0, patches);  // the result framed as the steps
        drawWalkBodies(c, walkBodies(call), common_.hasLayer("labels"));
        FrameText text;
        Frame f;
        if (st) drawStepView(c, call, *st, labels, text, f);
        else drawResultView(c, call, labels, text, f);
        drawPanelHeading(c, text.heading, text.sub);
        const Image main = c.readPixels();
        const Image diagram = common_.hasLayer("diagram") ? stateDiagram(gl, ss, call, st, index)
                                                          : blank(L.columnWidth, L.diagramHeight());
        const Image plot = common_.hasLayer("plot") ? distancePlot(gl, ss, call.trace, st, index)
                                                    : blank(L.columnWidth, L.plotHeight());
        f.image = composeFrame(gl, L, ss, common_.title, common_.caption, main, diagram, plot, text.lines);
        return f;
    }

    // The main panel's heading, its subtitle and the text lines under the figure.
    struct FrameText {
        std::string heading, sub;
        std::vector<std::string> lines;
    };

    // One step: the two features, the plane tests (with many planes, as on a 60-gon face, only the
    // violated and the maximal ones), clips, closest points and the update; its text.
    void drawStepView(Canvas& c, const Call& call, const VClipTraceStep& step, bool labels, FrameText& text,
                      Frame& f) const {
        const VClipTraceStep* st = &step;
        const VClipTrace& tr = call.trace;
        const VClipResult& r = call.result;
        std::string& heading = text.heading;
        std::string& sub = text.sub;
        std::vector<std::string>& lines = text.lines;
        const std::vector<Vec3> ga = st->featureAWorld, gb = st->featureBWorld;
        const bool update = common_.hasLayer("update") && st->kind == VClipStepKind::Update && st->updatedBody >= 0;
        const Body& ub = body(std::max(st->updatedBody, 0));
        const Transform& upose = st->updatedBody == 0 ? s_.a.pose : call.poseB;
        const std::vector<Vec3> gTo = update ? featureGeometry(ub.regions, upose, st->to) : std::vector<Vec3>{};
        const auto drawNew = [&](bool firstPass) {  // drawNewFeature: a face now, an edge or vertex last
            if (update)
                drawNewFeature(c, gTo, featureNormals(ub, upose, st->to), featureColor(st->updatedBody),
                               "new " + featureLabel(st->to, st->updatedBody), firstPass);
        };
        drawNew(true);
        drawFeature(c, ga, featureNormals(s_.a, s_.a.pose, st->featureA), featureColor(0), featureLabel(st->featureA, 0),
                    centroidB(call.poseB), labels);
        drawFeature(c, gb, featureNormals(s_.b, call.poseB, st->featureB), featureColor(1), featureLabel(st->featureB, 1),
                    centroidA(), labels);
        int shown = 0, violatedCount = 0;
        for (const VClipPlaneTest& p : st->planes) violatedCount += p.violated;
        if (common_.hasLayer("planes"))
            for (const VClipPlaneTest& p : st->planes) {
                if (!planeTestDrawn(st->planes, p)) continue;  // the sub-heading says how many are drawn
                drawPlaneTest(c, body(p.regionBody), p.regionBody == 0 ? s_.a.pose : call.poseB, p.plane, p.owner,
                              p.testedPoint, p.signedDistance, p.planeNormal, p.violated, p.maximal, radius_);
                ++shown;
            }
        if (common_.hasLayer("clip"))
            for (const VClipClip& cl : st->clips) drawClip(c, cl, common_.hasLayer("derivative"));
        if (common_.hasLayer("closest")) drawClosest(c, st->closestA, st->closestB, false);
        if (update) {
            const Vec3 from = featureCenter(st->updatedBody == 0 ? ga : gb), to = featureCenter(gTo);
            drawUpdateArrow(c, from, to, radius_);
            drawNew(false);
            if (labels)
                drawLabelAway(c, to, from, "new " + featureLabel(st->to, st->updatedBody),
                              TextStyle{16.0f, roleColor(Role::Ink), Anchor::Center, true, true}, 12.0,
                              featureLabelPoints(gTo));
        }
        heading = "Step " + std::to_string(st->step) + ": state " + nameOf(st->state);
        const bool faceSearch =
            std::any_of(st->planes.begin(), st->planes.end(), [](const VClipPlaneTest& p) { return p.plane < 0; });
        sub = std::to_string(st->planes.size()) + " plane test(s), " + std::to_string(violatedCount) + " violated";
        if (faceSearch) sub = "local minimum: violated = face plane V is farthest above";
        if (labels && shown > 0)
            drawKey(c, 14, 64, planeKey());
        if (int(st->planes.size()) > shown) sub += "; " + std::to_string(shown) + " drawn";
        if (!st->clips.empty()) sub += "; " + std::to_string(st->clips.size()) + " clip(s)";

        lines.push_back("Step " + std::to_string(st->step) + " (" + nameOf(st->state) +
                        "): " + featureLabel(st->featureA, 0) + " vs " + featureLabel(st->featureB, 1) +
                        ";  rule: " + st->rule);
        std::string l2;
        for (const VClipClip& cl : st->clips) {
            if (!l2.empty()) l2 += ";  ";
            l2 += "clip " + nameOf(cl.edge) + " by VR(" + nameOf(cl.region) + "): ";
            if (cl.simplyExcluded) l2 += "simply excluded by " + nameOf(cl.excludedBy);
            else if (cl.compoundExcluded)
                l2 += "compound excluded: past the plane to " + nameOf(cl.neighborMin) + " until λmin = " +
                      formatNumber(cl.lambdaMin) + ", past the one to " + nameOf(cl.neighborMax) + " from λmax = " +
                      formatNumber(cl.lambdaMax) + " < λmin";
            else
                l2 += "λ ∈ [" + formatNumber(cl.lambdaMin) + ", " + formatNumber(cl.lambdaMax) +
                      "], N = " + nameOf(cl.neighborMin) + ", " + nameOf(cl.neighborMax) + ", D′ signs " +
                      signName(cl.derivativeMin) + " " + signName(cl.derivativeMax);
        }
        if (l2.empty()) {
            const VClipPlaneTest* worst = nullptr;
            for (const VClipPlaneTest& p : st->planes)
                if (!worst || (p.maximal && !worst->maximal) ||
                    (p.maximal == worst->maximal && p.signedDistance < worst->signedDistance))
                    worst = &p;
            if (!worst) l2 = "no plane test";
            else if (worst->plane < 0)
                l2 = "handleLocalMin: V lies on or behind " +
                     nameOf(st->featureB.type == VClipFeatureType::Face ? st->featureB : st->featureA) +
                     "'s plane; the face it is farthest above is " + nameOf(worst->owner) + " (height " +
                     formatNumber(worst->signedDistance) + ")";
            else
                l2 = std::string(worst->maximal    ? "maximally violated"
                                 : worst->violated ? "most violated"
                                                   : "closest") +
                     " plane: VR(" + nameOf(worst->owner) + ") | " + nameOf(worst->neighbor) + " at signed distance " +
                     formatNumber(worst->signedDistance);
        }
        lines.push_back(l2);
        std::string l3;
        if (st->kind == VClipStepKind::Update) {
            l3 = "update " + updateText(*st) + ";  distance " + formatNumber(st->distanceBefore) + " → " +
                 formatNumber(st->distanceAfter) +
                 (st->localMinimum          ? " (handleLocalMin: the face the vertex is farthest above)"
                  : st->distanceChange < 0  ? " (decreased: dimension up)"
                  : st->distanceChange == 0 ? " (equal: dimension down)"
                                            : " (increased)");
        } else if (st->kind == VClipStepKind::Done) {
            l3 = "DONE: each closest point lies in the other feature's Voronoi region; distance " +
                 formatNumber(st->distanceBefore);
        } else if (st->kind == VClipStepKind::Penetration) {
            l3 = std::string("penetration found (") + nameOf(r.penetration) + ")";
        } else {
            l3 = std::string("aborted: ") + nameOf(tr.status);
        }
        lines.push_back(l3);
        f.name = stepFrameName(st->step);
        f.caption = "step " + std::to_string(st->step) + " " + nameOf(st->state) + ": " +
                    (st->kind == VClipStepKind::Update ? updateText(*st) : std::string(nameOf(st->kind)));
    }

    // The result: the final features, the region-plane checks of Mirtich's Theorem 1 (separated)
    // or the penetration verdict; its text.
    void drawResultView(Canvas& c, const Call& call, bool labels, FrameText& text, Frame& f) const {
        const VClipResult& r = call.result;
        std::string& heading = text.heading;
        std::string& sub = text.sub;
        std::vector<std::string>& lines = text.lines;
        const std::vector<Vec3> ga = featureGeometry(s_.a.regions, s_.a.pose, r.featureA);
        const std::vector<Vec3> gb = featureGeometry(s_.b.regions, call.poseB, r.featureB);
        drawFeature(c, ga, featureNormals(s_.a, s_.a.pose, r.featureA), featureColor(0), featureLabel(r.featureA, 0),
                    centroidB(call.poseB), labels);
        drawFeature(c, gb, featureNormals(s_.b, call.poseB, r.featureB), featureColor(1), featureLabel(r.featureB, 1),
                    centroidA(), labels);
        const bool separated = r.status == VClipStatus::Separated;
        std::string l2;
        if (separated) {
            const RegionCheck inB = checkInRegion(s_.b, call.poseB, r.featureB, r.pointA);
            const RegionCheck inA = checkInRegion(s_.a, s_.a.pose, r.featureA, r.pointB);
            // Of each region, the plane with the least margin (the one Theorem 1's minimum comes
            // from): all of them stacked 8 translucent planes over the closest pair (the review).
            const auto tightest = [](const RegionCheck& k) {
                const RegionCheck::Test* best = nullptr;
                for (const auto& t : k.tests)
                    if (t.plane >= 0 && (!best || t.distance < best->distance)) best = &t;
                return best;
            };
            if (common_.hasLayer("planes")) {
                if (const RegionCheck::Test* t = tightest(inB))
                    drawPlaneTest(c, s_.b, call.poseB, t->plane, r.featureB, r.pointA, t->distance,
                                  call.poseB.rotate(s_.b.regions.plane(t->plane).normal *
                                                    (r.featureB.type == VClipFeatureType::Edge ? 1.0 : -1.0)),
                                  t->distance < 0, false, radius_);
                if (const RegionCheck::Test* t = tightest(inA))
                    drawPlaneTest(c, s_.a, s_.a.pose, t->plane, r.featureA, r.pointB, t->distance,
                                  s_.a.pose.rotate(s_.a.regions.plane(t->plane).normal *
                                                   (r.featureA.type == VClipFeatureType::Edge ? 1.0 : -1.0)),
                                  t->distance < 0, false, radius_);
            }
            auto verdict = [](const RegionCheck& k) {
                return k.minDistance >= -1e-12 ? " ≥ 0: inside" : " < 0: OUTSIDE";
            };
            l2 = "Theorem 1: p_A ∈ VR(" + featureLabel(r.featureB, 1) + "): " + std::to_string(inB.tests.size()) +
                 " planes, min " + formatNumber(inB.minDistance) + verdict(inB) + ";  p_B ∈ VR(" +
                 featureLabel(r.featureA, 0) + "): " + std::to_string(inA.tests.size()) + " planes, min " +
                 formatNumber(inA.minDistance) + verdict(inA);
        } else {
            l2 = std::string("verdict: ") + nameOf(r.penetration) + ", common point " + formatPoint(r.pointA) +
                 " (distance 0)";
        }
        if (common_.hasLayer("closest")) drawClosest(c, r.pointA, r.pointB, true);
        heading = std::string("Result: ") + nameOf(r.status) + " after " + std::to_string(r.steps) + " update(s)";
        sub = separated ? "closest points; green: each one's tightest region plane"
                        : std::string("penetration: ") + nameOf(r.penetration);
        lines.push_back(std::string("Result: ") + nameOf(r.status) +
                        (separated ? ", closest features " : ", found at features ") + featureLabel(r.featureA, 0) +
                        " and " + featureLabel(r.featureB, 1) + ", distance " + formatNumber(r.distance) + "  (GJK: " +
                        (call.gjk.intersect() ? std::string("intersecting") : formatNumber(call.gjk.distance)) + ")");
        lines.push_back(l2);
        lines.push_back(
            separated
                ? "so no other feature pair is closer (Mirtich 1998, Thm. 1): p_A = " + formatPoint(r.pointA) +
                      ", p_B = " + formatPoint(r.pointB)
                : "the bodies intersect: V-Clip stops with this feature pair (a depth needs EPA or another method)" +
                      (r.message.empty() ? std::string() : "; " + r.message));
        f.name = "result";
        f.caption = std::string("result: ") + nameOf(r.status) + ", distance " + formatNumber(r.distance);
    }

    // The five-state diagram with the states visited up to this step and the transition it takes.
    Image stateDiagram(GlContext& gl, int ss, const Call& call, const VClipTraceStep* st, int index) const {
        const Layout L = layout();
        const VClipTrace& tr = call.trace;
        const VClipResult& r = call.result;
        DiagramInput din;
        int upto = st ? index : int(tr.steps.size()) - 1;
        for (int i = 0; i <= upto; ++i) din.visits[stateIndex(tr.steps[i].state)]++;
        if (upto >= 0) din.current = stateIndex(tr.steps[upto].state);
        if (st && st->kind == VClipStepKind::Update && index + 1 < int(tr.steps.size())) {
            din.from = stateIndex(st->state);
            din.to = stateIndex(tr.steps[index + 1].state);
        }
        if (st)
            din.terminal =
                st->kind == VClipStepKind::Update
                    ? "update → " +
                          std::string(index + 1 < int(tr.steps.size()) ? nameOf(tr.steps[index + 1].state) : "?")
                : st->kind == VClipStepKind::Done ? "DONE"
                                                  : nameOf(st->kind);
        else
            din.terminal = std::string(nameOf(r.status)) + ": " + std::to_string(tr.steps.size()) + " states, " +
                           std::to_string(r.steps) + " update(s)";
        return drawStateDiagram(gl, L.columnWidth, L.diagramHeight(), ss, din);
    }

    // The inter-feature distance per update, coloured by what the update did.
    Image distancePlot(GlContext& gl, int ss, const VClipTrace& tr, const VClipTraceStep* st, int index) const {
        const Layout L = layout();
        PlotInput pin;
        pin.heading = "Inter-feature distance";
        pin.xLabel = "update";
        PlotSeries sd;
        sd.lineColor = roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f);
        if (!tr.steps.empty()) {
            sd.x.push_back(0);
            sd.y.push_back(tr.steps.front().distanceBefore);
            sd.pointColors.push_back(roleColor(Role::Ink));
        }
        for (const VClipTraceStep& s : tr.steps) {
            if (s.kind != VClipStepKind::Update) continue;
            sd.x.push_back(s.step + 1);
            sd.y.push_back(s.distanceAfter);
            sd.pointColors.push_back(s.localMinimum          ? clipColor()
                                     : s.distanceChange < 0  ? satisfiedColor()
                                     : s.distanceChange == 0 ? roleColor(Role::Muted)
                                                             : violatedColor());
        }
        pin.series.push_back(sd);
        pin.marker = st ? index : -1;
        pin.legend = {{satisfiedColor(), "decrease (dim. up)"}, {roleColor(Role::Muted), "equal (dim. down)"}};
        if (std::any_of(tr.steps.begin(), tr.steps.end(), [](const VClipTraceStep& s) { return s.localMinimum; }))
            pin.legend.push_back({clipColor(), "handleLocalMin (face → face)"});
        return drawPlot(gl, L.columnWidth, L.plotHeight(), ss, pin);
    }

    static Image blank(int w, int h) {
        Image im(w, h);
        std::fill(im.rgba.begin(), im.rgba.end(), std::uint8_t(255));
        return im;
    }

    Frame drawMotionFrame(GlContext& gl, int ss, const std::vector<Call>& calls, int k) const {
        const Layout L = layout();
        const bool labels = common_.hasLayer("labels");
        const Call& call = calls[k];
        const VClipResult& r = call.result;
        Canvas c(gl, mainOptions(ss));
        // Framed to hold B at every call, so the drawn calls share one framing.
        std::vector<Vec3> everyB;
        for (const Call& cc : calls)
            for (const Vec3& q : worldVertices(s_.b, cc.poseB)) everyB.push_back(q);
        setupMain(c, s_.view, call.poseB, 48.0, everyB);
        drawWalkBodies(c, walkBodies(call), common_.hasLayer("labels"));
        // B's path: its centre over every call, the part already travelled solid.
        std::vector<Vec3> path;
        for (const Call& cc : calls) path.push_back(cc.poseB.apply(s_.b.regions.mesh().centroid()));
        c.drawPolyline(path, false, lineStyle(Role::Muted, 1.5f, true, false));
        if (k > 0)
            c.drawPolyline(std::vector<Vec3>(path.begin(), path.begin() + k + 1), false,
                           lineStyle(Role::ShapeB, 2.0f, false, false));
        const std::vector<Vec3> ga = featureGeometry(s_.a.regions, s_.a.pose, r.featureA);
        const std::vector<Vec3> gb = featureGeometry(s_.b.regions, call.poseB, r.featureB);
        drawFeature(c, ga, featureNormals(s_.a, s_.a.pose, r.featureA), featureColor(0), featureLabel(r.featureA, 0),
                    centroidB(call.poseB), labels);
        drawFeature(c, gb, featureNormals(s_.b, call.poseB, r.featureB), featureColor(1), featureLabel(r.featureB, 1),
                    centroidA(), labels);
        if (common_.hasLayer("closest")) drawClosest(c, r.pointA, r.pointB, true);
        drawPanelHeading(c,
                         "Call " + std::to_string(k) + " of " + std::to_string(calls.size()) + ": " +
                             std::to_string(r.steps) + " update(s)",
                         std::string(k == 0 ? "first call, seeded with " : "warm start from ") + nameOf(call.seed.a) +
                             ", " + nameOf(call.seed.b));
        const Image main = c.readPixels();

        DiagramInput din;
        for (const VClipTraceStep& s : call.trace.steps) din.visits[stateIndex(s.state)]++;
        if (!call.trace.steps.empty()) din.current = stateIndex(call.trace.steps.back().state);
        if (call.trace.steps.size() >= 2) {
            const auto& s0 = call.trace.steps[call.trace.steps.size() - 2];
            din.from = stateIndex(s0.state);
            din.to = din.current;
        }
        din.heading = "States of this call";
        din.terminal = std::string(nameOf(r.status)) + " after " + std::to_string(r.steps) + " update(s)";
        const Image diagram = common_.hasLayer("diagram")
                                  ? drawStateDiagram(gl, L.columnWidth, L.diagramHeight(), ss, din)
                                  : blank(L.columnWidth, L.diagramHeight());

        Image plot = blank(L.columnWidth, L.plotHeight());
        if (common_.hasLayer("plot")) {
            PlotInput pd, ps;
            pd.heading = "Distance per call";
            pd.xLabel = "call";
            ps.heading = "Updates per call";
            ps.xLabel = "call";
            ps.integerY = true;
            PlotSeries d, g, s;
            d.lineColor = roleColor(Role::ShapeB);
            g.lineColor = roleColor(Role::Ink);
            s.bars = true;
            s.lineColor = roleColor(Role::Simplex);
            for (std::size_t i = 0; i < calls.size(); ++i) {
                d.x.push_back(double(i));
                d.y.push_back(calls[i].result.distance);
                s.x.push_back(double(i));
                s.y.push_back(calls[i].result.steps);
                s.pointColors.push_back(int(i) == k ? roleColor(Role::Highlight) : roleColor(Role::Simplex));
            }
            pd.series = {d};
            pd.marker = k;
            pd.legend = {{roleColor(Role::ShapeB), "V-Clip distance (= GJK)"}};
            ps.series = {s};
            ps.marker = k;
            const int h1 = L.plotHeight() / 2;
            plot = stackVertically(drawPlot(gl, L.columnWidth, h1, ss, pd),
                                   drawPlot(gl, L.columnWidth, L.plotHeight() - h1, ss, ps));
        }
        std::vector<std::string> lines;
        std::string states;
        for (const VClipTraceStep& s : call.trace.steps)
            states += std::string(states.empty() ? "" : " → ") + nameOf(s.state);
        lines.push_back("Call " + std::to_string(k) + ": " + nameOf(r.status) + ", features " +
                        featureLabel(r.featureA, 0) + ", " + featureLabel(r.featureB, 1) + ", distance " +
                        formatNumber(r.distance) + "  (GJK " +
                        (call.gjk.intersect() ? std::string("intersecting") : formatNumber(call.gjk.distance)) + ")");
        lines.push_back(std::string(k == 0 ? "first call, seeded with " : "started from the previous call's pair ") +
                        nameOf(call.seed.a) + ", " + nameOf(call.seed.b) + "; states: " + states);
        int total = 0;
        for (const Call& cc : calls) total += cc.result.steps;
        lines.push_back("B orbits " + formatNumber(s_.motion->orbitDegrees) + "° and spins " +
                        formatNumber(s_.motion->spinDegrees) +
                        "° per call; coherence: " + formatNumber(double(total) / calls.size()) +
                        " updates per call on average over " + std::to_string(calls.size()) + " calls");
        char name[32];
        std::snprintf(name, sizeof name, "call_%02d", k);
        return Frame{
            name,
            "call " + std::to_string(k) + ": " + std::to_string(r.steps) + " update(s), d " + formatNumber(r.distance),
            composeFrame(gl, L, ss, common_.title, common_.caption, main, diagram, plot, lines)};
    }
};

class VclipDemo final : public Demo {
public:
    std::string name() const override { return "vclip"; }
    std::string description() const override {
        return "V-Clip step by step: closest features of two polyhedra, Voronoi planes, edge clipping, the five "
               "states, coherence";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {800, 600, 2048, 1536}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        Settings s;
        readWalkSceneKeys(r, s);
        if (auto m = r.find("motion")) {
            ObjectReader mr(*m);
            Motion mo;
            if (auto n = mr.find("calls")) mo.calls = n->asInt(2, 400);
            // Angles per call: one turn at most (1e308 degrees has no usable sine).
            const auto degreesPerCall = [](const JsonNode& n) {
                const double d = n.asNumber();
                if (std::abs(d) > 360) n.fail("expected degrees per call in [-360, 360], got " + n.raw().dump());
                return d;
            };
            if (auto n = mr.find("center")) mo.center = sceneVec3(*n);
            if (auto n = mr.find("orbit_axis")) mo.orbitAxis = sceneVec3(*n);
            if (auto n = mr.find("orbit_degrees")) mo.orbitDegrees = degreesPerCall(*n);
            if (auto n = mr.find("spin_axis")) mo.spinAxis = sceneVec3(*n);
            if (auto n = mr.find("spin_degrees")) mo.spinDegrees = degreesPerCall(*n);
            if (auto n = mr.find("drawn_frames")) mo.drawnFrames = n->asInt(1, 60);
            mr.finish();
            if (mo.orbitAxis.squaredNorm() == 0 || mo.spinAxis.squaredNorm() == 0)
                m->fail("motion axes must be non-zero");
            s.motion = mo;
        }
        r.finish();
        return std::make_unique<VclipScene>(std::move(common), std::move(s));
    }
};

}  // namespace

const Demo& vclipDemo() {
    static const VclipDemo demo;
    return demo;
}

}  // namespace cdlab::demos
