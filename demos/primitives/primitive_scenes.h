// The three families of the primitives demo: what each scene holds once read, and the function
// that runs it (core test once, its trace as JSON, the figure when a GL context is given).
#pragma once

#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "core/base/types.h"
#include "app/scene/demo.h"

namespace cdlab::demos {

/// A shape of the primitives demo, in the words of `cdlab query` (docs/query.md): sphere
/// {center | position, radius}, aabb {min, max}, obb / box {center | position, half_extents,
/// rotation}, segment [p, q], triangle [a, b, c], point p, tetrahedron [a, b, c, d]. World frame.
struct PrimitiveShape {
    enum class Kind { Sphere, Aabb, Obb, Segment, Triangle, Point, Tetrahedron };
    Kind kind = Kind::Sphere;
    std::vector<Vec3> vertices;  // sphere: its centre; boxes: the 8 corners; point, segment, triangle, tetrahedron: as given
    double radius = 0.0;         // sphere
    Obb box{Vec3::Zero(), Vec3::Zero(), Mat3::Identity()};  // aabb / obb: centre, half extents, axes

    /// An aabb's min and max exactly as given: its corners 0 and 7 (box holds them rounded).
    Aabb aabb() const { return {vertices.front(), vertices.back()}; }
};
const char* nameOf(PrimitiveShape::Kind kind);
/// Reads one shape (its kind among `allowed`, else an error naming the kinds in `what`).
PrimitiveShape readPrimitiveShape(const JsonNode& node, const std::vector<PrimitiveShape::Kind>& allowed,
                                  const std::string& what);

/// "test": "raycast" — a ray {origin, direction} or a segment [p, q] against a sphere, an aabb,
/// an obb / box or a triangle (the query's shape words).
struct RaycastInput {
    bool segment = false;
    Vec3 origin = Vec3::Zero();
    Vec3 direction = Vec3::UnitX();  // segment: q - p (t in [0, 1])
    PrimitiveShape shape;
};
DemoOutput runRaycast(const SceneCommon& scene, const RaycastInput& input, const RunContext& context);

/// "test": "sat" — two shapes: box and box (15 axes), segment and box (6), triangle and aabb (13).
struct SatInput {
    PrimitiveShape a, b;
};
DemoOutput runSat(const SceneCommon& scene, const SatInput& input, const RunContext& context);

/// "test": "closest_features" — two simplices (point, segment, triangle, tetrahedron): their closest
/// feature pair by trying every pair, checked against GJK.
struct ClosestFeaturesInput {
    PrimitiveShape a, b;
};
DemoOutput runClosestFeatures(const SceneCommon& scene, const ClosestFeaturesInput& input, const RunContext& context);

/// "test": "sphere_overlap" — a sphere against a sphere, an aabb, an obb or a triangle: the other
/// shape's closest point to the centre against the radius.
struct SphereOverlapInput {
    PrimitiveShape sphere, other;
};
DemoOutput runSphereOverlap(const SceneCommon& scene, const SphereOverlapInput& input, const RunContext& context);

/// A 2D game object (plane z = 0): point, segment, rectangle {center, half_extents, angle (degrees)},
/// triangle or circle {center, radius}; a circle is its centre with a radius.
struct Shape2d {
    std::string kind;
    std::vector<Vec3> corners;  // z = 0
    double radius = 0.0;
};
Shape2d readShape2d(const JsonNode& node);

/// "test": "moving_2d" — a 2D object moving by `velocity` over t in [0, 1] against a still one.
struct Moving2dInput {
    Shape2d moving, still;
    Vec3 velocity = Vec3::Zero();
};
DemoOutput runMoving2d(const SceneCommon& scene, const Moving2dInput& input, const RunContext& context);

/// "test": "point_in_polygon" — a 2D polygon (any, self-intersecting allowed) and query points.
struct PointInPolygonInput {
    std::vector<Vec2> polygon;
    std::vector<Vec2> queries;
};
DemoOutput runPointInPolygon(const SceneCommon& scene, const PointInPolygonInput& input, const RunContext& context);

}  // namespace cdlab::demos
