#include "demos/drop/impulse_figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/dynamics/impulse_solver.h"
#include "core/dynamics/rigid_body.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/plot.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

struct ImpulseSettings {
    Vec3 halfExtents = Vec3(0.5, 0.3, 0.2);
    double mass = 1.0;
    Quat rotation = Quat::Identity();
    Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
    ImpulseSolverOptions solver;
    Vec3 view = Vec3(0.35, -1.0, 0.3);
};

/// The solve and everything the frames print, in world units (m, kg, s).
struct ImpulseRun {
    RigidBody before, after;
    Mat3 inertiaBody = Mat3::Zero();
    std::vector<Vec3> corners;  ///< the box's 8 vertices (world)
    double ground = 0;          ///< z of the ground plane (the lowest vertex)
    std::vector<ContactConstraintPoint> contacts;
    ImpulseSolverResult result;
    std::vector<double> inverseMassTerm, angularTerm;  ///< per point: 1/m and n·((I⁻¹(r×n))×r)
    std::vector<Vec3> velocityBefore, velocityAfter;   ///< of the body point at each contact
    double closedFormJ = 0;                            ///< Baraff's j at point 0, frictionless
};

const Vec3 kNormal = Vec3::UnitZ();

// The three arrows at a contact: the body point's velocity before (pink) and after (bluish green),
// the impulse (vermillion).
Color beforeColor() { return roleColor(Role::Direction); }
Color afterColor() { return categorical(2); }
Color impulseColor() { return roleColor(Role::Support); }

/// The box's principal inertia about its centre, m/12 (b² + c², a² + c², a² + b²) for sides a, b, c.
Mat3 boxInertia(const ImpulseSettings& s) {
    const Vec3 side = 2 * s.halfExtents;
    return (s.mass / 12.0 * Vec3(side.y() * side.y() + side.z() * side.z(), side.x() * side.x() + side.z() * side.z(),
                                 side.x() * side.x() + side.y() * side.y()))
        .asDiagonal();
}

RigidBodyBuild buildBox(const ImpulseSettings& s) {
    return makeDynamicBody(s.mass, boxInertia(s), Transform{Vec3::Zero(), s.rotation}, s.velocity, s.angularVelocity);
}

/// The solve of a scene whose box builds (readImpulseScene refuses one that does not): a dynamic
/// body touching at one or more corners, so solveContacts answers every contact.
ImpulseRun solve(const ImpulseSettings& s) {
    ImpulseRun run;
    run.inertiaBody = boxInertia(s);
    for (int k = 0; k < 8; ++k)
        run.corners.push_back(s.rotation * Vec3(k & 1 ? s.halfExtents.x() : -s.halfExtents.x(),
                                                k & 2 ? s.halfExtents.y() : -s.halfExtents.y(),
                                                k & 4 ? s.halfExtents.z() : -s.halfExtents.z()));
    run.ground = INFINITY;
    for (const Vec3& c : run.corners) run.ground = std::min(run.ground, c.z());
    const double touch = 1e-9 * s.halfExtents.maxCoeff();
    for (const Vec3& c : run.corners)
        if (c.z() <= run.ground + touch) run.contacts.push_back(ContactConstraintPoint{c, c.z() - run.ground});
    run.before = buildBox(s).body;
    const Mat3 invI = run.before.inverseInertiaWorld();
    for (const ContactConstraintPoint& c : run.contacts) {
        const Vec3 rn = c.point.cross(kNormal);  // r = p − x, x = 0
        run.inverseMassTerm.push_back(run.before.inverseMass);
        run.angularTerm.push_back(kNormal.dot((invI * rn).cross(c.point)));
        run.velocityBefore.push_back(run.before.velocityAt(c.point));
    }
    run.closedFormJ = singleContactImpulse(run.before, kNormal, run.contacts[0].point, s.solver.restitution);
    run.after = run.before;
    ImpulseSolverOptions o = s.solver;
    o.recordIterations = true;
    run.result = solveContacts(run.after, kNormal, run.contacts, o);
    for (const ContactConstraintPoint& c : run.contacts) run.velocityAfter.push_back(run.after.velocityAt(c.point));
    return run;
}

std::string sub(int i) {
    static const char* kSub[10] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
    return kSub[i % 10];
}

Vec3 tangential(const Vec3& v) { return v - v.dot(kNormal) * kNormal; }

class ImpulseScene final : public PreparedScene {
public:
    ImpulseScene(SceneCommon common, ImpulseSettings s) : PreparedScene(std::move(common)), s_(s) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const ImpulseRun run = solve(s_);
        DemoOutput out;
        out.trace = traceJson(run);
        if (numericOnly(ctx, out)) return out;
        const int ss = figureScale(common_, ctx);
        out.frames.push_back(drawImpulse(*ctx.gl, ss, run));
        if (run.contacts.size() >= 2) out.frames.push_back(drawIterations(*ctx.gl, ss, run));
        return out;
    }

private:
    ImpulseSettings s_;

    Json traceJson(const ImpulseRun& run) const {
        Json t = Json::object();
        t["mass"] = s_.mass;
        t["inertia_body"] = vec3Json(run.inertiaBody.diagonal());
        t["normal"] = vec3Json(kNormal);
        t["ground"] = run.ground;
        t["restitution"] = s_.solver.restitution;
        t["friction"] = s_.solver.friction;
        t["velocity_before"] = vec3Json(run.before.linearVelocity);
        t["angular_velocity_before"] = vec3Json(run.before.angularVelocity);
        t["velocity_after"] = vec3Json(run.after.linearVelocity);
        t["angular_velocity_after"] = vec3Json(run.after.angularVelocity);
        t["closed_form_j"] = run.closedFormJ;
        Json pts = Json::array();
        for (std::size_t i = 0; i < run.contacts.size(); ++i) {
            const ContactImpulse& c = run.result.points[i];
            pts.push_back({{"point", vec3Json(c.point)},
                           {"r", vec3Json(c.r)},
                           {"inverse_mass_term", run.inverseMassTerm[i]},
                           {"angular_term", run.angularTerm[i]},
                           {"normal_mass", c.normalMass},
                           {"velocity_before", vec3Json(run.velocityBefore[i])},
                           {"velocity_after", vec3Json(run.velocityAfter[i])},
                           {"normal_velocity_before", c.normalVelocityBefore},
                           {"normal_velocity_after", c.normalVelocityAfter},
                           {"target_velocity", c.targetVelocity},
                           {"bounce", c.bounce},
                           {"normal_impulse", c.normalImpulse},
                           {"restitution_impulse", c.restitutionImpulse},
                           {"tangent_impulse", vec3Json(c.tangentImpulse)}});
        }
        t["points"] = pts;
        t["history"] = run.result.history;
        t["history_change"] = run.result.historyChange;
        t["history_restitution"] = run.result.historyRestitution;
        return t;
    }

    // The box and the ground from the side; at each contact n, the velocity of the body point before
    // and after, and the impulse, each kind of arrow to one scale.
    Image drawView(GlContext& gl, int ss, const ImpulseRun& run, int w, int h) const {
        Canvas c(gl, canvasOptions(w, h, ss));
        const double size = s_.halfExtents.norm();
        c.setCamera(framingCamera(Vec3(0, 0, run.ground + 0.3 * size), 1.35 * size, s_.view, Vec3::UnitZ()));
        const double g = run.ground, e = 2.2 * size;
        c.drawPolygon({Vec3(-e, -e, g), Vec3(e, -e, g), Vec3(e, e, g), Vec3(-e, e, g)}, roleColor(Role::Muted).withAlpha(0.25f));
        const std::vector<Eigen::Vector3i> tris = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
        c.drawMesh(run.corners, tris, roleColor(Role::ShapeA).withAlpha(0.3f), true);
        const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (const auto& ed : edges) c.drawLine(run.corners[ed[0]], run.corners[ed[1]], lineStyle(Role::ShapeA, 2.0f));
        double vMax = 1e-12, jMax = 1e-12;
        for (std::size_t i = 0; i < run.contacts.size(); ++i) {
            vMax = std::max({vMax, run.velocityBefore[i].norm(), run.velocityAfter[i].norm()});
            const ContactImpulse& ci = run.result.points[i];
            jMax = std::max(jMax, (ci.normalImpulse * kNormal + ci.tangentImpulse).norm());
        }
        const double vScale = 0.7 * size / vMax, jScale = 0.7 * size / jMax;
        c.drawPoint(Vec3::Zero(), 7.0f, roleColor(Role::Ink), true);
        c.drawLine(Vec3::Zero(), run.contacts[0].point, lineStyle(Role::Ink, 1.5f, true, true));
        drawLabelAwayText(c, 0.5 * run.contacts[0].point, "r" + sub(0));
        for (std::size_t i = 0; i < run.contacts.size(); ++i) {
            const Vec3 p = run.contacts[i].point;
            const ContactImpulse& ci = run.result.points[i];
            c.drawArrow(p, p + run.velocityBefore[i] * vScale, LineStyle{3.0f, beforeColor(), 0.0f, true});
            c.drawArrow(p, p + run.velocityAfter[i] * vScale, LineStyle{3.0f, afterColor(), 0.0f, true});
            c.drawArrow(p, p + (ci.normalImpulse * kNormal + ci.tangentImpulse) * jScale, LineStyle{3.0f, impulseColor(), 0.0f, true});
            c.drawPoint(p, 9.0f, roleColor(Role::Highlight), true, 1.5f, roleColor(Role::Ink));
            TextStyle ts = labelStyle(Role::Ink, 16.0f);
            ts.place = true;
            ts.offsetPx = Eigen::Vector2d(-14, 14);
            c.drawText(p, "p" + sub(int(i)), ts);
        }
        return c.readPixels();
    }

    static void drawLabelAwayText(Canvas& c, const Vec3& at, const std::string& text) {
        TextStyle ts = labelStyle(Role::Ink, 16.0f);
        ts.place = true;
        ts.offsetPx = Eigen::Vector2d(-12, -12);
        c.drawText(at, text, ts);
    }

    Frame drawImpulse(GlContext& gl, int ss, const ImpulseRun& run) const {
        const int W = common_.image.width, H = common_.image.height;
        Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
        const int viewW = W / 2, viewH = H - 320;
        const TextStyle body{16.0f, roleColor(Role::Ink), Anchor::Left, false, false};
        TextStyle bold = body;
        bold.bold = true;
        // Right of the view: before -> after, and the key.
        double y = 74;
        const double xr = viewW + 30;
        const auto line = [&](double x, const std::string& text, const TextStyle& st, double dy = 22) {
            c.drawTextPx(x, y, text, st);
            y += dy;
        };
        const double ke0 = run.before.kineticEnergy(), ke1 = run.after.kineticEnergy();
        line(xr, "Before → after the impulses", bold, 26);
        line(xr, "v  " + formatPoint(run.before.linearVelocity) + " → " + formatPoint(run.after.linearVelocity), body);
        line(xr, "ω  " + formatPoint(run.before.angularVelocity) + " → " + formatPoint(run.after.angularVelocity), body);
        line(xr, "kinetic energy " + formatNumber(ke0) + " → " + formatNumber(ke1) + " J", body, 34);
        drawKey(c, xr, y, {{beforeColor(), "v_p before"}, {afterColor(), "v_p after"}, {impulseColor(), "impulse"}}, 15.0f);
        y += 30;
        line(xr, "m = " + formatNumber(s_.mass) + " kg, box " + formatPoint(2 * s_.halfExtents) + " m", body);
        line(xr, "e = " + formatNumber(s_.solver.restitution) + ", μ = " + formatNumber(s_.solver.friction) +
                     "; the ground does not move (1/m_B = 0)", body);
        // Below: the single contact's arithmetic at p0, then the solver's answer per point.
        y = viewH + 64;
        const ContactImpulse& c0 = run.result.points[0];
        const double vn = c0.normalVelocityBefore;
        const double invK = run.inverseMassTerm[0] + run.angularTerm[0];
        line(20, "At p₀: r₀ = p₀ − x = " + formatPoint(c0.r) + ",  v_p = v + ω × r₀ = " + formatPoint(run.velocityBefore[0]) +
                     ",  v_n = v_p · n = " + formatNumber(vn), body);
        line(20, "1/k = 1/m + n · ((I⁻¹ (r₀ × n)) × r₀) = " + formatNumber(run.inverseMassTerm[0]) + " + " +
                     formatNumber(run.angularTerm[0]) + " = " + formatNumber(invK), body);
        line(20, vn < 0 ? "j = −(1 + e) v_n k = −(1 + " + formatNumber(s_.solver.restitution) + ") · " + formatNumber(vn) + " / " +
                              formatNumber(invK) + " = " + formatNumber(run.closedFormJ) + " N·s  (one frictionless contact)"
                        : "v_n ≥ 0: p₀ is not approaching, j = 0", bold, 26);
        if (s_.solver.friction > 0 || run.contacts.size() > 1)
            line(20, "(j is one frictionless contact's; friction" +
                         std::string(run.contacts.size() > 1 ? " and the other points also change" : " also changes") +
                         " v_n at p₀, so the solver's λ_n below differs)", body, 30);
        for (std::size_t i = 0; i < run.contacts.size() && i < 2; ++i) {
            const ContactImpulse& ci = run.result.points[i];
            const double lt = ci.tangentImpulse.norm(), cone = s_.solver.friction * ci.normalImpulse;
            const double vt = tangential(run.velocityAfter[i]).norm();
            const bool clamped = lt >= cone * (1 - 1e-9) && lt > 0;
            line(20, "solver at p" + sub(int(i)) + ": λ_n = " + formatNumber(ci.normalImpulse) + " N·s" +
                         (ci.bounce ? " (" + formatNumber(ci.normalImpulse - ci.restitutionImpulse) + " compression + " +
                                          formatNumber(ci.restitutionImpulse) + " restitution)"
                                    : "") +
                         ", v_n " + formatNumber(ci.normalVelocityBefore) + " → " + formatNumber(ci.normalVelocityAfter),
                 body);
            line(48, "friction: |λ_t| = " + formatNumber(lt) +
                         (clamped ? " = μ λ_n: clamped to the cone" : " < μ λ_n = " + formatNumber(cone) + ": inside the cone") +
                         ";  |v_t| " + formatNumber(tangential(run.velocityBefore[i]).norm()) + " → " + formatNumber(vt) +
                         " m/s",
                 body);
        }
        line(20, "(|v_t| after includes what the restitution pass does: a normal impulse off the centre turns the body)", body);
        if (run.contacts.size() > 2)
            line(20, "… and " + std::to_string(run.contacts.size() - 2) + " more points (frame iterations, trace.json)", body);
        drawTitleAndCaption(c, common_.title, common_.caption);
        Image img = c.readPixels();
        blit(img, drawView(gl, ss, run, viewW, viewH), 10 * ss, 50 * ss);
        return Frame{"impulse", common_.title, std::move(img)};
    }

    Frame drawIterations(GlContext& gl, int ss, const ImpulseRun& run) const {
        PlotOptions po = scenePlotOptions(common_, ss);
        po.title += ": sequential impulses";
        po.logX = po.logY = false;
        po.legendWidth = 190;
        po.xLabel = "sweep (" + std::to_string(s_.solver.iterations) + " compression" +
                    (run.result.historyRestitution ? ", then " + std::to_string(run.result.historyRestitution) + " restitution)" : ")");
        po.yLabel = "accumulated normal impulse λ_n (N·s)";
        po.subtitle = "A sweep visits the points in turn, clamping the accumulated λ_n ≥ 0; last sweep's max |Δλ| " +
                      formatNumber(run.result.historyChange.empty() ? 0.0 : run.result.historyChange.back());
        std::vector<PlotSeries> series;
        for (std::size_t i = 0; i < run.contacts.size(); ++i) {
            static constexpr int kStyles[4] = {1, 2, 0, 5};  // not yellow: faint on white
            PlotSeries p{"p" + sub(int(i)), kStyles[i % 4], true, true, {}, {}};
            for (std::size_t k = 0; k < run.result.history.size(); ++k) p.points.emplace_back(double(k + 1), run.result.history[k][i]);
            series.push_back(std::move(p));
        }
        return Frame{"iterations", common_.title + ": λ_n per sweep", drawLogLogPlot(gl, po, series)};
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readImpulseScene(ObjectReader& r, SceneCommon common) {
    ImpulseSettings s;
    ObjectReader br(r.get("box"));
    const JsonNode he = br.get("half_extents");
    s.halfExtents = sceneVec3(he);
    if (!(s.halfExtents.minCoeff() > 0)) he.fail("half extents must be positive");
    br.finish();
    if (auto m = r.find("mass")) {
        s.mass = m->asPositive();
        requireAtMost(*m, s.mass, 1e6, "mass", "the physical range an impulse scene accepts");
        requireAtLeast(*m, s.mass, 1e-6, "mass", "the impulse solver divides by it");
    }
    if (auto q = r.find("rotation")) s.rotation = q->asQuat();
    if (auto v = r.find("velocity")) s.velocity = sceneVec3(*v);
    if (auto w = r.find("angular_velocity")) s.angularVelocity = sceneVec3(*w);
    requireAtMost(r.node(), std::max(s.velocity.norm(), s.angularVelocity.norm()), 1e3, "speed",
                  "the physical range an impulse scene accepts");
    if (auto e = r.find("restitution")) {
        s.solver.restitution = e->asNonNegative();
        if (s.solver.restitution > 1) e->fail("restitution is at most 1");
    }
    if (auto m = r.find("friction")) {
        s.solver.friction = m->asNonNegative();
        requireAtMost(*m, s.solver.friction, 10.0, "friction", "a Coulomb coefficient");
    }
    if (auto t = r.find("restitution_threshold")) s.solver.restitutionThreshold = t->asNonNegative();
    if (auto n = r.find("iterations")) s.solver.iterations = n->asInt(1, 64);
    if (auto v = r.find("view")) {
        s.view = sceneVec3(*v);
        if (!(s.view.norm() > 0)) v->fail("view direction must be non-zero");
    }
    r.finish();
    // A box so thin that its inertia is no valid rigid body (a near-singular inertia) is refused here,
    // naming the box: the solver would treat it as static and answer no contact at all.
    if (const RigidBodyBuild built = buildBox(s); !built.ok()) he.fail("this box makes no valid rigid body: " + built.message);
    return std::make_unique<ImpulseScene>(std::move(common), s);
}

}  // namespace cdlab::demos
