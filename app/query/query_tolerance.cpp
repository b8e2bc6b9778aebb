#include "app/query/query_tolerance.h"

#include <algorithm>
#include <cmath>

#include "app/query/query_shapes.h"

namespace cdlab::demos {

double minkowskiExtent(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.empty() || b.empty()) return 0.0;
    Vec3 loA = a.front(), hiA = a.front(), loB = b.front(), hiB = b.front();
    for (const Vec3& v : a) loA = loA.cwiseMin(v), hiA = hiA.cwiseMax(v);
    for (const Vec3& v : b) loB = loB.cwiseMin(v), hiB = hiB.cwiseMax(v);
    return std::max((hiA - loB).cwiseAbs().maxCoeff(), (loA - hiB).cwiseAbs().maxCoeff());
}

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

}  // namespace cdlab::demos
