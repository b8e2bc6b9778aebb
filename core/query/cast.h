// Casts on the query's shapes (core/query/shape.h): a ray against a shape (`cdlab query`'s
// "raycast") and two shapes translating over t in [0, 1] ("time_of_impact"). Each works on the
// input scaled by a power of two (exact) and answers in the input's units:
//   ray: against a plane in closed form (a two-sided surface), a cylinder or cone in its own frame
//        (core/cast/ray_cast_curved.h), any rounded hull (core/cast/ray_cast.h);
//   time of impact: a plane by the span of the other shape's signed distances, two rounded hulls by
//        the ray cast against their Minkowski difference (core/cast/time_of_impact.h), a cylinder or
//        cone by conservative advancement on the pair query's distance.
// Tests: tests/app/query/*cast*_test.cpp and the time-of-impact oracles of tests/core/cast.
#pragma once

#include <cstddef>
#include <vector>

#include "core/cast/ray_cast.h"
#include "core/cast/time_of_impact.h"
#include "core/query/pair.h"
#include "core/query/shape.h"

namespace cdlab {

/// What a ray cast ran, for its trace (lengths in the scaled problem; see tExponent / lengthExponent).
struct RayCastQueryTrace {
    enum class Algorithm { RayPlane, RayCylinder, RayCone, RayCast };
    Algorithm algorithm = Algorithm::RayCast;
    double signedDistance = 0.0, slope = 0.0;  ///< RayPlane: the origin's signed distance and its rate
    ConvexCastTrace cast;                      ///< RayCast: the rounded hull's candidates
    int tExponent = 0;                         ///< the input's t = 2^tExponent · a trace t
    int lengthExponent = 0;                    ///< the input's lengths = 2^lengthExponent · a trace length
};

struct RayCastQueryResult {
    PairStatus status = PairStatus::Ok;  ///< Overflow: t or the hit point overflows double precision
    bool hit = false, inside = false;    ///< inside: the origin is in the shape (t 0, point the origin)
    double t = 0.0;
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();  ///< normal: unit, toward the side the ray comes from
};

/// The first t in [0, maxT] at which origin + t · direction (direction non-zero) meets the shape
/// (not a ray). trace: optional.
RayCastQueryResult rayCastQuery(const Vec3& origin, const Vec3& direction, QueryShape shape, double maxT,
                                RayCastQueryTrace* trace = nullptr);

/// What a time-of-impact query ran, for its trace.
struct ImpactQueryTrace {
    enum class Algorithm { PlaneSpan, ConservativeAdvancement, RayCast };
    Algorithm algorithm = Algorithm::RayCast;
    double low = 0.0, high = 0.0, rate = 0.0;  ///< PlaneSpan: the shape's signed-distance span and its rate
    struct Step {
        double t, distance;  ///< ConservativeAdvancement: the distance at t (input units; 0 when touching)
    };
    std::vector<Step> steps;
    /// RayCast: the cast against A − B; a candidate's index i·|b| + j names b's vertex j minus a's i
    /// (the input's vertex indices).
    ConvexCastTrace cast;
    int pairedWith = 0;        ///< |b|, the input's vertex count of b
    int lengthExponent = 0;    ///< the input's lengths = 2^lengthExponent · a trace length
    int tExponent = 0;         ///< RayCast: the input's t = 2^tExponent · a trace t
};

struct ImpactQueryOptions {
    /// Points of the Minkowski difference of two hulls (hull vertices of a × of b) a query may build.
    std::size_t maxDifferencePoints = 100000;
};

struct ImpactQueryResult {
    /// WorkLimit: hullA × hullB is over maxDifferencePoints; Overflow: the points overflow; a pair
    /// query's failure during conservative advancement passes through.
    PairStatus status = PairStatus::Ok;
    bool pairFailed = false;                 ///< status is a pair query's (conservative advancement)
    TimeOfImpactResult result;               ///< t, normal (from a toward b), points: input units
    std::size_t hullA = 0, hullB = 0;        ///< the hulls' vertex counts (WorkLimit)
};

/// The first t in [0, 1] at which a moved by t · motionA and b by t · motionB touch (not both planes,
/// no ray). trace: optional.
ImpactQueryResult timeOfImpactQuery(QueryShape a, const Vec3& motionA, QueryShape b, const Vec3& motionB,
                                    const ImpactQueryOptions& options = {}, ImpactQueryTrace* trace = nullptr);

}  // namespace cdlab
