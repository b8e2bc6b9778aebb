#include "core/query/shape.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/shapes.h"

namespace cdlab {

namespace {

// Corner i (bit k of i picks hi over lo on axis k) of the box [lo, hi]: the aabb's eight vertices, and
// the obb's in its own frame with lo = -half extents.
Vec3 boxCorner(int i, const Vec3& lo, const Vec3& hi) {
    return Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
}

QueryShape curvedShape(bool cone, const Vec3& center, double halfHeight, double radius, const Mat3& rotation) {
    QueryShape s;
    s.kind = cone ? QueryShape::Kind::Cone : QueryShape::Kind::Cylinder;
    s.curved.cone = cone;
    s.curved.center = center;
    s.curved.rotation = rotation;
    s.curved.halfHeight = halfHeight;
    s.curved.radius = radius;
    return s;
}

}  // namespace

const char* nameOf(QueryShape::Kind kind) {
    switch (kind) {
        case QueryShape::Kind::Point: return "point";
        case QueryShape::Kind::Segment: return "segment";
        case QueryShape::Kind::Ray: return "ray";
        case QueryShape::Kind::Triangle: return "triangle";
        case QueryShape::Kind::Sphere: return "sphere";
        case QueryShape::Kind::Aabb: return "aabb";
        case QueryShape::Kind::Obb: return "obb";
        case QueryShape::Kind::Capsule: return "capsule";
        case QueryShape::Kind::Polytope: return "polytope";
        case QueryShape::Kind::Plane: return "plane";
        case QueryShape::Kind::Cylinder: return "cylinder";
        case QueryShape::Kind::Cone: return "cone";
    }
    return "?";
}

QueryShape QueryShape::point(const Vec3& p) {
    QueryShape s;
    s.kind = Kind::Point;
    s.vertices = {p};
    return s;
}

QueryShape QueryShape::segment(const Vec3& p, const Vec3& q) {
    QueryShape s;
    s.kind = Kind::Segment;
    s.vertices = {p, q};
    return s;
}

QueryShape QueryShape::triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    QueryShape s;
    s.kind = Kind::Triangle;
    s.vertices = {a, b, c};
    return s;
}

QueryShape QueryShape::sphere(const Vec3& center, double radius) {
    QueryShape s;
    s.kind = Kind::Sphere;
    s.vertices = {center};
    s.radius = radius;
    return s;
}

QueryShape QueryShape::capsule(const Vec3& a, const Vec3& b, double radius) {
    QueryShape s;
    s.kind = Kind::Capsule;
    s.vertices = {a, b};
    s.radius = radius;
    return s;
}

QueryShape QueryShape::aabb(const Vec3& lo, const Vec3& hi) {
    QueryShape s;
    s.kind = Kind::Aabb;
    for (int i = 0; i < 8; ++i) s.vertices.push_back(boxCorner(i, lo, hi));
    return s;
}

QueryShape QueryShape::obb(const Vec3& center, const Vec3& half, const Mat3& rotation) {
    QueryShape s;
    s.kind = Kind::Obb;
    for (int i = 0; i < 8; ++i) s.vertices.push_back(rotation * boxCorner(i, Vec3(-half), half) + center);
    return s;
}

QueryShape QueryShape::polytope(const std::vector<Vec3>& vertices, const Mat3& rotation, const Vec3& position) {
    QueryShape s;
    s.kind = Kind::Polytope;
    s.vertices.reserve(vertices.size());
    for (const Vec3& v : vertices) s.vertices.push_back(rotation * v + position);  // rotated, then translated
    return s;
}

QueryShape QueryShape::ray(const Vec3& origin, const Vec3& direction) {
    QueryShape s;
    s.kind = Kind::Ray;
    s.origin = origin;
    s.direction = scaled(direction, -largestExponent(direction));  // the same ray
    return s;
}

QueryShape QueryShape::plane(const Vec3& normal, double offset) {
    QueryShape s;
    s.kind = Kind::Plane;
    const int k = -largestExponent(normal);  // n·x = d and (2^k n)·x = 2^k d are the same plane
    s.normal = scaled(normal, k);
    s.offset = std::ldexp(offset, k);
    return s;
}

QueryShape QueryShape::cylinder(const Vec3& center, double halfHeight, double radius, const Mat3& rotation) {
    return curvedShape(false, center, halfHeight, radius, rotation);
}

QueryShape QueryShape::cone(const Vec3& center, double halfHeight, double radius, const Mat3& rotation) {
    return curvedShape(true, center, halfHeight, radius, rotation);
}

bool isFinite(const QueryShape& s) {
    for (const Vec3& v : s.vertices)
        if (!v.allFinite()) return false;
    if (s.isCurved()) {
        Vec3 lo, hi;
        s.curved.bounds(lo, hi);
        if (!lo.allFinite() || !hi.allFinite() || !std::isfinite(s.curved.halfHeight) || !std::isfinite(s.curved.radius))
            return false;
    }
    return std::isfinite(s.radius) && std::isfinite(s.offset) && s.origin.allFinite() && s.direction.allFinite() &&
           s.normal.allFinite();
}

Vec3 CurvedSolid::support(const Vec3& d) const {
    const Vec3 local = rotation.transpose() * d;
    const Vec3 s = cone ? ConeShape{halfHeight, radius}.support(local) : CylinderShape{halfHeight, radius}.support(local);
    return center + rotation * s;
}

void CurvedSolid::bounds(Vec3& lo, Vec3& hi) const {
    // A disc of radius r with unit normal u spans r·sqrt(1 − u_i²) on axis i about its centre.
    const Vec3 u = axis();
    const Vec3 disc = radius * (Vec3::Ones() - u.cwiseProduct(u)).cwiseMax(0.0).cwiseSqrt();
    const Vec3 top = center + halfHeight * u, bottom = center - halfHeight * u;
    lo = bottom - disc;
    hi = bottom + disc;
    const Vec3 topReach = cone ? Vec3::Zero() : disc;
    lo = lo.cwiseMin(top - topReach);
    hi = hi.cwiseMax(top + topReach);
}

std::vector<Vec3> boundingPoints(const QueryShape& s) {
    if (!s.isCurved()) return s.vertices;
    Vec3 lo, hi;
    s.curved.bounds(lo, hi);
    return {lo, hi};
}

Vec3 supportPoint(const QueryShape& s, const Vec3& d) {
    if (s.isCurved()) return s.curved.support(d);
    const Vec3* best = &s.vertices.front();
    for (const Vec3& v : s.vertices)
        if (d.dot(v) > d.dot(*best)) best = &v;
    const double n = d.norm();
    return n > 0 ? Vec3(*best + s.radius / n * d) : *best;
}

int largestExponent(const Vec3& v) {
    int e = 0;
    std::frexp(v.cwiseAbs().maxCoeff(), &e);
    return e;
}

Vec3 scaled(const Vec3& v, int k) {
    return v.unaryExpr([k](double x) { return std::ldexp(x, k); });
}

int normalisingExponent(const QueryShape& a, const QueryShape& b) {
    double m = 0;
    for (const QueryShape* s : {&a, &b}) {
        for (const Vec3& v : boundingPoints(*s)) m = std::max(m, v.cwiseAbs().maxCoeff());
        m = std::max({m, s->radius, s->curved.radius, s->curved.halfHeight, s->origin.cwiseAbs().maxCoeff()});
        if (s->kind == QueryShape::Kind::Plane) m = std::max(m, std::abs(s->offset) / s->normal.norm());
    }
    if (m == 0 || !std::isfinite(m)) return 0;
    int e;
    std::frexp(m, &e);  // m = f 2^e, f in [0.5, 1)
    return -e;
}

void scaleShape(QueryShape& s, int k) {
    for (Vec3& v : s.vertices) v = scaled(v, k);
    s.radius = std::ldexp(s.radius, k);
    s.origin = scaled(s.origin, k);
    s.offset = std::ldexp(s.offset, k);  // n·(2^k x) = 2^k d
    s.curved.center = scaled(s.curved.center, k);
    s.curved.halfHeight = std::ldexp(s.curved.halfHeight, k);
    s.curved.radius = std::ldexp(s.curved.radius, k);
}

}  // namespace cdlab
