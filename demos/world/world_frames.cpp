// The world demo's frames (demos/world/world_record.h): a snapshot from the side and from above,
// one step as the pipeline, and the per-step plots. Numbers drawn come from the snapshot's step
// stats and contacts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/plot.h"
#include "demos/world/world_record.h"
#include "render/canvas.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr double kHeadroomPx = 185;
constexpr std::size_t kMaxContactDots = 600;  // more would cover the bodies
// Bodies drawn with their edges and outlines up to this many: a 1000-body pile's strokes (~30 a
// body) made each frame's layout record 2.5 MB; past it the shading and the contact tint show them.
constexpr std::size_t kMaxOutlinedBodies = 300;  // text band at a panel's top: title, status lines, legend

// The extent of every bounded body over every snapshot (x, y, z), for cameras shared by all frames.
struct Extent {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    void add(const Vec3& p, double r) {
        lo = lo.cwiseMin(p - Vec3::Constant(r));
        hi = hi.cwiseMax(p + Vec3::Constant(r));
    }
};

// The extent of every bounded body over every snapshot drawn: one camera for all frames, so a
// body's motion reads from frame to frame (framed on each snapshot, a row moving 0.7 m looked the
// same in every frame: the hostile review).
Extent extentOf(const WorldRun& run) {
    Extent e;
    const auto addAll = [&](const StepSnapshot& s) {
        for (std::size_t i = 0; i < s.poses.size(); ++i)
            if (run.shapes[i].kind != WorldShape::Kind::Plane) {
                const Aabb b = worldBounds(run.shapes[i], s.poses[i]);
                e.add(b.min, 0.0);
                e.add(b.max, 0.0);
            }
    };
    for (const StepSnapshot& s : run.frames) addAll(s);
    if (run.hasPipeline) addAll(run.pipeline);
    e.lo.z() = std::min(e.lo.z(), 0.0);
    if (!(e.hi.x() > e.lo.x())) e.lo = Vec3::Constant(-1), e.hi = Vec3::Constant(1);
    return e;
}

// An orthographic camera looking along `back` (towards the eye) at the box [lo, hi] projected on
// its (right, up) axes, leaving kHeadroomPx at the top and 40 px at the bottom for text.
Camera orthoCamera(const Extent& e, const Vec3& back, const Vec3& up, int width, int height) {
    const Vec3 right = up.cross(back);
    const Vec3 c = 0.5 * (e.lo + e.hi), h = 0.5 * (e.hi - e.lo);
    const double halfRight = std::abs(right.x()) * h.x() + std::abs(right.y()) * h.y() + std::abs(right.z()) * h.z();
    const double halfUp = std::abs(up.x()) * h.x() + std::abs(up.y()) * h.y() + std::abs(up.z()) * h.z();
    const double usable = (height - kHeadroomPx - 40.0) / height;
    Camera cam;
    cam.projection = Camera::Projection::Orthographic;
    cam.viewHeight = std::max(2.1 * halfUp, 2.1 * halfRight * height / width) / usable;
    // The scene's box sits centred in the band under the headroom.
    const double shift = (0.5 * (kHeadroomPx - 40.0) / height) * cam.viewHeight;
    cam.target = c + shift * up;
    const double distance = 4.0 * (cam.viewHeight + h.norm());
    cam.eye = cam.target + distance * back;
    cam.up = up;
    cam.nearPlane = 0.01 * distance;
    cam.farPlane = 8.0 * distance;
    return cam;
}

// A rounded body's outline as the eye sees it (orthographic): a circle around a sphere's centre, a
// stadium around a capsule's segment, in the plane through the centre facing the eye.
std::vector<Vec3> roundedOutline(const WorldShape& s, const Transform& t, const Vec3& back) {
    Vec3 axis = s.kind == WorldShape::Kind::Capsule ? Vec3(t.rotation * Vec3(0, s.halfHeight, 0)) : Vec3::Zero();
    axis -= axis.dot(back) * back;
    Vec3 u = axis.norm() > 1e-9 ? Vec3(axis.normalized()) : Vec3(back.unitOrthogonal());
    const Vec3 v = back.cross(u);
    std::vector<Vec3> out;
    const int n = 24;
    for (int half = 0; half < 2; ++half) {
        const Vec3 centre = t.position + (half == 0 ? axis : Vec3(-axis));
        const double start = half == 0 ? -0.5 * M_PI : 0.5 * M_PI;
        for (int k = 0; k <= n; ++k) {
            const double a = start + M_PI * k / n;
            out.push_back(centre + s.radius * (std::cos(a) * u + std::sin(a) * v));
        }
    }
    return out;
}

// Every body of a snapshot: dynamic ones in the first body colour, static ones muted; those in
// contact (a point with λ_n > 0) tinted and outlined in the colliding colour.
// staticFill false: static bodies as their edges only (the side view looks through the bin's near
// wall).
void drawBodies(Canvas& c, const WorldRun& run, const StepSnapshot& s, const Vec3& back, bool outlineContacts,
                float fade = 0.0f, bool staticFill = true) {
    for (std::size_t i = 0; i < s.poses.size(); ++i) {
        const WorldShape& shape = run.shapes[i];
        if (shape.kind == WorldShape::Kind::Plane) continue;
        const bool touching = outlineContacts && !s.touching.empty() && s.touching[i];
        Color fill = run.isStatic[i] ? roleColor(Role::Muted) : roleColor(Role::ShapeA);
        if (touching) fill = fill.mixed(roleColor(Role::Colliding), 0.3f);
        if (fade > 0) fill = fill.mixed(roleColor(Role::Background), fade);
        const BodyMesh& m = run.meshes[i];
        std::vector<Vec3> wv;
        for (const Vec3& v : m.vertices) wv.push_back(s.poses[i].apply(v));
        if (staticFill || !run.isStatic[i]) c.drawMesh(wv, m.triangles, fill, true);
        if (s.poses.size() > kMaxOutlinedBodies && !run.isStatic[i]) continue;
        LineStyle edge = lineStyle(Role::Ink, touching ? 2.5f : 1.0f);
        edge.color = touching ? roleColor(Role::Colliding) : roleColor(run.isStatic[i] ? Role::Muted : Role::ShapeA).scaled(0.5f);
        if (fade > 0) edge.color = edge.color.mixed(roleColor(Role::Background), fade);
        for (const auto& [a, b] : m.edges) c.drawLine(wv[std::size_t(a)], wv[std::size_t(b)], edge);
        if (shape.rounded()) {
            LineStyle o = edge;
            o.onTop = false;
            c.drawPolyline(roundedOutline(shape, s.poses[i], back), true, o);
        }
    }
}

// The ground z = 0 seen edge-on from the side: a line across the bodies' extent.
void drawGround(Canvas& c, const Extent& e) {
    const double pad = 0.04 * (e.hi - e.lo).head<2>().maxCoeff();
    c.drawLine(Vec3(e.lo.x() - pad, e.hi.y() + pad, 0), Vec3(e.hi.x() + pad, e.hi.y() + pad, 0),
               lineStyle(Role::Muted, 2.5f));
}

bool hasGround(const WorldRun& run) {
    return std::any_of(run.shapes.begin(), run.shapes.end(),
                       [](const WorldShape& s) { return s.kind == WorldShape::Kind::Plane; });
}

// The typical body size: the median bounding radius of the dynamic bodies.
double typicalRadius(const WorldRun& run) {
    std::vector<double> r;
    for (std::size_t i = 0; i < run.shapes.size(); ++i)
        if (!run.isStatic[i]) r.push_back(run.shapes[i].boundingRadius);
    if (r.empty()) return 1.0;
    std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
    return r[r.size() / 2];
}

// Contact points (filled: pushing, hollow: speculative) and, with arrows, each pushing point's
// impulse λ_n n (the push on B) to one scale: the run's largest λ_n is `arrowLength` long.
void drawContacts(Canvas& c, const WorldRun& run, const StepSnapshot& s, bool arrows, double arrowLength) {
    if (arrows && run.maxImpulse > 0)
        for (const ContactSnapshot& ct : s.contacts)
            if (ct.impulse > 0.02 * run.maxImpulse)
                c.drawArrow(ct.point, ct.point + arrowLength * ct.impulse / run.maxImpulse * ct.normal,
                            lineStyle(Role::Direction, 2.0f, false, true));
    // Dense snapshots (over 200 points) get smaller dots, so the bodies under them still read; over
    // kMaxContactDots none (the legend says so).
    if (s.contacts.size() > kMaxContactDots) return;
    const float r = s.contacts.size() > 200 ? 2.0f : 3.5f;
    for (const ContactSnapshot& ct : s.contacts) {
        if (ct.impulse > 0) c.drawPoint(ct.point, r, roleColor(Role::Result), true, 1.0f, roleColor(Role::Ink));
        else c.drawPoint(ct.point, r - 0.5f, roleColor(Role::Background), true, 1.5f, roleColor(Role::Result));
    }
}

Image panel(GlContext& gl, int scale, int width, int height, const Camera& cam, const std::function<void(Canvas&)>& draw) {
    Canvas c(gl, canvasOptions(width, height, scale), cam);
    draw(c);
    return c.readPixels();
}

Image sideBySide(const std::vector<Image>& panels, int scale) {
    int w = 0, h = 0;
    for (const Image& p : panels) w += p.width, h = std::max(h, p.height);
    Image frame = Image::blank(w, h, scale);
    int x = 0;
    for (const Image& p : panels) {
        frame.layout.panels.push_back({double(x), 0.0, double(p.width), double(p.height)});
        blit(frame, p, x, 0);
        if (x > 0) paintRect(frame, x - 1, 0, 2, h, roleColor(Role::Muted));
        x += p.width;
    }
    return frame;
}

const TextStyle kStatus{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
const TextStyle kHeading{20.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true};

}  // namespace

Frame drawWorldFrame(GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run, const StepSnapshot& s,
                     int index) {
    const int W = common.image.width / 2, H = common.image.height;
    const Extent e = extentOf(run);
    const Camera side = orthoCamera(e, -Vec3::UnitY(), Vec3::UnitZ(), W, H);
    const Camera top = orthoCamera(e, Vec3::UnitZ(), Vec3::UnitY(), W, H);
    const bool contacts = common.hasLayer("contacts"), arrows = common.hasLayer("impulses");
    const bool labels = common.hasLayer("labels");
    const bool ground = common.hasLayer("ground") && hasGround(run);
    const double arrowLength = 1.5 * typicalRadius(run);
    int pushing = 0;
    for (const ContactSnapshot& c : s.contacts) pushing += c.impulse > 0;
    char line1[200], line2[200], line3[200], line4[200];
    std::snprintf(line1, sizeof line1, "t = %.2f s, step %d: %d pairs tested, %d manifolds", s.time, s.step,
                  s.stats.narrowTests, s.stats.manifolds);
    std::snprintf(line2, sizeof line2, "%d contact points, %d pushing; deepest %.3g (slop %.3g)", s.stats.contactPoints,
                  pushing, s.stats.deepestPenetration, run.options.slop);
    std::snprintf(line3, sizeof line3, "after the step: E = %.4g J (KE %.3g + PE %.4g)", s.stats.kinetic + s.stats.potential,
                  s.stats.kinetic, s.stats.potential);
    std::snprintf(line4, sizeof line4, "momentum (%.4g, %.4g, %.4g) N·s", s.stats.momentum.x() + 0.0,
                  s.stats.momentum.y() + 0.0, s.stats.momentum.z() + 0.0);
    bool drawsArrows = false, hasStatic = false;
    for (const ContactSnapshot& c : s.contacts) drawsArrows |= arrows && c.impulse > 0.02 * run.maxImpulse;
    for (std::size_t i = 0; i < run.shapes.size(); ++i)
        hasStatic |= run.isStatic[i] && run.shapes[i].kind != WorldShape::Kind::Plane;
    const Image left = panel(gl, scale, W, H, side, [&](Canvas& c) {
        if (ground) drawGround(c, e);
        drawBodies(c, run, s, side.viewDirection(), contacts, 0.0f, false);
        if (contacts) drawContacts(c, run, s, arrows, arrowLength);
        drawTitleAndCaption(c, common.title, "");
        if (labels) {
            c.drawTextPx(18, 54, line1, kStatus);
            c.drawTextPx(18, 76, line2, kStatus);
            c.drawTextPx(18, 98, line3, kStatus);
            c.drawTextPx(18, 120, line4, kStatus);
            c.drawTextPx(18, 146, "Side view (looking along +y)", kHeading);
        }
    });
    const Image right = panel(gl, scale, W, H, top, [&](Canvas& c) {
        drawBodies(c, run, s, top.viewDirection(), contacts);
        if (contacts) drawContacts(c, run, s, false, arrowLength);
        if (!labels) return;
        c.drawTextPx(18, 18, "Top view (looking down)", kHeading);
        // The legend, one entry a row, each in the colour of what it names.
        double y = 50;
        const auto item = [&](const std::string& text, Role role) {
            const Color color = role == Role::Result ? roleColor(Role::Result).scaled(0.75f)
                                : role == Role::Muted ? roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f)
                                                      : roleColor(role);
            c.drawTextPx(18, y, text, TextStyle{16.0f, color, Anchor::TopLeft, true, false});
            y += 22;
        };
        if (contacts) {
            item(s.poses.size() > kMaxOutlinedBodies ? "tint: body with a pushing contact (outlines: up to 300 bodies)"
                                                     : "tint and outline: body with a pushing contact",
                 Role::Colliding);
            if (s.contacts.size() <= kMaxContactDots)
                item("filled dot: contact pushing (λₙ > 0); hollow: speculative", Role::Result);
            else
                item("contact points not drawn: " + std::to_string(s.contacts.size()) + " (over " +
                         std::to_string(kMaxContactDots) + ")", Role::Result);
        }
        if (drawsArrows)
            item("arrow (side view): λₙ n, one scale for all frames (longest " + formatNumber(run.maxImpulse) + " N·s)",
                 Role::Direction);
        if (hasStatic) item("grey: static walls (side view: their edges)", Role::Muted);
    });
    char name[32], cap[160];
    std::snprintf(name, sizeof name, "frame_%02d", index);
    std::snprintf(cap, sizeof cap, "t = %.2f s: %d points, E = %.3g J", s.time, s.stats.contactPoints,
                  s.stats.kinetic + s.stats.potential);
    return Frame{name, cap, sideBySide({left, right}, scale)};
}

Frame drawPipelineFrame(GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run) {
    const StepSnapshot& s = run.pipeline;
    const int W = common.image.width / 3, H = common.image.height;
    const Extent e = extentOf(run);
    const Camera side = orthoCamera(e, -Vec3::UnitY(), Vec3::UnitZ(), W, H);
    const Vec3 back = side.viewDirection();
    const double arrowLength = 1.5 * typicalRadius(run);
    char head[3][120];
    std::snprintf(head[0], sizeof head[0], "1. Broad phase: %d pairs of grown boxes", s.stats.broadPairs);
    std::snprintf(head[1], sizeof head[1], "2. Narrow phase: %d manifolds, %d points", s.stats.manifolds,
                  s.stats.contactPoints);
    std::snprintf(head[2], sizeof head[2], "3. Solver: impulses λₙ n (%d warm-started)", s.stats.warmStartedPoints);
    std::vector<Image> panels;
    for (int p = 0; p < 3; ++p)
        panels.push_back(panel(gl, scale, W, H, side, [&](Canvas& c) {
            if (hasGround(run)) drawGround(c, e);
            drawBodies(c, run, s, back, p == 2, p == 0 ? 0.45f : 0.0f, false);
            if (p == 0) {
                // Each grown box as its side-view rectangle; each pair as a line between the centres.
                LineStyle box = lineStyle(Role::Highlight, 1.5f, true);
                for (std::size_t i = 0; i < s.grownBoxes.size(); ++i) {
                    if (run.shapes[i].kind == WorldShape::Kind::Plane) continue;
                    const Aabb& b = s.grownBoxes[i];
                    const double y = b.min.y() - 0.01;
                    c.drawPolyline({Vec3(b.min.x(), y, b.min.z()), Vec3(b.max.x(), y, b.min.z()),
                                    Vec3(b.max.x(), y, b.max.z()), Vec3(b.min.x(), y, b.max.z())},
                                   true, box);
                }
                for (const auto& [a, b] : s.pairs)
                    c.drawLine(s.poses[std::size_t(a)].position, s.poses[std::size_t(b)].position,
                               lineStyle(Role::Simplex, 2.0f, false, true));
            } else if (p == 1) {
                for (const ContactSnapshot& ct : s.contacts)
                    c.drawLine(ct.point, ct.point + 0.5 * arrowLength * ct.normal, lineStyle(Role::Ink, 1.5f, false, true));
                drawContacts(c, run, s, false, arrowLength);
            } else {
                drawContacts(c, run, s, true, arrowLength);
            }
            if (p == 0) drawTitleAndCaption(c, common.title + ": one step", "");
            c.drawTextPx(18, 60, head[p], kHeading);
            const std::string note[3] = {"dashed: a body's grown box; line: a pair",
                                         "dot: contact point; line: its normal n (A → B)",
                                         "arrow: λₙ n on B; longest " + formatNumber(run.maxImpulse) + " N·s"};
            c.drawTextPx(18, 90, note[p], kStatus);
        }));
    char cap[160];
    std::snprintf(cap, sizeof cap, "step %d as the pipeline: %d pairs, %d manifolds, %d points", s.step,
                  s.stats.broadPairs, s.stats.manifolds, s.stats.contactPoints);
    return Frame{"pipeline", cap, sideBySide(panels, scale)};
}

std::vector<Frame> drawWorldPlots(GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run) {
    std::vector<Frame> out;
    const auto series = [&](const std::string& label, int style, auto value) {
        PlotSeries s;
        s.label = label;
        s.style = style;
        s.line = true;
        s.markers = false;
        for (const WorldStepStats& st : run.stats) s.points.emplace_back(st.time, value(st));
        return s;
    };
    PlotOptions o = scenePlotOptions(common, scale);
    o.logX = false;
    o.xLabel = "time (s)";
    o.logY = false;
    o.title = common.title + ": pairs and contacts per step";
    o.yLabel = "count";
    out.push_back(Frame{"counts", "pairs and contact points per step",
                        drawLogLogPlot(gl, o, {series("narrow-phase pairs", 0, [](const WorldStepStats& s) { return double(s.narrowTests); }),
                                               series("broad-phase pairs", 1, [](const WorldStepStats& s) { return double(s.broadPairs); }),
                                               series("manifolds", 2, [](const WorldStepStats& s) { return double(s.manifolds); }),
                                               series("contact points", 3, [](const WorldStepStats& s) { return double(s.contactPoints); })})});
    o.title = common.title + ": energy";
    o.yLabel = "energy (J)";
    out.push_back(Frame{"energy", "kinetic, potential and total energy",
                        drawLogLogPlot(gl, o, {series("total E = KE + PE", 0, [](const WorldStepStats& s) { return s.energy(); }),
                                               series("kinetic KE", 1, [](const WorldStepStats& s) { return s.kinetic; }),
                                               series("potential PE = −m g · x", 2, [](const WorldStepStats& s) { return s.potential; })})});
    o.title = common.title + ": deepest penetration";
    o.yLabel = "deepest contact (world units)";
    o.logY = true;
    o.yFloor = 1e-6;
    o.hLines = {{run.options.slop, "slop " + formatNumber(run.options.slop)}};
    o.subtitle = "the deepest point the narrow phase finds at each step's start; ≤ 1e-6 drawn at 1e-6";
    out.push_back(Frame{"penetration", "deepest penetration against the slop",
                        drawLogLogPlot(gl, o, {series("deepest penetration", 0, [](const WorldStepStats& s) { return s.deepestPenetration; })})});
    return out;
}

}  // namespace cdlab::demos
