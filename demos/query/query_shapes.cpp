#include "demos/query/query_shapes.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "demos/scene/body_scene.h"

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

}  // namespace

QueryShape parseQueryShape(const JsonNode& node) {
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(
            "expected a shape: an object with exactly one key (point, segment, ray, triangle, sphere, aabb, obb, "
            "box, capsule, polytope, hull, plane), got " +
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
    } else if (key == "compound" || key == "mesh") {
        node.fail("a " + key + " is taken by the intersect, distance and penetration ops only");
    } else {
        node.fail("unknown shape '" + key +
                  "' (expected point, segment, ray, triangle, sphere, aabb, obb, box, capsule, "
                  "polytope, hull or plane)");
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
        for (const Vec3& v : s->vertices) m = std::max(m, v.cwiseAbs().maxCoeff());
        m = std::max({m, s->radius, s->origin.cwiseAbs().maxCoeff()});
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
}

}  // namespace cdlab::demos
