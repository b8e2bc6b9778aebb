// Earliest time of impact of a point moving at constant velocity against a sphere, a capsule
// (segment with radius r >= 0) and a triangle (Ericson, Real-Time Collision Detection §5.5:
// a moving point against a static shape is a segment (ray) test parameterized by time;
// §5.3.2 segment-sphere, §5.3.7 segment-cylinder, §5.3.6 segment-triangle).
//
// World frame, any consistent units (t in the same time unit as velocity). Shapes are closed:
// the first time the point touches the shape counts. A point that starts inside (or on) the
// shape hits at t = tBegin. Degenerate input (NaN / inf, tBegin > tEnd, negative radius,
// zero-area triangle) gives hit == false; a zero velocity is allowed (a static point).
#pragma once

#include "core/base/primitives.h"

namespace cdlab {

/// A point moving at constant velocity: position + t * velocity for t in [tBegin, tEnd].
struct MovingPoint {
    Vec3 position;  ///< position at t = 0
    Vec3 velocity;
    double tBegin = 0.0;
    double tEnd = 1.0;

    Vec3 at(double t) const { return position + t * velocity; }
};

/// Earliest contact of a moving point with a shape.
struct MovingPointHit {
    bool hit = false;
    /// Time of impact in [tBegin, tEnd] (tBegin when the point starts inside).
    double t = 0.0;
    /// Position of the point at t (on the shape's surface unless it started inside).
    Vec3 point = Vec3::Zero();
    /// Unit outward surface normal of the shape at point; zero when the point started inside
    /// or the normal is undefined (radius 0: the contact is with a point or a segment).
    Vec3 normal = Vec3::Zero();
};

/// Moving point against a solid sphere (Ericson §5.3.2 on the path segment).
MovingPointHit intersectMovingPointSphere(const MovingPoint& point, const Sphere& sphere);

/// Moving point against a capsule (Ericson §5.3.7 cylinder side + the two end spheres). With
/// radius 0 the capsule is the segment itself and only an exact crossing counts (decided by
/// exact orientation predicates on the path's end points).
MovingPointHit intersectMovingPointCapsule(const MovingPoint& point, const Capsule& capsule);

/// Moving point against a triangle (Ericson §5.3.6, both faces; exact decision, see
/// intersectSegmentTriangle). normal faces the side the point comes from (zero if it moves
/// within the triangle's plane).
MovingPointHit intersectMovingPointTriangle(const MovingPoint& point, const Triangle& triangle);

}  // namespace cdlab
