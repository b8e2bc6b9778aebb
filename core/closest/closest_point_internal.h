// Shared by closest_point.cpp (segments, triangles) and closest_point_tetrahedron.cpp: the closest
// point inside a known edge or face region, plain in double or exact in BigDyadic arithmetic.
// Internal to core/closest (not part of the public closest_point.h).
#pragma once

#include <algorithm>
#include <array>

#include "core/base/exact_predicates.h"
#include "core/base/types.h"

namespace cdlab::closest_internal {

using exact::BigDyadic;

// The plain double formulas below (degree <= 4 in the coordinates) neither overflow nor lose
// precision to underflow when every coordinate they read is 0 or of magnitude in [2^-200, 2^241)
// (exact::inExpansionRange): every nonzero difference is then a multiple of 2^-252, and every
// nonzero product of up to four of them lies in [2^-1008, 2^973] (as for the expansions,
// core/base/exact_predicates.h). Outside that range the points are computed exactly in BigDyadic
// arithmetic and rounded once.

using BigVec = std::array<BigDyadic, 3>;
inline BigVec big(const Vec3& v) { return {BigDyadic(v.x()), BigDyadic(v.y()), BigDyadic(v.z())}; }
inline BigVec operator-(const BigVec& a, const BigVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline BigDyadic dot(const BigVec& a, const BigVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline BigVec cross(const BigVec& a, const BigVec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// numerator_i / denominator rounded (exact::quotient: within one ulp), kept inside [lo_i, hi_i]:
// the exact quotient lies there, so this only undoes rounding past a bound (or past DBL_MAX).
inline Vec3 roundedPoint(const BigVec& numerator, const BigDyadic& denominator, const Vec3& lo, const Vec3& hi) {
    Vec3 point;
    for (int i = 0; i < 3; ++i) point[i] = std::clamp(exact::quotient(numerator[i], denominator), lo[i], hi[i]);
    return point;
}

// Closest point of the segment xy to p when it is known (exactly) to lie inside the closed
// segment, with the weights of y (s) and x (r): point = r x + s y. In the plain range the
// projection is taken from the nearer endpoint, so the point's error is relative to that
// endpoint's distance, not to |x|, and r = 1 - s; outside it, exactly (exactEdgePoint).
struct EdgePoint {
    Vec3 point;
    double s;
    double r;
};

// With u = y - x and w = p - x: s = (u.w)/(u.u), point_i = (x_i (u.u) + u_i (u.w)) / (u.u) and
// r = (u.u - u.w)/(u.u), each an exact rational rounded once: every coordinate and weight within
// one ulp of the exact one (exact::quotient).
[[gnu::noinline, gnu::cold]] inline EdgePoint exactEdgePoint(const Vec3& p, const Vec3& x, const Vec3& y) {
    const BigVec bx = big(x), u = big(y) - bx, w = big(p) - bx;
    const BigDyadic uu = dot(u, u), uw = dot(u, w);
    if (uu.sign() == 0) return {x, 0.0, 1.0};  // x == y: not an edge interior; never NaN
    BigVec numerator;
    for (int i = 0; i < 3; ++i) numerator[i] = bx[i] * uu + u[i] * uw;
    return {roundedPoint(numerator, uu, x.cwiseMin(y), x.cwiseMax(y)), std::clamp(exact::quotient(uw, uu), 0.0, 1.0),
            std::clamp(exact::quotient(uu - uw, uu), 0.0, 1.0)};
}

inline EdgePoint edgeInterior(const Vec3& p, const Vec3& x, const Vec3& y, bool plain) {
    if (!plain) return exactEdgePoint(p, x, y);
    const Vec3 xy = y - x;
    const double length2 = xy.squaredNorm();
    if (!(length2 > 0.0)) return {x, 0.0, 1.0};     // x == y (never for an edge region): never NaN
    const double fromX = xy.dot(p - x) / length2;   // weight of y
    const double fromY = -xy.dot(p - y) / length2;  // weight of x
    if (fromX <= fromY) {
        const double s = std::clamp(fromX, 0.0, 1.0);
        return {x + s * xy, s, 1.0 - s};
    }
    const double r = std::clamp(fromY, 0.0, 1.0);
    return {y - r * xy, 1.0 - r, r};
}

// Closest point of the plane of (x, y, z) to p, known (exactly) to lie in the closed triangle,
// with barycentric weights. In the plain range the projection is taken from the vertex nearest
// to p; the weights are the signed sub-areas n·((y-p)×(z-p)) etc. (equal to Ericson's va, vb,
// vc, but without the cancellation of d1*d4 - d3*d2), clamped at 0 against rounding and
// normalised. Outside it, exactly (exactFacePoint).
struct FacePoint {
    Vec3 point;
    Vec3 weights;
};

// With n = (y-x)×(z-x) and w = p - x: point_i = (p_i (n.n) - n_i (n.w)) / (n.n), weights
// n·((y-p)×(z-p)) / (n.n) etc. (they sum to 1 exactly), each an exact rational rounded once.
[[gnu::noinline, gnu::cold]] inline FacePoint exactFacePoint(const Vec3& p, const Vec3& x, const Vec3& y, const Vec3& z) {
    const BigVec bp = big(p), bx = big(x), by = big(y), bz = big(z);
    const BigVec n = cross(by - bx, bz - bx);
    const BigDyadic nn = dot(n, n);
    if (nn.sign() == 0) return {x, Vec3(1, 0, 0)};  // collinear (never for a face region): never NaN
    const BigDyadic height = dot(n, bp - bx);
    BigVec numerator;
    for (int i = 0; i < 3; ++i) numerator[i] = bp[i] * nn - n[i] * height;
    const BigVec px = bx - bp, py = by - bp, pz = bz - bp;
    const Vec3 weights(exact::quotient(dot(n, cross(py, pz)), nn), exact::quotient(dot(n, cross(pz, px)), nn),
                       exact::quotient(dot(n, cross(px, py)), nn));
    return {roundedPoint(numerator, nn, x.cwiseMin(y).cwiseMin(z), x.cwiseMax(y).cwiseMax(z)),
            weights.cwiseMax(0.0).cwiseMin(1.0)};
}

inline FacePoint faceInterior(const Vec3& p, const Vec3& x, const Vec3& y, const Vec3& z, bool plain) {
    if (!plain) return exactFacePoint(p, x, y, z);
    const Vec3 n = (y - x).cross(z - x);
    const double n2 = n.squaredNorm();
    const Vec3 px = x - p, py = y - p, pz = z - p;
    Vec3 weights(std::max(0.0, n.dot(py.cross(pz))), std::max(0.0, n.dot(pz.cross(px))),
                 std::max(0.0, n.dot(px.cross(py))));
    const double sum = weights.sum();
    weights = sum > 0.0 ? Vec3(weights / sum) : Vec3::Constant(1.0 / 3.0);
    if (!(n2 > 0.0)) return {weights.x() * x + weights.y() * y + weights.z() * z, weights};
    const Vec3* origin = &x;
    if (py.squaredNorm() < (p - *origin).squaredNorm()) origin = &y;
    if (pz.squaredNorm() < (p - *origin).squaredNorm()) origin = &z;
    const Vec3 point = p - n * (n.dot(p - *origin) / n2);
    return {point, weights};
}

}  // namespace cdlab::closest_internal
