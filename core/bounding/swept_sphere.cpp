#include "core/bounding/swept_sphere.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/base/tolerances.h"
#include "core/bounding/bounding_sphere.h"

namespace cdlab {

namespace {

constexpr double kPi = std::numbers::pi;

// Radius pad after the final max-distance pass. The caller's containment test recomputes the
// distance to the stored core in double, with rounding of a few eps times the numbers involved:
// the distance itself (relative) and the coordinates p - core (absolute, eps * |p|_inf, which
// dominates at large offsets). 8 eps of each covers both with a margin.
double padded(double r, double magnitude) { return r * (1.0 + 8.0 * kMachineEpsilon) + 8.0 * kMachineEpsilon * magnitude; }

double magnitudeOf(std::span<const Vec3> points) {
    double m = 0.0;
    for (const Vec3& p : points)
        if (p.allFinite()) m = std::max(m, p.cwiseAbs().maxCoeff());
    return m;
}

// Projections u = A^T (p - ref) of the finite points on the principal box's axes.
std::vector<Vec3> localCoordinates(std::span<const Vec3> points, const Obb& box) {
    std::vector<Vec3> u;
    for (const Vec3& p : points)
        if (p.allFinite()) u.push_back(box.axes.transpose() * (p - box.center));
    return u;
}

// The ends of an interval [lo, hi] on one axis such that a point at coordinate x with slack s
// (the distance it may still be off the core across this axis) satisfies lo - s <= x <= hi + s:
// hi = max(x - s), lo = min(x + s). When lo > hi (a set shorter than 2 s) every point is within
// its slack of any value between them: both ends collapse to the midpoint.
void pullInEnds(double& lo, double& hi) {
    if (lo > hi) lo = hi = 0.5 * (lo + hi);
}

// The covariance box both swept-sphere fits start from (its fit in `cov`), recorded in the trace.
Obb principalBox(std::span<const Vec3> points, ObbFitTrace& cov, SweptSphereFitTrace* trace) {
    const Obb box = fitObbCovariance(points, &cov);
    if (trace) {
        *trace = SweptSphereFitTrace{};
        trace->principalBox = box;
        trace->covariance = cov;
    }
    return box;
}

}  // namespace

Sphere fitPss(std::span<const Vec3> points) { return fitSphereWelzl(points); }

Capsule fitLss(std::span<const Vec3> points, SweptSphereFitTrace* trace) {
    ObbFitTrace cov;
    const Obb box = principalBox(points, cov, trace);
    if (cov.method == ObbFitMethod::Empty) return Capsule{Vec3::Constant(kNaN), Vec3::Constant(kNaN), -1.0};
    const std::vector<Vec3> u = localCoordinates(points, box);
    // Minimum circle of the points projected across the major axis (Welzl on coplanar points).
    std::vector<Vec3> across;
    for (const Vec3& p : u) across.emplace_back(0.0, p.y(), p.z());
    const Sphere circle = fitSphereWelzl(across);
    const double r = std::max(circle.radius, 0.0);
    const double cy = circle.center.y(), cz = circle.center.z();
    // Ends along the axis: t - sqrt(r^2 - d^2) <= t1 and t + sqrt(r^2 - d^2) >= t0.
    double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
    for (const Vec3& p : u) {
        const double d2 = (p.y() - cy) * (p.y() - cy) + (p.z() - cz) * (p.z() - cz);
        const double s = std::sqrt(std::max(r * r - d2, 0.0));
        t1 = std::max(t1, p.x() - s);
        t0 = std::min(t0, p.x() + s);
    }
    pullInEnds(t0, t1);
    Capsule capsule{box.center + box.axes * Vec3(t0, cy, cz), box.center + box.axes * Vec3(t1, cy, cz), 0.0};
    if (trace) trace->coreRadius = r;
    // Final radius: max distance to the stored segment (containment whatever the rounding above).
    double maxD = 0.0;
    for (const Vec3& p : points)
        if (p.allFinite()) maxD = std::max(maxD, coreDistance(capsule, p));
    capsule.radius = padded(maxD, magnitudeOf(points));
    return capsule;
}

Rss fitRss(std::span<const Vec3> points, SweptSphereFitTrace* trace) {
    ObbFitTrace cov;
    const Obb box = principalBox(points, cov, trace);
    if (cov.method == ObbFitMethod::Empty) return Rss{Vec3::Constant(kNaN), Mat3::Identity(), Vec2::Zero(), -1.0};
    const std::vector<Vec3> u = localCoordinates(points, box);
    // Thickness along the minor axis (column 2) gives the radius and the rectangle's plane.
    double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
    for (const Vec3& p : u) {
        zlo = std::min(zlo, p.z());
        zhi = std::max(zhi, p.z());
    }
    const double r = 0.5 * (zhi - zlo), zm = 0.5 * (zlo + zhi);
    // Slack of each point across the plane: it may lie s = sqrt(r^2 - dz^2) off the rectangle.
    std::vector<double> slack;
    for (const Vec3& p : u) slack.push_back(std::sqrt(std::max(r * r - (p.z() - zm) * (p.z() - zm), 0.0)));
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (size_t i = 0; i < u.size(); ++i) {
        x1 = std::max(x1, u[i].x() - slack[i]);
        x0 = std::min(x0, u[i].x() + slack[i]);
        y1 = std::max(y1, u[i].y() - slack[i]);
        y0 = std::min(y0, u[i].y() + slack[i]);
    }
    pullInEnds(x0, x1);
    pullInEnds(y0, y1);
    // A point beyond a corner is off in x AND y: its in-plane distance sqrt(dx^2 + dy^2) must stay
    // within its slack. Push that x end out just enough (dy <= slack holds from the pass above).
    // Growing the rectangle never uncovers another point, so one pass suffices.
    int fixes = 0;
    for (size_t i = 0; i < u.size(); ++i) {
        const double dx = std::max({x0 - u[i].x(), 0.0, u[i].x() - x1});
        const double dy = std::max({y0 - u[i].y(), 0.0, u[i].y() - y1});
        if (dx * dx + dy * dy <= slack[i] * slack[i]) continue;
        const double reach = std::sqrt(std::max(slack[i] * slack[i] - dy * dy, 0.0));
        if (u[i].x() > x1) {
            x1 = u[i].x() - reach;
        } else if (u[i].x() < x0) {
            x0 = u[i].x() + reach;
        } else {
            // Off in y only, by more than its slack: possible by rounding of the slack alone
            // (the pass above guarantees dy <= slack in exact arithmetic). Reach the point in y.
            y1 = std::max(y1, u[i].y());
            y0 = std::min(y0, u[i].y());
        }
        ++fixes;
    }
    Rss rss;
    rss.axes = box.axes;
    rss.center = box.center + box.axes * Vec3(0.5 * (x0 + x1), 0.5 * (y0 + y1), zm);
    rss.halfLengths = Vec2(0.5 * (x1 - x0), 0.5 * (y1 - y0));
    if (trace) {
        trace->coreRadius = r;
        trace->cornerFixes = fixes;
    }
    double maxD = 0.0;
    for (const Vec3& p : points)
        if (p.allFinite()) maxD = std::max(maxD, coreDistance(rss, p));
    rss.radius = padded(maxD, magnitudeOf(points));
    return rss;
}

double volume(const Capsule& capsule) {
    const double r = capsule.radius;
    if (std::isnan(r)) return kNaN;
    if (r < 0.0) return 0.0;
    return kPi * r * r * (capsule.b - capsule.a).norm() + 4.0 / 3.0 * kPi * r * r * r;
}

double volume(const Rss& rss) {
    const double r = rss.radius, a = rss.halfLengths.x(), b = rss.halfLengths.y();
    if (std::isnan(r)) return kNaN;
    if (r < 0.0) return 0.0;
    return 8.0 * a * b * r + 2.0 * kPi * r * r * (a + b) + 4.0 / 3.0 * kPi * r * r * r;
}

double coreDistance(const Capsule& capsule, const Vec3& p) {
    // Clamped projection in plain double (Ericson §5.1.2): the containment test a caller would
    // write. closestPointOnSegment's exact region signs are not needed for a distance and cost
    // ~1 us per call, which dominated fitLss on large inputs.
    const Vec3 ab = capsule.b - capsule.a, ap = p - capsule.a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (ap - t * ab).norm();
}

double coreDistance(const Rss& rss, const Vec3& p) {
    const Vec3 local = rss.axes.transpose() * (p - rss.center);
    const double dx = std::max(std::abs(local.x()) - rss.halfLengths.x(), 0.0);
    const double dy = std::max(std::abs(local.y()) - rss.halfLengths.y(), 0.0);
    return std::sqrt(dx * dx + dy * dy + local.z() * local.z());
}

}  // namespace cdlab
