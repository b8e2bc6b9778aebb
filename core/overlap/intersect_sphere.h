// Sphere tests: sphere-sphere, sphere-box and sphere-triangle (Ericson, Real-Time Collision
// Detection §4.3.1, §5.2.5, §5.2.6, §5.2.7; closest points §5.1.3, §5.1.4, §5.1.5).
//
// World frame, any consistent length unit. All shapes are closed sets: touching (distance
// exactly equal to the radius sum) counts as a hit. NaN / inf inputs, negative radii and empty
// boxes (min > max) give hit == false; a zero radius is a point and is allowed.
#pragma once

#include "core/base/primitives.h"

namespace cdlab {

/// Sphere-sphere overlap (Ericson §4.3.1) with contact data.
struct SphereSphereResult {
    bool hit = false;
    /// Distance between the centers.
    double distance = 0.0;
    /// ra + rb - distance: the penetration depth when hit (>= 0), minus the gap otherwise.
    double depth = 0.0;
    /// Unit vector from a's center to b's center; (1, 0, 0) when the centers coincide.
    Vec3 normal = Vec3::UnitX();
    /// Midpoint between the two surface points along normal (meaningful when the inputs are
    /// finite).
    Vec3 point = Vec3::Zero();
};

/// Sphere-sphere test: hit iff |cb - ca|^2 <= (ra + rb)^2 (squared form, no square root).
SphereSphereResult intersectSphereSphere(const Sphere& a, const Sphere& b);

/// Sphere against a shape through the closest point of the shape to the sphere's center.
struct SphereShapeResult {
    bool hit = false;
    /// Point of the shape closest to the sphere's center (meaningful for finite valid inputs,
    /// also when !hit).
    Vec3 closestPoint = Vec3::Zero();
    /// Squared distance from the center to closestPoint (0 when the center is inside the shape).
    double distanceSquared = 0.0;
};

/// Sphere-AABB test (Ericson §5.2.5): hit iff the squared distance from the center to the box
/// is <= radius^2.
SphereShapeResult intersectSphereAabb(const Sphere& sphere, const Aabb& box);

/// Sphere-OBB test (Ericson §5.2.6), same rule in the box's frame.
SphereShapeResult intersectSphereObb(const Sphere& sphere, const Obb& box);

/// Sphere-triangle test (Ericson §5.2.7) through the closest point on the triangle
/// (Ericson §5.1.5). A zero-area triangle is the segment or point it spans.
SphereShapeResult intersectSphereTriangle(const Sphere& sphere, const Triangle& triangle);

}  // namespace cdlab
