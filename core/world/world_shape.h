// The shapes of a many-body world (core/world/world.h): boxes, convex hulls, spheres and capsules
// that move, boxes that stand still (walls, ramps, a bin) and ground planes. Each shape lives in
// its body frame, whose origin is the centre of mass and whose axes are the body's: a hull is
// recentred when it is made, a capsule's segment runs along the body's y axis.
//
// Mass properties (uniform density ρ): boxes and hulls exactly from their faces
// (core/geometry/mass_properties.h); a sphere 2/5 m r²; a capsule as a cylinder of length 2h and two
// hemispheres of mass m_s in all, each hemisphere's inertia about the capsule's centre by the
// parallel-axis theorem through its own centre of mass (3r/8 from its flat face):
//     I_yy = m_c r²/2 + m_s 2r²/5,   I_xx = I_zz = m_c (r²/4 + h²/3) + m_s (2r²/5 + h² + 3hr/4)
// (tests/core/world/world_shape_test.cpp checks them against a fine voxel sum).
#pragma once

#include <string>

#include "core/base/primitives.h"
#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

struct WorldShape {
    enum class Kind { Box, Hull, Sphere, Capsule, Plane };
    Kind kind = Kind::Box;
    Vec3 halfExtents = Vec3::Zero();  ///< Box
    /// Box and Hull: the solid in the body frame (origin at the centre of mass).
    ConvexPolyhedron hull;
    double radius = 0.0;      ///< Sphere, Capsule
    double halfHeight = 0.0;  ///< Capsule: its segment is (0, ±halfHeight, 0) in the body frame
    Plane plane{Vec3::UnitZ(), 0.0};  ///< Plane (world frame): the solid half-space n · x <= d, n unit
    /// The farthest point of the solid from the body origin (0 for a plane).
    double boundingRadius = 0.0;

    bool rounded() const { return kind == Kind::Sphere || kind == Kind::Capsule; }
    bool polytope() const { return kind == Kind::Box || kind == Kind::Hull; }
};

/// "box", "hull", "sphere", "capsule", "plane".
const char* nameOf(WorldShape::Kind kind);

/// A shape and its mass properties for density 1 (mass = volume, inertia about the origin of the
/// body frame = the centre of mass), or why it is refused (message, one line; empty when ok).
struct WorldShapeBuild {
    WorldShape shape;
    double volume = 0.0;
    Mat3 unitInertia = Mat3::Zero();
    /// Where the input's frame sits in the body frame: a hull's vertices were moved by −centre of
    /// mass, so a pose given for the input frame is the body pose composed with this offset.
    Vec3 inputOrigin = Vec3::Zero();
    std::string message;
    bool ok() const { return message.empty(); }
};

/// A box of the given half extents (each finite and > 0).
WorldShapeBuild worldBox(const Vec3& halfExtents);
/// The convex hull of the points (at least 4, not flat, finite), recentred at its centre of mass.
WorldShapeBuild worldHull(const std::vector<Vec3>& points);
WorldShapeBuild worldSphere(double radius);
WorldShapeBuild worldCapsule(double halfHeight, double radius);
/// The half-space n · x <= d (n non-zero and finite; it is normalised).
WorldShapeBuild worldPlane(const Vec3& normal, double offset);

/// World-frame bounding box of a bounded shape at `pose` (boxes and hulls: their rotated vertices'
/// extent; spheres and capsules in closed form). A plane has none (the box is empty: min > max).
Aabb worldBounds(const WorldShape& shape, const Transform& pose);

}  // namespace cdlab
