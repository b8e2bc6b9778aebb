// The shapes of the `cdlab query` format (README "cdlab query"), parsed from JSON into one
// world-frame description: every bounded shape is conv(vertices) ⊕ ball(radius); a ray and a
// plane are unbounded and handled separately by each op.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// A cylinder or cone of the query in the world frame: core/geometry/shapes.h's CylinderShape /
/// ConeShape (axis y, apex of a cone at +halfHeight) rotated by `rotation` about `center`.
struct CurvedSolid {
    bool cone = false;
    Vec3 center = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();
    double halfHeight = 0.0, radius = 0.0;

    Vec3 axis() const { return rotation.col(1); }
    /// Support point in the world frame (a point of the solid extreme along d).
    Vec3 support(const Vec3& d) const;
    /// Its axis-aligned bounding box: the cap discs' (the apex's) extents, in closed form.
    void bounds(Vec3& lo, Vec3& hi) const;
};

struct QueryShape {
    enum class Kind { Point, Segment, Ray, Triangle, Sphere, Aabb, Obb, Capsule, Polytope, Plane, Cylinder, Cone };
    Kind kind = Kind::Point;
    std::vector<Vec3> vertices;  // bounded shapes but cylinder and cone: world-frame core points
    double radius = 0.0;         // sphere / capsule: the shape is conv(vertices) ⊕ ball(radius)
    Vec3 origin = Vec3::Zero(), direction = Vec3::Zero();  // ray (largest |direction_i| in [0.5, 1))
    Vec3 normal = Vec3::Zero();  // plane: normal · x = offset (normal non-zero, not unit; its
    double offset = 0.0;         // largest coordinate is in [0.5, 1) — see parseQueryShape)

    CurvedSolid curved;          // cylinder / cone (their vertices stay empty, radius 0)

    bool bounded() const { return kind != Kind::Ray && kind != Kind::Plane; }
    bool isCurved() const { return kind == Kind::Cylinder || kind == Kind::Cone; }
};

/// Points whose bounding box is the shape's core's: the vertices, or a curved solid's box corners
/// lo and hi. For extents and tolerances, never as the shape itself.
std::vector<Vec3> boundingPoints(const QueryShape& s);

/// The support point of a bounded shape along d (radius included) and its value d·point.
Vec3 supportPoint(const QueryShape& s, const Vec3& d);


const char* nameOf(QueryShape::Kind kind);

/// Parses {"sphere": {...}} and friends; errors name the JSON path. Plane normals (with their
/// offsets) and ray directions are rescaled by a power of two — exactly, the same plane or ray — so
/// that their largest coordinate is in [0.5, 1): normalising a 1e-161 or 1e200 vector then neither
/// underflows nor overflows.
QueryShape parseQueryShape(const JsonNode& node);

/// The exponent k such that 2^k times the largest coordinate, radius, ray origin or plane offset of
/// the two shapes is in [0.5, 1) (0 when all are zero). Scaling by 2^k changes no mantissa bit, so
/// an answer computed on the scaled shapes and scaled back by 2^-k is the answer; tiny inputs
/// (1e-300) no longer underflow squared norms and huge ones (1e308) no longer overflow differences.
int normalisingExponent(const QueryShape& a, const QueryShape& b);
/// Multiplies every length of the shape by 2^k (exact).
void scaleShape(QueryShape& s, int k);
/// 2^k · v, exact.
Vec3 scaled(const Vec3& v, int k);

}  // namespace cdlab::demos
