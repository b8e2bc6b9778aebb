#include "core/query/touch.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

double touchTolerance(const QueryShape& a, const QueryShape& b) {
    return kTouchRelative * (minkowskiExtent(boundingPoints(a), boundingPoints(b)) + a.radius + b.radius);
}

double planeTouchTolerance(double unitOffset, double magnitude) {
    return kTouchRelative * (magnitude + std::abs(unitOffset));
}

double largestCoordinate(const QueryShape& s) {
    double m = 0.0;
    for (const Vec3& v : boundingPoints(s)) m = std::max(m, v.cwiseAbs().maxCoeff());
    return m;
}

UnitPlane unitPlane(const QueryShape& plane) {
    const double m = plane.normal.norm();
    return {plane.normal / m, plane.offset / m};
}

PlaneSpan planeSpan(const QueryShape& plane, const QueryShape& s) {
    const auto [n, d] = unitPlane(plane);
    PlaneSpan span{INFINITY, -INFINITY, Vec3::Zero(), Vec3::Zero(),
                   planeTouchTolerance(d, largestCoordinate(s) + s.radius)};
    if (s.isCurved()) {  // the support points along ∓n, in closed form
        span.lowPoint = s.curved.support(-n);
        span.highPoint = s.curved.support(n);
        span.lo = n.dot(span.lowPoint) - d;
        span.hi = n.dot(span.highPoint) - d;
    }
    for (const Vec3& v : s.vertices) {
        double x = n.dot(v) - d;
        if (x < span.lo) span.lo = x, span.lowPoint = v;
        if (x > span.hi) span.hi = x, span.highPoint = v;
    }
    span.lo -= s.radius;
    span.hi += s.radius;
    span.lowPoint -= s.radius * n;
    span.highPoint += s.radius * n;
    return span;
}

}  // namespace cdlab
