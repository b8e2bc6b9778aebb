#include "demos/draw/support_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/convex_hull.h"
#include "demos/draw/figure_style.h"
#include "demos/scene/scene_limits.h"
#include "render/gif_writer.h"

namespace cdlab::demos {

using namespace render;

// ------------------------------------------------------------------------------------ shapes

Vec3 SceneShape::support(const Vec3& dWorld) const {
    Vec3 d = pose.rotateInverse(dWorld);
    if (planar) d.z() = 0.0;  // in-plane directions only (a rotation about z keeps z = 0 exactly)
    Vec3 s = Vec3::Zero();
    switch (kind) {
        case Kind::Box: s = BoxShape{halfExtents}.support(d); break;
        case Kind::Sphere: s = SphereShape{radius}.support(d); break;
        case Kind::Cylinder: s = CylinderShape{halfHeight, radius}.support(d); break;
        case Kind::Cone: s = ConeShape{halfHeight, radius}.support(d); break;
        case Kind::Polytope: s = polytope.support(d); break;
    }
    return pose.apply(s);
}

std::vector<Vec3> SceneShape::worldVertices() const {
    std::vector<Vec3> out;
    if (kind == Kind::Box) {
        const int corners = planar ? 4 : 8;
        for (int i = 0; i < corners; ++i)
            out.push_back(pose.apply(Vec3((i & 1 ? 1 : -1) * halfExtents.x(), (i & 2 ? 1 : -1) * halfExtents.y(),
                                          planar ? 0.0 : (i & 4 ? 1 : -1) * halfExtents.z())));
    } else if (kind == Kind::Polytope) {
        for (const Vec3& v : polytope.vertices()) out.push_back(pose.apply(v));
    }
    return out;
}

std::string SceneShape::kindName() const {
    switch (kind) {
        case Kind::Box: return planar ? "rectangle" : "box";
        case Kind::Sphere: return planar ? "circle" : "sphere";
        case Kind::Cylinder: return "cylinder";
        case Kind::Cone: return "cone";
        case Kind::Polytope: return planar ? "polygon" : "polytope";
    }
    return "?";
}

namespace {

Vec3 readVec2(const JsonNode& n) { return sceneVec2(n); }

// An explicit polygon / polytope: at most kMaxShapeVertices (the configuration-space view draws
// the hull of all n·m differences of the pair).
void requireShapeVertices(const JsonNode& vn) {
    requireAtMost(vn, double(vn.size()), double(kMaxShapeVertices), "the number of vertices",
                  "the Minkowski-difference view builds the hull of all n·m differences of the pair");
}

}  // namespace

SceneShape parseSceneShape(const JsonNode& node, bool planar) {
    const char* kinds3 = "box, sphere, cylinder, cone or polytope";
    const char* kinds2 = "polygon, box or circle";
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(std::string("expected a shape: an object with exactly one key (") + (planar ? kinds2 : kinds3) +
                  "), got " + JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    const JsonNode body(node.raw().begin().value(), node.path() + "." + key, node.source());
    ObjectReader r(body);
    SceneShape s;
    s.planar = planar;
    if (planar) {
        if (key == "box") {
            s.kind = SceneShape::Kind::Box;
            JsonNode h = r.get("half_extents");
            if (!h.isArray() || h.size() != 2) h.fail("expected [x, y], got " + JsonNode::describe(h.raw()));
            s.halfExtents = Vec3(sceneSize(h.at(0)), sceneSize(h.at(1)), 0.0);
        } else if (key == "circle") {
            s.kind = SceneShape::Kind::Sphere;
            s.radius = sceneSize(r.get("radius"));
        } else if (key == "polygon") {
            s.kind = SceneShape::Kind::Polytope;
            JsonNode vn = r.get("vertices");
            requireShapeVertices(vn);
            std::vector<Vec3> v;
            for (const JsonNode& item : vn.items()) v.push_back(readVec2(item));
            if (v.size() < 3) vn.fail("a polygon needs at least 3 vertices, got " + std::to_string(v.size()));
            s.polytope = PolytopeShape(std::move(v));
        } else {
            node.fail("unknown 2D shape '" + key + "' (expected " + kinds2 + ")");
        }
        if (auto p = r.find("position")) s.pose.position = readVec2(*p);
        if (auto a = r.find("angle")) {
            if (s.kind == SceneShape::Kind::Sphere) a->fail("a circle has no angle");
            s.pose.rotation = Quat(Eigen::AngleAxisd(std::fmod(a->asNumber(), 360.0) * M_PI / 180.0, Vec3::UnitZ()));
        }
    } else {
        if (key == "box") {
            s.kind = SceneShape::Kind::Box;
            JsonNode h = r.get("half_extents");
            s.halfExtents = sceneSizes(h);
        } else if (key == "sphere") {
            s.kind = SceneShape::Kind::Sphere;
            s.radius = sceneSize(r.get("radius"));
        } else if (key == "cylinder" || key == "cone") {
            s.kind = key == "cylinder" ? SceneShape::Kind::Cylinder : SceneShape::Kind::Cone;
            s.radius = sceneSize(r.get("radius"));
            s.halfHeight = sceneSize(r.get("half_height"));
        } else if (key == "polytope") {
            s.kind = SceneShape::Kind::Polytope;
            JsonNode vn = r.get("vertices");
            requireShapeVertices(vn);
            std::vector<Vec3> v = sceneVec3List(vn, 0, kMaxShapeVertices);
            if (v.size() < 4) vn.fail("a polytope needs at least 4 vertices, got " + std::to_string(v.size()));
            if (!convexHull(v).ok()) vn.fail("the polytope's vertices span no volume");
            s.polytope = PolytopeShape(std::move(v));
        } else {
            node.fail("unknown shape '" + key + "' (expected " + kinds3 + ")");
        }
        if (auto p = r.find("position")) s.pose.position = sceneVec3(*p);
        if (auto q = r.find("rotation")) s.pose.rotation = q->asQuat();
    }
    r.finish();
    return s;
}

// --------------------------------------------------------------------------------- drawables

namespace {

// Evenly spread unit directions: Fibonacci sphere (3D) or equal angles (2D). Deterministic.
std::vector<Vec3> sampleDirections(bool planar, int n) {
    std::vector<Vec3> out;
    if (planar) {
        for (int i = 0; i < n; ++i) {
            const double t = 2.0 * M_PI * (i + 0.5) / n;
            out.emplace_back(std::cos(t), std::sin(t), 0.0);
        }
        return out;
    }
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / n;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        out.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
    }
    // The poles and the equator's axis directions exactly: cylinder / cone caps and rims.
    for (int k = 0; k < 3; ++k) {
        out.push_back(Vec3::Unit(k));
        out.push_back(-Vec3::Unit(k));
    }
    return out;
}


ConvexDrawable drawableFromPoints(const std::vector<Vec3>& points, bool planar, bool polytopeEdges) {
    ConvexDrawable d;
    d.planar = planar;
    if (planar) {
        d.outline = hull2d(points);
        d.vertices = d.outline;
        for (std::size_t i = 0; i < d.outline.size(); ++i) d.edges.emplace_back(int(i), int((i + 1) % d.outline.size()));
        d.valid = d.outline.size() >= 3;
    } else {
        HullResult h = convexHull(points);
        if (h.ok()) {
            const ConvexPolyhedron& poly = h.polyhedron;
            d.vertices = poly.positions();
            for (int f = 0; f < poly.faceCount(); ++f) {
                std::vector<int> fv = poly.faceVertices(f);
                for (std::size_t i = 1; i + 1 < fv.size(); ++i) d.triangles.emplace_back(fv[0], fv[i], fv[i + 1]);
            }
            if (polytopeEdges)
                for (int e = 0; e < poly.edgeCount(); ++e) d.edges.push_back(poly.edgeVertices(e));
            d.valid = true;
        }
    }
    boundingSphere(d.valid ? d.vertices : points, d.center, d.radius);
    return d;
}

}  // namespace

// Andrew's monotone chain; drops collinear points. Counter-clockwise.
std::vector<Vec3> hull2d(std::vector<Vec3> p) {
    std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    auto cross = [](const Vec3& o, const Vec3& a, const Vec3& b) {
        return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
    };
    std::vector<Vec3> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

void boundingSphere(const std::vector<Vec3>& points, Vec3& center, double& radius) {
    center.setZero();
    radius = 0.0;
    if (points.empty()) return;
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    center = 0.5 * (lo + hi);
    for (const Vec3& p : points) radius = std::max(radius, (p - center).norm());
}

ConvexDrawable shapeDrawable(const SceneShape& shape) {
    std::vector<Vec3> points;
    if (shape.isPolytope()) {
        points = shape.worldVertices();
    } else {
        for (const Vec3& d : sampleDirections(shape.planar, shape.planar ? 160 : 900)) points.push_back(shape.support(d));
    }
    return drawableFromPoints(points, shape.planar, shape.isPolytope());
}

ConvexDrawable minkowskiDrawable(const SceneShape& a, const SceneShape& b, bool* exact) {
    std::vector<Vec3> points;
    const bool polytopes = a.isPolytope() && b.isPolytope();
    if (polytopes) {
        for (const Vec3& p : a.worldVertices())
            for (const Vec3& q : b.worldVertices()) points.push_back(p - q);
    } else {
        for (const Vec3& d : sampleDirections(a.planar, a.planar ? 360 : 1500)) points.push_back(a.support(d) - b.support(-d));
    }
    if (exact) *exact = polytopes;
    return drawableFromPoints(points, a.planar, polytopes);
}

// ---------------------------------------------------------------------------------- drawing

Camera panelCamera(bool planar, const Vec3& center, double radius, const Vec3& view, const TwoPanelLayout& layout) {
    if (planar) {
        const double aspect = double(layout.panelWidth()) / layout.panelHeight();
        // Fit the circle in the shorter side with a margin for labels, and leave room for the heading.
        const double height = std::max(2.0 * radius, 2.0 * radius / aspect) * 1.3;
        return Camera::twoD(center.x(), center.y() + 0.04 * height, height);
    }
    return framingCamera(center, radius * 1.05, view, Vec3::UnitY(), true);
}

void drawBody(Canvas& canvas, const ConvexDrawable& body, const Color& fill, float alpha, const Color& edge, float edgeWidth) {
    if (!body.valid) return;
    LineStyle ls;
    ls.widthPx = edgeWidth;
    ls.color = edge;
    if (body.planar) {
        canvas.drawPolygon(body.outline, fill.withAlpha(alpha));
        canvas.drawPolyline(body.outline, true, ls);
        return;
    }
    canvas.drawMesh(body.vertices, body.triangles, fill.withAlpha(alpha), true);
    for (const auto& [i, j] : body.edges) canvas.drawLine(body.vertices[i], body.vertices[j], ls);
}

void drawOrigin(Canvas& canvas, double size, bool planar) {
    LineStyle ls = lineStyle(Role::Origin, 2.0f, false, true);
    for (int k = 0; k < (planar ? 2 : 3); ++k) {
        Vec3 u = Vec3::Unit(k) * size;
        canvas.drawLine(-u, u, ls);
    }
    canvas.drawPoint(Vec3::Zero(), 7.0f, roleColor(Role::Origin), true, 1.5f, roleColor(Role::Ink));
    TextStyle ts = labelStyle(Role::Origin, 20.0f);
    ts.anchor = Anchor::TopRight;
    ts.offsetPx = Eigen::Vector2d(-6, 6);
    canvas.drawText(Vec3::Zero(), "O", ts);
}

void drawLabelAway(Canvas& canvas, const Vec3& at, const Vec3& from, const std::string& text, TextStyle style, double px) {
    Eigen::Vector2d pa, pf;
    Eigen::Vector2d dir(0.7071, -0.7071);  // up and to the right when there is no better direction
    if (canvas.project(at, pa) && canvas.project(from, pf) && (pa - pf).norm() > 1.0) dir = (pa - pf).normalized();
    style.anchor = Anchor::Center;
    const Eigen::Vector2d box = canvas.measureText(text, style);
    // Push the box centre out so its nearest edge is px away from the point.
    const double reach = px + 0.5 * std::abs(dir.x()) * box.x() + 0.5 * std::abs(dir.y()) * box.y();
    style.offsetPx = dir * reach;
    canvas.drawText(at, text, style);
}

void drawPanelHeading(Canvas& canvas, const std::string& heading, const std::string& sub) {
    canvas.drawTextPx(14, 10, heading, TextStyle{20.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    if (!sub.empty())
        canvas.drawTextPx(14, 38, sub, TextStyle{17.0f, roleColor(Role::Highlight).scaled(0.8f), Anchor::TopLeft, true, true});
}

Image composeTwoPanel(GlContext& gl, const TwoPanelLayout& layout, int supersample, const std::string& title,
                      const Image& left, const Image& right, const std::vector<std::string>& captionLines) {
    CanvasOptions o;
    o.width = layout.width;
    o.height = layout.height;
    o.supersample = supersample;
    Canvas canvas(gl, o);
    canvas.setBackground(roleColor(Role::Background));
    canvas.setCamera(Camera::twoD(0, 0, 1));
    canvas.drawTextPx(18, 10, title, TextStyle{24.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    const double lineH = 25.0;
    double y = layout.height - layout.captionBand + 8;
    for (const std::string& line : captionLines) {
        canvas.drawTextPx(18, y, line, TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += lineH;
    }
    Image frame = canvas.readPixels();
    blit(frame, left, 0, layout.titleBand);
    blit(frame, right, layout.panelWidth(), layout.titleBand);
    // A 2-pixel rule between the panels.
    const Color m = roleColor(Role::Muted);
    for (int yy = layout.titleBand; yy < layout.titleBand + layout.panelHeight(); ++yy)
        for (int xx = layout.panelWidth() - 1; xx <= layout.panelWidth(); ++xx) {
            std::uint8_t* p = frame.pixel(xx, yy);
            p[0] = std::uint8_t(std::lround(std::clamp(m.r, 0.0f, 1.0f) * 255));
            p[1] = std::uint8_t(std::lround(std::clamp(m.g, 0.0f, 1.0f) * 255));
            p[2] = std::uint8_t(std::lround(std::clamp(m.b, 0.0f, 1.0f) * 255));
            p[3] = 255;
        }
    return frame;
}

std::vector<int> framedSteps(int n, int maxFrames) {
    std::vector<int> out;
    if (n <= maxFrames) {
        for (int i = 0; i < n; ++i) out.push_back(i);
        return out;
    }
    for (int i = 0; i < maxFrames - 1; ++i) out.push_back(i);
    out.push_back(n - 1);
    return out;
}

std::string stepFrameName(int i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "step_%02d", i);
    return buf;
}

Json vec3Json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

PairScene readPairScene(ObjectReader& r) {
    PairScene s;
    if (auto d = r.find("dimension")) {
        s.dimension = d->asInt(2, 3);
    }
    JsonNode shapes = r.get("shapes");
    if (!shapes.isArray() || shapes.size() != 2) shapes.fail("expected [shapeA, shapeB]");
    s.a = parseSceneShape(shapes.at(0), s.dimension == 2);
    s.b = parseSceneShape(shapes.at(1), s.dimension == 2);
    if (s.a.isPolytope() && s.b.isPolytope())
        requireAtMost(shapes, double(s.a.worldVertices().size()) * double(s.b.worldVertices().size()), kMaxMinkowskiPoints,
                      "vertices of A x vertices of B", "the Minkowski-difference view builds the hull of every difference");
    if (auto v = r.find("view")) {
        if (s.dimension == 2) v->fail("'view' is for 3D scenes");
        s.view = sceneVec3(*v);
        if (s.view.squaredNorm() == 0) v->fail("view direction must be non-zero");
    }
    if (auto m = r.find("max_step_frames")) s.maxStepFrames = m->asInt(2, 60);
    s.gif = r.boolOr("gif", true);
    return s;
}

void addGif(DemoOutput& out, const std::vector<const Frame*>& frames, int downscale) {
    std::vector<Image> images;
    for (const Frame* f : frames) images.push_back(downscale > 1 ? downsample(f->image, downscale) : f->image);
    if (images.empty()) return;
    out.files.emplace_back("animation.gif", encodeGif(images));
}

PairDrawing makePairDrawing(const PairScene& pair, bool drawMinkowski, std::vector<Vec3> csPoints,
                            std::vector<std::string>& skipped) {
    PairDrawing d;
    d.planar = pair.dimension == 2;
    d.a = shapeDrawable(pair.a);
    d.b = shapeDrawable(pair.b);
    if (drawMinkowski) d.c = minkowskiDrawable(pair.a, pair.b, &d.exact);
    else skipped.push_back("Minkowski difference hull (no 'minkowski' layer)");
    if (d.c.valid) csPoints.insert(csPoints.end(), d.c.vertices.begin(), d.c.vertices.end());
    csPoints.push_back(Vec3::Zero());
    boundingSphere(csPoints, d.cCenter, d.cRadius);
    std::vector<Vec3> wpts = d.a.vertices;
    wpts.insert(wpts.end(), d.b.vertices.begin(), d.b.vertices.end());
    boundingSphere(wpts, d.wCenter, d.wRadius);
    return d;
}

}  // namespace cdlab::demos
