// V-Clip demo: reading bodies and drawing the 3D pieces (polyhedra, features, Voronoi plane patches)
// and the Theorem-1 check. Drawing geometry only; the walk's numbers come from core/feature_walk/vclip.h.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/feature_walk_figure.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "app/scene/body_scene.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos::walkfigure {

using namespace render;

Color violatedColor() { return roleColor(Role::Highlight); }
Color satisfiedColor() { return roleColor(Role::Simplex); }
Color clipColor() { return roleColor(Role::Direction); }

Body parseBody(const JsonNode& node) {
    ObjectReader r(node);
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(
            "expected an object with one key: tetrahedron, box, octahedron, icosahedron, dodecahedron, prism, disk, "
            "geodesic_sphere or hull");
    const std::string kind = node.raw().begin().key();
    JsonNode spec = r.get(kind);
    ObjectReader s(spec);
    Body body;
    body.kind = kind;
    ConvexPolyhedron mesh;
    if (kind == "tetrahedron" || kind == "octahedron" || kind == "icosahedron" || kind == "dodecahedron") {
        const std::optional<JsonNode> r = findEither(s, "radius", "circumradius");
        const double radius = r ? sceneSize(*r) : 1.0;
        mesh = kind == "tetrahedron"   ? presets::tetrahedron(radius)
               : kind == "octahedron"  ? presets::octahedron(radius)
               : kind == "icosahedron" ? presets::icosahedron(radius)
                                       : presets::dodecahedron(radius);
    } else if (kind == "box") {
        const Vec3 h = sceneSizes(s.get("half_extents"));
        mesh = presets::box(h);
    } else if (kind == "prism" || kind == "disk") {
        const int n = getEither(s, "n", "sides").asInt(3, 200);
        const double radius = sceneSize(s.get("radius"));
        if (kind == "prism") mesh = presets::prism(n, radius, sceneSize(s.get("half_height")));
        else {
            std::optional<double> halfThickness;  // std::nullopt: disk()'s default
            if (s.find("half_thickness")) halfThickness = sceneSize(s.get("half_thickness"));
            mesh = presets::disk(n, radius, halfThickness);
        }
    } else if (kind == "geodesic_sphere") {
        mesh = presets::geodesicSphere(s.get("level").asInt(0, 3), s.find("radius") ? sceneSize(s.get("radius")) : 1.0);
    } else if (kind == "hull" || kind == "polytope") {
        // The walk's step bound and the brute-force checks are quadratic in the feature count.
        const std::vector<Vec3> points = sceneVec3List(s.get("vertices"), 4, kMaxShapeVertices);
        HullResult h = convexHull(points);
        if (!h.ok()) spec.fail("the hull of these vertices is not a solid polyhedron");
        mesh = h.polyhedron;
    } else {
        node.fail("unknown body kind '" + kind +
                  "' (tetrahedron, box, octahedron, icosahedron, dodecahedron, prism, disk, "
                  "geodesic_sphere, hull)");
    }
    if (auto p = s.find("position")) body.pose.position = sceneVec3(*p);
    if (auto q = s.find("rotation")) body.pose.rotation = q->asQuat();
    s.finish();
    r.finish();
    VClipBuild build = buildVClipPolyhedron(mesh);
    if (!build.ok())
        spec.fail(std::string("V-Clip cannot use this body: ") + nameOf(build.status) + ": " + build.message);
    body.regions = std::move(build.polyhedron);
    return body;
}

VClipFeature parseFeature(const JsonNode& node, const Body& body) {
    const std::string s = node.asString();
    const ConvexPolyhedron& m = body.regions.mesh();
    if (s.size() >= 2 && (s[0] == 'V' || s[0] == 'E' || s[0] == 'F') &&
        std::all_of(s.begin() + 1, s.end(), [](char c) { return c >= '0' && c <= '9'; }) && s.size() <= 7) {
        const int i = std::stoi(s.substr(1));
        const int count = s[0] == 'V' ? m.vertexCount() : s[0] == 'E' ? m.edgeCount() : m.faceCount();
        if (i >= count) node.fail("feature " + s + " out of range (the body has " + std::to_string(count) + ")");
        return s[0] == 'V' ? VClipFeature::vertex(i) : s[0] == 'E' ? VClipFeature::edge(i) : VClipFeature::face(i);
    }
    node.fail("expected a feature name like \"V3\", \"E12\" or \"F0\", got \"" + s + "\"");
}

void sceneSphere(const std::vector<const Body*>& bodies, Vec3& center, double& radius) {
    std::vector<Vec3> pts;
    for (const Body* b : bodies)
        for (const Vec3& p : b->regions.mesh().positions()) pts.push_back(b->pose.apply(p));
    boundingSphere(pts, center, radius);
}

void drawPolyhedron(Canvas& canvas, const Body& body, const Transform& pose, const Color& fill, float alpha,
                    const std::string& name, const std::string& apartFrom) {
    const ConvexPolyhedron& m = body.regions.mesh();
    std::vector<Vec3> verts;
    for (const Vec3& p : m.positions()) verts.push_back(pose.apply(p));
    canvas.noteBody(name, verts, apartFrom);
    std::vector<Eigen::Vector3i> tris;
    for (int f = 0; f < m.faceCount(); ++f) {
        const std::vector<int> fv = m.faceVertices(f);
        for (std::size_t i = 1; i + 1 < fv.size(); ++i) tris.emplace_back(fv[0], fv[i], fv[i + 1]);
    }
    canvas.drawMesh(verts, tris, fill.withAlpha(alpha), true);
    LineStyle ls;
    ls.widthPx = 1.5f;
    ls.color = fill.scaled(0.6f);
    for (int e = 0; e < m.edgeCount(); ++e) {
        const auto [i, j] = m.edgeVertices(e);
        const auto [f1, f2] = m.edgeFaces(e);
        canvas.drawLine(verts[i], verts[j],
                        edgeStyleSeen(canvas.camera(), 0.5 * (verts[i] + verts[j]), pose.rotate(m.plane(f1).normal),
                                      pose.rotate(m.plane(f2).normal), ls));
    }
}

std::vector<Vec3> worldVertices(const Body& body, const Transform& pose) {
    std::vector<Vec3> out;
    for (const Vec3& p : body.regions.mesh().positions()) out.push_back(pose.apply(p));
    return out;
}

bool verticesInside(const Canvas& c, const std::vector<Vec3>& points, double top) {
    for (const Vec3& p : points) {
        Eigen::Vector2d px;
        if (!c.project(p, px) || px.x() < kSideMarginPx || px.x() > c.width() - kSideMarginPx || px.y() < top ||
            px.y() > c.height() - kSideMarginPx)
            return false;
    }
    return true;
}

Vec3 featureCenter(const std::vector<Vec3>& g) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : g) c += p;
    return g.empty() ? c : Vec3(c / double(g.size()));
}

std::vector<Vec3> featureNormals(const Body& body, const Transform& pose, const VClipFeature& f) {
    const ConvexPolyhedron& m = body.regions.mesh();
    std::vector<Vec3> normals;
    if (f.type == VClipFeatureType::Face) {
        normals.push_back(pose.rotate(m.plane(f.index).normal));
    } else if (f.type == VClipFeatureType::Edge) {
        const auto [f1, f2] = m.edgeFaces(f.index);
        normals = {pose.rotate(m.plane(f1).normal), pose.rotate(m.plane(f2).normal)};
    } else if (f.type == VClipFeatureType::Vertex) {
        for (int k = 0; k < m.faceCount(); ++k) {
            const std::vector<int> fv = m.faceVertices(k);
            if (std::find(fv.begin(), fv.end(), f.index) != fv.end()) normals.push_back(pose.rotate(m.plane(k).normal));
        }
    }
    return normals;
}

namespace {

// The gap between two point sets seen along v (orthographic): the largest separation of their
// projections on any direction across v among their hulls' edge normals, approximated by 64
// directions in the plane across v (negative: they overlap that deep).
double gapAlong(const Vec3& v, const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    const Vec3 u = v.unitOrthogonal(), w = v.cross(u).normalized();
    double best = -INFINITY;
    for (int k = 0; k < 64; ++k) {
        const double t = k * M_PI / 64;
        const Vec3 s = std::cos(t) * u + std::sin(t) * w;
        double aLo = INFINITY, aHi = -INFINITY, bLo = INFINITY, bHi = -INFINITY;
        for (const Vec3& p : a) aLo = std::min(aLo, s.dot(p)), aHi = std::max(aHi, s.dot(p));
        for (const Vec3& p : b) bLo = std::min(bLo, s.dot(p)), bHi = std::max(bHi, s.dot(p));
        best = std::max({best, bLo - aHi, aLo - bHi});
    }
    return best;
}

}  // namespace

namespace {

// A body's face planes in the world (unit outward normals, n · x <= d inside).
std::vector<Plane> worldPlanes(const Body& body, const Transform& pose) {
    std::vector<Plane> out;
    const ConvexPolyhedron& mesh = body.regions.mesh();
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const Vec3 n = pose.rotate(mesh.plane(f).normal);
        out.push_back({n, mesh.plane(f).offset + n.dot(pose.position)});
    }
    return out;
}

// How badly a view shows the steps (chooseWalkView's order): 1000 for bodies apart in space
// overlapping on the picture, 100 for each new feature not seen from its front and 100 more for
// one seen through the other body, 25 for each current feature edge-on and 10 for each seen from
// behind, plus the turn from `view0` in degrees.
struct ViewScorer {
    struct Feature {
        std::vector<Vec3> points, normals;
        bool step;
        std::vector<Plane> other{};  // a step's feature: the other body, which must not hide it
                                 // (StepFeatureFaded: seen through it, its colour blends)
    };
    std::vector<Feature> features;
    std::vector<Vec3> apartA, apartB;
    double size = 0;

    // A face within 63° of the view; an edge or a vertex with some face holding it within 72°,
    // an edge at least 20° off the view (render::featureView measures both, as the gate does).
    static bool frontOn(const Feature& f, const Vec3& v) {
        const render::FeatureView seen = render::featureView(f.points, f.normals, v);
        return seen.facing >= (f.points.size() > 2 ? 0.45 : 0.3) && seen.foreshortening >= std::sin(20 * M_PI / 180);
    }
    double cost(const Vec3& v, const Vec3& v0) const {
        double c = std::acos(std::clamp(v.dot(v0), -1.0, 1.0)) * 180 / M_PI;
        for (const Feature& f : features) {
            if (f.step) {
                c += (frontOn(f, v) ? 0 : 100) + (insideAlong(featureCenter(f.points), v, f.other, 0.0) ? 100 : 0);
                continue;
            }
            const render::FeatureView seen = render::featureView(f.points, f.normals, v);
            c += (f.points.size() > 1 && seen.foreshortening < 0.3 ? 25 : 0) + (seen.facing < 0 ? 10 : 0);
        }
        if (!apartA.empty() && !apartB.empty() && gapAlong(v, apartA, apartB) < 0.08 * size) c += 1000;
        return c;
    }
};

ViewScorer scorer(const WalkBodies& w, const std::vector<WalkStepFeatures>& steps) {
    ViewScorer s;
    const auto add = [&](int body, const VClipFeature& f, bool step) {
        const Body& b = body == 0 ? *w.a : *w.b;
        const Transform& pose = body == 0 ? w.poseA : w.poseB;
        if (f.type == VClipFeatureType::None) return;
        s.features.push_back({featureGeometry(b.regions, pose, f), featureNormals(b, pose, f), step,
                              step ? worldPlanes(body == 0 ? *w.b : *w.a, body == 0 ? w.poseB : w.poseA)
                                   : std::vector<Plane>{}});
    };
    for (const WalkStepFeatures& st : steps) {
        add(0, st.fa, false);
        add(1, st.fb, false);
        if (st.updated >= 0) add(st.updated, st.to, true);
    }
    if (w.apart) {
        s.apartA = worldVertices(*w.a, w.poseA), s.apartB = worldVertices(*w.b, w.poseB);
        for (const std::vector<Vec3>* body : {&s.apartA, &s.apartB})
            for (const Vec3& p : *body) s.size = std::max(s.size, (p - body->front()).norm());
    }
    return s;
}

}  // namespace

Vec3 chooseWalkView(const WalkBodies& w, const Vec3& view, const std::vector<WalkStepFeatures>& steps,
                    double maxTurnDegrees) {
    const Vec3 v0 = view.normalized();
    if (!v0.allFinite() || !w.a || !w.b) return view;
    const ViewScorer s = scorer(w, steps);
    // The view itself, then 600 directions spread evenly over the sphere (a Fibonacci lattice).
    Vec3 best = view;  // returned as it is unless a direction shows the steps better
    double bestCost = s.cost(v0, v0);
    constexpr int kDirections = 600;
    for (int k = 0; k < kDirections; ++k) {
        const double y = 1 - 2 * (k + 0.5) / kDirections, r = std::sqrt(1 - y * y), phi = k * M_PI * (3 - std::sqrt(5.0));
        const Vec3 v(r * std::cos(phi), y, r * std::sin(phi));
        if (std::abs(y) > 0.95 || v.dot(v0) < std::cos(maxTurnDegrees * M_PI / 180)) continue;
        if (const double c = s.cost(v, v0); c < bestCost) bestCost = c, best = v * view.norm();
    }
    return best;
}

void drawWalkBodies(Canvas& c, const WalkBodies& w, bool names) {
    c.setStrokeOwner(bodyOwner("A"));
    drawPolyhedron(c, *w.a, w.poseA, roleColor(Role::ShapeA), 0.18f, "A", w.apart ? "B" : "");
    c.setStrokeOwner(bodyOwner("B"));
    drawPolyhedron(c, *w.b, w.poseB, roleColor(Role::ShapeB), 0.18f, "B", w.apart ? "A" : "");
    c.setStrokeOwner(0);
    if (!names) return;
    const Vec3 ca = w.poseA.apply(w.a->regions.mesh().centroid()), cb = w.poseB.apply(w.b->regions.mesh().centroid());
    const Vec3 away = (cb - ca).norm() > 0 ? Vec3((cb - ca).normalized()) : Vec3::UnitX();
    const double ra = (w.a->regions.mesh().boundsMax() - w.a->regions.mesh().boundsMin()).norm() * 0.3;
    const double rb = (w.b->regions.mesh().boundsMax() - w.b->regions.mesh().boundsMin()).norm() * 0.3;
    // Each may cross its own body's edges, nothing else; on its point when free, else beside it.
    drawBodyName(c, ca - away * ra, "A", Role::ShapeA);
    drawBodyName(c, cb + away * rb, "B", Role::ShapeB);
}

void drawClosestPoints(Canvas& c, const Vec3& pa, const Vec3& pb, bool named, double sceneRadius) {
    const bool apart = (pa - pb).norm() > 1e-3 * sceneRadius;
    if (apart) c.drawLine(pa, pb, lineStyle(Role::Ink, 2.5f, true, true));
    c.drawPoint(pa, 6.0f, roleColor(Role::Ink), true, 1.5f, roleColor(Role::Background));
    c.drawPoint(pb, 6.0f, roleColor(Role::Ink), true, 1.5f, roleColor(Role::Background));
    if (!named) return;
    const Camera& cam = c.camera();
    const Vec3 right = (cam.target - cam.eye).cross(cam.up).normalized() * (0.3 * sceneRadius);
    TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    if (apart) drawLabelAway(c, pa, pa + right, "p_A", ts, 10.0);
    drawLabelAway(c, pb, pb - right, apart ? "p_B" : "p_A = p_B", ts, 10.0);
}

void drawUpdateArrow(Canvas& c, const Vec3& from, const Vec3& to, double sceneRadius) {
    if (!((to - from).norm() > 1e-6 * sceneRadius)) return;
    Vec3 side = (to - from).cross(c.camera().directionToEye(0.5 * (from + to)));
    side = side.norm() > 0 ? Vec3(side.normalized() * (0.05 * sceneRadius)) : Vec3::Zero();
    c.drawArrow(from + side, to + side, lineStyle(Role::Ink, 4.0f, false, true));
}

Vec3 stepView(const WalkBodies& w, const Vec3& sceneView, const WalkStepFeatures& step) {
    if (step.updated < 0 || !w.a || !w.b) return sceneView;
    const ViewScorer s = scorer(w, {{VClipFeature{}, VClipFeature{}, step.updated, step.to}});
    const ViewScorer::Feature& f = s.features.front();
    if (ViewScorer::frontOn(f, sceneView.normalized()) &&
        !insideAlong(featureCenter(f.points), sceneView.normalized(), f.other, 0.0))
        return sceneView;
    return chooseWalkView(w, sceneView, {step}, 180.0);
}

std::vector<KeyItem> planeKey() {
    return {{violatedColor(), "violated plane"},
            {satisfiedColor(), "satisfied plane"},
            {roleColor(Role::Ink), "tested point to its plane (in the plane's colour)", "- -"}};
}

void drawFeature(Canvas& canvas, const std::vector<Vec3>& g, const std::vector<Vec3>& normals, const Color& color,
                 const std::string& label, const Vec3& awayFrom, bool labels, bool step) {
    if (g.empty()) return;
    // Seen from behind: every face holding it turned away from the eye (as Canvas::noteFeature judges).
    const Vec3 centre = featureCenter(g);
    const bool hidden = !normals.empty() && std::none_of(normals.begin(), normals.end(), [&](const Vec3& n) {
        return facesCamera(canvas.camera(), centre, n);
    });
    const bool filled = g.size() > 2 && !hidden;
    canvas.noteFeature({label, g, normals, filled, step, color});
    if (g.size() == 1) {
        canvas.drawPoint(g[0], 9.0f, color, true, 2.0f, roleColor(Role::Ink));
    } else if (g.size() == 2) {
        LineStyle ls = lineStyle(Role::Ink, 6.0f, false, true);
        ls.color = color;
        if (hidden) ls.dashPx = 10.0f;
        canvas.drawLine(g[0], g[1], ls);
    } else {
        // The step's face saturated (issue 42 §3; StepFeatureFaded judges its colour), others tinted.
        if (filled) canvas.drawPolygon(g, color.withAlpha(step ? 0.9f : 0.55f));
        LineStyle ls = lineStyle(Role::Ink, 3.5f, false, true);
        ls.color = step ? color.scaled(0.6f) : color;  // a saturated fill keeps a darker rim
        if (hidden) ls.dashPx = 9.0f;
        canvas.drawPolyline(g, true, ls);
    }
    if (labels) {
        TextStyle ts{18.0f, color.scaled(0.75f), Anchor::Center, true, true};
        drawLabelAway(canvas, centre, awayFrom, label, ts, g.size() == 1 ? 14.0 : 10.0, featureLabelPoints(g));
    }
}

void drawNewFeature(Canvas& canvas, const std::vector<Vec3>& g, const std::vector<Vec3>& normals,
                    const Color& bodyFeature, const std::string& label, bool firstPass) {
    if (g.empty() || (g.size() > 2) != firstPass) return;
    const Color color = g.size() > 2 ? bodyFeature : roleColor(Role::Ink).mixed(bodyFeature, 0.5f);
    drawFeature(canvas, g, normals, color, label, featureCenter(g), false, true);
}

std::vector<Vec3> featureLabelPoints(const std::vector<Vec3>& g) {
    std::vector<Vec3> points;
    if (g.size() == 2)
        for (const double t : {0.25, 0.75, 1.0 / 6.0, 5.0 / 6.0, 0.4, 0.6}) points.push_back((1 - t) * g[0] + t * g[1]);
    else if (g.size() > 2)
        for (const Vec3 centre = featureCenter(g); const Vec3& corner : g) points.push_back(0.5 * (centre + corner));
    return points;
}

std::vector<Vec3> planeTestPatch(const Body& regionBody, const Transform& pose, int plane, const VClipFeature& owner,
                                 const Vec3& tested, double sceneRadius) {
    if (plane >= 0) return planePatch(regionBody, pose, plane, tested, 0.25 * sceneRadius);
    if (owner.type != VClipFeatureType::Face) return {};
    // The face plane itself (a face region's floor, or handleLocalMin's face search).
    std::vector<Vec3> patch = featureGeometry(regionBody.regions, pose, owner);
    const Vec3 mid = featureCenter(patch);
    for (Vec3& q : patch) q = mid + 1.2 * (q - mid);
    return patch;
}

bool planeTestDrawn(const std::vector<VClipPlaneTest>& tests, const VClipPlaneTest& p) {
    if (tests.size() <= 6 || p.violated || p.maximal) return true;
    // None violated and none maximal: the one nearest to being violated, so the step shows a plane.
    const auto marked = [](const VClipPlaneTest& t) { return t.violated || t.maximal; };
    if (std::any_of(tests.begin(), tests.end(), marked)) return false;
    const auto nearest = std::min_element(tests.begin(), tests.end(), [](const VClipPlaneTest& a, const VClipPlaneTest& b) {
        return a.signedDistance < b.signedDistance;
    });
    return &*nearest == &p;
}

std::vector<Vec3> drawnPatchPoints(const WalkBodies& w, const std::vector<VClipPlaneTest>& tests, double sceneRadius) {
    std::vector<Vec3> points;
    for (const VClipPlaneTest& p : tests)
        if (planeTestDrawn(tests, p))
            for (const Vec3& q : planeTestPatch(p.regionBody == 0 ? *w.a : *w.b, p.regionBody == 0 ? w.poseA : w.poseB,
                                                p.plane, p.owner, p.testedPoint, sceneRadius))
                points.push_back(q);
    return points;
}

void drawPlaneTest(Canvas& c, const Body& regionBody, const Transform& pose, int plane, const VClipFeature& owner,
                   const Vec3& tested, double signedDistance, const Vec3& normalIntoOwner, bool violated, bool maximal,
                   double sceneRadius) {
    const std::vector<Vec3> patch = planeTestPatch(regionBody, pose, plane, owner, tested, sceneRadius);
    if (patch.empty()) return;
    const Color col = violated ? violatedColor() : satisfiedColor();
    c.drawPolygon(patch, col.withAlpha(violated ? 0.40f : 0.12f));
    LineStyle ls = lineStyle(Role::Ink, maximal ? 3.0f : violated ? 1.5f : 1.0f, false, false);
    ls.color = violated ? col.scaled(0.8f) : col.withAlpha(0.6f);
    c.drawPolyline(patch, true, ls);
    const Vec3 foot = tested - signedDistance * normalIntoOwner;
    LineStyle d = lineStyle(Role::Ink, 1.5f, true, true);
    d.color = col.scaled(0.8f);
    if ((foot - tested).norm() > 1e-6 * sceneRadius) c.drawLine(tested, foot, d);
    c.drawPoint(tested, 4.0f, col, true, 1.0f, roleColor(Role::Ink));
}

std::string featureLabel(const VClipFeature& f, int body) { return nameOf(f) + (body == 0 ? " (A)" : " (B)"); }

std::vector<Vec3> planePatch(const Body& body, const Transform& pose, int planeIndex, const Vec3& toward, double size) {
    const VClipPolyhedron& p = body.regions;
    const VClipPlane& pl = p.plane(planeIndex);
    const int e = pl.edge.index;
    const Vec3 tail = pose.apply(p.mesh().position(p.edgeTail(e)));
    const Vec3 head = pose.apply(p.mesh().position(p.edgeHead(e)));
    if (pl.other.type == VClipFeatureType::Face) {
        // FE plane: contains the edge and the face normal; the region boundary rises from the edge.
        const Vec3 n = pose.rotate(p.mesh().face(pl.other.index).normal);
        return {tail, head, head + size * n, tail + size * n};
    }
    // VE plane: through the vertex, normal along the edge. A square about the vertex, one side
    // turned towards the tested point's projection so that its foot lands on the patch.
    const Vec3 v = pose.apply(p.mesh().position(pl.other.index));
    const Vec3 n = (head - tail).normalized();
    Vec3 u = (toward - v) - (toward - v).dot(n) * n;
    if (u.norm() < 1e-9 * size) u = n.unitOrthogonal();
    u.normalize();
    const Vec3 w = n.cross(u);
    const double h = 0.5 * size;
    return {v - h * u - h * w, v + 2 * h * u - h * w, v + 2 * h * u + h * w, v - h * u + h * w};
}

RegionCheck checkInRegion(const Body& body, const Transform& pose, const VClipFeature& f, const Vec3& xWorld) {
    RegionCheck out;
    const VClipPolyhedron& p = body.regions;
    const Vec3 x = pose.applyInverse(xWorld);
    auto add = [&](int i) { out.tests.push_back({i, p.regionDistance(i, f, x)}); };
    if (f.type == VClipFeatureType::Vertex) {
        for (int i : p.vertexPlanes(f.index)) add(i);
    } else if (f.type == VClipFeatureType::Edge) {
        for (int k = 0; k < 4; ++k) add(VClipPolyhedron::edgePlane(f.index, k));
    } else if (f.type == VClipFeatureType::Face) {
        for (int i : p.facePlanes(f.index)) add(i);
        out.tests.push_back({-1, p.mesh().planeDistance(f.index, x)});  // above the face
    }
    out.minDistance = INFINITY;
    for (const auto& t : out.tests) out.minDistance = std::min(out.minDistance, t.distance);
    return out;
}

Image composeFrame(GlContext& gl, const Layout& layout, int scale, const std::string& title,
                   const std::string& sceneCaption, const Image& main, const Image& diagram, const Image& plot,
                   const std::vector<std::string>& captionLines) {
    Canvas canvas(gl, canvasOptions(layout.width, layout.height, scale), Camera::twoD(0, 0, 1));
    canvas.drawTextPx(16, 8, title, TextStyle{22.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    double y = layout.height - layout.captionBand + 5;
    if (!sceneCaption.empty())
        canvas.drawTextPx(
            16, y, sceneCaption,
            TextStyle{16.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.55f), Anchor::TopLeft, false, false});
    y += 25.0;
    for (const std::string& line : captionLines) {
        canvas.drawTextPx(16, y, line, TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += 25.0;
    }
    Image frame = canvas.readPixels();
    blit(frame, main, 0, layout.titleBand);
    blit(frame, diagram, layout.mainWidth(), layout.titleBand);
    blit(frame, plot, layout.mainWidth(), layout.titleBand + layout.diagramHeight());
    // 2-pixel rules between the panels.
    const Color m = roleColor(Role::Muted);
    paintRect(frame, layout.mainWidth() - 1, layout.titleBand, 2, layout.panelHeight(), m);
    paintRect(frame, layout.mainWidth(), layout.titleBand + layout.diagramHeight() - 1,
              layout.width - layout.mainWidth(), 2, m);
    return frame;
}

}  // namespace cdlab::demos::walkfigure
