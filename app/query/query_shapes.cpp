#include "app/query/query_shapes.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/geometry/shapes.h"
#include "app/scene/body_scene.h"

namespace cdlab::demos {

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

namespace {

// Radii: 0 is allowed (a sphere of radius 0 is a point), negative is an error.
double readRadius(ObjectReader& r) { return r.get("radius").asNonNegative(); }

// The exponent e of the largest |coordinate| (x = f 2^e, f in [0.5, 1)); 0 for the zero vector.
int largestExponent(const Vec3& v) {
    int e = 0;
    std::frexp(v.cwiseAbs().maxCoeff(), &e);
    return e;
}

// Corner i (bit k of i picks hi over lo on axis k) of the box [lo, hi]: the aabb's eight vertices, and
// the obb's in its own frame with lo = -half extents.
Vec3 boxCorner(int i, const Vec3& lo, const Vec3& hi) {
    return Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
}

// {"cylinder": {...}} or {"cone": {...}}: radius, half_height and a pose (center or position,
// rotation), the scenes' fields; a cylinder may instead give its cap centres "a" and "b" (its axis
// from a to b), as a capsule gives its segment.
CurvedSolid parseCurved(const JsonNode& body, bool cone) {
    ObjectReader r(body);
    CurvedSolid c;
    c.cone = cone;
    c.radius = readRadius(r);
    if (!cone && (r.find("a") || r.find("b"))) {
        const JsonNode an = r.get("a"), bn = r.get("b");
        const Vec3 a = an.asVec3(), b = bn.asVec3();
        for (const char* key : {"half_height", "center", "position", "rotation"})
            if (auto extra = r.find(key))
                extra->fail(std::string("a cylinder given by its cap centres a and b has no ") + key +
                            " (give either a and b, or half_height with center and rotation)");
        r.finish();
        const Vec3 axis = b - a;
        if (axis.isZero(0.0)) bn.fail("the cylinder's cap centres a and b coincide (its axis has no direction)");
        const double length = axis.stableNorm();
        c.center = a + 0.5 * axis;
        c.halfHeight = 0.5 * length;
        c.rotation = Quat::FromTwoVectors(Vec3::UnitY(), Vec3(axis / length)).toRotationMatrix();
    } else {
        c.halfHeight = r.get("half_height").asNonNegative();
        if (auto p = findEither(r, "center", "position")) c.center = p->asVec3();
        if (auto q = r.find("rotation")) c.rotation = q->asQuat().toRotationMatrix();
        r.finish();
    }
    Vec3 lo, hi;
    c.bounds(lo, hi);
    if (!lo.allFinite() || !hi.allFinite() || !std::isfinite(c.halfHeight) || !std::isfinite(c.radius))
        body.fail("shape coordinates overflow after transformation");
    return c;
}

}  // namespace

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

QueryShape parseQueryShape(const JsonNode& node) {
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(
            "expected a shape: an object with exactly one key (point, segment, ray, triangle, sphere, aabb, obb, "
            "box, capsule, cylinder, cone, polytope, hull, plane), got " +
            JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    const JsonNode body(node.raw().begin().value(), node.path() + "." + key, node.source());
    QueryShape s;
    using K = QueryShape::Kind;
    if (key == "point") {
        s.kind = K::Point;
        s.vertices = {body.asVec3()};
    } else if (key == "segment") {
        s.kind = K::Segment;
        if (body.size() != 2) body.fail("expected [p, q]");
        s.vertices = body.asVec3List();
    } else if (key == "triangle") {
        s.kind = K::Triangle;
        if (body.size() != 3) body.fail("expected [a, b, c]");
        s.vertices = body.asVec3List();
    } else if (key == "ray") {
        s.kind = K::Ray;
        ObjectReader r(body);
        s.origin = r.get("origin").asVec3();
        JsonNode d = r.get("direction");
        s.direction = d.asVec3();
        r.finish();
        if (s.direction.isZero(0.0)) d.fail("ray direction must be non-zero");
        s.direction = scaled(s.direction, -largestExponent(s.direction));  // the same ray
    } else if (key == "sphere") {
        s.kind = K::Sphere;
        ObjectReader r(body);
        s.vertices = {getEither(r, "center", "position").asVec3()};  // the demos' pose key too
        s.radius = readRadius(r);
        r.finish();
    } else if (key == "aabb") {
        s.kind = K::Aabb;
        ObjectReader r(body);
        Vec3 lo = r.get("min").asVec3();
        JsonNode maxNode = r.get("max");
        Vec3 hi = maxNode.asVec3();
        r.finish();
        if ((hi.array() < lo.array()).any()) maxNode.fail("aabb max is below min on some axis");
        for (int i = 0; i < 8; ++i) s.vertices.push_back(boxCorner(i, lo, hi));
    } else if (key == "obb" || key == "box") {
        // "box" is the demos' word for the same shape (half extents about its position, rotated);
        // its position defaults to the origin as in the scenes.
        s.kind = K::Obb;
        ObjectReader r(body);
        const std::optional<JsonNode> cn = findEither(r, "center", "position");
        if (!cn && key == "obb") r.get("center");  // the obb's error: its center is required
        Vec3 c = cn ? cn->asVec3() : Vec3::Zero();
        JsonNode en = r.get("half_extents");
        Vec3 e = en.asVec3();
        if ((e.array() < 0).any()) en.fail("half extents must be non-negative");
        Quat q = Quat::Identity();
        if (auto rot = r.find("rotation")) q = rot->asQuat();
        r.finish();
        Mat3 R = q.toRotationMatrix();
        for (int i = 0; i < 8; ++i) s.vertices.push_back(R * boxCorner(i, Vec3(-e), e) + c);
    } else if (key == "capsule") {
        s.kind = K::Capsule;
        ObjectReader r(body);
        s.vertices = {r.get("a").asVec3(), r.get("b").asVec3()};
        s.radius = readRadius(r);
        r.finish();
    } else if (key == "polytope" || key == "hull") {  // "hull": the feature-walk scenes' word
        s.kind = K::Polytope;
        ObjectReader r(body);
        JsonNode vn = r.get("vertices");
        std::vector<Vec3> body_vertices = vn.asVec3List();
        if (body_vertices.size() < 4)
            vn.fail("a polytope needs at least 4 vertices, got " + std::to_string(body_vertices.size()));
        Transform t;
        if (auto p = r.find("position")) t.position = p->asVec3();
        if (auto q = r.find("rotation")) t.rotation = q->asQuat();
        r.finish();
        // Rotated then translated, exactly as the format says; the same world vertices feed every method.
        Mat3 R = t.rotation.toRotationMatrix();
        for (const Vec3& v : body_vertices) s.vertices.push_back(R * v + t.position);
    } else if (key == "plane") {
        s.kind = K::Plane;
        ObjectReader r(body);
        JsonNode nn = r.get("normal");
        s.normal = nn.asVec3();
        JsonNode on = r.get("offset");
        s.offset = on.asNumber();
        r.finish();
        if (s.normal.isZero(0.0)) nn.fail("plane normal must be non-zero");
        // n·x = d and (2^k n)·x = 2^k d are the same plane.
        const int k = -largestExponent(s.normal);
        s.normal = scaled(s.normal, k);
        s.offset = std::ldexp(s.offset, k);
        if (!std::isfinite(s.offset))
            on.fail("the plane's distance from the origin, offset / |normal|, overflows double precision");
    } else if (key == "cylinder" || key == "cone") {
        s.kind = key == "cylinder" ? K::Cylinder : K::Cone;
        s.curved = parseCurved(body, key == "cone");
    } else if (key == "compound" || key == "mesh") {
        node.fail("a " + key + " is taken by the intersect, distance and penetration ops only");
    } else {
        node.fail("unknown shape '" + key +
                  "' (expected point, segment, ray, triangle, sphere, aabb, obb, box, capsule, "
                  "cylinder, cone, polytope, hull or plane)");
    }
    for (const Vec3& v : s.vertices)
        if (!v.allFinite()) node.fail("shape coordinates overflow after transformation");
    return s;
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

}  // namespace cdlab::demos
