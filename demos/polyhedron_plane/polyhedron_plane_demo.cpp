// Contact-model figures. Every number comes from core (contactPolyhedronPlane, featureDistance,
// contactPolyhedra) and their traces; this file only chooses what to draw.
//
// Scene keys (besides the common ones), by "mode":
//   "plane" (default): "body" ({"box": {"half_extents"}} | {"tetrahedron"|"icosahedron": {"circumradius"}}
//            | {"prism": {"sides", "radius", "half_height"}}), "poses": [{"position", "rotation", "label",
//            "view" (this pose's camera direction, same framing), "rest_height" (lowest vertex that high)}]
//            (1..6, one frame each), "plane": {"normal", "offset"} (default z = 0), "max_points" (4).
//   "features": "pairs": [{"a": F, "b": F, "label"}] (1..6, one frame each), F = {"vertex": p} |
//            {"edge": [p, q]} | {"face": [p, ...]} (convex, counter-clockwise seen from outside).
//   "sat": "a", "b": {"body": ..., "position", "rotation"}; frames "contact" and "clip".
//   "view": camera direction (default (1, -1.6, 0.8)), z up.
// Layers: "plane", "contacts", "normals", "polygon", "labels".
#include "demos/polyhedron_plane/polyhedron_plane_demo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include "core/closest/feature_distance.h"
#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/geometry/polyhedron_presets.h"
#include "app/scene/body_scene.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/zoom_inset.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"plane", "contacts", "normals", "polygon", "labels"};
constexpr int kMaxFrames = 6;

std::string fmt(double x) { return formatNumber(x); }

struct Posed {
    ConvexPolyhedron mesh;
    Transform pose;
    std::string name;
    std::vector<Vec3> world() const {
        std::vector<Vec3> w;
        for (const Vec3& v : mesh.positions()) w.push_back(pose.apply(v));
        return w;
    }
};

ConvexPolyhedron readBody(const JsonNode& b, std::string& name) { return readConvexBody(b, name); }

Transform readPose(ObjectReader& r) {
    Transform t;
    if (auto p = r.find("position")) t.position = sceneVec3(*p);
    if (auto q = r.find("rotation")) t.rotation = q->asQuat();
    return t;
}

FeatureGeometry readFeature(const JsonNode& n) {
    if (!n.isObject() || n.raw().size() != 1)
        n.fail("expected {\"vertex\": p}, {\"edge\": [p, q]} or {\"face\": [p, ...]}");
    const std::string key = n.raw().begin().key();
    const JsonNode v(n.raw().begin().value(), n.path() + "." + key, n.source());
    FeatureGeometry f;
    if (key == "vertex") f = {FeatureType::Vertex, {sceneVec3(v)}};
    else if (key == "edge") {
        if (v.size() != 2) v.fail("an edge is [p, q]");
        f = {FeatureType::Edge, sceneVec3List(v, 2, 2)};
    } else if (key == "face") {
        f = {FeatureType::Face, sceneVec3List(v, 3, kMaxFacePoints)};
    } else {
        n.fail("unknown feature '" + key + "'");
    }
    return f;
}

std::vector<Eigen::Vector3i> triangles(const ConvexPolyhedron& m) {
    std::vector<Eigen::Vector3i> t;
    for (int f = 0; f < m.faceCount(); ++f) {
        const std::vector<int> fv = m.faceVertices(f);
        for (size_t i = 1; i + 1 < fv.size(); ++i) t.emplace_back(fv[0], fv[i], fv[i + 1]);
    }
    return t;
}

// A colliding body keeps its colour; its outline says it collides (Role::Colliding, thicker).
void drawPosed(Canvas& c, const Posed& b, const Color& fill, float alpha, bool colliding = false) {
    const std::vector<Vec3> w = b.world();
    c.noteBody(b.name.empty() ? "body" : b.name, w);
    c.drawMesh(w, triangles(b.mesh), fill.withAlpha(alpha), true);
    LineStyle edge;
    edge.widthPx = colliding ? 3.5f : 2.0f;
    edge.color = colliding ? roleColor(Role::Colliding) : fill.scaled(0.55f);
    for (int e = 0; e < b.mesh.edgeCount(); ++e) {
        const auto [u, v] = b.mesh.edgeVertices(e);
        const auto [f1, f2] = b.mesh.edgeFaces(e);
        c.drawLine(w[u], w[v],
                   edgeStyleSeen(c.camera(), 0.5 * (w[u] + w[v]), b.pose.rotate(b.mesh.plane(f1).normal),
                                 b.pose.rotate(b.mesh.plane(f2).normal), edge));
    }
}

std::vector<Vec3> facePolygon(const Posed& b, int f) {
    std::vector<Vec3> p;
    for (int v : b.mesh.faceVertices(f)) p.push_back(b.pose.apply(b.mesh.position(v)));
    return p;
}

Vec3 centroid(const std::vector<Vec3>& p) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : p) c += x;
    return p.empty() ? c : Vec3(c / double(p.size()));
}

// Legend at the top right: entries in the colour of what they name.
struct Legend {
    Canvas& c;
    double y = 60.0;
    void item(const std::string& text, Role role) {
        c.drawTextPx(c.width() - 18.0, y, text, TextStyle{16.0f, roleColor(role), Anchor::TopRight, true, true});
        y += 22.0;
    }
};

// The frame's title, its result line at the bottom and, above it, the scene's caption (docs/scenes.md
// promises the caption on every frame).
Frame finish(Canvas& c, const std::string& name, const std::string& title, const std::string& caption,
             const std::string& shortCaption, const std::string& sceneCaption,
             const std::function<Image(Canvas&)>& read = {}) {
    drawTitleAndCaption(c, title, caption);
    if (!sceneCaption.empty())
        c.drawTextPx(18.0, c.height() - 18.0 - 28.0, sceneCaption,
                     TextStyle{17.0f, roleColor(Role::Muted).scaled(0.8f), Anchor::BottomLeft, true, false});
    return Frame{name, shortCaption, read ? read(c) : c.readPixels()};
}

Json pointsJson(std::span<const ContactPoint> pts) {
    Json a = Json::array();
    for (const ContactPoint& p : pts)
        a.push_back({{"point_a", vec3Json(p.pointA)}, {"point_b", vec3Json(p.pointB)}, {"depth", p.depth}});
    return a;
}

// ---------------------------------------------------------------------------------------------

class ContactScene final : public PreparedScene {
public:
    std::string mode;
    Posed body;  // plane mode
    std::vector<Transform> poses;
    std::vector<std::string> poseLabels;
    std::vector<std::optional<Vec3>> poseViews;  // a pose's own camera direction ("view" in the pose)
    Plane plane{Vec3::UnitZ(), 0.0};
    int maxPoints = 4;
    std::vector<std::pair<FeatureGeometry, FeatureGeometry>> pairs;  // features mode
    std::vector<std::string> pairLabels;
    Posed a, b;  // sat mode
    Vec3 view{1.0, -1.6, 0.8};

    explicit ContactScene(SceneCommon common) : PreparedScene(std::move(common)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        DemoOutput out;
        const int ss = figureScale(common_, ctx);
        if (mode == "plane") runPlane(ctx, ss, out);
        else if (mode == "features") runFeatures(ctx, ss, out);
        else runSat(ctx, ss, out);
        numericOnly(ctx, out);  // records that nothing was drawn
        return out;
    }

private:
    // ---- plane mode ---------------------------------------------------------------------------
    void runPlane(const RunContext& ctx, int ss, DemoOutput& out) const {
        std::vector<PlaneContactResult> results;
        std::vector<PlaneContactTrace> traces(poses.size());
        Json frames = Json::array();
        for (size_t i = 0; i < poses.size(); ++i) {
            PlaneContactOptions opt;
            opt.maxPoints = maxPoints;
            results.push_back(contactPolyhedronPlane(body.mesh, poses[i], plane, opt, &traces[i]));
            const PlaneContactResult& r = results.back();
            Json fr = {{"label", poseLabels[i]},
                       {"status", nameOf(r.status)},
                       {"signed_distance", r.signedDistance},
                       {"depth", r.depth},
                       {"normal", vec3Json(r.normal)},
                       {"feature", featureLabel(r.feature)},
                       {"vertex_signed_distances", traces[i].vertexDistances},
                       {"crossings", traces[i].crossings.size()},
                       {"polygon", pointsJson(r.polygon)},
                       {"manifold", pointsJson(r.manifold)}};
            Json red = Json::array();
            for (const auto& s : traces[i].reduction)
                red.push_back({{"rule", s.rule}, {"candidate", s.chosen}, {"score", s.score}});
            fr["reduction"] = red;
            frames.push_back(fr);
        }
        out.trace = {{"mode", "plane"}, {"body", body.name}, {"frames", frames}};
        if (!ctx.gl) return;

        const PlaneView v = planeView();
        for (size_t i = 0; i < poses.size(); ++i)
            out.frames.push_back(planeFrame(*ctx.gl, ss, v, i, results[i], traces[i]));
    }

    // The plane (unit normal n, offset d) and one camera for all poses: the bodies and the plane patch under them.
    struct PlaneView {
        Vec3 n;
        double d;
        Vec3 center;
        double radius;
        Vec3 up;
        Camera cam;
        // Pose i's camera: its own "view" direction with the same framing, else the common one.
        Camera cameraFor(std::size_t i, const ContactScene& scene) const {
            if (scene.common_.camera || !scene.poseViews[i]) return cam;
            return framingCamera(center, radius * 1.1, *scene.poseViews[i], up);
        }
    };
    PlaneView planeView() const {
        const Vec3 n = plane.normal.normalized();
        const double d = plane.offset / plane.normal.norm();
        std::vector<Vec3> pts;
        for (const Transform& t : poses)
            for (const Vec3& v : body.mesh.positions()) {
                const Vec3 x = t.apply(v);
                pts.push_back(x);
                pts.push_back(x - (n.dot(x) - d) * n);
            }
        Vec3 center;
        double radius;
        boundingSphere(pts, center, radius);
        const Vec3 up = std::abs(n.z()) > 0.5 ? Vec3(n) : Vec3::UnitZ();
        const Camera cam = common_.camera ? *common_.camera : framingCamera(center, radius * 1.1, view, up);
        return {n, d, center, radius, up, cam};
    }

    // Where the plane's name goes: the point of the drawn patch (centre g, half size h along u and
    // w) that is well inside the picture and farthest from the body's on-screen bounds, so the
    // name sits on the plane, not on the body (text is drawn over everything).
    Vec3 planeLabelPoint(const Canvas& c, const Vec3& g, const Vec3& u, const Vec3& w, double h,
                         const Transform& pose) const {
        render::Box bodyBounds{INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (const Vec3& p : body.mesh.positions()) {
            Eigen::Vector2d px;
            if (!c.project(pose.apply(p), px)) continue;
            bodyBounds = {std::min(bodyBounds.x0, px.x()), std::min(bodyBounds.y0, px.y()),
                          std::max(bodyBounds.x1, px.x()), std::max(bodyBounds.y1, px.y())};
        }
        Vec3 best = g;
        double bestClearance = -1;
        for (int a = -4; a <= 4; ++a)
            for (int b = -4; b <= 4; ++b) {
                const Vec3 q = g + (0.2 * a) * h * u + (0.2 * b) * h * w;
                Eigen::Vector2d px;
                if (!c.project(q, px) || px.x() < 90 || px.y() < 110 || px.x() > c.width() - 90 ||
                    px.y() > c.height() - 70)
                    continue;
                const double dx = std::max({bodyBounds.x0 - px.x(), 0.0, px.x() - bodyBounds.x1});
                const double dy = std::max({bodyBounds.y0 - px.y(), 0.0, px.y() - bodyBounds.y1});
                const double clearance = std::min(std::hypot(dx, dy), 120.0);  // far enough is enough
                if (clearance > bestClearance + 1e-9) best = q, bestClearance = clearance;
            }
        return best;
    }

    // The part of the plane patch (corners in order) the picture shows above the caption band
    // at the canvas's foot (its lowest 70 px): the fill, and the border's pieces (no stroke runs
    // through the caption: a label on a stroke, render/legibility.h). The screen row is a plane
    // through the eye: clip.y - t clip.w >= 0 in clip coordinates, cut in 3D.
    static void drawPlanePatch(Canvas& c, const std::vector<Vec3>& corners) {
        const double aspect = double(c.width()) / double(c.height());
        const Eigen::Matrix4d m = c.camera().viewProjection(aspect);
        const double t = 1.0 - 2.0 * (c.height() - 70.0) / c.height();
        const Eigen::RowVector4d row = m.row(1) - t * m.row(3);
        const auto side = [&](const Vec3& p) { return row.dot(Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0)); };
        std::vector<Vec3> kept;
        const LineStyle border = lineStyle(Role::Muted, 1.5f);
        for (std::size_t k = 0; k < corners.size(); ++k) {
            const Vec3& p = corners[k];
            const Vec3& q = corners[(k + 1) % corners.size()];
            const double sp = side(p), sq = side(q);
            if (sp >= 0) kept.push_back(p);
            if ((sp >= 0) != (sq >= 0)) kept.push_back(p + (sp / (sp - sq)) * (q - p));
            if (sp >= 0 && sq >= 0) c.drawLine(p, q, border);
            else if (sp >= 0 || sq >= 0) c.drawLine(sp >= 0 ? p : q, p + (sp / (sp - sq)) * (q - p), border);
        }
        if (kept.size() >= 3) c.drawPolygon(kept, roleColor(Role::Muted).withAlpha(0.25f));
    }

    // Pose i against the plane: the contact polygon, manifold and normals, or the closest feature.
    Frame planeFrame(GlContext& gl, int ss, const PlaneView& v, size_t i, const PlaneContactResult& r,
                     const PlaneContactTrace& tr) const {
        const Vec3& n = v.n;
        const double d = v.d, radius = v.radius, rho = v.radius;
        const Vec3& center = v.center;
        Canvas c(gl, sceneCanvasOptions(common_, ss), v.cameraFor(i, *this));
        const bool labels = common_.hasLayer("labels");
        if (common_.hasLayer("plane")) {
            const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
            const Vec3 g = center - (n.dot(center) - d) * n;
            const double h = 1.5 * radius;
            drawPlanePatch(c, {g - h * u - h * w, g + h * u - h * w, g + h * u + h * w, g - h * u + h * w});
            if (labels) {
                TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, false};
                ts.place = true;
                c.drawText(planeLabelPoint(c, g, u, w, h, poses[i]), "plane n·x = d", ts);
            }
        }
        Posed pb = body;
        pb.pose = poses[i];
        // Separated: opaque, so the plane's border behind it is hidden (the review: "the plane's far
        // border drawn across the separated box").
        drawPosed(c, pb, roleColor(Role::ShapeA), r.colliding() ? 0.45f : 1.0f, r.colliding());
        Legend lg{c};
        if (labels)
            lg.item(r.colliding() ? "body colliding (outline)" : "body separated",
                    r.colliding() ? Role::Colliding : Role::ShapeA);
        if (r.colliding()) {
            // Vertices below the plane and the crossing points.
            if (common_.hasLayer("polygon")) {
                std::vector<Vec3> outline;
                for (const ContactPoint& p : r.polygon) outline.push_back(p.pointB);
                if (outline.size() >= 3) c.drawPolygon(outline, roleColor(Role::Result).withAlpha(0.28f));
                if (outline.size() >= 2)
                    c.drawPolyline(outline, outline.size() >= 3, lineStyle(Role::Result, 3.0f, false, true));
                for (const auto& x : tr.crossings)
                    c.drawPoint(x.point, 4.0f, roleColor(Role::Background), true, 1.5f, roleColor(Role::Ink));
                if (labels) {
                    lg.item("contact polygon (on the plane)", Role::Result);
                    lg.item("○ edge–plane crossings", Role::Ink);
                }
            }
            if (common_.hasLayer("contacts")) {
                for (size_t k = 0; k < r.manifold.size(); ++k) {
                    const ContactPoint& p = r.manifold[k];
                    c.drawLine(p.pointA, p.pointB, lineStyle(Role::Ink, 2.0f, false, true));
                    if (k == 0 && p.depth > 0) c.noteQuantity("deepest depth", p.pointA, p.pointB);
                    c.drawPoint(p.pointA, 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                    c.drawPoint(p.pointB, 4.0f, roleColor(Role::Ink), true);
                    if (labels && (k == 0 || p.depth > 0))
                        drawLabelAway(c, p.pointA,
                                      centroid({r.manifold.front().pointA, p.pointA}) + 0.3 * rho * r.normal,
                                      (k == 0 ? "deepest " : "") + fmt(p.depth), labelStyle(Role::Result, 16.0f), 14.0);
                }
                if (labels) lg.item("manifold points, with depth", Role::Result);
            }
            if (common_.hasLayer("normals")) {
                for (const ContactPoint& p : r.manifold)
                    c.drawArrow(p.pointB, p.pointB - 0.35 * rho * r.normal,
                                lineStyle(Role::Direction, 3.0f, false, true));
                if (labels) lg.item("→ plane normal n (pushes the body out)", Role::Direction);
            }
        } else if (common_.hasLayer("contacts")) {
            // Closest feature and its projection onto the plane.
            for (size_t k = 0; k < r.featurePoints.size(); ++k) {
                c.drawLine(r.featurePoints[k], r.featurePointsOnPlane[k], lineStyle(Role::Result, 2.0f, true, true));
                c.drawPoint(r.featurePoints[k], 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                c.drawPoint(r.featurePointsOnPlane[k], 4.0f, roleColor(Role::Ink), true);
            }
            if (r.featurePoints.size() >= 2)
                c.drawPolyline(r.featurePoints, r.featurePoints.size() >= 3,
                               lineStyle(Role::Result, 4.0f, false, true));
            if (labels) {
                drawLabelAway(c, 0.5 * (r.featurePoints[0] + r.featurePointsOnPlane[0]), center,
                              "distance " + fmt(r.signedDistance), labelStyle(Role::Result, 17.0f), 18.0);
                lg.item("closest feature and its projection", Role::Result);
            }
        }
        char cap[400];
        if (r.colliding())
            std::snprintf(cap, sizeof cap,
                          "%s: %s, depth %s at %s %s; polygon of %d (%d crossings) → %d manifold points",
                          poseLabels[i].c_str(), nameOf(r.status), fmt(r.depth).c_str(), nameOf(r.feature.type),
                          featureLabel(r.feature).c_str(), int(r.polygon.size()), int(tr.crossings.size()),
                          int(r.manifold.size()));
        else
            std::snprintf(cap, sizeof cap, "%s: separated, distance %s; closest feature %s %s (%d point%s)",
                          poseLabels[i].c_str(), fmt(r.signedDistance).c_str(), nameOf(r.feature.type),
                          featureLabel(r.feature).c_str(), int(r.featurePoints.size()),
                          r.featurePoints.size() == 1 ? "" : "s");
        char name[32];
        std::snprintf(name, sizeof name, "pose_%02d", int(i));
        return finish(c, name, common_.title, cap, poseLabels[i] + ": " + nameOf(r.status), common_.caption);
    }

    // ---- features mode ------------------------------------------------------------------------
    void runFeatures(const RunContext& ctx, int ss, DemoOutput& out) const {
        Json frames = Json::array();
        std::vector<FeatureDistanceResult> results;
        for (size_t i = 0; i < pairs.size(); ++i) {
            results.push_back(featureDistance(pairs[i].first, pairs[i].second));
            const FeatureDistanceResult& r = results.back();
            frames.push_back({{"label", pairLabels[i]},
                              {"type", nameOf(r.type)},
                              {"distance", r.distance},
                              {"point_a", vec3Json(r.pointA)},
                              {"point_b", vec3Json(r.pointB)},
                              {"normal", vec3Json(r.normal)},
                              {"normal_rule", r.normalRule},
                              {"normal_unstable", r.normalUnstable},
                              {"parallel", r.parallel}});
        }
        out.trace = {{"mode", "features"}, {"frames", frames}};
        if (!ctx.gl) return;
        for (size_t i = 0; i < pairs.size(); ++i) {
            const FeatureDistanceResult& r = results[i];
            std::vector<Vec3> all = pairs[i].first.points;
            all.insert(all.end(), pairs[i].second.points.begin(), pairs[i].second.points.end());
            Vec3 center;
            double radius;
            boundingSphere(all, center, radius);
            radius = std::max(radius, 0.6);
            const Camera cam =
                common_.camera ? *common_.camera : framingCamera(center, radius * 1.25, view, Vec3::UnitZ());
            Canvas c(*ctx.gl, sceneCanvasOptions(common_, ss), cam);
            const bool labels = common_.hasLayer("labels");
            const auto drawFeature = [&](const FeatureGeometry& f, Role role, const std::string& tag) {
                const Color col = roleColor(role);
                if (f.type == FeatureType::Face) {
                    c.drawPolygon(f.points, col.withAlpha(0.45f), false);
                    c.drawPolyline(f.points, true, lineStyle(role, 3.0f));
                } else if (f.type == FeatureType::Edge) {
                    c.drawLine(f.points[0], f.points[1], lineStyle(role, 6.0f, false, true));
                }
                for (const Vec3& p : f.points)
                    c.drawPoint(p, f.type == FeatureType::Vertex ? 8.0f : 4.0f, col, true, 1.5f, roleColor(Role::Ink));
                // Edges are labelled a fifth of the way along (their midpoint is often the closest point).
                const Vec3 at = f.type == FeatureType::Edge ? Vec3(f.points[0] + 0.2 * (f.points[1] - f.points[0]))
                                                            : centroid(f.points);
                if (labels) drawLabelAway(c, at, center, tag + " " + nameOf(f.type), labelStyle(role, 20.0f), 30.0);
            };
            drawFeature(pairs[i].first, Role::ShapeA, "A:");
            drawFeature(pairs[i].second, Role::ShapeB, "B:");
            if (common_.hasLayer("contacts")) {
                c.drawLine(r.pointA, r.pointB, lineStyle(Role::Result, 2.5f, true, true));
                c.drawPoint(r.pointA, 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                c.drawPoint(r.pointB, 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                if (labels) {
                    drawLabelAway(c, r.pointA, r.pointB, "p_A", labelStyle(Role::Result, 18.0f), 16.0);
                    drawLabelAway(c, r.pointB, r.pointA, "p_B", labelStyle(Role::Result, 18.0f), 16.0);
                }
            }
            if (common_.hasLayer("normals") && r.normalDefined) {
                c.drawArrow(r.pointA, r.pointA + 0.45 * radius * r.normal,
                            lineStyle(Role::Direction, 3.5f, false, true));
                if (labels)
                    c.drawText(r.pointA + 0.5 * radius * r.normal, "n",
                               TextStyle{20.0f, roleColor(Role::Direction), Anchor::Left, true, true, {8, 0}});
            }
            Legend lg{c};
            if (labels) {
                lg.item("feature A", Role::ShapeA);
                lg.item("feature B", Role::ShapeB);
                lg.item("closest points p_A, p_B", Role::Result);
                lg.item("→ contact normal n (A to B)", Role::Direction);
            }
            std::string flags;
            if (r.parallel) flags += "; parallel: one of many closest pairs";
            if (r.normalUnstable)
                flags +=
                    r.normalDefined ? "; normal UNSTABLE (features almost touch)" : "; no normal (points coincide)";
            char cap[400];
            std::snprintf(cap, sizeof cap, "%s: distance %s, normal from %s%s", nameOf(r.type), fmt(r.distance).c_str(),
                          r.normalRule, flags.c_str());
            char name[32];
            std::snprintf(name, sizeof name, "pair_%02d", int(i));
            const std::string title =
                common_.title + ": " + nameOf(r.type) + (pairLabels[i].empty() ? "" : " (" + pairLabels[i] + ")");
            out.frames.push_back(
                finish(c, name, title, cap, std::string(nameOf(r.type)) + ", distance " + fmt(r.distance), common_.caption));
        }
    }

    // ---- sat mode -----------------------------------------------------------------------------
    void runSat(const RunContext& ctx, int ss, DemoOutput& out) const {
        SatContactTrace tr;
        const SatContactResult r = contactPolyhedra(a.mesh, a.pose, b.mesh, b.pose, {}, &tr);
        out.trace = satTrace(r, tr);
        if (!ctx.gl) return;
        out.frames.push_back(satContactFrame(*ctx.gl, ss, r, tr));
        const bool faceContact = r.axisKind != SatAxisKind::EdgeEdge && r.colliding();
        if (!faceContact) {
            out.skipped.push_back("clip frame (no face contact)");
            return;
        }
        out.frames.push_back(satClipFrame(*ctx.gl, ss, r, tr));
    }

    static Json satTrace(const SatContactResult& r, const SatContactTrace& tr) {
        Json axes = Json::array();
        for (const SatAxisRecord& x : tr.axes)
            axes.push_back({{"kind", nameOf(x.kind)},
                            {"a", x.indexA},
                            {"b", x.indexB},
                            {"axis", vec3Json(x.axis)},
                            {"separation", x.separation}});
        Json clips = Json::array();
        for (const SatClipStep& s : tr.clipSteps)
            clips.push_back(
                {{"reference_edge", s.referenceEdge}, {"before", s.before.size()}, {"after", s.after.size()}});
        return {{"mode", "sat"},
                {"status", nameOf(r.status)},
                {"separation", r.separation},
                {"depth", r.depth},
                {"normal", vec3Json(r.normal)},
                {"axis_kind", nameOf(r.axisKind)},
                {"axes", axes},
                {"edge_pairs", tr.edgePairsTotal},
                {"edge_pairs_pruned", tr.edgePairsPruned},
                {"edge_pairs_parallel", tr.edgePairsParallel},
                {"chosen", tr.chosen},
                {"reference_on_a", tr.referenceOnA},
                {"reference_face", tr.referenceFace},
                {"incident_face", tr.incidentFace},
                {"clip_steps", clips},
                {"manifold", pointsJson(r.manifold)}};
    }

    // The body that holds the reference face and the one that holds the incident face, with their colours.
    struct ClipSides {
        const Posed& ref;
        const Posed& inc;
        Role refRole, incRole;
    };
    ClipSides clipSides(const SatContactTrace& tr) const {
        return {tr.referenceOnA ? a : b, tr.referenceOnA ? b : a, tr.referenceOnA ? Role::ShapeA : Role::ShapeB,
                tr.referenceOnA ? Role::ShapeB : Role::ShapeA};
    }

    // The two bodies, the faces or edges that decide the axis, the axis and the manifold.
    Frame satContactFrame(GlContext& gl, int ss, const SatContactResult& r, const SatContactTrace& tr) const {
        std::vector<Vec3> all = a.world();
        for (const Vec3& p : b.world()) all.push_back(p);
        Vec3 center;
        double radius;
        boundingSphere(all, center, radius);
        const bool labels = common_.hasLayer("labels");
        const bool faceContact = r.axisKind != SatAxisKind::EdgeEdge && r.colliding();
        const auto [ref, inc, refRole, incRole] = clipSides(tr);
        char counts[200];
        std::snprintf(counts, sizeof counts, "axes: %d+%d faces, %d/%d edge pairs (%d Gauss-map pruned, %d parallel)",
                      a.mesh.faceCount(), b.mesh.faceCount(),
                      int(tr.axes.size()) - a.mesh.faceCount() - b.mesh.faceCount(), tr.edgePairsTotal,
                      tr.edgePairsPruned, tr.edgePairsParallel);
        Camera cam = common_.camera ? *common_.camera : framingCamera(center, radius * 1.1, view, Vec3::UnitZ());
        if (!common_.camera) {  // the bodies left of centre: the legend's column is on the right
            const Vec3 forward = (cam.target - cam.eye).normalized();
            const Vec3 right = forward.cross(cam.up).normalized();
            cam.eye += 0.3 * radius * right;
            cam.target += 0.3 * radius * right;
        }
        Canvas c(gl, sceneCanvasOptions(common_, ss), cam);
        // The bodies, the clipped faces and the manifold: the picture, and again in the depth's inset.
        const std::vector<Vec3> rp = faceContact ? facePolygon(ref, tr.referenceFace) : std::vector<Vec3>{};
        const auto drawGeometry = [&](Canvas& on) {
            drawPosed(on, a, roleColor(Role::ShapeA), 0.35f, r.colliding());
            drawPosed(on, b, roleColor(Role::ShapeB), 0.35f, r.colliding());
            if (faceContact) {
                on.drawPolygon(rp, roleColor(refRole).withAlpha(0.6f));
                on.drawPolyline(rp, true, lineStyle(Role::Ink, 3.5f, false, true));
                on.drawPolyline(facePolygon(inc, tr.incidentFace), true, lineStyle(incRole, 4.0f, true, true));
            }
            if (!faceContact && r.colliding() && !r.manifold.empty()) {
                const auto [a0, a1] = a.mesh.edgeVertices(r.featureA.index);
                const auto [b0, b1] = b.mesh.edgeVertices(r.featureB.index);
                on.drawLine(a.pose.apply(a.mesh.position(a0)), a.pose.apply(a.mesh.position(a1)),
                            lineStyle(Role::ShapeA, 6.0f, false, true));
                on.drawLine(b.pose.apply(b.mesh.position(b0)), b.pose.apply(b.mesh.position(b1)),
                            lineStyle(Role::ShapeB, 6.0f, false, true));
            }
            if (!common_.hasLayer("contacts")) return;
            for (const ContactPoint& p : r.manifold) {
                on.drawLine(p.pointA, p.pointB, lineStyle(Role::Ink, 2.0f, false, true));
                on.drawPoint(p.pointA, 6.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
                on.drawPoint(p.pointB, 4.0f, roleColor(Role::Ink), true);
            }
        };
        drawGeometry(c);
        Legend lg{c};
        if (labels) {
            lg.item("body A", Role::ShapeA);
            lg.item("body B", Role::ShapeB);
            if (r.colliding()) lg.item("colliding (outlines)", Role::Colliding);
        }
        Vec3 axisFrom = center;
        if (faceContact) {
            axisFrom = centroid(rp);
            if (labels) {
                lg.item(std::string("reference face (") + (tr.referenceOnA ? "A" : "B") + "), black outline", refRole);
                lg.item(std::string("- - incident face (") + (tr.referenceOnA ? "B" : "A") + ")", incRole);
            }
        } else if (r.colliding() && !r.manifold.empty()) {
            axisFrom = r.manifold[0].pointA;
            if (labels) lg.item("edges of the edge–edge axis", Role::Ink);
        }
        if (common_.hasLayer("normals")) {
            c.drawArrow(axisFrom, axisFrom + 0.6 * radius * r.normal, lineStyle(Role::Direction, 4.0f, false, true));
            if (labels) {
                TextStyle ts{18.0f, roleColor(Role::Direction), Anchor::Left, true, true, {10, 0}};
                ts.place = true;  // beside the arrow's tip, off the key in the corner
                c.drawText(axisFrom + 0.62 * radius * r.normal, std::string("SAT axis (") + nameOf(r.axisKind) + ")",
                           ts);
                lg.item("→ axis of least penetration", Role::Direction);
            }
        }
        // The depth the caption names, drawn as the deepest point's segment (magnified under 12 px).
        const ContactPoint* deepest = nullptr;
        if (common_.hasLayer("contacts")) {
            for (const ContactPoint& p : r.manifold)
                if (!deepest || p.depth > deepest->depth) deepest = &p;
            if (deepest && deepest->depth > 0) c.noteQuantity("depth", deepest->pointA, deepest->pointB);
            if (labels && !r.manifold.empty()) lg.item("manifold points (on A), depth segments", Role::Result);
        }
        std::function<Image(Canvas&)> read;
        if (deepest && deepest->depth > 0)
            read = [&, p = deepest->pointA, q = deepest->pointB](Canvas& on) {
                const ZoomTarget depth{"depth", "depth " + fmt(deepest->depth), p, q, drawGeometry};
                return readPixelsZoomed(gl, on, ss, depth,
                                        Box{14.0, 70.0, common_.image.width - 14.0, common_.image.height - 80.0});
            };
        char cap[400];
        if (r.colliding())
            std::snprintf(cap, sizeof cap, "%s axis, depth %s, %d point%s; %s", nameOf(r.axisKind),
                          fmt(r.depth).c_str(), int(r.manifold.size()), r.manifold.size() == 1 ? "" : "s", counts);
        else
            std::snprintf(cap, sizeof cap, "Separated by %s along the %s axis; %s", fmt(r.separation).c_str(),
                          nameOf(r.axisKind), counts);
        return finish(c, "contact", common_.title, cap, std::string("SAT contact: ") + nameOf(r.axisKind), common_.caption,
                      read);
    }

    // The clip seen along the reference normal: reference face, incident face, each side-plane step.
    Frame satClipFrame(GlContext& gl, int ss, const SatContactResult& r, const SatContactTrace& tr) const {
        const bool labels = common_.hasLayer("labels");
        const auto [ref, inc, refRole, incRole] = clipSides(tr);
        const std::vector<Vec3> rp = facePolygon(ref, tr.referenceFace);
        const Vec3 nr = ref.pose.rotate(ref.mesh.face(tr.referenceFace).normal);
        Vec3 cc;
        double cr;
        std::vector<Vec3> both = rp;
        for (const Vec3& p : facePolygon(inc, tr.incidentFace)) both.push_back(p);
        boundingSphere(both, cc, cr);
        // Turned as the contact frame's camera is, tipped to look straight down the normal: its
        // screen up, laid into the face's plane, is up here too (the review: with an arbitrary up
        // the clip read rotated 180° from the contact frame).
        const Camera contact = common_.camera ? *common_.camera : framingCamera(cc, cr, view, Vec3::UnitZ());
        const Vec3 forward = (contact.target - contact.eye).normalized();
        Vec3 up = contact.up - contact.up.dot(forward) * forward;
        up -= up.dot(nr) * nr;
        if (!(up.norm() > 1e-6)) up = nr.unitOrthogonal();
        const Camera cam = framingCamera(cc, cr * 1.15, nr, up.normalized(), false);
        Canvas c(gl, sceneCanvasOptions(common_, ss), cam);
        c.drawPolygon(rp, roleColor(refRole).withAlpha(0.3f));
        c.drawPolyline(rp, true, lineStyle(Role::Ink, 3.5f, false, true));
        c.drawPolyline(facePolygon(inc, tr.incidentFace), true, lineStyle(incRole, 4.0f, true, true));
        for (size_t k = 0; k + 1 < tr.clipSteps.size(); ++k)
            if (tr.clipSteps[k].after.size() >= 2)
                c.drawPolyline(tr.clipSteps[k].after, true, lineStyle(Role::Muted, 1.5f, true, true));
        if (!tr.clipSteps.empty() && tr.clipSteps.back().after.size() >= 3) {
            c.drawPolygon(tr.clipSteps.back().after, roleColor(Role::Result).withAlpha(0.3f));
            c.drawPolyline(tr.clipSteps.back().after, true, lineStyle(Role::Result, 3.0f, false, true));
        }
        for (const ContactPoint& p : tr.clipped)
            c.drawPoint(tr.referenceOnA ? p.pointB : p.pointA, 4.0f, roleColor(Role::Ink), true);
        for (const ContactPoint& p : r.manifold) {
            const Vec3 q = tr.referenceOnA ? p.pointB : p.pointA;
            c.drawPoint(q, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            if (labels) drawLabelAway(c, q, cc, fmt(p.depth), labelStyle(Role::Result, 16.0f), 16.0);
        }
        Legend lg{c};
        if (labels) {
            lg.item("reference face", refRole);
            lg.item("- - incident face", incRole);
            lg.item("- - after each side-plane clip", Role::Muted);
            lg.item("clipped polygon; kept points, depth", Role::Result);
        }
        char cap[300];
        std::snprintf(cap, sizeof cap,
                      "Sutherland–Hodgman: %d side planes clip the incident face to %d points; %d below the reference "
                      "face → %d kept",
                      int(tr.clipSteps.size()), tr.clipSteps.empty() ? 0 : int(tr.clipSteps.back().after.size()),
                      int(tr.clipped.size()), int(r.manifold.size()));
        return finish(c, "clip", "Face clipping, seen along the reference normal", cap, "face clipping", common_.caption);
    }
};

class PolyhedronPlaneDemo final : public Demo {
public:
    std::string name() const override { return "polyhedron_plane"; }
    std::string description() const override {
        return "contact model: polyhedron vs plane manifolds, the six feature-pair contact types, SAT face clipping";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{960, 720}, {}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        auto scene = std::make_unique<ContactScene>(std::move(common));
        scene->mode = "plane";
        if (auto m = r.find("mode")) scene->mode = m->asEnum({"plane", "features", "sat"});
        if (auto v = r.find("view")) {
            scene->view = sceneVec3(*v);
            if (!(scene->view.norm() > 0)) v->fail("view direction must be non-zero");
        }
        if (scene->mode == "plane") {
            scene->body.mesh = readBody(r.get("body"), scene->body.name);
            const JsonNode ps = r.get("poses");
            const std::vector<JsonNode> items = ps.items();
            if (items.empty() || int(items.size()) > kMaxFrames)
                ps.fail("1 to " + std::to_string(kMaxFrames) + " poses");
            std::vector<std::optional<double>> restHeights;  // a pose's "rest_height", applied once the plane is read
            for (const JsonNode& it : items) {
                ObjectReader pr(it);
                scene->poses.push_back(readPose(pr));
                restHeights.emplace_back();
                if (auto h = pr.find("rest_height")) restHeights.back() = sceneCoordinate(*h);
                scene->poseLabels.push_back(pr.stringOr("label", ""));
                scene->poseViews.emplace_back();
                if (auto pv = pr.find("view")) {
                    scene->poseViews.back() = sceneVec3(*pv);
                    if (!(scene->poseViews.back()->norm() > 0)) pv->fail("view direction must be non-zero");
                }
                pr.finish();
            }
            if (auto p = r.find("plane")) {
                ObjectReader pr(*p);
                const JsonNode nn = pr.get("normal");
                scene->plane.normal = sceneVec3(nn);
                scene->plane.offset = sceneCoordinate(pr.get("offset"));
                pr.finish();
                if (!(scene->plane.normal.norm() > 0)) nn.fail("plane normal must be non-zero");
            }
            // "rest_height": h moves the posed body along the plane's normal until its lowest vertex
            // is h above the plane (h < 0: sunk that deep). polyhedron_plane_test "rest_height".
            const Vec3 n = scene->plane.normal.normalized();
            const double d = scene->plane.offset / scene->plane.normal.norm();
            for (std::size_t i = 0; i < restHeights.size(); ++i) {
                if (!restHeights[i]) continue;
                double lowest = INFINITY;
                for (const Vec3& v : scene->body.mesh.positions()) lowest = std::min(lowest, n.dot(scene->poses[i].apply(v)) - d);
                scene->poses[i].position += (*restHeights[i] - lowest) * n;
            }
            if (auto m = r.find("max_points")) scene->maxPoints = m->asInt(1, 64);
        } else if (scene->mode == "features") {
            const JsonNode ps = r.get("pairs");
            const std::vector<JsonNode> items = ps.items();
            if (items.empty() || int(items.size()) > kMaxFrames)
                ps.fail("1 to " + std::to_string(kMaxFrames) + " pairs");
            for (const JsonNode& it : items) {
                ObjectReader pr(it);
                scene->pairs.emplace_back(readFeature(pr.get("a")), readFeature(pr.get("b")));
                scene->pairLabels.push_back(pr.stringOr("label", ""));
                pr.finish();
            }
        } else {
            for (auto [key, posed] : {std::pair{"a", &scene->a}, std::pair{"b", &scene->b}}) {
                ObjectReader br(r.get(key));
                posed->mesh = readBody(br.get("body"), posed->name);
                posed->pose = readPose(br);
                br.finish();
            }
        }
        r.finish();
        return scene;
    }
};

}  // namespace

const Demo& polyhedronPlaneDemo() {
    static const PolyhedronPlaneDemo demo;
    return demo;
}

}  // namespace cdlab::demos
