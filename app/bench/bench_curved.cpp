#include "app/bench/bench_curved.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/direction_refinement.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab::demos {

namespace {

struct SphereCylinder {
    PointShape centre;  // the sphere's core; its radius is added in closed form, as the query does
    double radius = 0;
    Transformed<CylinderShape> cylinder;
    double distance = 0;  // signed: negative = depth
};

// Signed distance of p to the cylinder (closed form in its frame: side, cap, rim or inside).
double signedDistance(const Vec3& p, const Transformed<CylinderShape>& c) {
    const Vec3 local = c.transform.rotateInverse(p - c.transform.position);
    const double rho = std::hypot(local.x(), local.z()), y = std::abs(local.y());
    const double dr = rho - c.shape.radius, dy = y - c.shape.halfHeight;
    if (dr <= 0 && dy <= 0) return std::max(dr, dy);
    return std::hypot(std::max(dr, 0.0), std::max(dy, 0.0));
}

// Spheres about a random cylinder; `inside`: centres inside it (overlapping cores, EPA's case).
std::vector<SphereCylinder> pairs(int count, bool inside, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> size(0.3, 1.0), u(-1.0, 1.0);
    std::vector<SphereCylinder> out;
    while (int(out.size()) < count) {
        SphereCylinder p;
        p.cylinder.shape = CylinderShape{size(rng), size(rng)};
        p.cylinder.transform.rotation = randomRotation(rng);
        p.radius = 0.5 * size(rng);
        p.centre.point = (inside ? 0.9 : 2.5) * Vec3(u(rng), u(rng), u(rng));
        const double d = signedDistance(p.centre.point, p.cylinder);
        if (inside ? !(d < 0) : !(d > p.radius + 0.05)) continue;
        p.distance = d - p.radius;
        out.push_back(p);
    }
    return out;
}

}  // namespace

void benchCylinders(const Settings& settings, std::vector<Row>& rows) {
    const int n = settings.quick ? 200 : 1000;
    std::cerr << "cdlab bench: sphere against cylinder\n";
    const auto sep = pairs(n, false, 61), pen = pairs(n, true, 62);
    const auto scaleOf = [](const SphereCylinder& p) { return p.centre.point.norm() + p.cylinder.boundingRadius(); };
    const auto separatedError = [&](int i, const Answer& a) { return relativeError(a.value, sep[i].distance, 1.0); };
    const auto depthError = [&](int i, const Answer& a) { return relativeError(a.value, -pen[i].distance, 1.0); };
    rows.push_back(measure(
        settings, "gjk_distance", "sphere-cylinder separated", "SV tol 1e-13, supports only", n,
        [&](int i) {
            const GjkResult r = gjkDistance(sep[i].centre, sep[i].cylinder);
            return Answer{r.distance - sep[i].radius, r.iterations};
        },
        separatedError));
    rows.push_back(measure(
        settings, "gjk_distance", "sphere-cylinder separated", "SV + direction polish (query)", n,
        [&](int i) {
            const GjkResult r = gjkDistance(sep[i].centre, sep[i].cylinder);
            const double gap = (r.upperBound - r.lowerBound) / r.upperBound;  // as the query starts it
            const DirectionRefinement d = refineDirection(sep[i].centre, sep[i].cylinder, r.separatingAxis, scaleOf(sep[i]),
                                                          std::clamp(4 * std::sqrt(std::max(gap, 0.0)), 1e-10, 1e-3));
            return Answer{-d.value - sep[i].radius, r.iterations + d.steps};
        },
        separatedError));
    EpaOptions loose;
    loose.relativeTolerance = 1e-10;  // the query's EPA tolerance on curved cores
    rows.push_back(measure(
        settings, "epa_depth", "sphere in cylinder", "GJK+EPA tol 1e-13, supports only", n,
        [&](int i) {
            const EpaResult r = penetration(pen[i].centre, pen[i].cylinder);
            return Answer{r.depth + pen[i].radius, r.iterations};
        },
        depthError));
    rows.push_back(measure(
        settings, "epa_depth", "sphere in cylinder", "GJK+EPA 1e-10 + polish (query)", n,
        [&](int i) {
            const EpaResult r = penetration(pen[i].centre, pen[i].cylinder, loose);
            const double gap = (r.upperBound - r.lowerBound) / r.upperBound;
            const DirectionRefinement d = refineDirection(pen[i].centre, pen[i].cylinder, r.normal, scaleOf(pen[i]),
                                                          std::clamp(4 * std::sqrt(std::max(gap, 0.0)), 1e-10, 1e-3));
            return Answer{d.value + pen[i].radius, r.iterations + d.steps};
        },
        depthError));
}

}  // namespace cdlab::demos
