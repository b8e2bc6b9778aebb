// Sweep and prune, frame by frame (Baraff 1992 §6.2; Cohen et al., I-COLLIDE 1995; Ericson,
// Real-Time Collision Detection §7.5.2). Every number drawn comes from core's SweepAndPrune
// (core/broadphase/sweep_and_prune.h): its endpoint lists before and after each update, its SapTrace (the
// swaps of insertion sort with the pair events they caused) and its pair set. This file computes
// only drawing geometry.
//
// Scene keys (besides the common ones in scene.h):
//   "boxes": [{"min": [x, y, z], "max": [x, y, z], "velocity": [vx, vy, vz]}, ...]  2..7 boxes,
//            named A, B, C, ...; at frame f a box is its frame-0 box moved by f * velocity
//   "frames": number of updates after the initial build (0..6, default 3; 0: the build alone)
//   "view": direction from the scene centre towards the 3D camera (default [1.2, -1.6, 1.1], z up)
// Layers: "view3d" (the boxes, reported pairs highlighted), "intervals" (the three axis panels),
// "events" (the sweep table of frame 0, the swap and pair lists after). Frames: frame_00 (initial
// sort and sweep), frame_01, ...
// trace.json: per frame the endpoint order per axis, every swap (axis, moving and passed
// endpoint, event, axes overlapping), the pairs, added and removed; frame 0 also the sweep along
// x (each endpoint, the active boxes a min meets with their y and z overlap, the active list
// after). Test: tests/demos/sweep_and_prune/sap_demo_test.cpp.
#include "demos/sweep_and_prune/sweep_and_prune_demo.h"

#include "demos/sweep_and_prune/sap_coherence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/broadphase/sweep_and_prune.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"view3d", "intervals", "events"};
const char* const kAxisName[3] = {"x", "y", "z"};
constexpr int kW = 1024, kH = 768;  // fixed figure layout (output pixels)

struct MovingBox {
    Aabb box;
    Vec3 velocity = Vec3::Zero();
};

struct Settings {
    std::vector<MovingBox> boxes;
    int frames = 3;
    Vec3 view = Vec3(1.2, -1.6, 1.1);
};

/// One frame: the boxes, the endpoint order per axis before and after, what the call did.
struct FrameData {
    std::vector<Aabb> boxes;
    std::vector<SapEndpoint> before[3], after[3];
    SapTrace trace;
    SapResult result;
    std::vector<BoxPair> pairs;  // sorted
};

std::string boxName(int id) { return std::string(1, static_cast<char>('A' + id)); }

// Box A and box B wear the bodies' colours of every other demo; the rest the other hues in turn.
Color boxColor(int id) {
    if (id == 0) return roleColor(Role::ShapeA);
    if (id == 1) return roleColor(Role::ShapeB);
    // Not vermillion: it marks the pairs found.
    static constexpr int kOthers[4] = {2, 3, 1, 6};  // bluish green, yellow, sky blue, reddish purple
    return categorical(kOthers[(id - 2) % 4]);
}
/// "[A" for a min endpoint, "A]" for a max endpoint.
std::string endName(int id, bool isMax) { return isMax ? boxName(id) + "]" : "[" + boxName(id); }
std::string pairName(const BoxPair& p) { return boxName(p.a) + boxName(p.b); }

std::string pairList(const std::vector<BoxPair>& pairs) {
    if (pairs.empty()) return "none";
    std::string s;
    for (const BoxPair& p : pairs)
        s += (s.empty() ? "" : "  ") + std::string("{") + boxName(p.a) + "," + boxName(p.b) + "}";
    return s;
}

std::vector<FrameData> simulate(const Settings& s) {
    std::vector<FrameData> frames;
    SweepAndPrune sap;
    for (int f = 0; f <= s.frames; ++f) {
        FrameData d;
        for (const MovingBox& m : s.boxes)
            d.boxes.push_back(Aabb{m.box.min + f * m.velocity, m.box.max + f * m.velocity});
        if (f == 0) {
            // "Before" the initial sort: the endpoints in id order.
            for (int k = 0; k < 3; ++k)
                for (int i = 0; i < static_cast<int>(d.boxes.size()); ++i) {
                    d.before[k].push_back(SapEndpoint{d.boxes[i].min[k], static_cast<std::uint32_t>(2 * i)});
                    d.before[k].push_back(SapEndpoint{d.boxes[i].max[k], static_cast<std::uint32_t>(2 * i + 1)});
                }
            d.result = sap.build(d.boxes, &d.trace);
        } else {
            for (int k = 0; k < 3; ++k) d.before[k] = sap.endpoints(k);
            d.result = sap.update(d.boxes, &d.trace);
        }
        for (int k = 0; k < 3; ++k) d.after[k] = sap.endpoints(k);
        d.pairs = sap.pairs();
        std::sort(d.pairs.begin(), d.pairs.end());
        frames.push_back(std::move(d));
    }
    return frames;
}

/// The sweep's met boxes for one min endpoint, each with what pruned it: "A: z apart   B: PAIR AB";
/// compact ("A: z  B: PAIR") when the full line does not fit its column.
std::string sweepTests(const SapSweepStep& step, int self, bool compact, bool& paired) {
    std::string s;
    paired = false;
    for (const SapSweepTest& t : step.tests) {
        std::string what;
        if (t.overlapY && t.overlapZ) {
            what = "PAIR";
            if (!compact) what += " " + pairName(BoxPair{std::min(self, t.other), std::max(self, t.other)});
            paired = true;
        } else {
            what = std::string(t.overlapY ? "" : "y") + (!t.overlapY && !t.overlapZ ? "," : "") + (t.overlapZ ? "" : "z");
            if (!compact) what += " apart";
        }
        s += (s.empty() ? "" : compact ? "  " : "   ") + boxName(t.other) + ": " + what;
    }
    return s.empty() ? "no active box" : s;
}

/// One line per swap for the events list.
std::string swapLine(const SapSwap& s) {
    std::string line = std::string(kAxisName[s.axis]) + ": " + endName(s.movingObject, s.movingIsMax) + " jumps over " +
                       endName(s.passedObject, s.passedIsMax) + ": ";
    const std::string ab =
        boxName(std::min(s.movingObject, s.passedObject)) + boxName(std::max(s.movingObject, s.passedObject));
    if (s.movingIsMax == s.passedIsMax) return line + "same kind, no overlap change";
    if (!s.movingIsMax) {
        line += ab + " start overlapping on " + kAxisName[s.axis];
        return line + (s.event == SapPairEvent::Added ? "; all 3 axes: pair ADDED"
                                                      : " (" + std::to_string(s.axesOverlapping) + " of 3 axes)");
    }
    line += ab + " stop overlapping on " + kAxisName[s.axis];
    return line + (s.event == SapPairEvent::Removed ? ": pair REMOVED" : "");
}

class SapScene final : public PreparedScene {
public:
    SapScene(SceneCommon common, Settings settings) : PreparedScene(std::move(common)), s_(std::move(settings)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const std::vector<FrameData> frames = simulate(s_);
        DemoOutput out;
        out.trace = traceJson(frames);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        for (std::size_t f = 0; f < frames.size(); ++f)
            out.frames.push_back(drawFrame(*ctx.gl, ss, frames, static_cast<int>(f)));
        return out;
    }

private:
    Settings s_;

    Json traceJson(const std::vector<FrameData>& frames) const {
        Json t = Json::object();
        Json names = Json::array();
        for (std::size_t i = 0; i < s_.boxes.size(); ++i) names.push_back(boxName(static_cast<int>(i)));
        t["boxes"] = names;
        t["tie_rule"] =
            "at equal coordinates a min endpoint sorts before a max endpoint (closed boxes: touching overlaps)";
        Json fs = Json::array();
        std::int64_t totalSwaps = 0;
        for (std::size_t f = 0; f < frames.size(); ++f) {
            const FrameData& d = frames[f];
            Json j = Json::object();
            j["frame"] = f;
            j["kind"] = f == 0 ? "build: sort + sweep along x" : "update: insertion sort per axis";
            Json order = Json::object(), values = Json::object();
            for (int k = 0; k < 3; ++k) {
                Json o = Json::array(), v = Json::array();
                for (const SapEndpoint& e : d.after[k]) {
                    o.push_back(endName(e.object(), e.isMax()));
                    v.push_back(e.value);
                }
                order[kAxisName[k]] = o;
                values[kAxisName[k]] = v;
            }
            j["order"] = order;
            j["values"] = values;
            Json swaps = Json::array();
            for (const SapSwap& s : d.trace.swaps)
                swaps.push_back({{"axis", kAxisName[s.axis]},
                                 {"moving", endName(s.movingObject, s.movingIsMax)},
                                 {"moving_value", s.movingValue},
                                 {"passed", endName(s.passedObject, s.passedIsMax)},
                                 {"passed_value", s.passedValue},
                                 {"position", s.position},
                                 {"event", nameOf(s.event)},
                                 {"axes_overlapping", s.axesOverlapping}});
            j["swaps"] = swaps;
            j["swaps_per_axis"] = {d.result.swapsPerAxis[0], d.result.swapsPerAxis[1], d.result.swapsPerAxis[2]};
            totalSwaps += d.result.swaps;
            auto names = [](const std::vector<BoxPair>& ps) {
                Json a = Json::array();
                for (const BoxPair& p : ps) a.push_back(pairName(p));
                return a;
            };
            if (f == 0) {
                Json sweep = Json::array();
                for (const SapSweepStep& st : d.trace.sweep) {
                    Json meets = Json::array(), active = Json::array();
                    for (const SapSweepTest& t : st.tests)
                        meets.push_back({{"box", boxName(t.other)}, {"y", t.overlapY}, {"z", t.overlapZ}});
                    for (int a : st.active) active.push_back(boxName(a));
                    sweep.push_back({{"endpoint", endName(st.endpoint.object(), st.endpoint.isMax())},
                                     {"value", st.endpoint.value},
                                     {"meets", meets},
                                     {"active", active}});
                }
                j["sweep"] = sweep;
            }
            j["pairs"] = names(d.pairs);
            j["added"] = names(d.trace.added);
            j["removed"] = names(d.trace.removed);
            fs.push_back(j);
        }
        t["frames"] = fs;
        t["total_swaps"] = totalSwaps;
        return t;
    }

    // ---- drawing ------------------------------------------------------------------------------------

    // Layout (output pixels, y down): 3D view top left, events top right, three axis panels below.
    static constexpr double kTopY = 62, kTopH = 300;
    static constexpr double kViewX = 80, kViewW = 322;  // the triad sits left of the view
    static constexpr double kPanelY = 372, kPanelH = 118;
    static constexpr double kBarX0 = 70, kBarX1 = 540;
    static constexpr double kOrderX0 = 600, kOrderX1 = 1004;

    Image draw3d(GlContext& gl, int ss, const FrameData& d, Eigen::Vector2d axisDir[3]) const {
        Canvas c(gl, canvasOptions(static_cast<int>(kViewW), static_cast<int>(kTopH), ss));
        // Frame the union of every frame's boxes so the camera does not move between frames.
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (int f = 0; f <= s_.frames; ++f)
            for (const MovingBox& m : s_.boxes) {
                lo = lo.cwiseMin(m.box.min + f * m.velocity);
                hi = hi.cwiseMax(m.box.max + f * m.velocity);
            }
        const Vec3 center = 0.5 * (lo + hi);
        const double radius = 0.5 * (hi - lo).norm();
        c.setCamera(framingCamera(center, radius * 0.92, s_.view, Vec3::UnitZ()));
        std::vector<char> paired(d.boxes.size(), 0);
        for (const BoxPair& p : d.pairs) paired[p.a] = paired[p.b] = 1;
        for (std::size_t i = 0; i < d.boxes.size(); ++i) {
            const Aabb& b = d.boxes[i];
            std::vector<Eigen::Vector3d> v(8);
            for (int k = 0; k < 8; ++k)
                v[k] =
                    Vec3(k & 1 ? b.max.x() : b.min.x(), k & 2 ? b.max.y() : b.min.y(), k & 4 ? b.max.z() : b.min.z());
            const std::vector<Eigen::Vector3i> tris = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                                       {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                                       {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
            const Color col = boxColor(static_cast<int>(i));
            c.drawMesh(v, tris, col.withAlpha(0.35f), true);
            const LineStyle edge = paired[i] ? LineStyle{3.0f, roleColor(Role::Highlight), 0.0f, false}
                                             : LineStyle{1.5f, col.scaled(0.7f), 0.0f, false};
            const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                      {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
            c.setStrokeOwner(bodyOwner(boxName(static_cast<int>(i))));
            for (const auto& e : edges) c.drawLine(v[e[0]], v[e[1]], edge);
            c.setStrokeOwner(0);
            TextStyle ts = labelStyle(Role::Ink, 18.0f);
            ts.color = col.scaled(0.6f);
            ts.names = bodyOwner(boxName(static_cast<int>(i)));  // on its own box's edges, nothing else
            // On the box's centre when free, else beside it (identical boxes share a centre; another
            // box's edge may run through it).
            ts.place = true;
            c.drawText(0.5 * (b.min + b.max), boxName(static_cast<int>(i)), ts);
        }
        // Screen directions of the world axes, for the triad drawn beside the view.
        Eigen::Vector2d p0;
        c.project(center, p0);
        for (int k = 0; k < 3; ++k) {
            Eigen::Vector2d pk;
            c.project(center + 0.1 * radius * Vec3::Unit(k), pk);
            axisDir[k] = (pk - p0).normalized();
        }
        return c.readPixels();
    }

    Frame drawFrame(GlContext& gl, int ss, const std::vector<FrameData>& frames, int f) const {
        const FrameData& d = frames[f];
        Canvas c(gl, canvasOptions(kW, kH, ss), Camera::pixels(kW, kH));
        auto P = [](double x, double y) { return Eigen::Vector3d(x, kH - y, 0); };
        const int n = static_cast<int>(d.boxes.size());
        const TextStyle small{14.0f, roleColor(Role::Ink), Anchor::Left, false, false};
        const TextStyle smallBold{14.0f, roleColor(Role::Ink), Anchor::Left, false, true};

        // ---- events (top right) ----
        std::vector<BoxPair> added = d.trace.added, removed = d.trace.removed;
        if (common_.hasLayer("events")) {
            double y = kTopY + 8;
            const double x0 = kViewX + kViewW + 40;
            auto line = [&](const std::string& text, const TextStyle& st, double dy = 21) {
                c.drawTextPx(x0, y, text, st);
                y += dy;
            };
            TextStyle head{17.0f, roleColor(Role::Ink), Anchor::Left, false, true};
            TextStyle body{15.0f, roleColor(Role::Ink), Anchor::Left, false, false};
            if (f == 0) {
                line("Frame 0: initial sort of the 2n endpoints per axis, then one", head);
                line("sweep along x: a min meets each active box, paired if y and z overlap", body, 24);
                y = drawSweepTable(c, d, x0, y);
            } else {
                line("Frame " + std::to_string(f) + ": boxes moved; insertion sort repairs each axis", head);
                line("swaps: x " + std::to_string(d.result.swapsPerAxis[0]) + ", y " +
                         std::to_string(d.result.swapsPerAxis[1]) + ", z " + std::to_string(d.result.swapsPerAxis[2]) +
                         "  (= inversions of the old order)",
                     body, 26);
                // At most 6 lines: every swap that added or removed a pair, then the others in order.
                const int maxLines = 6;
                std::vector<char> keep(d.trace.swaps.size(), 0);
                int kept = 0;
                for (std::size_t i = 0; i < d.trace.swaps.size(); ++i)
                    if (d.trace.swaps[i].event != SapPairEvent::None && kept < maxLines) keep[i] = 1, ++kept;
                for (std::size_t i = 0; i < d.trace.swaps.size() && kept < maxLines; ++i)
                    if (!keep[i]) keep[i] = 1, ++kept;
                for (std::size_t i = 0; i < d.trace.swaps.size(); ++i) {
                    if (!keep[i]) continue;
                    const SapSwap& sw = d.trace.swaps[i];
                    TextStyle st = body;
                    st.sizePx = 14.0f;
                    if (sw.event != SapPairEvent::None) st.color = roleColor(Role::Highlight), st.bold = true;
                    line(swapLine(sw), st, 19);
                }
                const int shown = kept;
                if (d.trace.swaps.empty()) line("no swaps: every order still holds, no pair changes", body);
                if (static_cast<int>(d.trace.swaps.size()) > shown)
                    line("... and " + std::to_string(d.trace.swaps.size() - shown) + " more swaps (no pair change)",
                         body);
                y += 6;
            }
            TextStyle pairsStyle = head;
            pairsStyle.color = roleColor(Role::Highlight);
            line("pairs (overlap on all 3 axes): " + pairList(d.pairs), pairsStyle, 24);
            if (f > 0) line("added: " + pairList(added) + "     removed: " + pairList(removed), body);
        }

        // ---- axis panels ----
        if (common_.hasLayer("intervals")) {
            for (int k = 0; k < 3; ++k) drawAxisPanel(c, P, frames, f, k, small, smallBold, n);
        }
        // The 3D view is rendered on its own canvas and pasted in; its axis triad goes beside it.
        Image view;
        if (common_.hasLayer("view3d")) {
            Eigen::Vector2d dir[3];
            view = draw3d(gl, ss, d, dir);
            const Eigen::Vector2d o(38, kTopY + kTopH - 80);
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector2d q = o + 22.0 * dir[k];
                c.drawArrow(P(o.x(), o.y()), P(q.x(), q.y()), lineStyle(Role::Ink, 2.0f, false, true));
                const Eigen::Vector2d t = o + 33.0 * dir[k];
                c.drawTextPx(t.x(), t.y(), kAxisName[k],
                             TextStyle{15.0f, roleColor(Role::Ink), Anchor::Center, false, true});
            }
        }
        drawTitleAndCaption(c, common_.title + " — frame " + std::to_string(f), common_.caption);
        Image img = c.readPixels();
        if (common_.hasLayer("view3d")) blit(img, view, static_cast<int>(kViewX), static_cast<int>(kTopY));
        Frame fr;
        char name[32];
        std::snprintf(name, sizeof name, "frame_%02d", f);
        fr.name = name;
        fr.caption = f == 0 ? "initial sort: pairs " + pairList(d.pairs)
                            : "frame " + std::to_string(f) + ": " + std::to_string(d.result.swaps) + " swaps, +" +
                                  std::to_string(added.size()) + " / -" + std::to_string(removed.size()) + " pairs";
        fr.image = std::move(img);
        return fr;
    }

    /// Frame 0's sweep along x, one row per endpoint in sorted order: the endpoint and its x, what a
    /// min met in the active list, the active list after. Returns the y below the table.
    double drawSweepTable(Canvas& c, const FrameData& d, double x0, double y) const {
        const double rowH = std::min(19.0, 236.0 / std::max<std::size_t>(1, d.trace.sweep.size() + 1));
        const float size = static_cast<float>(std::min(14.0, rowH - 3));
        const TextStyle head{size, roleColor(Role::Muted).scaled(0.7f), Anchor::Left, false, false};
        const double xMeet = x0 + 92, xActive = x0 + 462;
        c.drawTextPx(x0, y, "x endpoint", head);
        c.drawTextPx(xMeet, y, "meets in the active list", head);
        c.drawTextPx(xActive, y, "active after", head);
        y += rowH;
        for (const SapSweepStep& st : d.trace.sweep) {
            const int id = st.endpoint.object();
            TextStyle t{size, boxColor(id).scaled(0.6f), Anchor::Left, false, true};
            c.drawTextPx(x0, y, endName(id, st.endpoint.isMax()) + " " + formatNumber(st.endpoint.value), t);
            t.bold = false;
            t.color = roleColor(Role::Ink);
            bool paired = false;
            std::string met = st.endpoint.isMax() ? "leaves" : sweepTests(st, id, false, paired);
            if (paired) t.color = roleColor(Role::Highlight), t.bold = true;
            if (c.measureText(met, t).x() > xActive - xMeet - 12) met = sweepTests(st, id, true, paired);
            c.drawTextPx(xMeet, y, met, t);
            std::string active;
            for (int a : st.active) active += (active.empty() ? "" : " ") + boxName(a);
            t.color = roleColor(Role::Ink), t.bold = false;
            c.drawTextPx(xActive, y, active.empty() ? "—" : active, t);
            y += rowH;
        }
        return y + 4;
    }

    template <class ToWorld>
    void drawAxisPanel(Canvas& c, const ToWorld& P, const std::vector<FrameData>& frames, int f, int k,
                       const TextStyle& small, const TextStyle& smallBold, int n) const {
        const FrameData& d = frames[f];
        const double y0 = kPanelY + k * kPanelH;
        // Separator and axis name.
        c.drawLine(P(16, y0 - 4), P(kW - 16, y0 - 4), lineStyle(Role::Muted, 1.0f));
        c.drawTextPx(24, y0 + 46, kAxisName[k], TextStyle{30.0f, roleColor(Role::Ink), Anchor::Center, false, true});
        // Endpoints that moved in this frame's swaps on this axis.
        std::vector<char> moved(2 * n, 0);
        for (const SapSwap& s : d.trace.swaps)
            if (s.axis == k) moved[2 * s.movingObject + s.movingIsMax] = moved[2 * s.passedObject + s.passedIsMax] = 1;
        drawIntervals(c, P, frames, f, k, small, n, moved);
        drawEndpointOrder(c, P, d, f, k, small, smallBold, n, moved);
    }

    // Left: each box's interval on axis k as a bar (moved endpoints marked), the ties, and the number line.
    template <class ToWorld>
    void drawIntervals(Canvas& c, const ToWorld& P, const std::vector<FrameData>& frames, int f, int k,
                       const TextStyle& small, int n, const std::vector<char>& moved) const {
        const FrameData& d = frames[f];
        const double y0 = kPanelY + k * kPanelH;
        // Fixed range over all frames so the motion reads from frame to frame.
        double lo = INFINITY, hi = -INFINITY;
        for (const FrameData& g : frames)
            for (const Aabb& b : g.boxes) lo = std::min(lo, b.min[k]), hi = std::max(hi, b.max[k]);
        const double pad = 0.04 * (hi - lo) + 1e-9;
        lo -= pad, hi += pad;
        auto X = [&](double v) { return kBarX0 + (v - lo) / (hi - lo) * (kBarX1 - kBarX0); };
        // Interval bars, one row per box.
        const double rowH = std::min(13.0, 84.0 / n);
        for (int i = 0; i < n; ++i) {
            const Aabb& b = d.boxes[i];
            const double yc = y0 + 6 + (i + 0.5) * rowH;
            const double xa = X(b.min[k]), xb = std::max(X(b.max[k]), xa + 2.0);
            const double hh = 0.36 * rowH;
            const Color col = boxColor(i);
            c.drawPolygon({P(xa, yc - hh), P(xb, yc - hh), P(xb, yc + hh), P(xa, yc + hh)}, col.withAlpha(0.85f));
            c.drawPolyline({P(xa, yc - hh), P(xb, yc - hh), P(xb, yc + hh), P(xa, yc + hh)}, true,
                           LineStyle{1.0f, col.scaled(0.6f), 0.0f, true});
            TextStyle lab = small;
            lab.anchor = Anchor::Right;
            lab.sizePx = std::min(13.0f, static_cast<float>(rowH));
            lab.color = col.scaled(0.6f);
            lab.bold = true;
            c.drawTextPx(xa - 4, yc, boxName(i), lab);
            for (int e = 0; e < 2; ++e)
                if (moved[2 * i + e]) {
                    const double x = e ? xb : xa;
                    // Within its own row (rows are 13 px; the next row's name starts there).
                    c.drawLine(P(x, yc - hh - 1), P(x, yc + hh + 1),
                               LineStyle{3.0f, roleColor(Role::Highlight), 0.0f, true});
                }
        }
        // Ties: a max of one box at the same coordinate as the min of another (touching intervals),
        // one dashed line and one label per coordinate.
        const double barsBottom = y0 + 6 + n * rowH;
        std::vector<std::pair<double, std::string>> ties;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                if (i != j && d.boxes[i].max[k] == d.boxes[j].min[k]) {
                    const double v = d.boxes[i].max[k];
                    auto it = std::find_if(ties.begin(), ties.end(), [&](const auto& t) { return t.first == v; });
                    const std::string what = endName(j, false) + " before " + endName(i, true);
                    if (it == ties.end()) ties.emplace_back(v, "tie: " + what);
                    else it->second += ", " + what;
                }
        for (const auto& [v, label] : ties) {
            const double x = X(v);
            c.drawLine(P(x, y0 + 2), P(x, barsBottom + 2), LineStyle{1.5f, roleColor(Role::Ink), 4.0f, true});
            TextStyle t = small;
            t.anchor = Anchor::Left;
            t.sizePx = 13.0f;
            t.bold = true;
            c.drawTextPx(x + 4, y0 + 2, label, t);
        }
        // Number line with ticks.
        const double yl = y0 + 96;
        c.drawLine(P(kBarX0, yl), P(kBarX1, yl), lineStyle(Role::Ink, 1.0f, false, true));
        const double span = hi - lo;
        const double step = std::pow(10.0, std::floor(std::log10(span / 2.0)));
        const double nice = span / step > 12 ? 2 * step : step;
        for (double v = std::ceil(lo / nice) * nice; v <= hi; v += nice) {
            c.drawLine(P(X(v), yl), P(X(v), yl + 4), lineStyle(Role::Ink, 1.0f, false, true));
            TextStyle t = small;
            t.anchor = Anchor::Top;
            t.sizePx = 13.0f;
            c.drawTextPx(X(v), yl + 5, formatNumber(v), t);
        }
    }

    // Right: the sorted endpoint list before (top row) and after (bottom row) the insertion sort.
    template <class ToWorld>
    void drawEndpointOrder(Canvas& c, const ToWorld& P, const FrameData& d, int f, int k, const TextStyle& small,
                           const TextStyle& smallBold, int n, const std::vector<char>& moved) const {
        const double y0 = kPanelY + k * kPanelH;
        // Endpoint order before (top row) and after (bottom row) insertion sort.
        const int m = 2 * n;
        const double slot = (kOrderX1 - kOrderX0) / m;
        const double yBefore = y0 + 24, yAfter = y0 + 86;
        auto slotX = [&](int r) { return kOrderX0 + (r + 0.5) * slot; };
        TextStyle hdr = small;
        hdr.sizePx = 13.0f;
        hdr.color = roleColor(Role::Muted).scaled(0.7f);
        c.drawTextPx(kOrderX0 - 8, yBefore, f == 0 ? "by id" : "before",
                     TextStyle{13.0f, hdr.color, Anchor::Right, false, false});
        c.drawTextPx(kOrderX0 - 8, yAfter, "after", TextStyle{13.0f, hdr.color, Anchor::Right, false, false});
        std::vector<int> oldRank(m, 0);
        for (int r = 0; r < m; ++r) oldRank[d.before[k][r].tag] = r;
        for (int r = 0; r < m; ++r) {
            const SapEndpoint& e = d.after[k][r];
            const int r0 = oldRank[e.tag];
            const bool changed = r0 != r;
            const Eigen::Vector3d a = P(slotX(r0), yBefore + 10), b = P(slotX(r), yAfter - 10);
            if (changed)
                c.drawArrow(a, b,
                            LineStyle{2.5f, f == 0 ? roleColor(Role::Muted).scaled(0.8f) : roleColor(Role::Highlight),
                                      0.0f, true});
            else c.drawLine(a, b, LineStyle{1.0f, roleColor(Role::Muted), 0.0f, true});
        }
        auto token = [&](double x, double y, const SapEndpoint& e, bool hot) {
            TextStyle t = hot ? smallBold : small;
            t.anchor = Anchor::Center;
            t.sizePx = 14.0f;
            t.bold = true;
            t.color = hot ? roleColor(Role::Highlight) : boxColor(e.object()).scaled(0.6f);
            c.drawTextPx(x, y, endName(e.object(), e.isMax()), t);
        };
        for (int r = 0; r < m; ++r) {
            token(slotX(r), yBefore, d.before[k][r], f > 0 && moved[d.before[k][r].tag]);
            token(slotX(r), yAfter, d.after[k][r], f > 0 && moved[d.after[k][r].tag]);
        }
    }
};

class SapDemo final : public Demo {
public:
    std::string name() const override { return "sweep_and_prune"; }
    std::string description() const override {
        return "sweep and prune: endpoint lists on x, y, z, insertion-sort swaps and the pair set, frame by frame";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{kW, kH}, {kW, kH, kW, kH}, "figures"}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        if (auto f = r.find("figure"); f && f->asEnum({"frames", "coherence"}) == "coherence")
            return readCoherenceScene(r, std::move(common));
        Settings s;
        const JsonNode boxes = r.get("boxes");
        if (boxes.size() < 2 || boxes.size() > 7) boxes.fail("expected 2 to 7 boxes (named A..G)");
        for (const JsonNode& b : boxes.items()) {
            ObjectReader br(b);
            MovingBox m;
            m.box.min = sceneVec3(br.get("min"));
            m.box.max = sceneVec3(br.get("max"));
            if (auto v = br.find("velocity")) m.velocity = sceneVec3(*v);
            br.finish();
            if (checkBox(m.box) != BoxStatus::Ok) b.fail("a box needs finite min <= max on every axis");
            s.boxes.push_back(m);
        }
        if (auto f = r.find("frames")) s.frames = f->asInt(0, 6);
        if (auto v = r.find("view")) {
            s.view = sceneVec3(*v);
            if (!(s.view.norm() > 0)) v->fail("view direction must be non-zero");
        }
        r.finish();
        return std::make_unique<SapScene>(std::move(common), std::move(s));
    }
};

}  // namespace

const Demo& sweepAndPruneDemo() {
    static const SapDemo demo;
    return demo;
}

}  // namespace cdlab::demos
