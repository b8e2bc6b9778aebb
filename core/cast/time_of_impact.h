// Time of impact of two translating convex shapes, A = conv(PA) ⊕ ball(rA) moving by motionA and
// B = conv(PB) ⊕ ball(rB) moving by motionB over t in [0, 1] (at time t, A is at its pose +
// t·motionA).
//
// A(t) and B(t) touch when some b − a, a in A, b in B, equals t·(motionA − motionB): the first
// contact is the ray cast from the origin along motionA − motionB against the Minkowski difference
// B − A = conv{pb − pa} ⊕ ball(rA + rB), clipped at t = 1 (van den Bergen, "Ray Casting against
// General Convex Objects with Application to Continuous Collision Detection", 2004, §4; Ericson
// §5.5.8 for moving spheres, its special case). The cast's outward normal of B − A points from B
// toward A, so the contact normal from A toward B is its opposite; the cast's feature, a face, edge
// or vertex of B − A, names pairs (pa, pb) and gives the touching points on each shape.
#pragma once

#include <span>

#include "core/base/types.h"
#include "core/cast/ray_cast.h"

namespace cdlab {

struct TimeOfImpactOptions {
    /// Distances at or below this count as touching (the ray cast's option, and the t = 0 test).
    double touchTolerance = 0.0;
    /// The end of the time interval [0, maxT] (1 for the motions as given; a caller that scales the
    /// motions down by 2^j to keep them next to the shapes' size casts up to 2^j).
    double maxT = 1.0;
};

struct TimeOfImpactResult {
    bool hit = false;
    bool initiallyOverlapping = false;  ///< touching or overlapping at t = 0 (then no normal or points)
    double t = 0.0;
    Vec3 normal = Vec3::Zero();  ///< unit, from A toward B at the first contact
    Vec3 pointA = Vec3::Zero();  ///< the touching points at time t (equal up to rounding)
    Vec3 pointB = Vec3::Zero();
};

/// First contact in [0, maxT] (maxT = 1 by default); see above. The Minkowski difference has |PA|·|PB| points: callers
/// reduce PA and PB to their hull vertices first when they may be large.
TimeOfImpactResult translationalTimeOfImpact(std::span<const Vec3> pointsA, double radiusA, const Vec3& motionA,
                                             std::span<const Vec3> pointsB, double radiusB, const Vec3& motionB,
                                             const TimeOfImpactOptions& options = {},
                                             ConvexCastTrace* trace = nullptr);

}  // namespace cdlab
