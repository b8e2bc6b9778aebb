// The scene format of the two-shape demos (gjk, epa): shapes read from the scene — support mappings
// placed by a pose, in 3D or in the z = 0 plane — and the "dimension", "shapes" [A, B], "view" keys.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// One convex shape of a GJK / EPA scene, world frame. 3D kinds: box, sphere, cylinder, cone,
/// polytope; 2D kinds (z = 0 plane, rotation about z): polygon, box, circle.
struct SceneShape {
    enum class Kind { Box, Sphere, Cylinder, Cone, Polytope };
    Kind kind = Kind::Box;
    bool planar = false;  ///< 2D scene: the shape lies in z = 0 (box: a rectangle, sphere: a disc)
    Transform pose;       ///< body -> world
    Vec3 halfExtents = Vec3::Ones();
    double radius = 0.5;
    double halfHeight = 0.5;
    PolytopeShape polytope;  ///< Polytope kind: body-frame vertices

    /// World-frame support point (core/base/support.h concept).
    Vec3 support(const Vec3& d) const;
    /// Exactly the convex hull of finitely many points (box, polytope, polygon)?
    bool isPolytope() const { return kind == Kind::Box || kind == Kind::Polytope; }
    /// Polytopes: the world vertices (a superset of the extreme points).
    std::vector<Vec3> worldVertices() const;
    std::string kindName() const;
};

/// Reads {"box": {...}} etc. (see docs/scenes.md, "gjk"). `planar`: the 2D forms.
SceneShape parseSceneShape(const JsonNode& node, bool planar);

/// Tail of the scene reader shared by both demos: "dimension", "shapes" [A, B], "view".
struct PairScene {
    int dimension = 3;
    SceneShape a, b;
    Vec3 view = Vec3(1.0, 0.8, 1.7);
    int maxStepFrames = 6;
    bool gif = true;
};
PairScene readPairScene(ObjectReader& reader);

}  // namespace cdlab::demos
