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
                    const std::string& name) {
    const ConvexPolyhedron& m = body.regions.mesh();
    std::vector<Vec3> verts;
    for (const Vec3& p : m.positions()) verts.push_back(pose.apply(p));
    canvas.noteBody(name, verts);
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

Vec3 featureCenter(const std::vector<Vec3>& g) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : g) c += p;
    return g.empty() ? c : Vec3(c / double(g.size()));
}

void drawFeature(Canvas& canvas, const std::vector<Vec3>& g, const Color& color, const std::string& label,
                 const Vec3& awayFrom, bool labels) {
    if (g.empty()) return;
    if (g.size() == 1) {
        canvas.drawPoint(g[0], 9.0f, color, true, 2.0f, roleColor(Role::Ink));
    } else if (g.size() == 2) {
        LineStyle ls = lineStyle(Role::Ink, 6.0f, false, true);
        ls.color = color;
        canvas.drawLine(g[0], g[1], ls);
    } else {
        canvas.drawPolygon(g, color.withAlpha(0.55f));
        LineStyle ls = lineStyle(Role::Ink, 3.5f, false, true);
        ls.color = color;
        canvas.drawPolyline(g, true, ls);
    }
    if (labels) {
        TextStyle ts{18.0f, color.scaled(0.75f), Anchor::Center, true, true};
        drawLabelAway(canvas, featureCenter(g), awayFrom, label, ts, g.size() == 1 ? 14.0 : 10.0, featureLabelPoints(g));
    }
}

std::vector<Vec3> featureLabelPoints(const std::vector<Vec3>& g) {
    std::vector<Vec3> points;
    if (g.size() == 2)
        for (const double t : {0.25, 0.75, 1.0 / 6.0, 5.0 / 6.0, 0.4, 0.6}) points.push_back((1 - t) * g[0] + t * g[1]);
    else if (g.size() > 2)
        for (const Vec3 centre = featureCenter(g); const Vec3& corner : g) points.push_back(0.5 * (centre + corner));
    return points;
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
