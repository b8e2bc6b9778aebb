// Accurate closest points of two segments (an edge of A and an edge of B), for the final
// simplex of GJK and the final face of EPA.
//
// Why: when the closest features are two nearly parallel edges, the Minkowski-difference
// triangle GJK ends on is a sliver of width ~angle x length, and its normal, computed from the
// rounded differences a_i - b_j, is off by ~u / angle. GJK's distance then errs by ~u L / angle
// (5e-9 L at 1e-8 rad: `cdlab stress`, family "nearly parallel edges"), although the distance
// itself is well conditioned (it is 1-Lipschitz in the inputs). Here the edge directions and
// their cross product are formed in double-double arithmetic from the original end points, so
// the distance comes out with a relative error of a few u whatever the angle.
//
// Segment-segment distance as a convex minimisation over [0,1]^2 (Ericson, Real-Time Collision
// Detection §5.1.9): the minimum is either the lines' common perpendicular, when its foot
// parameters lie in [0,1] on both segments, or on the boundary, i.e. an end point against the
// other segment.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// Closest points of segments [a0, a1] (of A) and [b0, b1] (of B), world frame.
struct EdgePairDistance {
    bool ok = false;             ///< false: non-finite input (every other field is then unset)
    double distance = 0.0;       ///< >= 0, world units
    Vec3 pointA = Vec3::Zero();  ///< closest point on [a0, a1]
    Vec3 pointB = Vec3::Zero();  ///< closest point on [b0, b1]
    Vec3 axis = Vec3::Zero();    ///< unit, from pointA toward pointB; zero when distance == 0
    bool interior = false;       ///< the closest points are the lines' common perpendicular
};

/// Accurate segment-segment distance (see the file comment). Zero-length segments are points.
EdgePairDistance edgePairDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

/// Closest points of point p (of A) and triangle [t0, t1, t2] (of B) in the same arithmetic: the
/// face case from the triangle normal formed in double-double (a sliver's normal is then
/// exact to a few u), otherwise the nearest edge. Result fields as for edgePairDistance, with
/// pointA = p. For a triangle of A and a point of B, swap the roles and negate the axis.
EdgePairDistance pointTriangleDistance(const Vec3& p, const Vec3& t0, const Vec3& t1, const Vec3& t2);

/// The lines through [a0, a1] and [b0, b1] and their common perpendicular: for EPA, whose final
/// face spans an edge of A and an edge of B (edge-edge penetration).
struct LinePairSeparation {
    bool ok = false;             ///< false: parallel (or zero-length) edges, or non-finite input
    double separation = 0.0;     ///< (pointB - pointA) . normal, world units (signed)
    Vec3 normal = Vec3::Zero();  ///< unit, along (a1 - a0) x (b1 - b0)
    Vec3 pointA = Vec3::Zero();  ///< foot on line A: a0 + s (a1 - a0)
    Vec3 pointB = Vec3::Zero();  ///< foot on line B: b0 + t (b1 - b0)
    double s = 0.0;              ///< in [0, 1] when the foot lies on the segment
    double t = 0.0;
};

/// Common perpendicular of two lines, in double-double arithmetic (see the file comment).
LinePairSeparation linePairSeparation(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

}  // namespace cdlab
