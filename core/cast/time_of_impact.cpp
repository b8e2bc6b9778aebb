#include "core/cast/time_of_impact.h"

#include <algorithm>
#include <vector>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

namespace {

std::vector<Vec3> moved(std::span<const Vec3> points, const Vec3& by) {
    std::vector<Vec3> out;
    out.reserve(points.size());
    for (const Vec3& v : points) out.push_back(v + by);
    return out;
}

}  // namespace

TimeOfImpactResult translationalTimeOfImpact(std::span<const Vec3> pointsA, double radiusA, const Vec3& motionA,
                                             std::span<const Vec3> pointsB, double radiusB, const Vec3& motionB,
                                             const TimeOfImpactOptions& options, ConvexCastTrace* trace) {
    TimeOfImpactResult out;
    if (pointsA.empty() || pointsB.empty() || !allFinite(pointsA) || !allFinite(pointsB) || !motionA.allFinite() ||
        !motionB.allFinite() || !(radiusA >= 0) || !(radiusB >= 0))
        return out;
    const double radii = radiusA + radiusB;
    const PolytopeShape coreA(std::vector<Vec3>(pointsA.begin(), pointsA.end()));
    const PolytopeShape coreB(std::vector<Vec3>(pointsB.begin(), pointsB.end()));
    const GjkResult start = gjkDistance(coreA, coreB);
    if (start.status == GjkStatus::InvalidInput) return out;
    if (start.distance <= radii + options.touchTolerance) {
        out.hit = out.initiallyOverlapping = true;
        return out;
    }

    // The cast of the origin along motionA − motionB against B − A, up to t = maxT.
    const Vec3 motion = motionA - motionB;
    if (motion.isZero(0.0)) return out;
    const std::size_t nB = pointsB.size();
    std::vector<Vec3> difference;
    difference.reserve(pointsA.size() * nB);
    for (const Vec3& a : pointsA)
        for (const Vec3& b : pointsB) difference.push_back(b - a);
    ConvexCastOptions cast;
    cast.maxT = options.maxT;
    cast.touchTolerance = options.touchTolerance;
    const ConvexCastHit h = castRayRoundedHull(Ray{Vec3::Zero(), motion}, difference, radii, cast, trace);
    if (!h.hit) return out;
    out.hit = true;
    if (h.inside) {
        // The cast's origin test and the t = 0 test above disagree by rounding: contact at t = 0.
        out.normal = start.separatingAxis;
        out.pointA = start.pointA + radiusA * out.normal;
        out.pointB = start.pointB - radiusB * out.normal;
        return out;
    }
    out.t = h.t;
    out.normal = -h.normal;  // the cast's normal points out of B − A, from B toward A
    if (h.count > 0) {
        // Difference point k is pointsB[k % nB] − pointsA[k / nB]: the same weights on both shapes.
        Vec3 a = Vec3::Zero(), b = Vec3::Zero();
        for (int i = 0; i < h.count; ++i) {
            a += h.weight[i] * pointsA[std::size_t(h.index[i]) / nB];
            b += h.weight[i] * pointsB[std::size_t(h.index[i]) % nB];
        }
        out.pointA = a + out.t * motionA + radiusA * out.normal;
        out.pointB = b + out.t * motionB - radiusB * out.normal;
        return out;
    }
    // A graze the cast found by its verdict only: the touching points from GJK at time t.
    const GjkResult g = gjkDistance(PolytopeShape(moved(pointsA, out.t * motionA)),
                                    PolytopeShape(moved(pointsB, out.t * motionB)));
    out.pointA = g.pointA + radiusA * out.normal;
    out.pointB = g.pointB - radiusB * out.normal;
    return out;
}

}  // namespace cdlab
