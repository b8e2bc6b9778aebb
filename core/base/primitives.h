// World-frame primitive shapes for the intersection tests (Ericson, Real-Time Collision
// Detection, ch. 4-5). Segment, Triangle and Plane live in core/base/types.h.
//
// Every shape is a CLOSED set: its boundary belongs to it, so touching counts as intersecting
// in every test built on these types.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// Ray: the points origin + t * direction for t >= 0. direction need not be unit; every t
/// reported for a ray is in units of |direction|. A zero (or non-finite) direction is not a
/// ray: tests report no hit for it.
struct Ray {
    Vec3 origin;
    Vec3 direction;

    Vec3 at(double t) const { return origin + t * direction; }
};

/// Axis-aligned box [min.x, max.x] x [min.y, max.y] x [min.z, max.z]. min == max on an axis is
/// a flat box (allowed); min > max on any axis is empty (tests report no hit).
struct Aabb {
    Vec3 min;
    Vec3 max;
};

/// Oriented box: the points center + axes * u with |u_i| <= halfExtents_i. The columns of axes
/// are the box's unit, mutually orthogonal axes in world frame (a rotation matrix).
struct Obb {
    Vec3 center;
    Vec3 halfExtents;
    Mat3 axes = Mat3::Identity();

    /// Box whose axes are the columns of rotation (a unit quaternion).
    static Obb fromRotation(const Vec3& center, const Vec3& halfExtents, const Quat& rotation) {
        return Obb{center, halfExtents, rotation.toRotationMatrix()};
    }
};

/// Solid ball of points within radius of center. radius == 0 is a point; radius < 0 is empty.
struct Sphere {
    Vec3 center;
    double radius = 0.0;
};

/// Capsule: the points within radius of segment ab (a == b gives a sphere, radius == 0 the
/// segment itself).
struct Capsule {
    Vec3 a;
    Vec3 b;
    double radius = 0.0;
};

}  // namespace cdlab
