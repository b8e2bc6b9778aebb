// Rigid-body drop step-through. Every number comes from core's simulateDrop and its per-step trace
// (state, manifold with impulses, energies, penetration); this file only chooses frames and draws.
//
// Scene keys (besides the common ones):
//   "body": any body of app/scene/body_scene.h: box, tetrahedron, icosahedron, prism, or a
//           {"polytope": {"vertices": [...]}} of your own (its hull, recentred at its centre of mass)
//   "density", "position", "rotation" [w,x,y,z], "velocity", "angular_velocity" (world, rad/s),
//   "gravity" (m/s² along −z; the ground is the plane z = 0),
//   "simulation": {"time_step", "duration", "restitution", "friction", "restitution_threshold",
//                  "iterations", "slop"},
//   "frame_every" (steps between frames), "view" (camera direction, z up).
// Layers: "ground", "shadow", "trail", "contacts", "labels", "plot".
// Frames: frame_NN (every frame_every steps from step 0, and the first step of each impact, captioned
// with the normal velocity before and after it; the scene's camera on the left, a low side view
// looking horizontally on the right), "energy" (plot), with "steps" a contact sheet.
#include "demos/drop/drop_demo.h"

#include "demos/drop/impulse_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "core/dynamics/simulation.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/polyhedron_presets.h"
#include "demos/draw/contact_sheet.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/step_frames.h"
#include "app/scene/body_scene.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"ground", "shadow", "trail", "contacts", "labels", "plot"};
constexpr int kMaxFrames = 16;  // frames (plus plot and sheet) per scene: golden size and render time
constexpr double kSideWidth = 0.45;  // the low side view's width, of the main view's
constexpr int kSideHeading = 70;     // px at the side view's top for its heading

Json quatJson(const Quat& q) { return Json::array({q.w(), q.x(), q.y(), q.z()}); }

// Energy (top) and penetration on a log scale (bottom) against time, drawn in pixel units (y up)
// on one time axis; the frames drawn as figures are ticked on it.
class TimePlot {
public:
    TimePlot(Canvas& c, const SimulationTrace& tr, const std::vector<int>& frameSteps, int W, int H)
        : c_(c), tr_(tr), frameSteps_(frameSteps), x1_(W - 40), tMax_(tr.steps.back().time), H_(H) {}

    void energyPanel() {
        double eLo = 0.0, eHi = 0.0;
        for (const SimulationStep& s : tr_.steps) {
            eLo = std::min({eLo, s.kinetic, s.potential, s.energy});
            eHi = std::max({eHi, s.kinetic, s.potential, s.energy});
        }
        if (!(eHi > eLo)) eHi = eLo + 1.0;
        const double eY0 = H_ * 0.50, eY1 = H_ - 95;
        const auto YE = [&](double v) { return eY0 + (v - eLo) / (eHi - eLo) * (eY1 - eY0); };
        c_.drawLine(P(x0_, eY0), P(x0_, eY1), axis_);
        c_.noteAxis(P(x0_, eY0), P(x0_, eY1), false);
        lx_ = x1_ - 300;
        ly_ = eY1 - 12;
        const std::vector<std::string> names = {"total E = KE + PE", "kinetic KE", "potential PE"};
        reserveLegend(names);
        // Round tick values (1, 2 or 5 times a power of ten), 4 to 7 of them.
        const double raw = (eHi - eLo) / 6.0, decade = std::pow(10.0, std::floor(std::log10(raw)));
        const double step = raw / decade <= 1.0 ? decade : raw / decade <= 2.0 ? 2 * decade : raw / decade <= 5.0 ? 5 * decade : 10 * decade;
        const double first = std::ceil(eLo / step);
        for (int i = 0; (first + i) * step <= eHi + 1e-9 * step; ++i) {
            const double tick = (first + i) * step + 0.0;  // a multiple, not a running sum (+ 0.0: no "-0")
            hline(YE(tick), lineStyle(Role::Muted, 1.0f, true));
            c_.drawText(P(x0_ - 8, YE(tick)), formatNumber(tick), ytick_);
        }
        timeAxis(eY0, false);
        c_.drawText(P(x0_, eY1 + 12), "energy (J): kinetic, potential m g z, total", heading_);
        std::vector<Vec3> ke, pe, te;
        for (const SimulationStep& s : tr_.steps) {
            ke.push_back(P(X(s.time), YE(s.kinetic)));
            pe.push_back(P(X(s.time), YE(s.potential)));
            te.push_back(P(X(s.time), YE(s.energy)));
        }
        c_.drawPolyline(pe, false, lineStyle(Role::ShapeB, 2.5f));
        c_.drawPolyline(ke, false, lineStyle(Role::ShapeA, 2.5f));
        c_.drawPolyline(te, false, lineStyle(Role::Ink, 3.0f));
        legendLine(Role::Ink, 3.0f, false, names[0]);
        legendLine(Role::ShapeA, 2.5f, false, names[1]);
        legendLine(Role::ShapeB, 2.5f, false, names[2]);
    }

    // Log10 from 1e-10 to 1e-2 (0 is drawn at the bottom).
    void penetrationPanel(double slop) {
        const double pY0 = 110, pY1 = H_ * 0.50 - 70;
        const double lLo = -10, lHi = -2;
        const auto YP = [&](double pen) {
            const double l = pen > 0 ? std::clamp(std::log10(pen), lLo, lHi) : lLo;
            return pY0 + (l - lLo) / (lHi - lLo) * (pY1 - pY0);
        };
        c_.drawLine(P(x0_, pY0), P(x0_, pY1), axis_);
        c_.noteAxis(P(x0_, pY0), P(x0_, pY1), true);  // LogAxisWithoutValues
        // Legend on the left, below the slop line: bodies in flight have no depth there.
        lx_ = x0_ + 24;
        ly_ = YP(slop) - 26;
        const std::vector<std::string> names = {"after the step", "before the position correction",
                                                "slop (allowed depth)"};
        reserveLegend(names);
        for (int e = int(lLo); e <= int(lHi); e += 2) {
            const double y = YP(std::pow(10.0, e));
            hline(y, lineStyle(Role::Muted, 1.0f, true));
            c_.drawText(P(x0_ - 8, y), "1e" + std::to_string(e), ytick_);
        }
        timeAxis(pY0, true);
        c_.drawText(P(0.5 * (x0_ + x1_), pY0 - 34), "time (s); ticks under the axis: the frames drawn",
                    TextStyle{16.0f, roleColor(Role::Ink), Anchor::Top, false, true});
        c_.drawText(P(x0_, pY1 + 12), "deepest vertex below the ground (log scale; ≤ 1e-10 drawn at the bottom)",
                    heading_);
        std::vector<Vec3> before, after;
        for (const SimulationStep& s : tr_.steps) {
            before.push_back(P(X(s.time), YP(s.penetrationBeforeCorrection)));
            after.push_back(P(X(s.time), YP(s.maxPenetration)));
        }
        // The slop in dark grey, not the ink of the energy plot's total above it: two lines of one
        // figure in one colour read as one thing (the rule SeriesShareColour).
        LineStyle slopStyle = lineStyle(Role::Ink, 1.5f, true);
        slopStyle.color = roleColor(Role::Muted).scaled(0.55f);
        hline(YP(slop), slopStyle);
        c_.drawPolyline(after, false, lineStyle(Role::Result, 3.0f));
        c_.drawPolyline(before, false, lineStyle(Role::Direction, 1.5f, true));  // on top: equal unless corrected
        legendLine(Role::Result, 3.0f, false, names[0]);
        legendLine(Role::Direction, 1.5f, true, names[1]);
        legendLine(slopStyle, names[2]);
    }

private:
    static Vec3 P(double x, double y) { return Vec3(x, y, 0); }
    double X(double t) const { return x0_ + (tMax_ > 0 ? t / tMax_ : 0.0) * (x1_ - x0_); }

    void timeAxis(double y0, bool labelsOn) {
        c_.drawLine(P(x0_, y0), P(x1_, y0), axis_);
        const double dtTick = tMax_ > 4 ? 1.0 : tMax_ > 1.5 ? 0.5 : 0.25;
        for (double t = 0; t <= tMax_ + 1e-9; t += dtTick) {
            c_.drawLine(P(X(t), y0), P(X(t), y0 - 6), axis_);
            if (labelsOn) c_.drawText(P(X(t), y0 - 9), formatNumber(t), tick_);
        }
        for (int k : frameSteps_)
            c_.drawLine(P(X(tr_.steps[k].time), y0), P(X(tr_.steps[k].time), y0 + 8), lineStyle(Role::Highlight, 2.0f));
    }
    // The legend's rows from (lx_, ly_) down, 24 px apart, kept clear of the grid and reference
    // lines (hline), as an opaque legend frame would: no label over a line (render/legibility.h).
    void reserveLegend(const std::vector<std::string>& names) {
        double widest = 0;
        for (const std::string& n : names) widest = std::max(widest, c_.measureText(n, legend_).x());
        legendX0_ = lx_ - 6, legendX1_ = lx_ + 44 + widest + 6;
        legendY1_ = ly_ + 12, legendY0_ = ly_ - 24.0 * double(names.size() - 1) - 12;
    }
    // A horizontal grid or reference line across the plot, with a gap where the legend is.
    void hline(double y, const LineStyle& style) {
        if (y < legendY0_ || y > legendY1_ || legendX1_ <= legendX0_) {
            c_.drawLine(P(x0_, y), P(x1_, y), style);
            return;
        }
        if (legendX0_ > x0_) c_.drawLine(P(x0_, y), P(legendX0_, y), style);
        if (legendX1_ < x1_) c_.drawLine(P(legendX1_, y), P(x1_, y), style);
    }
    // One legend entry at (lx_, ly_), the next one below it.
    void legendLine(Role role, float w, bool dashed, const std::string& text) {
        legendLine(lineStyle(role, w, dashed), text);
    }
    void legendLine(const LineStyle& style, const std::string& text) {
        c_.drawLine(P(lx_, ly_), P(lx_ + 36, ly_), style);
        c_.noteSeries(text, style.color, P(lx_, ly_));  // SeriesShareColour
        c_.drawText(P(lx_ + 44, ly_), text, legend_);
        ly_ -= 24;
    }

    Canvas& c_;
    const SimulationTrace& tr_;
    const std::vector<int>& frameSteps_;
    const double x0_ = 110, x1_, tMax_;
    const int H_;
    double lx_ = 0, ly_ = 0;
    double legendX0_ = 0, legendX1_ = 0, legendY0_ = 0, legendY1_ = 0;  // reserveLegend's box (y up)
    const LineStyle axis_ = lineStyle(Role::Ink, 2.0f);
    const TextStyle tick_{14.0f, roleColor(Role::Ink), Anchor::Top, false, false};
    const TextStyle ytick_{14.0f, roleColor(Role::Ink), Anchor::Right, false, false};
    const TextStyle heading_{17.0f, roleColor(Role::Ink), Anchor::BottomLeft, false, true};
    const TextStyle legend_{15.0f, roleColor(Role::Ink), Anchor::Left, true, false};
};

class DropScene final : public PreparedScene {
public:
    DropScene(SceneCommon common, DropInput input, SimulationOptions options, std::string body, int frameEvery,
              Vec3 view, bool gif)
        : PreparedScene(std::move(common)),
          input_(std::move(input)),
          options_(options),
          body_(std::move(body)),
          frameEvery_(frameEvery),
          view_(view),
          gif_(gif) {}

    DemoOutput execute(const RunContext& ctx) const override {
        SimulationTrace tr;
        const SimulationResult r = simulateDrop(input_, options_, &tr);
        DemoOutput out;
        out.trace = traceJson(r, tr);
        if (numericOnly(ctx, out)) return out;
        if (!r.ok()) return out;  // prepare() validated the inputs; nothing to draw otherwise
        const int ss = figureScale(common_, ctx);

        // One camera for every frame: the bounding sphere of the body along its whole path.
        std::vector<Vec3> path;
        for (const SimulationStep& s : tr.steps) {
            path.push_back(s.position);
            path.push_back(s.position + r.boundingRadius * Vec3::UnitZ());
            path.push_back(Vec3(s.position.x(), s.position.y(), 0.0));
        }
        Vec3 center;
        double radius;
        boundingSphere(path, center, radius);
        radius += r.boundingRadius;
        const Camera cam = common_.camera ? *common_.camera : framingCamera(center, radius, view_, Vec3::UnitZ());
        const CanvasOptions main = sceneCanvasOptions(common_, 1);
        const Camera side = sideCamera(tr, r.boundingRadius, cam.eye - cam.target,
                                       int(std::lround(kSideWidth * main.width)), main.height);

        const std::vector<int> frameSteps = chooseFrameSteps(tr);
        // Impulse arrows share one scale over the run, so frames compare.
        double maxImpulse = 0.0;
        for (const SimulationStep& st : tr.steps)
            for (const ContactImpulse& ct : st.contacts) maxImpulse = std::max(maxImpulse, ct.normalImpulse);
        for (std::size_t i = 0; i < frameSteps.size(); ++i)
            out.frames.push_back(drawFrame(*ctx.gl, ss, cam, side, center, radius, r, tr, frameSteps[i], int(i), maxImpulse));
        std::vector<const Frame*> stepFrames;
        for (const Frame& f : out.frames) stepFrames.push_back(&f);
        if (gif_) addGif(out, stepFrames, 1);
        Frame sheet;
        const bool wantSheet = common_.steps || ctx.stepsOverride;
        if (wantSheet) {
            // Thumbnails without text (each tile's caption says what it is; the frames' legends and
            // status lines were ~3 px there), and of the frames at rest only the first: the rest
            // are the same picture (figure review of 2026-11-29).
            std::vector<Frame> thumbs;
            int atRest = 0;
            for (std::size_t i = 0; i < frameSteps.size(); ++i) {
                const bool resting = r.restTime >= 0 && tr.steps[std::size_t(frameSteps[i])].time >= r.restTime;
                if (resting && atRest++ > 0) continue;
                thumbs.push_back(drawFrame(*ctx.gl, ss, cam, side, center, radius, r, tr, frameSteps[i], int(i),
                                           maxImpulse, true));
            }
            std::vector<const Frame*> tiles;
            for (const Frame& f : thumbs) tiles.push_back(&f);
            ContactSheetOptions o;
            o.caption = common_.caption +
                        (atRest > 1 ? " At rest from t = " + formatNumber(r.restTime) + " s: " +
                                          std::to_string(atRest - 1) + " later frame" + (atRest > 2 ? "s" : "") +
                                          " not shown."
                                    : std::string());
            o.title = common_.title + ": every " + std::to_string(frameEvery_) + " steps (" +
                      formatNumber(frameEvery_ * options_.timeStep) + " s) and at each impact";
            o.cellWidth = 300;
            o.columns = 4;
            sheet = contactSheetFrame(*ctx.gl, tiles, common_.title, o);
        }
        if (common_.hasLayer("plot")) out.frames.push_back(drawPlot(*ctx.gl, ss, r, tr, frameSteps));
        else out.skipped.push_back("energy / penetration plot (no 'plot' layer)");
        if (wantSheet) out.frames.push_back(std::move(sheet));
        return out;
    }

private:
    DropInput input_;
    SimulationOptions options_;
    std::string body_;
    int frameEvery_;
    Vec3 view_;
    bool gif_;  // also write animation.gif of the frames, like the other stepping demos

    Json traceJson(const SimulationResult& r, const SimulationTrace& tr) const {
        Json t;
        t["body"] = body_;
        t["status"] = nameOf(r.status);
        if (!r.ok()) {
            t["message"] = r.message;
            return t;
        }
        Json inertia = Json::array();
        for (int i = 0; i < 3; ++i)
            inertia.push_back(Json::array({r.mass.inertia(i, 0), r.mass.inertia(i, 1), r.mass.inertia(i, 2)}));
        t["mass_properties"] = {{"volume", r.mass.volume},
                                {"mass", r.mass.mass},
                                {"center_of_mass", vec3Json(r.mass.centerOfMass)},
                                {"inertia", inertia},
                                {"frame", "shape frame; inertia about the centre of mass"}};
        t["options"] = {{"time_step", options_.timeStep},
                        {"steps", options_.steps},
                        {"restitution", options_.solver.restitution},
                        {"friction", options_.solver.friction},
                        {"restitution_threshold", options_.solver.restitutionThreshold},
                        {"iterations", options_.solver.iterations},
                        {"slop", options_.slop},
                        {"gravity", vec3Json(input_.gravity)},
                        {"max_contact_points", options_.maxContactPoints}};
        t["summary"] = {{"rest_time", r.restTime},
                        {"max_penetration", r.maxPenetration},
                        {"max_penetration_before_correction", r.maxPenetrationBeforeCorrection},
                        {"max_energy_increase", r.maxEnergyIncrease},
                        {"total_correction", r.totalCorrection},
                        {"bounding_radius", r.boundingRadius}};
        Json steps = Json::array();
        for (const SimulationStep& s : tr.steps) {
            Json contacts = Json::array();
            for (const ContactImpulse& c : s.contacts)
                contacts.push_back({{"point", vec3Json(c.point)},
                                    {"separation", c.separation},
                                    {"normal_impulse", c.normalImpulse},
                                    {"restitution_impulse", c.restitutionImpulse},
                                    {"tangent_impulse", vec3Json(c.tangentImpulse)},
                                    {"normal_velocity_before", c.normalVelocityBefore},
                                    {"normal_velocity_after", c.normalVelocityAfter},
                                    {"bounce", c.bounce}});
            steps.push_back({{"step", s.step},
                             {"time", s.time},
                             {"position", vec3Json(s.position)},
                             {"orientation", quatJson(s.orientation)},
                             {"linear_velocity", vec3Json(s.linearVelocity)},
                             {"angular_velocity", vec3Json(s.angularVelocity)},
                             {"contact_status", nameOf(s.contactStatus)},
                             {"contacts", contacts},
                             {"kinetic", s.kinetic},
                             {"potential", s.potential},
                             {"energy", s.energy},
                             {"penetration_before_correction", s.penetrationBeforeCorrection},
                             {"correction", s.correction},
                             {"max_penetration", s.maxPenetration}});
        }
        t["steps"] = steps;
        return t;
    }

    // The first step of an impact: a contact bounces (the restitution rule applied) where the step
    // before had none. Regular frames every frame_every steps miss them (a bounce lasts a step).
    static bool impactAt(const SimulationTrace& tr, int k) {
        const auto bounces = [&](int i) {
            return std::any_of(tr.steps[std::size_t(i)].contacts.begin(), tr.steps[std::size_t(i)].contacts.end(),
                               [](const ContactImpulse& c) { return c.bounce && c.normalImpulse > 0.0; });
        };
        return k > 0 && bounces(k) && !bounces(k - 1);
    }

    // Frames: every frame_every steps from step 0, and the first step of each impact (the first
    // ones, up to kMaxFrames in all), in time order.
    std::vector<int> chooseFrameSteps(const SimulationTrace& tr) const {
        std::vector<int> steps;
        for (int k = 0; k < int(tr.steps.size()); k += frameEvery_) steps.push_back(k);
        for (int k = 1; k < int(tr.steps.size()) && int(steps.size()) < kMaxFrames; ++k)
            if (impactAt(tr, k) && std::find(steps.begin(), steps.end(), k) == steps.end()) steps.push_back(k);
        std::sort(steps.begin(), steps.end());
        return steps;
    }

    // How many of a step's contacts push, bounce, and are seen through the body from a camera.
    struct ContactMarks {
        int pushing = 0, bounces = 0, hidden = 0;
        double undrawn = 0;  // the largest λ_n of a pushing contact whose arrow is too short to draw
        int undrawnCount = 0;
    };

    // The body at step k, tinted and outlined in the colliding role while a contact pushes, with the
    // step's contacts: filled = pushing (λ_n > 0), hollow = speculative (λ_n = 0); each pushing
    // contact's impulse λ_n n as an arrow to one scale over the run (the largest λ_n of the run is
    // 0.6 of the body's radius long). A contact seen through the body (on its far side, from `cam`)
    // and its arrow are drawn faded, as hidden edges are elsewhere: the body is opaque, the marker
    // must not read as in front.
    ContactMarks drawBodyAndContacts(Canvas& c, const Camera& cam, const SimulationResult& r, const SimulationTrace& tr,
                                     int k, double maxImpulse, bool labelImpulse) const {
        const SimulationStep& s = tr.steps[std::size_t(k)];
        const double rho = r.boundingRadius;
        std::vector<Vec3> wv;
        for (const Vec3& v : r.shape.positions()) wv.push_back(s.orientation * v + s.position);
        std::vector<Eigen::Vector3i> tris;
        for (int f = 0; f < r.shape.faceCount(); ++f) {
            const std::vector<int> fv = r.shape.faceVertices(f);
            for (std::size_t i = 1; i + 1 < fv.size(); ++i) tris.emplace_back(fv[0], fv[i], fv[i + 1]);
        }
        const bool touching = inContact(s);
        const Color fill = roleColor(Role::ShapeA);
        c.drawMesh(wv, tris, touching ? fill.mixed(roleColor(Role::Colliding), 0.3f) : fill, true);
        LineStyle edge = lineStyle(Role::ShapeA, touching ? 3.5f : 2.0f);
        edge.color = touching ? roleColor(Role::Colliding) : roleColor(Role::ShapeA).scaled(0.5f);
        for (int e = 0; e < r.shape.edgeCount(); ++e) {
            const auto [a, b] = r.shape.edgeVertices(e);
            c.drawLine(wv[std::size_t(a)], wv[std::size_t(b)], edge);
        }
        ContactMarks marks;
        if (!common_.hasLayer("contacts")) return marks;
        // The contacts were found at the pose the step started from (the previous step's).
        const SimulationStep& start = tr.steps[std::size_t(std::max(k - 1, 0))];
        std::vector<Plane> faces;
        for (int f = 0; f < r.shape.faceCount(); ++f) {
            const Vec3 n = start.orientation * r.shape.face(f).normal;
            faces.push_back({n, r.shape.face(f).offset + n.dot(start.position)});
        }
        std::vector<char> hidden;
        for (const ContactImpulse& ct : s.contacts) hidden.push_back(behindBody(cam, ct.point, faces, 1e-3 * rho));
        const auto faded = [](Color color) { return color.mixed(roleColor(Role::Background), 0.55f); };
        const ContactImpulse* largest = nullptr;
        for (std::size_t i = 0; i < s.contacts.size(); ++i) {
            const ContactImpulse& ct = s.contacts[i];
            const bool push = ct.normalImpulse > 0;
            marks.pushing += push;
            marks.bounces += ct.bounce && push;
            marks.hidden += hidden[i];
            const double length = maxImpulse > 0 ? 0.6 * rho * ct.normalImpulse / maxImpulse : 0.0;
            LineStyle arrow = lineStyle(Role::Direction, 3.0f, false, true);
            if (hidden[i]) arrow.color = faded(arrow.color);
            // Drawn where it reaches 12 px past its contact marker (7 px) on the picture; shorter, it
            // hides under the dot, and the status line says so.
            Eigen::Vector2d from, to;
            const bool seen = length > 0 && c.project(ct.point, from) &&
                              c.project(ct.point + length * s.normal, to) && (to - from).norm() >= 19.0;
            if (push && seen) c.drawArrow(ct.point, ct.point + length * s.normal, arrow);
            else if (push) marks.undrawn = std::max(marks.undrawn, ct.normalImpulse), ++marks.undrawnCount;
            // The one named: the largest seen (a contact behind the body has a faded arrow).
            if (push && !hidden[i] && (!largest || ct.normalImpulse > largest->normalImpulse)) largest = &ct;
        }
        // Markers after the arrows, so an arrow never paints over its contact point.
        for (std::size_t i = 0; i < s.contacts.size(); ++i) {
            const ContactImpulse& ct = s.contacts[i];
            const Color result = hidden[i] ? faded(roleColor(Role::Result)) : roleColor(Role::Result);
            const Color ink = hidden[i] ? faded(roleColor(Role::Ink)) : roleColor(Role::Ink);
            if (ct.normalImpulse > 0) c.drawPoint(ct.point, 7.0f, result, true, 1.5f, ink);
            else c.drawPoint(ct.point, 6.0f, roleColor(Role::Background).withAlpha(hidden[i] ? 0.0f : 1.0f), true, 2.0f, result);
        }
        // Named only where its arrow is seen: drawn, and reaching 12 px past its contact marker (7 px)
        // on the picture (the review: "λₙ n" beside an arrow hidden under its dot).
        if (labelImpulse && largest && 0.6 * largest->normalImpulse / maxImpulse > 0.02) {
            const Vec3 tip = largest->point + 0.6 * rho * largest->normalImpulse / maxImpulse * s.normal;
            Eigen::Vector2d from, to;
            if (c.project(largest->point, from) && c.project(tip, to) && (to - from).norm() >= 19.0)
                drawLabelAway(c, tip, largest->point, "λₙ n", labelStyle(Role::Direction, 20.0f), 10.0);
        }
        return marks;
    }

    // Some contact of the step pushes: the body is in contact with the ground.
    static bool inContact(const SimulationStep& s) {
        return std::any_of(s.contacts.begin(), s.contacts.end(), [](const ContactImpulse& c) { return c.normalImpulse > 0; });
    }

    void drawTrail(Canvas& c, const SimulationTrace& tr, int k) const {
        if (!common_.hasLayer("trail") || k == 0) return;
        std::vector<Vec3> trail;
        for (int i = 0; i <= k; ++i) trail.push_back(tr.steps[std::size_t(i)].position);
        LineStyle ls = lineStyle(Role::Ink, 2.0f, true, false);
        ls.color = roleColor(Role::Ink).withAlpha(0.55f);
        c.drawPolyline(trail, false, ls);
    }

    // The low side view's camera, the same for every frame: orthographic, the eye at ground level
    // looking horizontally the main camera's way, framing the whole path from a band under the
    // ground to the highest point of the body, below the panel's heading.
    static Camera sideCamera(const SimulationTrace& tr, double rho, const Vec3& view, int width, int height) {
        Vec3 back(view.x(), view.y(), 0.0);  // towards the eye
        if (!(back.norm() > 1e-9)) back = Vec3::UnitX();
        back.normalize();
        const Vec3 across = Vec3::UnitZ().cross(back);
        double lo = INFINITY, hi = -INFINITY, top = 0.0, depth = 0.0;
        for (const SimulationStep& s : tr.steps) {
            lo = std::min(lo, across.dot(s.position) - rho);
            hi = std::max(hi, across.dot(s.position) + rho);
            top = std::max(top, s.position.z() + rho);
            depth += back.dot(s.position) / double(tr.steps.size());
        }
        const double below = 0.12 * top;                     // the band under the ground
        const double usable = (height - kSideHeading) / double(height);  // of the panel, under its heading
        const double viewHeight = std::max((top + below) * 1.1, (hi - lo) * 1.1 * height / width) / usable;
        Camera cam;
        cam.projection = Camera::Projection::Orthographic;
        cam.viewHeight = viewHeight;
        const double bottom = -below - 0.05 * (top + below);  // the lowest world height shown
        cam.target = 0.5 * (lo + hi) * across + depth * back + (bottom + 0.5 * viewHeight) * Vec3::UnitZ();
        const double distance = 4.0 * (viewHeight + (hi - lo) + rho);
        cam.eye = cam.target + distance * back;
        cam.up = Vec3::UnitZ();
        cam.nearPlane = 0.01 * distance;
        cam.farPlane = 4.0 * distance;
        return cam;
    }

    // A low side view of step k: the ground seen edge-on as a line over a band, so the body's height,
    // its bounces and the corner or face it lands on read directly.
    Image drawSideView(GlContext& gl, int ss, int width, int height, const Camera& cam, const SimulationResult& r,
                       const SimulationTrace& tr, int k, double maxImpulse, bool text) const {
        CanvasOptions o = canvasOptions(width, height, ss);
        o.text = text;
        Canvas c(gl, o, cam);
        const Vec3 back = cam.viewDirection();
        const Vec3 across = Vec3::UnitZ().cross(back).normalized();
        const double half = 2.0 * cam.viewHeight * width / height;
        const Vec3 mid(cam.target.x(), cam.target.y(), 0.0);
        if (common_.hasLayer("ground")) {
            // Under the ground: a band in the plane through the target facing the eye, behind everything.
            const Vec3 far = mid - 2.0 * cam.viewHeight * back;
            c.drawPolygon({far - half * across, far + half * across, far + half * across - cam.viewHeight * Vec3::UnitZ(),
                           far - half * across - cam.viewHeight * Vec3::UnitZ()},
                          roleColor(Role::Muted).withAlpha(0.22f));
            LineStyle ground = lineStyle(Role::Muted, 2.5f);
            ground.onTop = true;
            c.drawLine(mid - half * across, mid + half * across, ground);
            // Named under the line near the left edge, placed off the contact markers.
            const double perPixel = cam.viewHeight / height;
            TextStyle ts{16.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f), Anchor::Center, true, false, {0, 16}};
            ts.place = true;
            c.drawText(mid - (0.5 * width - 70.0) * perPixel * across, "ground, z = 0", ts);
        }
        drawTrail(c, tr, k);
        drawBodyAndContacts(c, cam, r, tr, k, maxImpulse, false);
        c.drawTextPx(14, 10, "Side view", TextStyle{20.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
        c.drawTextPx(14, 38, "looking horizontally",
                     TextStyle{17.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f), Anchor::TopLeft, true, true});
        return c.readPixels();
    }

    // Step k's frame; a thumbnail (for the contact sheet) is the same picture without its text.
    Frame drawFrame(GlContext& gl, int ss, const Camera& cam, const Camera& side, const Vec3& center, double radius,
                    const SimulationResult& r, const SimulationTrace& tr, int k, int index, double maxImpulse,
                    bool thumbnail = false) const {
        CanvasOptions o = sceneCanvasOptions(common_, ss);
        o.text = !thumbnail;
        Canvas c(gl, o, cam);
        const SimulationStep& s = tr.steps[std::size_t(k)];
        const double rho = r.boundingRadius;
        const bool labels = common_.hasLayer("labels");

        // Ground: a square patch under the path with a grid (z = 0).
        if (common_.hasLayer("ground")) {
            const double half = 1.6 * radius;
            const Vec3 g(center.x(), center.y(), 0.0);
            c.drawPolygon({g + Vec3(-half, -half, 0), g + Vec3(half, -half, 0), g + Vec3(half, half, 0),
                           g + Vec3(-half, half, 0)},
                          roleColor(Role::Muted).withAlpha(0.22f));
            const double step = std::pow(10.0, std::floor(std::log10(half))) *
                                (half / std::pow(10.0, std::floor(std::log10(half))) > 4 ? 1.0 : 0.5);
            LineStyle grid = lineStyle(Role::Muted, 1.0f);
            grid.color = roleColor(Role::Muted).withAlpha(0.6f);
            for (double x = std::ceil((g.x() - half) / step) * step; x <= g.x() + half; x += step)
                c.drawLine(Vec3(x, g.y() - half, 0), Vec3(x, g.y() + half, 0), grid);
            for (double y = std::ceil((g.y() - half) / step) * step; y <= g.y() + half; y += step)
                c.drawLine(Vec3(g.x() - half, y, 0), Vec3(g.x() + half, y, 0), grid);
        }
        if (common_.hasLayer("shadow")) {
            std::vector<Vec3> wv;
            for (const Vec3& v : r.shape.positions()) wv.push_back(s.orientation * v + s.position);
            std::vector<Vec3> outline = hull2d(wv);
            for (Vec3& p : outline) p.z() = 1e-3 * rho;  // just above the grid
            if (outline.size() >= 3) c.drawPolygon(outline, roleColor(Role::Ink).withAlpha(0.16f));
        }
        drawTrail(c, tr, k);
        const ContactMarks marks = drawBodyAndContacts(c, cam, r, tr, k, maxImpulse, labels);
        const bool touching = inContact(s);
        double legendBottom = 0.0;  // the status lines go under the legend where they would meet it
        double legendWidest = 0.0;  // the widest legend entry from the status lines' row down
        if (labels) {
            // Legend (top right), each entry in the colour of what it names.
            const double x = c.width() - 18.0;
            double& y = legendBottom;
            y = 18.0;
            // faded: the entry in the faded colour it names (mixed as the markers, a little less so
            // the text stays legible).
            const auto item = [&](const std::string& text, Role role, bool faded = false) {
                Color color = role == Role::Result ? roleColor(Role::Result).scaled(0.75f) : roleColor(role);
                if (faded) color = color.mixed(roleColor(Role::Background), 0.45f);
                const TextStyle style{16.0f, color, Anchor::TopRight, true, true};
                c.drawTextPx(x, y, text, style);
                if (y + 22.0 > 58.0) legendWidest = std::max(legendWidest, c.measureText(text, style).x());
                y += 22.0;
            };
            if (common_.hasLayer("contacts")) {
                item("filled dot: contact pushing (λₙ > 0)", Role::Result);
                item("hollow dot: speculative contact (λₙ = 0)", Role::Result);
                item("arrow: impulse λₙ n, one scale for the run (longest " + formatNumber(maxImpulse) + " N·s)",
                     Role::Direction);
            }
            if (common_.hasLayer("trail")) item("dashed: centre-of-mass path", Role::Ink);
            if (marks.hidden > 0) item("faded: contact behind the body", Role::Result, true);
            if (touching) item("tint and outline: body in contact with the ground", Role::Colliding);
        }
        // Two caption lines: the contacts of the step, then energy and depth.
        // A pushing contact without an arrow says why (the review: the legend promises an arrow that
        // a resting contact's λₙ, a few thousandths of the run's longest, draws under a pixel).
        char line1[260], line2[200], undrawn[96] = "";
        if (marks.undrawn > 0)
            std::snprintf(undrawn, sizeof undrawn, "; λₙ %s%.2g N·s, too short to draw",
                          marks.undrawnCount > 1 ? "≤ " : "", marks.undrawn);
        std::snprintf(line1, sizeof line1, "t = %.3f s (step %d): %d contact%s, %d pushing%s%s", s.time, s.step,
                      int(s.contacts.size()), s.contacts.size() == 1 ? "" : "s", marks.pushing,
                      marks.bounces ? (", " + std::to_string(marks.bounces) + " bouncing").c_str() : "", undrawn);
        std::snprintf(line2, sizeof line2, "E = %.4g J (KE %.3g + PE %.4g); deepest vertex %.2g below the ground",
                      s.energy, s.kinetic, s.potential, s.maxPenetration);
        // Under the title, in the sky: at the bottom they sat on the ground's grid lines (the review
        // rule LabelOnStroke).
        const TextStyle status1{19.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
        const TextStyle status2{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
        const double statusRight = 18.0 + std::max(c.measureText(line1, status1).x(), c.measureText(line2, status2).x());
        const double statusTop = statusRight + 12.0 < c.width() - 18.0 - legendWidest ? 58.0 : std::max(58.0, legendBottom + 6.0);
        c.drawTextPx(18.0, statusTop, line1, status1);
        c.drawTextPx(18.0, statusTop + 26.0, line2, status2);
        drawTitleAndCaption(c, common_.title, "");
        char name[32];
        std::snprintf(name, sizeof name, "frame_%02d", index);
        char cap[200];
        std::snprintf(cap, sizeof cap, "t = %.2f s: %d contact%s, E = %.3g J", s.time, int(s.contacts.size()),
                      s.contacts.size() == 1 ? "" : "s", s.energy);
        if (impactAt(tr, k)) {
            // The impact's fastest approaching point: its normal velocity before and after the
            // step's impulses (restitution: after ≈ −e · before).
            const ContactImpulse* fastest = &s.contacts.front();
            for (const ContactImpulse& ct : s.contacts)
                if (ct.normalVelocityBefore < fastest->normalVelocityBefore) fastest = &ct;
            std::snprintf(cap, sizeof cap, "%.2f s impact: vₙ %.2f → %.2f", s.time, fastest->normalVelocityBefore,
                          fastest->normalVelocityAfter);
        }
        // The main view, and the low side view on its right (kSideWidth of the main width).
        const int sideWidth = int(std::lround(kSideWidth * c.width()));
        Image frame = Image::blank(c.width() + sideWidth, c.height(), ss);
        frame.layout.panels.push_back({0.0, 0.0, double(frame.width), double(frame.height)});
        blit(frame, c.readPixels(), 0, 0);
        blit(frame, drawSideView(gl, ss, sideWidth, c.height(), side, r, tr, k, maxImpulse, !thumbnail), c.width(), 0);
        paintRect(frame, c.width() - 1, 0, 2, c.height(), roleColor(Role::Muted));  // a rule between the views
        return Frame{name, cap, std::move(frame)};
    }

    // Energy (top) and penetration on a log scale (bottom) against time, drawn in pixel units.
    Frame drawPlot(GlContext& gl, int ss, const SimulationResult& r, const SimulationTrace& tr,
                   const std::vector<int>& frameSteps) const {
        const int W = common_.image.width, H = common_.image.height;
        Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));  // world = pixels, y up
        TimePlot plot(c, tr, frameSteps, W, H);
        plot.energyPanel();
        plot.penetrationPanel(options_.slop);

        char cap[300];
        if (r.restTime >= 0)
            std::snprintf(cap, sizeof cap,
                          "at rest from t = %.3g s; max depth %.2g (slop %.2g); max energy rise per step %.2g J",
                          r.restTime, r.maxPenetration, options_.slop, r.maxEnergyIncrease);
        else
            std::snprintf(cap, sizeof cap,
                          "still moving at the end; max depth %.2g (slop %.2g); max energy rise per step %.2g J",
                          r.maxPenetration, options_.slop, r.maxEnergyIncrease);
        drawTitleAndCaption(c, common_.title + ": energy and penetration", cap);
        return Frame{"energy", "energy and penetration vs time", c.readPixels()};
    }
};

// The body's mass and smallest principal moment of inertia at the scene's density: the solver
// divides by them and inverts the inertia tensor through its determinant (~ I³), so both must stay
// far above the smallest normal double (density 1e-300 gave a NaN trace). The presets and sizes the
// scene limits allow, at kMinDensity, stay above kMinMass and kMinInertia; a sliver of a polytope
// may not. Test: "hostile scene" / "drop: the smallest density, mass and inertia".
void requireSimulatedMass(const JsonNode& body, const DropInput& in) {
    const MassProperties mp = computeMassProperties(in.shape, {.density = in.density});
    if (!mp.ok()) body.fail("the body has no usable mass properties: " + mp.message);
    const std::string why = "the simulation divides by the mass and inverts the inertia tensor";
    requireAtLeast(body, mp.mass, kMinMass, "the body's mass (kg)", why);
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (mp.inertia + mp.inertia.transpose()), Eigen::EigenvaluesOnly);
    requireAtLeast(body, eig.eigenvalues()[0], kMinInertia, "the body's smallest principal moment of inertia (kg m²)",
                   why);
}

class DropDemo final : public Demo {
public:
    std::string name() const override { return "drop"; }
    std::string description() const override {
        return "rigid body dropped with spin onto a plane: mass properties, impulses with restitution and friction, "
               "energy and penetration";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{960, 720}, {480, 360}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        if (auto f = r.find("figure"); f && f->asEnum({"drop", "impulse"}) == "impulse")
            return readImpulseScene(r, std::move(common));
        DropInput in;
        std::string bodyName;
        in.shape = readConvexBody(r.get("body"), bodyName);
        // Physical ranges well beyond any teaching scene, and far inside what the energies (~ m v², in
        // double) and the impulse solver can hold: density up to 10^6 (osmium is 2.2·10^4), speeds
        // up to 10^3 m/s and rad/s, gravity up to 10^3 m/s² (100 g).
        const auto atMost = [](const JsonNode& n, double value, double limit, const char* what) {
            requireAtMost(n, value, limit, what, "the physical range a drop scene accepts");
            return value;
        };
        if (auto d = r.find("density")) {
            in.density = atMost(*d, d->asPositive(), kMaxDensity, "density");
            requireAtLeast(*d, in.density, kMinDensity, "density",
                           "mass and inertia must stay far from the smallest doubles: the simulation divides by them");
        }
        if (auto p = r.find("position")) in.pose.position = sceneVec3(*p);
        if (auto q = r.find("rotation")) in.pose.rotation = q->asQuat();
        if (auto v = r.find("velocity"))
            in.linearVelocity = sceneVec3(*v), atMost(*v, in.linearVelocity.norm(), kMaxSpeed, "|velocity|");
        if (auto w = r.find("angular_velocity"))
            in.angularVelocity = sceneVec3(*w), atMost(*w, in.angularVelocity.norm(), kMaxSpeed, "|angular_velocity|");
        in.ground = Plane{Vec3::UnitZ(), 0.0};
        double g = 9.81;
        if (auto gn = r.find("gravity")) g = atMost(*gn, gn->asNonNegative(), kMaxGravity, "gravity");
        in.gravity = Vec3(0, 0, -g);
        SimulationOptions o;
        double duration = 3.0;
        if (auto s = r.find("simulation")) {
            ObjectReader sr(*s);
            if (auto t = sr.find("time_step")) o.timeStep = t->asPositive();
            if (auto t = sr.find("duration")) duration = t->asPositive();
            if (auto t = sr.find("restitution")) o.solver.restitution = t->asNonNegative();
            if (auto t = sr.find("friction")) o.solver.friction = t->asNonNegative();
            if (auto t = sr.find("restitution_threshold")) o.solver.restitutionThreshold = t->asNonNegative();
            if (auto t = sr.find("iterations")) o.solver.iterations = t->asInt(1, 256);
            if (auto t = sr.find("slop")) o.slop = t->asNonNegative();
            sr.finish();
            if (o.solver.restitution > 1) s->fail("restitution must be in [0, 1]");
        }
        const double steps = std::round(duration / o.timeStep);
        if (!(steps >= 1 && steps <= 20000))  // the frames, the energy plot and the trace hold every step
            (r.has("simulation") ? r.get("simulation") : r.node())
                .fail("duration / time_step must give 1..20000 steps");
        o.steps = int(steps);
        int frameEvery = std::max(1, o.steps / 11);
        if (auto k = r.find("frame_every")) frameEvery = k->asInt(1, 20000);
        if (o.steps / frameEvery + 1 > kMaxFrames)
            r.node().fail("frame_every " + std::to_string(frameEvery) + " gives " +
                          std::to_string(o.steps / frameEvery + 1) + " frames; at most " + std::to_string(kMaxFrames));
        Vec3 view(1.0, -1.6, 0.8);
        if (auto v = r.find("view")) {
            view = sceneVec3(*v);
            if (!(view.norm() > 0)) v->fail("view direction must be non-zero");
        }
        const bool gif = r.boolOr("gif", true);
        r.finish();
        // The body must start above the ground (lowest vertex at z >= 0).
        double lowest = INFINITY;
        for (const Vec3& v : in.shape.positions()) lowest = std::min(lowest, in.pose.apply(v).z());
        if (!(lowest >= 0))
            r.node().fail("the body starts below the ground (lowest vertex z = " + formatNumber(lowest) + ")");
        requireSimulatedMass(r.get("body"), in);
        // At most kMaxFrames step frames and the plot; with "steps" the contact sheet too. Each frame
        // is the image with the low side view beside it, kSideWidth of its width.
        const int width = common.image.width;
        common.frames = {kMaxFrames + 1, kMaxFrames + 2, width + int(std::lround(kSideWidth * width))};
        return std::make_unique<DropScene>(std::move(common), std::move(in), o, bodyName, frameEvery, view, gif);
    }
};

}  // namespace

const Demo& dropDemo() {
    static const DropDemo demo;
    return demo;
}

}  // namespace cdlab::demos
