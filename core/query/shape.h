// The shapes of core's pair queries (core/query/pair.h) and of `cdlab query` (docs: the query
// format): one world-frame description for every kind. Every bounded shape is
// conv(vertices) ⊕ ball(radius) — a sphere a point core, a capsule a segment core, a box its eight
// corners — or a cylinder / cone with a closed-form support; a ray and a plane are unbounded and
// answered in closed form by each operation.
#pragma once

#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// A cylinder or cone in the world frame: core/geometry/shapes.h's CylinderShape / ConeShape (axis
/// y, apex of a cone at +halfHeight) rotated by `rotation` about `center`.
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
    std::vector<Vec3> vertices;  ///< bounded shapes but cylinder and cone: world-frame core points
    double radius = 0.0;         ///< sphere / capsule: the shape is conv(vertices) ⊕ ball(radius)
    Vec3 origin = Vec3::Zero(), direction = Vec3::Zero();  ///< ray (largest |direction_i| in [0.5, 1))
    Vec3 normal = Vec3::Zero();  ///< plane: normal · x = offset (normal non-zero, its largest
    double offset = 0.0;         ///<   coordinate in [0.5, 1): see plane())
    CurvedSolid curved;          ///< cylinder / cone (their vertices stay empty, radius 0)

    bool bounded() const { return kind != Kind::Ray && kind != Kind::Plane; }
    bool isCurved() const { return kind == Kind::Cylinder || kind == Kind::Cone; }

    // The constructors of each kind. They check nothing (the query format's reader does, with the
    // JSON path of each error): a negative radius, inverted box or zero direction is the caller's.
    static QueryShape point(const Vec3& p);
    static QueryShape segment(const Vec3& p, const Vec3& q);
    static QueryShape triangle(const Vec3& a, const Vec3& b, const Vec3& c);
    static QueryShape sphere(const Vec3& center, double radius);
    static QueryShape capsule(const Vec3& a, const Vec3& b, double radius);
    /// The box [lo, hi]; corner i has bit k of i choosing hi over lo on axis k.
    static QueryShape aabb(const Vec3& lo, const Vec3& hi);
    /// The box of half extents `half` rotated by `rotation` about `center` (corners as aabb's).
    static QueryShape obb(const Vec3& center, const Vec3& half, const Mat3& rotation = Mat3::Identity());
    /// conv(vertices), each rotated then translated: rotation · v + position.
    static QueryShape polytope(const std::vector<Vec3>& vertices, const Mat3& rotation = Mat3::Identity(),
                               const Vec3& position = Vec3::Zero());
    /// The ray origin + t · direction, t >= 0 (direction non-zero, rescaled by a power of two: the same ray).
    static QueryShape ray(const Vec3& origin, const Vec3& direction);
    /// The plane normal · x = offset (normal non-zero; both rescaled by a power of two so that the
    /// normal's largest coordinate is in [0.5, 1): the same plane, and normalising a 1e-161 or 1e200
    /// normal neither underflows nor overflows).
    static QueryShape plane(const Vec3& normal, double offset);
    static QueryShape cylinder(const Vec3& center, double halfHeight, double radius, const Mat3& rotation = Mat3::Identity());
    static QueryShape cone(const Vec3& center, double halfHeight, double radius, const Mat3& rotation = Mat3::Identity());
};

/// "point", "segment", ... — the query format's key of each kind.
const char* nameOf(QueryShape::Kind kind);

/// True when every coordinate, radius and offset of the shape is finite.
bool isFinite(const QueryShape& s);

/// Points whose bounding box is the shape's core's: the vertices, or a curved solid's box corners
/// lo and hi. For extents and tolerances, never as the shape itself.
std::vector<Vec3> boundingPoints(const QueryShape& s);

/// The support point of a bounded shape along d (radius included).
Vec3 supportPoint(const QueryShape& s, const Vec3& d);

/// The exponent k such that 2^k times the largest coordinate, radius, ray origin or plane offset of
/// the two shapes is in [0.5, 1) (0 when all are zero). Scaling by 2^k changes no mantissa bit, so
/// an answer computed on the scaled shapes and scaled back by 2^-k is the answer; tiny inputs
/// (1e-300) no longer underflow squared norms and huge ones (1e308) no longer overflow differences.
int normalisingExponent(const QueryShape& a, const QueryShape& b);
/// Multiplies every length of the shape by 2^k (exact).
void scaleShape(QueryShape& s, int k);
/// 2^k · v, exact.
Vec3 scaled(const Vec3& v, int k);
/// The exponent e of the largest |coordinate| of v (v = f 2^e, f in [0.5, 1)); 0 for the zero vector.
int largestExponent(const Vec3& v);

}  // namespace cdlab
