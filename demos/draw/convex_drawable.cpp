#include "demos/draw/convex_drawable.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "core/geometry/convex_hull.h"
#include "demos/draw/figure_style.h"

namespace cdlab::demos {

using namespace render;

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
        for (std::size_t i = 0; i < d.outline.size(); ++i)
            d.edges.emplace_back(int(i), int((i + 1) % d.outline.size()));
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
    std::sort(p.begin(), p.end(),
              [](const Vec3& a, const Vec3& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
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

ConvexDrawable boxDrawable(const Obb& box) {
    SceneShape s;
    s.kind = SceneShape::Kind::Box;
    s.halfExtents = box.halfExtents;
    s.pose.position = box.center;
    s.pose.rotation = Quat(box.axes);
    return shapeDrawable(s);
}

ConvexDrawable shapeDrawable(const SceneShape& shape) {
    std::vector<Vec3> points;
    if (shape.isPolytope()) {
        points = shape.worldVertices();
    } else {
        for (const Vec3& d : sampleDirections(shape.planar, shape.planar ? 160 : 900))
            points.push_back(shape.support(d));
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
        for (const Vec3& d : sampleDirections(a.planar, a.planar ? 360 : 1500))
            points.push_back(a.support(d) - b.support(-d));
    }
    if (exact) *exact = polytopes;
    return drawableFromPoints(points, a.planar, polytopes);
}

void drawBody(Canvas& canvas, const ConvexDrawable& body, const Color& fill, float alpha, const Color& edge,
              float edgeWidth, bool hiddenEdges) {
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
    // Outward normals of the triangles at each edge (oriented away from the centre).
    std::map<std::pair<int, int>, std::vector<Vec3>> normalsAt;
    for (const Eigen::Vector3i& t : body.triangles) {
        const Vec3 &a = body.vertices[std::size_t(t[0])], &b = body.vertices[std::size_t(t[1])],
                   &c = body.vertices[std::size_t(t[2])];
        Vec3 n = (b - a).cross(c - a);
        if (n.dot((a + b + c) / 3.0 - body.center) < 0) n = -n;
        for (int k = 0; k < 3; ++k) {
            const int u = t[k], v = t[(k + 1) % 3];
            normalsAt[{std::min(u, v), std::max(u, v)}].push_back(n);
        }
    }
    for (const auto& [i, j] : body.edges) {
        const auto it = normalsAt.find({std::min(i, j), std::max(i, j)});
        const Vec3 &p = body.vertices[std::size_t(i)], &q = body.vertices[std::size_t(j)];
        const bool twoFaces = it != normalsAt.end() && it->second.size() == 2;
        const LineStyle style =
            twoFaces ? edgeStyleSeen(canvas.camera(), 0.5 * (p + q), it->second[0], it->second[1], ls) : ls;
        if (hiddenEdges || style.dashPx == 0.0f) canvas.drawLine(p, q, style);
    }
}

bool facesCamera(const Camera& camera, const Vec3& point, const Vec3& normal) {
    return camera.projection == Camera::Projection::TwoD || normal.dot(camera.directionToEye(point)) > 0;
}

bool behindBody(const Camera& camera, const Vec3& point, const std::vector<Plane>& faces, double tolerance) {
    if (camera.projection == Camera::Projection::TwoD) return false;
    return insideAlong(point, camera.directionToEye(point), faces, tolerance);
}

bool insideAlong(const Vec3& point, const Vec3& toEye, const std::vector<Plane>& faces, double tolerance) {
    if (faces.empty()) return false;
    // The ray p + t u (t >= 0) clipped by every face's half-space (Cyrus–Beck).
    double enter = 0.0, leave = INFINITY;
    for (const Plane& f : faces) {
        const double along = f.normal.dot(toEye), room = f.offset - f.normal.dot(point);
        if (along > 0) leave = std::min(leave, room / along);
        else if (along < 0) enter = std::max(enter, room / along);
        else if (room < 0) return false;  // parallel to the face and outside it
    }
    return leave - enter > tolerance;
}

std::vector<Plane> facePlanes(const ConvexDrawable& body) {
    std::vector<Plane> out;
    if (body.planar) return out;
    for (const Eigen::Vector3i& t : body.triangles) {
        const Vec3 &a = body.vertices[std::size_t(t[0])], &b = body.vertices[std::size_t(t[1])],
                   &c = body.vertices[std::size_t(t[2])];
        Vec3 n = (b - a).cross(c - a);
        if (!(n.norm() > 0)) continue;
        n.normalize();
        if (n.dot(a - body.center) < 0) n = -n;  // outward: the body is convex about its centre
        out.push_back({n, n.dot(a)});
    }
    return out;
}

LineStyle edgeStyleSeen(const Camera& camera, const Vec3& midpoint, const Vec3& n1, const Vec3& n2, LineStyle visible) {
    if (facesCamera(camera, midpoint, n1) || facesCamera(camera, midpoint, n2)) return visible;
    LineStyle hidden = visible;
    hidden.color = visible.color.mixed(roleColor(Role::Background), 0.45f);
    hidden.dashPx = 5.0f;
    hidden.widthPx = std::max(1.0f, 0.8f * visible.widthPx);
    return hidden;
}

void drawConvexMeshEdges(Canvas& canvas, const std::vector<Vec3>& vertices, const std::vector<Eigen::Vector3i>& faces,
                         const LineStyle& visible) {
    Vec3 inside = Vec3::Zero();
    for (const Vec3& v : vertices) inside += v;
    inside /= double(std::max<std::size_t>(1, vertices.size()));
    std::map<std::pair<int, int>, std::vector<Vec3>> normals;  // by edge, its faces' outward normals
    for (const Eigen::Vector3i& f : faces) {
        const Vec3 &a = vertices[std::size_t(f[0])], &b = vertices[std::size_t(f[1])], &c = vertices[std::size_t(f[2])];
        Vec3 n = (b - a).cross(c - a);
        if (n.dot(a - inside) < 0) n = -n;
        for (int e = 0; e < 3; ++e) {
            const int u = f[e], w = f[(e + 1) % 3];
            normals[{std::min(u, w), std::max(u, w)}].push_back(n);
        }
    }
    for (const auto& [edge, ns] : normals) {
        const Vec3 &p = vertices[std::size_t(edge.first)], &q = vertices[std::size_t(edge.second)];
        const double flat = 1e-9 * (q - p).squaredNorm();
        const bool seenFaces = std::all_of(ns.begin(), ns.end(), [&](const Vec3& n) { return n.norm() > flat; });
        const Vec3& n2 = ns.size() > 1 ? ns[1] : ns[0];
        canvas.drawLine(p, q, seenFaces ? edgeStyleSeen(canvas.camera(), 0.5 * (p + q), ns[0], n2, visible) : visible);
    }
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
    ts.place = true;
    canvas.drawText(Vec3::Zero(), "O", ts);
}

void drawLabelAway(Canvas& canvas, const Vec3& at, const Vec3& from, const std::string& text, TextStyle style,
                   double px, const std::vector<Vec3>& alsoAt) {
    Eigen::Vector2d pa, pf;
    Eigen::Vector2d dir(0.7071, -0.7071);  // up and to the right when there is no better direction
    if (canvas.project(at, pa) && canvas.project(from, pf) && (pa - pf).norm() > 1.0) dir = (pa - pf).normalized();
    style.anchor = Anchor::Center;
    const Eigen::Vector2d box = canvas.measureText(text, style);
    // Push the box centre out so its nearest edge is px away from the point.
    const double reach = px + 0.5 * std::abs(dir.x()) * box.x() + 0.5 * std::abs(dir.y()) * box.y();
    style.offsetPx = dir * reach;  // the preferred side; the placement step moves it off anything in the way
    style.place = true;
    std::vector<Vec3> points{at};
    points.insert(points.end(), alsoAt.begin(), alsoAt.end());
    canvas.drawTextAtAnyOf(points, text, style);
}


int bodyOwner(const std::string& name) {
    std::uint32_t h = 2166136261u;  // FNV-1a, 31 bits, never 0
    for (const unsigned char ch : name) h = (h ^ ch) * 16777619u;
    return int(h & 0x7fffffffu) | 1;
}

void drawBodyName(Canvas& canvas, const Vec3& at, const std::string& name, Role role) {
    TextStyle style = labelStyle(role, 26.0f);
    style.place = true;  // on its point when free, else beside it
    style.names = bodyOwner(name);
    canvas.drawText(at, name, style);
}

std::pair<Vec3, Vec3> bodyNamePoints(const ConvexDrawable& a, const ConvexDrawable& b) {
    const double apart = (a.center - b.center).norm();
    if (!(apart < 0.5 * (a.radius + b.radius))) return {a.center, b.center};
    const bool aLarger = a.radius >= b.radius;
    const ConvexDrawable& big = aLarger ? a : b;
    const ConvexDrawable& small = aLarger ? b : a;
    // Past the small body's far side, still well inside the big one's bounding sphere; straight
    // "up" in the body frame when the centres coincide.
    const Vec3 away = apart > 1e-12 * big.radius ? Vec3((big.center - small.center) / apart) : Vec3::UnitZ();
    const double reach = std::min(0.75 * big.radius, small.radius + 0.3 * big.radius);
    const Vec3 moved = small.center + away * reach;
    return aLarger ? std::pair{moved, b.center} : std::pair{a.center, moved};
}

}  // namespace cdlab::demos
