// The shapes of the `cdlab query` format (README "cdlab query"), parsed from JSON into one
// world-frame description: every bounded shape is conv(vertices) ⊕ ball(radius); a ray and a
// plane are unbounded and handled separately by each op.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"
#include "demos/lib/json_reader.h"

namespace cdlab::demos {

struct QueryShape {
    enum class Kind { Point, Segment, Ray, Triangle, Sphere, Aabb, Obb, Capsule, Polytope, Plane };
    Kind kind = Kind::Point;
    std::vector<Vec3> vertices;  // bounded shapes: world-frame core points
    double radius = 0.0;         // sphere / capsule: the shape is conv(vertices) ⊕ ball(radius)
    Vec3 origin = Vec3::Zero(), direction = Vec3::Zero();  // ray (direction non-zero)
    Vec3 normal = Vec3::Zero();  // plane: normal · x = offset (normal non-zero, not normalised)
    double offset = 0.0;

    bool bounded() const { return kind != Kind::Ray && kind != Kind::Plane; }
};

const char* toString(QueryShape::Kind kind);

/// Parses {"sphere": {...}} and friends; errors name the JSON path.
QueryShape parseQueryShape(const JsonNode& node);

}  // namespace cdlab::demos
