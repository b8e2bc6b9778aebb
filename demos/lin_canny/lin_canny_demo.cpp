// Lin–Canny step-through (M. C. Lin, J. F. Canny, "A Fast Algorithm for Incremental Distance
// Calculation", ICRA 1991; Lin, PhD thesis 1993, ch. 3). Runs core's linCanny() once per scene and
// draws its LinCannyTrace; V-Clip (core's vclip()) and GJK run on the same pair for comparison. Every
// number drawn comes from the traces or results; this file adds only drawing geometry and layout.
// The drawing pieces (bodies, features, plane patches, frame composition, plots) are the V-Clip
// demo's (demos/draw/feature_walk_figure.h).
//
// Scene keys (besides the common ones in scene.h; docs/scenes.md, "lin_canny"):
//   "bodies": [A, B]          as in the vclip demo
//   "seed": ["V0", "F3"]      first feature pair of both walks (default: vertex 0 of each)
//   "view": [x, y, z]         view direction of the 3D panels
//   "max_step_frames": n      with "steps": at most n step frames (the first ones and the last)
//   "mode": "walk" | "side_by_side" | "cycling"
//   "applicability": t        LinCannyOptions::applicability (negative: a forced cycle, said so in the frames)
//   "inside_test": bool       LinCannyOptions::insideTest
//   "gif": bool
// Layers: "planes", "update", "closest", "labels", "list", "plot".
#include "demos/lin_canny/lin_canny_demo.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/feature_walk/lin_canny.h"
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

const std::vector<std::string> kLayers = {"planes", "update", "closest", "labels", "list", "plot"};

enum class Mode { Walk, SideBySide, Cycling };

struct Settings {
    Body a, b;
    std::optional<VClipCache> seed;
    Vec3 view = Vec3(1.0, 0.8, 1.7);
    int maxStepFrames = 8;
    bool gif = true;
    Mode mode = Mode::Walk;
    LinCannyOptions options;
};

/// Both algorithms and GJK on the scene's pair.
struct Runs {
    VClipCache seed;
    LinCannyResult lc;
    LinCannyTrace lcTrace;
    VClipResult vc;
    VClipTrace vcTrace;
    GjkResult gjk;
};

std::string pairText(const VClipFeature& a, const VClipFeature& b) { return nameOf(a) + "·" + nameOf(b); }

/// One row of a walk list: step number, the pair, its distance, the update (or the verdict).
struct ListRow {
    std::string text;
    Color color;
};

/// A list of the feature pairs visited, in pixel space: two columns when long; when it does not
/// fit, the first two rows, an ellipsis, and the last ones (where a cycle is).
Image drawWalkList(GlContext& gl, int W, int H, int ss, const std::string& heading, const std::string& sub,
                   const std::vector<ListRow>& rows, int current) {
    Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
    const Color ink = roleColor(Role::Ink);
    c.drawTextPx(12, 8, heading, TextStyle{17.0f, ink, Anchor::TopLeft, true, true});
    double top = 32;
    if (!sub.empty()) {
        c.drawTextPx(12, top, sub,
                     TextStyle{13.0f, ink.mixed(roleColor(Role::Muted), 0.4f), Anchor::TopLeft, false, false});
        top += 20;
    }
    const double rowH = 17;
    const int perColumn = std::max(1, int((H - top - 4) / rowH));
    const int columns = W >= 360 ? 2 : 1;
    const int capacity = perColumn * columns;
    std::vector<int> shown;  // row index, -1 = ellipsis
    const int n = int(rows.size());
    if (n <= capacity) {
        for (int i = 0; i < n; ++i) shown.push_back(i);
    } else {
        shown = {0, 1, -1};
        for (int i = n - (capacity - 3); i < n; ++i) shown.push_back(i);
    }
    for (int k = 0; k < int(shown.size()); ++k) {
        const int col = k / perColumn, row = k % perColumn;
        const double x = 12 + col * (W - 12) / double(columns), y = top + row * rowH;
        const int i = shown[k];
        if (i < 0) {
            c.drawTextPx(x, y, "… " + std::to_string(n - capacity + 1) + " more …",
                         TextStyle{13.0f, roleColor(Role::Muted).scaled(0.7f), Anchor::TopLeft, false, false});
            continue;
        }
        const bool now = i == current;
        c.drawTextPx(x, y, (now ? "> " : "   ") + rows[i].text,
                     TextStyle{13.0f, now ? roleColor(Role::Highlight).scaled(0.8f) : rows[i].color, Anchor::TopLeft,
                               false, now});
    }
    return c.readPixels();
}

Color changeColor(int change, bool localMinimum) {
    return localMinimum  ? clipColor()
           : change < 0  ? satisfiedColor()
           : change == 0 ? roleColor(Role::Muted)
                         : violatedColor();
}

/// Pair distance per update of a walk: x = update count, y = distance of the pair after it.
template <class Trace>
PlotSeries distanceSeries(const Trace& tr, const Color& line) {
    PlotSeries s;
    s.lineColor = line;
    if (tr.steps.empty()) return s;
    s.x.push_back(0);
    s.y.push_back(tr.steps.front().distanceBefore);
    s.pointColors.push_back(line);
    for (const auto& st : tr.steps) {
        if (st.updatedBody < 0) continue;
        s.x.push_back(st.step + 1);
        s.y.push_back(st.distanceAfter);
        s.pointColors.push_back(changeColor(st.distanceChange, st.localMinimum));
    }
    return s;
}

Image blank(int w, int h) {
    Image im(w, h);
    std::fill(im.rgba.begin(), im.rgba.end(), std::uint8_t(255));
    return im;
}

class LinCannyScene final : public PreparedScene {
public:
    LinCannyScene(SceneCommon common, Settings s) : PreparedScene(std::move(common)), s_(std::move(s)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const Runs r = compute();
        DemoOutput out;
        out.trace = traceJson(r);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        std::vector<Vec3> pts;
        for (const Vec3& p : s_.a.regions.mesh().positions()) pts.push_back(s_.a.pose.apply(p));
        for (const Vec3& p : s_.b.regions.mesh().positions()) pts.push_back(s_.b.pose.apply(p));
        boundingSphere(pts, center_, radius_);

        if (s_.mode == Mode::SideBySide) {
            out.frames.push_back(drawSideBySide(*ctx.gl, ss, r));
            out.skipped.push_back("step frames (side_by_side draws one frame)");
            return out;
        }
        const std::vector<int> framed = framedSteps(int(r.lcTrace.steps.size()), s_.maxStepFrames);
        if (common_.steps || ctx.stepsOverride)
            for (int i : framed) out.frames.push_back(drawStepFrame(*ctx.gl, ss, r, i));
        out.frames.push_back(drawStepFrame(*ctx.gl, ss, r, -1));
        std::vector<const Frame*> animated;
        for (const Frame& f : out.frames) animated.push_back(&f);
        if (s_.gif && animated.size() > 1) addGif(out, animated, 2);
        else if (s_.gif) out.skipped.push_back("animation.gif (a single frame)");
        if ((common_.steps || ctx.stepsOverride) && animated.size() > 1) {
            ContactSheetOptions o;
            o.caption = common_.caption;
            // Which steps the sheet leaves out (max_step_frames), from the trace.
            o.title = "Lin–Canny: " + iterationCoverage(int(r.lcTrace.steps.size()), framed, "step", 0);
            const bool many = animated.size() > 6;
            o.cellWidth = common_.image.width / (many ? 5 : 4) + 1;
            o.columns = many ? 4 : 3;
            out.frames.push_back(contactSheetFrame(*ctx.gl, animated, common_.title, o));
        }
        return out;
    }

private:
    Settings s_;
    mutable Vec3 center_ = Vec3::Zero();
    mutable double radius_ = 1.0;

    bool forced() const { return s_.options.applicability < 0; }

    Runs compute() const {
        Runs r;
        r.seed = s_.seed ? *s_.seed : VClipCache{VClipFeature::vertex(0), VClipFeature::vertex(0)};
        VClipCache lcCache = r.seed, vcCache = r.seed;
        r.lc = linCanny(s_.a.regions, s_.a.pose, s_.b.regions, s_.b.pose, &lcCache, s_.options, &r.lcTrace);
        r.vc = vclip(s_.a.regions, s_.a.pose, s_.b.regions, s_.b.pose, &vcCache, VClipOptions{}, &r.vcTrace);
        const Transformed<PolytopeShape> sa{PolytopeShape(s_.a.regions.mesh()), s_.a.pose};
        const Transformed<PolytopeShape> sb{PolytopeShape(s_.b.regions.mesh()), s_.b.pose};
        r.gjk = gjkDistance(sa, sb);
        return r;
    }

    // ------------------------------------------------------------------------------- trace JSON

    Json traceJson(const Runs& r) const {
        Json steps = Json::array();
        for (const LinCannyTraceStep& st : r.lcTrace.steps) steps.push_back(walkStepJson(st));
        Json vcPairs = Json::array();
        for (const VClipTraceStep& st : r.vcTrace.steps) vcPairs.push_back(pairText(st.featureA, st.featureB));
        Json lc = walkResultJson(r.lc);
        lc["cycle_length"] = r.lc.cycleLength;
        lc["applicability"] = s_.options.applicability;
        lc["inside_test"] = s_.options.insideTest;
        lc["trace"] = steps;
        return {{"lin_canny", lc},
                {"vclip",
                 {{"status", nameOf(r.vc.status)},
                  {"penetration", nameOf(r.vc.penetration)},
                  {"distance", r.vc.distance},
                  {"feature_a", featureJson(r.vc.featureA)},
                  {"feature_b", featureJson(r.vc.featureB)},
                  {"steps", r.vc.steps},
                  {"pairs", vcPairs}}},
                {"seed", {featureJson(r.seed.a), featureJson(r.seed.b)}},
                {"gjk_distance", r.gjk.distance},
                {"gjk_intersect", r.gjk.intersect()}};
    }

    // ---------------------------------------------------------------------------------- drawing

    Layout layout() const { return Layout{common_.image.width, common_.image.height}; }

    /// `view`: the scene's (none), or the walk's (chooseWalkView).
    Camera camera(double shiftUp, double zoom, const std::optional<Vec3>& view = std::nullopt) const {
        if (common_.camera) return *common_.camera;
        Camera cam = framingCamera(center_, radius_ * zoom, view ? *view : s_.view, Vec3::UnitY(), true);
        const Vec3 forward = (cam.target - cam.eye).normalized();
        const Vec3 screenUp = (Vec3::UnitY() - Vec3::UnitY().dot(forward) * forward).normalized();
        cam.eye += screenUp * shiftUp * radius_;
        cam.target += screenUp * shiftUp * radius_;
        return cam;
    }

    /// Do both bodies' vertices project inside the canvas, `top` px below its top edge (verticesInside)?
    bool bodiesInside(const Canvas& c, double top) const {
        return verticesInside(c, worldVertices(s_.a, s_.a.pose), top) &&
               verticesInside(c, worldVertices(s_.b, s_.b.pose), top);
    }

    /// shiftUp: the view moves down by this fraction of the scene radius (room for the panel
    /// heading); zoom: the fraction of the scene's bounding sphere that is framed.
    void setupPanel(Canvas& c, double shiftUp, double zoom, const std::optional<Vec3>& view = std::nullopt) const {
        c.setCamera(camera(shiftUp, zoom, view));
    }

    const Body& body(int i) const { return i == 0 ? s_.a : s_.b; }
    const Transform& pose(int i) const { return i == 0 ? s_.a.pose : s_.b.pose; }
    Vec3 centroid(int i) const { return pose(i).apply(body(i).regions.mesh().centroid()); }
    Color featureColor(int i) const { return roleColor(i == 0 ? Role::ShapeA : Role::ShapeB).scaled(0.8f); }

    /// The walk's bodies, apart when `apart` (the walk found them separated).
    WalkBodies walkBodies(bool apart) const { return {&s_.a, s_.a.pose, &s_.b, s_.b.pose, apart}; }

    void drawClosest(Canvas& c, const Vec3& pa, const Vec3& pb, bool named) const {
        drawClosestPoints(c, pa, pb, named && common_.hasLayer("labels"), radius_);
    }

    std::vector<ListRow> lcRows(const LinCannyTrace& tr) const {
        std::vector<ListRow> rows;
        for (const LinCannyTraceStep& st : tr.steps) {
            std::string t = std::to_string(st.step) + "  " + pairText(st.featureA, st.featureB) + "  " +
                            formatNumber(st.distanceBefore);
            if (st.updatedBody >= 0)
                t += std::string("  ") + (st.updatedBody == 0 ? "A " : "B ") + nameOf(st.from) + "→" + nameOf(st.to);
            else t += std::string("  ") + nameOf(st.kind);
            rows.push_back({t, st.updatedBody >= 0 ? changeColor(st.distanceChange, st.localMinimum).scaled(0.75f)
                                                   : roleColor(Role::Ink)});
        }
        return rows;
    }

    std::vector<ListRow> vcRows(const VClipTrace& tr) const {
        std::vector<ListRow> rows;
        for (const VClipTraceStep& st : tr.steps) {
            std::string t = std::to_string(st.step) + "  " + pairText(st.featureA, st.featureB) + "  " +
                            formatNumber(st.distanceBefore);
            if (st.kind == VClipStepKind::Update && st.updatedBody >= 0)
                t += std::string("  ") + (st.updatedBody == 0 ? "A " : "B ") + nameOf(st.from) + "→" + nameOf(st.to);
            else t += std::string("  ") + nameOf(st.kind);
            rows.push_back({t, st.kind == VClipStepKind::Update
                                   ? changeColor(st.distanceChange, st.localMinimum).scaled(0.75f)
                                   : roleColor(Role::Ink)});
        }
        return rows;
    }

    std::string verdict(const LinCannyResult& r) const {
        if (r.status == LinCannyStatus::Separated) return "Separated, distance " + formatNumber(r.distance);
        if (r.status == LinCannyStatus::Penetrating) return std::string("Penetrating (") + nameOf(r.penetration) + ")";
        if (r.status == LinCannyStatus::CycleDetected)
            return "CycleDetected (cycle of " + std::to_string(r.cycleLength) + " pairs)";
        return nameOf(r.status);
    }
    std::string verdict(const VClipResult& r) const {
        if (r.status == VClipStatus::Separated) return "Separated, distance " + formatNumber(r.distance);
        if (r.status == VClipStatus::Penetrating) return std::string("Penetrating (") + nameOf(r.penetration) + ")";
        return nameOf(r.status);
    }
    std::string gjkText(const GjkResult& g) const {
        return g.intersect() ? std::string("intersecting") : formatNumber(g.distance);
    }

    Frame drawStepFrame(GlContext& gl, int ss, const Runs& run, int index) const {
        const Layout L = layout();
        const LinCannyTrace& tr = run.lcTrace;
        const LinCannyResult& r = run.lc;
        const LinCannyTraceStep* st = index >= 0 ? &tr.steps[index] : nullptr;
        Canvas c(gl, canvasOptions(L.mainWidth(), L.panelHeight(), ss));
        // One view for the walk's frames, near the scene's; a step whose new feature it shows from
        // behind swings round to it (demos/draw/feature_walk_figure.h, chooseWalkView).
        const WalkBodies w = walkBodies(r.status == LinCannyStatus::Separated);
        std::vector<WalkStepFeatures> steps;
        for (const LinCannyTraceStep& t : tr.steps) steps.push_back({t.featureA, t.featureB, t.updatedBody, t.to});
        std::optional<Vec3> view = chooseWalkView(w, s_.view, steps, 180.0);
        if (st) view = stepView(w, *view, steps[std::size_t(index)]);
        // Pulled back until both bodies are whole below the heading and a step's plane key, which
        // ends 86 px down (BodyCutByPanel; the gate found B's edges through the key).
        double zoom = 0.92;
        setupPanel(c, 0.12, zoom, view);
        // The step's plane patches are kept whole too (the review found them cut).
        const std::vector<Vec3> patches =
            st && common_.hasLayer("planes") ? drawnPatchPoints(w, st->planes, radius_) : std::vector<Vec3>{};
        for (int k = 0; k < 16 && !(bodiesInside(c, 92.0) && verticesInside(c, patches, 92.0));  // result as steps
             ++k)
            setupPanel(c, 0.12, zoom *= 1.04, view);
        drawWalkBodies(c, walkBodies(r.status == LinCannyStatus::Separated), common_.hasLayer("labels"));
        Frame f;
        std::vector<std::string> lines;
        if (st) {
            const int shown = drawStep(c, *st);
            lines = describeStep(c, *st, r, shown, f);
        } else {
            drawResult(c, r, tr);
            lines = describeResult(c, run, f);
        }
        const Image main = c.readPixels();

        const int cur = st ? index : int(tr.steps.size()) - 1;
        std::string listSub = forced() ? "cycle forced (negative tolerance)" : "";
        if (r.status == LinCannyStatus::CycleDetected)
            listSub = "the last " + std::to_string(r.cycleLength) + " rows repeat" + (forced() ? " (forced)" : "");
        const Image list = common_.hasLayer("list")
                               ? drawWalkList(gl, L.columnWidth, L.diagramHeight(), ss, "Pairs visited (A·B, distance)",
                                              listSub, lcRows(tr), cur)
                               : blank(L.columnWidth, L.diagramHeight());
        const Image plot = common_.hasLayer("plot") ? drawDistancePlot(gl, ss, tr, st ? index : -1)
                                                    : blank(L.columnWidth, L.plotHeight());
        f.image = composeFrame(gl, L, ss, common_.title, common_.caption, main, list, plot, lines);
        return f;
    }

    /// A step in the 3D panel: the pair's features, the plane tests, the closest points, the update.
    /// Returns how many plane tests were drawn.
    int drawStep(Canvas& c, const LinCannyTraceStep& step) const {
        const bool labels = common_.hasLayer("labels");
        const bool update = common_.hasLayer("update") && step.updatedBody >= 0;
        const std::vector<Vec3> gTo =
            update ? featureGeometry(body(step.updatedBody).regions, pose(step.updatedBody), step.to) : std::vector<Vec3>{};
        const auto drawNew = [&](bool firstPass) {  // drawNewFeature: a face now, an edge or vertex last
            if (update)
                drawNewFeature(c, gTo, featureNormals(body(step.updatedBody), pose(step.updatedBody), step.to),
                               featureColor(step.updatedBody), "new " + featureLabel(step.to, step.updatedBody),
                               firstPass);
        };
        drawNew(true);
        drawFeature(c, step.featureAWorld, featureNormals(s_.a, s_.a.pose, step.featureA), featureColor(0), featureLabel(step.featureA, 0), centroid(1), labels);
        drawFeature(c, step.featureBWorld, featureNormals(s_.b, s_.b.pose, step.featureB), featureColor(1), featureLabel(step.featureB, 1), centroid(0), labels);
        int shown = 0;
        if (common_.hasLayer("planes"))
            for (const VClipPlaneTest& p : step.planes) {
                if (!planeTestDrawn(step.planes, p)) continue;  // the sub-heading says how many are drawn
                drawPlaneTest(c, body(p.regionBody), pose(p.regionBody), p.plane, p.owner, p.testedPoint,
                              p.signedDistance, p.planeNormal, p.violated, p.maximal, radius_);
                ++shown;
            }
        if (common_.hasLayer("closest")) drawClosest(c, step.closestA, step.closestB, false);
        if (update) {
            const Vec3 from = featureCenter(step.updatedBody == 0 ? step.featureAWorld : step.featureBWorld),
                       to = featureCenter(gTo);
            drawUpdateArrow(c, from, to, radius_);
            drawNew(false);
            if (labels)
                drawLabelAway(c, to, from, "new " + featureLabel(step.to, step.updatedBody),
                              TextStyle{16.0f, roleColor(Role::Ink), Anchor::Center, true, true}, 12.0,
                              featureLabelPoints(gTo));
        }
        return shown;
    }

    /// The 3D panel's heading and the caption lines of a step; names the frame.
    std::vector<std::string> describeStep(Canvas& c, const LinCannyTraceStep& step, const LinCannyResult& r, int shown,
                                          Frame& f) const {
        int violatedCount = 0;
        for (const VClipPlaneTest& p : step.planes) violatedCount += p.violated;
        std::string heading, sub;
        std::vector<std::string> lines;
        heading = "Step " + std::to_string(step.step) + ": pair " + nameOf(step.state);
        sub = std::to_string(step.planes.size()) + " applicability test(s), " + std::to_string(violatedCount) +
              " violated";
        if (common_.hasLayer("labels") && shown > 0)
            drawKey(c, 14, 64, planeKey());
        if (int(step.planes.size()) > shown) sub += "; " + std::to_string(shown) + " drawn";
        lines.push_back("Step " + std::to_string(step.step) + " (" + nameOf(step.state) +
                        "): " + featureLabel(step.featureA, 0) + " vs " + featureLabel(step.featureB, 1) +
                        ", closest points at distance " + formatNumber(step.distanceBefore) + ";  rule: " + step.rule);
        const VClipPlaneTest* worst = nullptr;
        for (const VClipPlaneTest& p : step.planes)
            if (!worst || (p.maximal && !worst->maximal) ||
                (p.maximal == worst->maximal && p.signedDistance < worst->signedDistance))
                worst = &p;
        if (!worst) lines.push_back("no plane test");
        else
            lines.push_back(std::string(worst->regionBody == 0 ? "p_B" : "p_A") + " against VR(" +
                            featureLabel(worst->owner, worst->regionBody) + "): " +
                            (worst->maximal    ? "most violated"
                             : worst->violated ? "violated"
                                               : "closest") +
                            " plane " +
                            (worst->plane < 0 ? std::string("(the face plane)") : "| " + nameOf(worst->neighbor)) +
                            " at signed distance " + formatNumber(worst->signedDistance) +
                            (!worst->violated            ? " ≥ 0"
                             : worst->signedDistance < 0 ? " < 0"
                                                         : " ≥ 0, violated only by the forced negative tolerance"));
        if (step.updatedBody >= 0)
            lines.push_back(std::string("update ") + (step.updatedBody == 0 ? "A: " : "B: ") + nameOf(step.from) +
                            " → " + nameOf(step.to) + ";  pair distance " + formatNumber(step.distanceBefore) + " → " +
                            formatNumber(step.distanceAfter) +
                            (step.localMinimum          ? " (local-minimum face jump)"
                             : step.distanceChange < 0  ? " (decreased)"
                             : step.distanceChange == 0 ? " (equal)"
                                                        : " (INCREASED)"));
        else if (step.kind == VClipStepKind::Done)
            lines.push_back(
                "DONE: each closest point lies in the other feature's Voronoi region (Lin & Canny, Thm. 1)");
        else lines.push_back(std::string(nameOf(step.kind)) + ": " + verdict(r));
        f.name = stepFrameName(step.step);
        f.caption =
            "step " + std::to_string(step.step) + " " + nameOf(step.state) + ": " +
            (step.updatedBody >= 0 ? nameOf(step.from) + " → " + nameOf(step.to) : std::string(nameOf(step.kind)));
        drawPanelHeading(c, heading, sub);
        return lines;
    }

    /// The result in the 3D panel: the final features and closest points; a cycle's features all,
    /// with the updates that go round it (the review: only the last pair of a two-pair cycle).
    void drawResult(Canvas& c, const LinCannyResult& r, const LinCannyTrace& tr) const {
        const bool labels = common_.hasLayer("labels");
        if (r.status == LinCannyStatus::CycleDetected && r.cycleLength >= 2 &&
            std::size_t(r.cycleLength) <= tr.steps.size()) {
            std::vector<std::pair<int, VClipFeature>> drawn;  // (body, feature) once each
            const auto feature = [&](int body, const VClipFeature& f) {
                for (const auto& [b, g] : drawn)
                    if (b == body && g.type == f.type && g.index == f.index) return;
                drawn.push_back({body, f});
                const std::vector<Vec3> g = featureGeometry(body == 0 ? s_.a.regions : s_.b.regions, pose(body), f);
                drawFeature(c, g, featureNormals(body == 0 ? s_.a : s_.b, pose(body), f), featureColor(body),
                            featureLabel(f, body), centroid(1 - body), labels);
            };
            for (std::size_t k = tr.steps.size() - std::size_t(r.cycleLength); k < tr.steps.size(); ++k) {
                const LinCannyTraceStep& st = tr.steps[k];
                feature(0, st.featureA);
                feature(1, st.featureB);
                if (st.updatedBody < 0) continue;
                const VClipPolyhedron& regions = st.updatedBody == 0 ? s_.a.regions : s_.b.regions;
                drawUpdateArrow(c, featureCenter(featureGeometry(regions, pose(st.updatedBody), st.from)),
                                featureCenter(featureGeometry(regions, pose(st.updatedBody), st.to)), radius_);
            }
            return;
        }
        const std::vector<Vec3> ga = featureGeometry(s_.a.regions, s_.a.pose, r.featureA);
        const std::vector<Vec3> gb = featureGeometry(s_.b.regions, s_.b.pose, r.featureB);
        drawFeature(c, ga, featureNormals(s_.a, s_.a.pose, r.featureA), featureColor(0), featureLabel(r.featureA, 0),
                    centroid(1), labels);
        drawFeature(c, gb, featureNormals(s_.b, s_.b.pose, r.featureB), featureColor(1), featureLabel(r.featureB, 1),
                    centroid(0), labels);
        if (common_.hasLayer("closest") && r.status != LinCannyStatus::CycleDetected)
            drawClosest(c, r.pointA, r.pointB, true);
    }

    /// The 3D panel's heading and the caption lines of the result, beside V-Clip and GJK; names the frame.
    std::vector<std::string> describeResult(Canvas& c, const Runs& run, Frame& f) const {
        const LinCannyResult& r = run.lc;
        std::string heading, sub;
        std::vector<std::string> lines;
        heading = std::string("Result: ") + nameOf(r.status) + " after " + std::to_string(r.steps) + " update(s)";
        sub = r.status == LinCannyStatus::Separated       ? "closest features and points"
              : r.status == LinCannyStatus::CycleDetected ? "the cycle's features; arrows: its updates"
                                                          : "";
        lines.push_back("Lin–Canny: " + verdict(r) + ", features " + featureLabel(r.featureA, 0) + " and " +
                        featureLabel(r.featureB, 1) + ", " + std::to_string(r.steps) + " update(s)");
        lines.push_back("V-Clip on the same pair and seed: " + verdict(run.vc) + ", features " +
                        featureLabel(run.vc.featureA, 0) + " and " + featureLabel(run.vc.featureB, 1) + ", " +
                        std::to_string(run.vc.steps) + " update(s);  GJK: " + gjkText(run.gjk));
        if (forced())
            lines.push_back("cycle FORCED with a negative applicability tolerance (" +
                            formatNumber(s_.options.applicability) +
                            " × scale): boundary points violate both regions; not a natural cycle");
        else if (r.status == LinCannyStatus::Separated)
            lines.push_back("|Lin–Canny − GJK| = " + formatNumber(std::abs(r.distance - run.gjk.distance)) +
                            ",  |Lin–Canny − V-Clip| = " + formatNumber(std::abs(r.distance - run.vc.distance)));
        f.name = "result";
        f.caption = std::string("result: ") + verdict(r);
        drawPanelHeading(c, heading, sub);
        return lines;
    }

    /// The pair distance against the update, `marker` the current step (-1: none).
    Image drawDistancePlot(GlContext& gl, int ss, const LinCannyTrace& tr, int marker) const {
        const Layout L = layout();
        PlotInput pin;
        pin.heading = "Pair distance";
        pin.xLabel = "update";
        pin.series.push_back(distanceSeries(tr, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f)));
        pin.marker = marker;
        pin.legend = {{satisfiedColor(), "decrease"}, {roleColor(Role::Muted), "equal"}};
        if (std::any_of(tr.steps.begin(), tr.steps.end(),
                        [](const LinCannyTraceStep& s) { return s.distanceChange > 0 && !s.localMinimum; }))
            pin.legend.push_back({violatedColor(), "increase"});
        if (std::any_of(tr.steps.begin(), tr.steps.end(), [](const LinCannyTraceStep& s) { return s.localMinimum; }))
            pin.legend.push_back({clipColor(), "local-min jump"});
        return drawPlot(gl, L.columnWidth, L.plotHeight(), ss, pin);
    }

    /// One walk in 3D: the bodies, the path of the closest points over the steps, the final features.
    template <class Trace>
    Image walkPanel(GlContext& gl, int w, int h, int ss, const Trace& tr, const VClipFeature& fa,
                    const VClipFeature& fb, const Vec3& pa, const Vec3& pb, bool closest, const std::string& heading,
                    const std::string& sub) const {
        Canvas c(gl, canvasOptions(w, h, ss));
        // Framed as close as the panel allows with both bodies whole below its heading (the view
        // rule: no body cut by its panel's edge; at 0.80 the review found box A cut at the bottom).
        double zoom = 0.80;
        setupPanel(c, 0.28, zoom);
        for (int k = 0; k < 24 && !bodiesInside(c, 96.0); ++k) setupPanel(c, 0.28, zoom *= 1.03);
        drawWalkBodies(c, walkBodies(closest), common_.hasLayer("labels"));  // closest points: apart
        const bool labels = common_.hasLayer("labels");
        drawFeature(c, featureGeometry(s_.a.regions, s_.a.pose, fa), featureNormals(s_.a, s_.a.pose, fa), featureColor(0),
                    featureLabel(fa, 0), centroid(1), labels);
        drawFeature(c, featureGeometry(s_.b.regions, s_.b.pose, fb), featureNormals(s_.b, s_.b.pose, fb), featureColor(1),
                    featureLabel(fb, 1), centroid(0), labels);
        std::vector<Vec3> pathA, pathB;
        for (const auto& st : tr.steps) {
            pathA.push_back(st.closestA);
            pathB.push_back(st.closestB);
        }
        for (int side = 0; side < 2; ++side) {
            const std::vector<Vec3>& path = side == 0 ? pathA : pathB;
            LineStyle ls = lineStyle(side == 0 ? Role::ShapeA : Role::ShapeB, 2.0f, false, true);
            ls.color = featureColor(side).scaled(0.8f);
            if (path.size() > 1) c.drawPolyline(path, false, ls);
            for (const Vec3& p : path) c.drawPoint(p, 3.5f, featureColor(side), true, 1.0f, roleColor(Role::Ink));
        }
        if (closest && common_.hasLayer("closest")) drawClosest(c, pa, pb, false);
        drawPanelHeading(c, heading, sub);
        return c.readPixels();
    }

    Frame drawSideBySide(GlContext& gl, int ss, const Runs& r) const {
        const int W = common_.image.width, H = common_.image.height;
        const int titleBand = 40, captionBand = 80, half = W / 2;
        const int panelH = H - titleBand - captionBand;
        const int top3d = panelH * 55 / 100, listH = panelH * 21 / 100, plotH = panelH - top3d - listH;
        const Image vc3 = walkPanel(gl, half, top3d, ss, r.vcTrace, r.vc.featureA, r.vc.featureB, r.vc.pointA,
                                    r.vc.pointB, r.vc.status == VClipStatus::Separated,
                                    "V-Clip: " + std::to_string(r.vc.steps) + " update(s)", verdict(r.vc));
        const Image lc3 = walkPanel(gl, W - half, top3d, ss, r.lcTrace, r.lc.featureA, r.lc.featureB, r.lc.pointA,
                                    r.lc.pointB, r.lc.status == LinCannyStatus::Separated,
                                    "Lin–Canny: " + std::to_string(r.lc.steps) + " update(s)", verdict(r.lc));
        const bool lists = common_.hasLayer("list");
        // The first row where the two walks update differently, marked in both lists and on the
        // plot (the review: nothing showed where E7 → V2 and E7 → F5 part).
        const std::vector<ListRow> vRows = vcRows(r.vcTrace), lRows = lcRows(r.lcTrace);
        int split = -1;
        for (std::size_t i = 0; split < 0 && i < std::min(vRows.size(), lRows.size()); ++i)
            if (vRows[i].text != lRows[i].text) split = int(i);
        const Image vcl =
            lists ? drawWalkList(gl, half, listH, ss, "V-Clip pairs (A·B, distance)", "", vRows, split)
                  : blank(half, listH);
        const Image lcl =
            lists ? drawWalkList(gl, W - half, listH, ss, "Lin–Canny pairs (A·B, distance)", "", lRows, split)
                  : blank(W - half, listH);
        Image plot = blank(W, plotH);
        if (common_.hasLayer("plot")) {
            PlotInput pin;
            pin.heading = split < 0 ? "Pair distance per update"
                                    : "Pair distance per update (dashed, and > in the lists: where the walks part)";
            pin.xLabel = "update";
            PlotSeries v = distanceSeries(r.vcTrace, roleColor(Role::Simplex));
            PlotSeries l = distanceSeries(r.lcTrace, roleColor(Role::Highlight));
            for (Color& col : v.pointColors) col = roleColor(Role::Simplex);
            for (Color& col : l.pointColors) col = roleColor(Role::Highlight);
            pin.series = {v, l};
            pin.legend = {{roleColor(Role::Simplex), "V-Clip"}, {roleColor(Role::Highlight), "Lin–Canny"}};
            pin.marker = split;
            plot = drawPlot(gl, W, plotH, ss, pin);
        }
        Canvas canvas(gl, canvasOptions(W, H, ss), Camera::twoD(0, 0, 1));
        canvas.drawTextPx(16, 8, common_.title, TextStyle{22.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
        double y = H - captionBand + 5;
        const Color soft = roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.55f);
        if (!common_.caption.empty())
            canvas.drawTextPx(16, y, common_.caption, TextStyle{16.0f, soft, Anchor::TopLeft, false, false});
        y += 25;
        canvas.drawTextPx(16, y,
                          "Same seed " + pairText(r.seed.a, r.seed.b) + ":  V-Clip " + verdict(r.vc) + " in " +
                              std::to_string(r.vc.steps) + " update(s);  Lin–Canny " + verdict(r.lc) + " in " +
                              std::to_string(r.lc.steps) + " update(s);  GJK " + gjkText(r.gjk),
                          TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += 25;
        canvas.drawTextPx(16, y,
                          "Dots: the pair's closest points at each step. V-Clip tests edges by clipping them; "
                          "Lin–Canny tests the pair's closest points only.",
                          TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        Image frame = canvas.readPixels();
        blit(frame, vc3, 0, titleBand);
        blit(frame, lc3, half, titleBand);
        blit(frame, vcl, 0, titleBand + top3d);
        blit(frame, lcl, half, titleBand + top3d);
        blit(frame, plot, 0, titleBand + top3d + listH);
        // 2-pixel rules between the panels.
        const Color m = roleColor(Role::Muted);
        paintRect(frame, half - 1, titleBand, 2, top3d + listH, m);
        paintRect(frame, 0, titleBand + top3d - 1, W, 2, m);
        paintRect(frame, 0, titleBand + top3d + listH - 1, W, 2, m);
        return Frame{
            "side_by_side",
            "V-Clip " + std::to_string(r.vc.steps) + " vs Lin–Canny " + std::to_string(r.lc.steps) + " update(s)",
            std::move(frame)};
    }
};

class LinCannyDemo final : public Demo {
public:
    std::string name() const override { return "lin_canny"; }
    std::string description() const override {
        return "Lin–Canny step by step: applicability tests, closest points of the feature pair, the walk beside "
               "V-Clip, a (forced) cycle";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {800, 600, 2048, 1536}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        Settings s;
        readWalkSceneKeys(r, s);
        if (auto m = r.find("mode")) {
            const std::string mode = m->asString();
            if (mode == "walk") s.mode = Mode::Walk;
            else if (mode == "side_by_side") s.mode = Mode::SideBySide;
            else if (mode == "cycling") s.mode = Mode::Cycling;
            else m->fail("expected \"walk\", \"side_by_side\" or \"cycling\"");
        }
        if (auto t = r.find("applicability")) {
            s.options.applicability = t->asNumber();
            if (!std::isfinite(s.options.applicability) || std::abs(s.options.applicability) > 0.5)
                t->fail("expected a number in [-0.5, 0.5]");
        }
        s.options.insideTest = r.boolOr("inside_test", false);
        r.finish();
        if (s.options.applicability < 0 && s.mode != Mode::Cycling)
            r.node().fail(
                "a negative \"applicability\" forces cycles: only with \"mode\": \"cycling\", whose frames say it is "
                "forced");
        return std::make_unique<LinCannyScene>(std::move(common), std::move(s));
    }
};

}  // namespace

const Demo& linCannyDemo() {
    static const LinCannyDemo demo;
    return demo;
}

}  // namespace cdlab::demos
