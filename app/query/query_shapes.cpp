#include "app/query/query_shapes.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/geometry/shapes.h"
#include "app/scene/body_scene.h"

namespace cdlab::demos {

namespace {

// Radii: 0 is allowed (a sphere of radius 0 is a point), negative is an error.
double readRadius(ObjectReader& r) { return r.get("radius").asNonNegative(); }

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

QueryShape parseQueryShape(const JsonNode& node) {
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(
            "expected a shape: an object with exactly one key (point, segment, ray, triangle, sphere, aabb, obb, "
            "box, capsule, cylinder, cone, polytope, hull, plane), got " +
            JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    const JsonNode body(node.raw().begin().value(), node.path() + "." + key, node.source());
    QueryShape s;
    if (key == "point") {
        s = QueryShape::point(body.asVec3());
    } else if (key == "segment") {
        if (body.size() != 2) body.fail("expected [p, q]");
        const std::vector<Vec3> v = body.asVec3List();
        s = QueryShape::segment(v[0], v[1]);
    } else if (key == "triangle") {
        if (body.size() != 3) body.fail("expected [a, b, c]");
        const std::vector<Vec3> v = body.asVec3List();
        s = QueryShape::triangle(v[0], v[1], v[2]);
    } else if (key == "ray") {
        ObjectReader r(body);
        const Vec3 origin = r.get("origin").asVec3();
        JsonNode d = r.get("direction");
        const Vec3 direction = d.asVec3();
        r.finish();
        if (direction.isZero(0.0)) d.fail("ray direction must be non-zero");
        s = QueryShape::ray(origin, direction);
    } else if (key == "sphere") {
        ObjectReader r(body);
        const Vec3 center = getEither(r, "center", "position").asVec3();  // the demos' pose key too
        s = QueryShape::sphere(center, readRadius(r));
        r.finish();
    } else if (key == "aabb") {
        ObjectReader r(body);
        Vec3 lo = r.get("min").asVec3();
        JsonNode maxNode = r.get("max");
        Vec3 hi = maxNode.asVec3();
        r.finish();
        if ((hi.array() < lo.array()).any()) maxNode.fail("aabb max is below min on some axis");
        s = QueryShape::aabb(lo, hi);
    } else if (key == "obb" || key == "box") {
        // "box" is the demos' word for the same shape (half extents about its position, rotated);
        // its position defaults to the origin as in the scenes.
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
        s = QueryShape::obb(c, e, q.toRotationMatrix());
    } else if (key == "capsule") {
        ObjectReader r(body);
        const Vec3 a = r.get("a").asVec3(), b = r.get("b").asVec3();
        s = QueryShape::capsule(a, b, readRadius(r));
        r.finish();
    } else if (key == "polytope" || key == "hull") {  // "hull": the feature-walk scenes' word
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
        s = QueryShape::polytope(body_vertices, t.rotation.toRotationMatrix(), t.position);
    } else if (key == "plane") {
        ObjectReader r(body);
        JsonNode nn = r.get("normal");
        const Vec3 normal = nn.asVec3();
        JsonNode on = r.get("offset");
        const double offset = on.asNumber();
        r.finish();
        if (normal.isZero(0.0)) nn.fail("plane normal must be non-zero");
        s = QueryShape::plane(normal, offset);
        if (!std::isfinite(s.offset))
            on.fail("the plane's distance from the origin, offset / |normal|, overflows double precision");
    } else if (key == "cylinder" || key == "cone") {
        s.kind = key == "cylinder" ? QueryShape::Kind::Cylinder : QueryShape::Kind::Cone;
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

}  // namespace cdlab::demos
