#include "core/closest/edge_pair_distance.h"

#include <algorithm>
#include <cmath>

#include "core/base/double_double.h"
#include "core/base/power_of_two.h"

namespace cdlab {

namespace {

using dd::DoubleDouble;
using dd::Vec3DD;

Vec3DD exactDifference(const Vec3& a, const Vec3& b) {
    return {dd::exactDifference(a.x(), b.x()), dd::exactDifference(a.y(), b.y()), dd::exactDifference(a.z(), b.z())};
}

Vec3 rounded(const Vec3DD& v) { return {v.x.value(), v.y.value(), v.z.value()}; }

/// The four points scaled by one power of two (exact) so that the largest |coordinate| is in
/// [0.5, 1): products of four coordinates (|c|^2) then neither overflow nor lose the split's
/// range, and tiny inputs do not underflow before they must. The exponent is in [-1073, 1024]
/// (frexp of a finite double), so both scalings are in PowerOfTwo's range.
struct ScaledQuad {
    Vec3 p[4];
    bool finite = true;
    PowerOfTwo up{0};  // original = up(scaled)

    ScaledQuad(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
        const Vec3 in[4] = {a0, a1, b0, b1};
        double m = 0.0;
        for (const Vec3& v : in) {
            finite = finite && v.allFinite();
            m = std::max(m, v.cwiseAbs().maxCoeff());
        }
        int exponent = 0;
        if (finite && m > 0.0) std::frexp(m, &exponent);
        const PowerOfTwo down(-exponent);
        for (int i = 0; i < 4; ++i) p[i] = in[i].unaryExpr(down);
        up = PowerOfTwo(exponent);
    }
    double unscale(double x) const { return up(x); }
    Vec3 unscale(const Vec3& v) const { return v.unaryExpr(up); }
};

/// Common perpendicular of lines a0 + s (a1 - a0) and b0 + t (b1 - b0), scaled coordinates.
/// With c = dA x dB and r = b0 - a0: s = (r x dB).c / |c|^2, t = (r x dA).c / |c|^2 (Cramer's
/// rule on s dA - t dB + u c = r), and the separation along c/|c| is r.c / |c|.
bool commonPerpendicular(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& s, double& t,
                         double& separation, Vec3& normal) {
    const Vec3DD dA = exactDifference(a1, a0), dB = exactDifference(b1, b0), r = exactDifference(b0, a0);
    const Vec3DD c = dd::cross(dA, dB);
    const double cc = dd::dot(c, c).value();
    if (!(cc > 0.0) || !std::isfinite(cc)) return false;
    s = dd::dot(dd::cross(r, dB), c).value() / cc;
    t = dd::dot(dd::cross(r, dA), c).value() / cc;
    const double length = std::sqrt(cc);
    normal = rounded(c) / length;
    separation = dd::dot(r, c).value() / length;
    return std::isfinite(s) && std::isfinite(t) && std::isfinite(separation);
}

/// Distance from x to segment [p, q] (scaled coordinates); closest point and x - closest.
double pointSegment(const Vec3& x, const Vec3& p, const Vec3& q, Vec3& closest, Vec3& offset) {
    const Vec3DD d = exactDifference(q, p), w = exactDifference(x, p);
    const double dd2 = dd::dot(d, d).value();
    double t = dd2 > 0.0 ? dd::dot(w, d).value() / dd2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);  // also maps NaN (0/0 cannot occur: dd2 > 0) safely
    offset = rounded(w - DoubleDouble(t) * d);
    closest = x - offset;
    return offset.norm();
}

}  // namespace

EdgePairDistance edgePairDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
    EdgePairDistance best;
    const ScaledQuad q(a0, a1, b0, b1);
    if (!q.finite) return best;
    const Vec3 &A0 = q.p[0], &A1 = q.p[1], &B0 = q.p[2], &B1 = q.p[3];
    best.ok = true;
    best.distance = INFINITY;
    auto consider = [&](double distance, const Vec3& pa, const Vec3& pb, const Vec3& axis, bool interior) {
        if (!(distance < best.distance)) return;
        best.distance = distance;
        best.pointA = pa;
        best.pointB = pb;
        best.axis = distance > 0.0 ? axis : Vec3::Zero();
        best.interior = interior;
    };
    // Interior minimum: the common perpendicular, when its feet lie on both segments.
    double s = 0.0, t = 0.0, separation = 0.0;
    Vec3 normal;
    if (commonPerpendicular(A0, A1, B0, B1, s, t, separation, normal) && s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0) {
        const Vec3 pa = A0 + s * (A1 - A0), pb = B0 + t * (B1 - B0);
        consider(std::abs(separation), pa, pb, separation < 0.0 ? Vec3(-normal) : normal, true);
    }
    // Boundary minima: an end point against the other segment.
    Vec3 closest, offset;
    for (const Vec3* a : {&A0, &A1}) {
        const double d = pointSegment(*a, B0, B1, closest, offset);
        consider(d, *a, closest, d > 0.0 ? Vec3(-offset / d) : Vec3::Zero(), false);
    }
    for (const Vec3* b : {&B0, &B1}) {
        const double d = pointSegment(*b, A0, A1, closest, offset);
        consider(d, closest, *b, d > 0.0 ? Vec3(offset / d) : Vec3::Zero(), false);
    }
    best.distance = q.unscale(best.distance);
    best.pointA = q.unscale(best.pointA);
    best.pointB = q.unscale(best.pointB);
    return best;
}

EdgePairDistance pointTriangleDistance(const Vec3& p, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
    EdgePairDistance best;
    const ScaledQuad q(p, t0, t1, t2);
    if (!q.finite) return best;
    const Vec3& P = q.p[0];
    const Vec3 T[3] = {q.p[1], q.p[2], q.p[3]};
    const Vec3DD n = dd::cross(exactDifference(T[1], T[0]), exactDifference(T[2], T[0]));
    const double nn = dd::dot(n, n).value();
    if (nn > 0.0 && std::isfinite(nn)) {
        // The projection of P lies in the triangle iff P is on the inner side of all three edge
        // planes: ((T[j] - T[i]) x (P - T[i])) . n >= 0 for the edges in counterclockwise order.
        bool inside = true;
        for (int i = 0; i < 3 && inside; ++i) {
            const int j = (i + 1) % 3;
            inside = dd::dot(dd::cross(exactDifference(T[j], T[i]), exactDifference(P, T[i])), n).value() >= 0.0;
        }
        if (inside) {
            const double length = std::sqrt(nn);
            const Vec3 unit = rounded(n) / length;
            const double separation = dd::dot(exactDifference(P, T[0]), n).value() / length;  // along unit
            best.ok = true;
            best.distance = q.unscale(std::abs(separation));
            best.pointA = p;
            best.pointB = q.unscale(Vec3(P - separation * unit));
            best.axis = separation > 0.0 ? Vec3(-unit) : separation < 0.0 ? unit : Vec3::Zero();
            best.interior = true;
            return best;
        }
    }
    // Outside the face (or a zero-area triangle): the nearest edge, a point being a zero-length edge.
    for (int i = 0; i < 3; ++i) {
        const EdgePairDistance e = edgePairDistance(p, p,
                                                    i == 0   ? t0
                                                    : i == 1 ? t1
                                                             : t2,
                                                    i == 0   ? t1
                                                    : i == 1 ? t2
                                                             : t0);
        if (e.ok && (!best.ok || e.distance < best.distance)) best = e;
    }
    return best;
}

LinePairSeparation linePairSeparation(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
    LinePairSeparation out;
    const ScaledQuad q(a0, a1, b0, b1);
    if (!q.finite) return out;
    double separation = 0.0;
    if (!commonPerpendicular(q.p[0], q.p[1], q.p[2], q.p[3], out.s, out.t, separation, out.normal)) return out;
    out.ok = true;
    out.separation = q.unscale(separation);
    out.pointA = a0 + out.s * (a1 - a0);
    out.pointB = b0 + out.t * (b1 - b0);
    return out;
}

}  // namespace cdlab
