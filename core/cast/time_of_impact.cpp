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

/// The first t in [0, tHit] at which the cores, moved along the path, come within `band` (radii +
/// the touching tolerance): Newton on the distance d(t) of A + t·mA and B + t·mB, convex in t, from
/// t = 0 where d > band. On a convex decreasing function the Newton step (d − band) / (n·m) from the
/// left of the root never passes it, so every iterate stays at or before the first contact; it
/// stops when d is within the band (or 8 roundings of the coordinates) or the step stops moving t;
/// a step that lands where GJK finds the cores touching (past the root by rounding), or that reaches
/// the cast's tHit, is bisected for the first touching t. atStart: GJK on the unmoved cores (the caller's t = 0 test). Returns tHit when it does
/// not converge in kSteps (a path that creeps along a curved face) or the distance stops
/// decreasing. Test: tests/core/cast/time_of_impact_scale_test.cpp (a path inside a facet plane of
/// B − A within rounding; cdlab stress "time of impact, sliding paths").
double firstTouchAlongPath(const PolytopeShape& coreA, const Vec3& motionA, const PolytopeShape& coreB,
                           const Vec3& motionB, double band, double tHit, const GjkResult& atStart, GjkResult& at) {
    double lastApart = 0.0;  // the last iterate at which GJK found the cores apart
    constexpr int kSteps = 64;
    const Vec3 m = motionA - motionB;
    const auto& pa = coreA.vertices();
    const auto& pb = coreB.vertices();
    const auto movedMagnitude = [&](double s) {
        double M = 0.0;
        for (const Vec3& v : pa) M = std::max(M, (v + s * motionA).cwiseAbs().maxCoeff());
        for (const Vec3& v : pb) M = std::max(M, (v + s * motionB).cwiseAbs().maxCoeff());
        return M;
    };
    const auto distanceAt = [&](double s) {
        return gjkDistance(PolytopeShape(moved(pa, s * motionA)), PolytopeShape(moved(pb, s * motionB)));
    };
    // Within the band plus 8 roundings of the moved coordinates counts as touching: a path sliding
    // along a facet keeps its distance at that level (4e-14 against a 1.8e-14 band, coordinates
    // ~100) while d' is ~1e-12, where further steps would creep along the facet (cdlab stress,
    // 600 s, #26565).
    const auto touching = [&](const GjkResult& g, double s) {
        return g.status != GjkStatus::Separated ||
               g.distance - band <= std::max(band, 8.0 * std::ldexp(movedMagnitude(s), -53));
    };
    // The first t in (lo, hi] touching, lo apart and hi touching (or the cast's hit): bisection;
    // `at` stays the last one apart.
    const auto bisect = [&](double lo, double hi) {
        for (int i = 0; i < 60 && lo < hi; ++i) {
            const double mid = 0.5 * (lo + hi);
            if (!(mid > lo && mid < hi)) break;
            const GjkResult gm = distanceAt(mid);
            if (touching(gm, mid)) hi = mid;
            else lo = mid, at = gm;
        }
        return lo;
    };
    double t = 0.0;
    for (int k = 0; k < kSteps; ++k) {
        const GjkResult g = k == 0 ? atStart : distanceAt(t);  // t = 0: the caller's start test
        if (g.status != GjkStatus::Separated) {
            // A step that landed on the root within rounding (a path sliding in a facet plane meets
            // the facet exactly there): bisect back between the last iterate, apart, and this one.
            return k == 0 ? tHit : bisect(lastApart, t);
        }
        at = g;
        lastApart = t;
        if (touching(g, t)) return t;
        const double rate = at.separatingAxis.dot(m);  // d'(t) = −n·m, n from A toward B
        if (!(rate > 0.0)) return tHit;
        const double next = t + (at.distance - band) / rate;
        if (!(next > t)) return t;
        // The step reaches the cast's hit: the root lies within the step's rounding of it. On a path
        // grazing a facet at 3e-10 rad the distance's last 1 % (its rounding) is 2e-4 of the path,
        // and the cast's crossing of the rounded facet came 2.8e-8 after the exact one (stress
        // "time of impact, sliding paths" #38204): the first touching t before it, by bisection.
        if (!(next < tHit)) return bisect(t, tHit);
        t = next;
    }
    return tHit;
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
    // A path that slides within rounding of a facet of B − A crosses the rounded facet up to
    // u·|B − A| / angle later than the exact one: the contact is the first t within the touching
    // band, found along the path when it lies more than 1e3 bands of travel before the cast's t.
    const double band = radii + options.touchTolerance;
    if (band > 0) {
        GjkResult g;
        const double t = firstTouchAlongPath(coreA, motionA, coreB, motionB, band, h.t, start, g);
        if ((h.t - t) * motion.norm() > 1e3 * band && g.status == GjkStatus::Separated) {
            out.t = t;
            out.normal = g.separatingAxis;
            out.pointA = g.pointA + radiusA * out.normal;
            out.pointB = g.pointB - radiusB * out.normal;
            return out;
        }
    }
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
