#include "core/base/orient.h"

#include <cmath>

#include "core/base/exact_predicates.h"
#include "core/base/tolerances.h"

namespace cdlab {

namespace {

// A-priori relative error bounds of the plain double evaluation (Shewchuk 1997, §4.3,
// ccwerrboundA and o3derrboundA) with his epsilon, the unit roundoff 2^-53:
// |det_computed - det_exact| <= bound * permanent.
constexpr double kEps = kUnitRoundoff;
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;

// det[u1 - v1; u2 - v2; u3 - v3] = (u1 - v1) · ((u2 - v2) × (u3 - v3)) in number type T, the
// differences taken in T (exact in Expansion and BigDyadic).
template <class T>
T det3OfDifferences(const Vec3* u, const Vec3* v) {
    T d[3][3];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) d[r][k] = T(u[r][k]) - T(v[r][k]);
    return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) + d[0][1] * (d[1][2] * d[2][0] - d[1][0] * d[2][2]) +
           d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

}  // namespace

int signDet3(const Vec3& u1, const Vec3& v1, const Vec3& u2, const Vec3& v2, const Vec3& u3, const Vec3& v3) {
    // Filter: Shewchuk's orient3d evaluation order, expanded along the z column.
    const Vec3 a = u1 - v1, b = u2 - v2, c = u3 - v3;
    const double bxcy = b.x() * c.y(), cxby = c.x() * b.y();
    const double cxay = c.x() * a.y(), axcy = a.x() * c.y();
    const double axby = a.x() * b.y(), bxay = b.x() * a.y();
    const double det = a.z() * (bxcy - cxby) + b.z() * (cxay - axcy) + c.z() * (axby - bxay);
    const double permanent = (std::abs(bxcy) + std::abs(cxby)) * std::abs(a.z()) +
                             (std::abs(cxay) + std::abs(axcy)) * std::abs(b.z()) +
                             (std::abs(axby) + std::abs(bxay)) * std::abs(c.z());
    // Comparison order matters: a NaN det or permanent fails both tests and falls through.
    const double bound = kOrient3dBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    const Vec3 u[3] = {u1, u2, u3}, v[3] = {v1, v2, v3};
    // An overflow of the products (coordinates beyond ~1e100) is no answer: finite inputs go to the
    // exact evaluation, which has no exponent limit; only non-finite inputs give 0.
    if (!std::isfinite(det) || !std::isfinite(permanent)) {
        for (int r = 0; r < 3; ++r)
            if (!u[r].allFinite() || !v[r].allFinite()) return 0;
    } else if (permanent == 0.0) {
        return 0;  // every product is zero: the determinant is exactly 0
    }
    // Exact: the one expansion kit of core/base/exact_predicates.h (BigDyadic beyond its range).
    return exact::exactSign([&](auto zero) { return det3OfDifferences<decltype(zero)>(u, v); });
}

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return signDet3(b, a, c, a, d, a); }

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
    const double left = (b.x() - a.x()) * (c.y() - a.y());
    const double right = (b.y() - a.y()) * (c.x() - a.x());
    const double det = left - right;
    const double detSum = std::abs(left) + std::abs(right);
    const double bound = kOrient2dBound * detSum;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    if (!std::isfinite(det) || !std::isfinite(detSum)) {
        if (!a.allFinite() || !b.allFinite() || !c.allFinite()) return 0;  // else exact, below
    } else if (detSum == 0.0) {
        return 0;
    }
    return exact::exactSign([&](auto zero) {
        using T = decltype(zero);
        return (T(b.x()) - T(a.x())) * (T(c.y()) - T(a.y())) - (T(b.y()) - T(a.y())) * (T(c.x()) - T(a.x()));
    });
}

int dominantAxis(const Vec3& n) {
    const Vec3 m = n.cwiseAbs();
    if (m.x() >= m.y() && m.x() >= m.z()) return 0;
    return m.y() >= m.z() ? 1 : 2;
}

Vec2 dropAxis(const Vec3& p, int axis) { return Vec2(p[(axis + 1) % 3], p[(axis + 2) % 3]); }

int projectionAxis(const Triangle& t) {
    const int first = dominantAxis((t.b - t.a).cross(t.c - t.a));
    for (int k = 0; k < 3; ++k) {
        const int axis = (first + k) % 3;
        if (orient2d(dropAxis(t.a, axis), dropAxis(t.b, axis), dropAxis(t.c, axis)) != 0) return axis;
    }
    return -1;
}

}  // namespace cdlab
