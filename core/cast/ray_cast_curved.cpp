#include "core/cast/ray_cast_curved.h"

#include <algorithm>
#include <cmath>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

// One face's signed distance at a point, its outward normal and its rate of change along the ray.
struct FaceValue {
    double value = 0.0;
    Vec3 normal = Vec3::UnitY();
    double slope = 0.0;
};

// The solid as the minimum of its faces' signed distances (see the header).
struct CurvedFaces {
    bool cone = false;
    double h = 0.0, r = 0.0;
    double k = 0.0, secant = 1.0;  // cone: side slope r / 2h and sqrt(1 + k²)

    // The active face (least signed distance) at p, for a ray along d.
    FaceValue at(const Vec3& p, const Vec3& d) const {
        const Vec3 across(p.x(), 0.0, p.z()), dAcross(d.x(), 0.0, d.z());
        const double rho = across.norm();
        // d|x⊥|/dt; at the axis |x⊥| has a kink (a peak of −|x⊥|), taken as 0.
        const double rhoSlope = rho > 0.0 ? across.dot(dAcross) / rho : 0.0;
        const Vec3 radial = rho > 0.0 ? Vec3(across / rho) : Vec3::UnitX();
        FaceValue cap, side;
        if (!cone) {
            const double sign = p.y() < 0.0 ? -1.0 : 1.0;
            cap = {h - std::abs(p.y()), Vec3(0.0, sign, 0.0), p.y() == 0.0 ? 0.0 : -sign * d.y()};
            side = {r - rho, radial, -rhoSlope};
        } else {
            // The base below, and above the plane of the apex (redundant unless r = 0, where the
            // side alone would admit the whole axis line).
            const FaceValue base{p.y() + h, Vec3(0.0, -1.0, 0.0), d.y()}, top{h - p.y(), Vec3::UnitY(), -d.y()};
            cap = top.value < base.value ? top : base;
            const Vec3 n = rho > 0.0 ? Vec3(Vec3(radial.x(), k, radial.z()) / secant) : Vec3::UnitY();  // +y at the apex
            side = {(k * (h - p.y()) - rho) / secant, n, (-k * d.y() - rhoSlope) / secant};
        }
        // Tied (a rim, the apex): the face the ray crosses, rising fastest — a ray in a cap's
        // plane enters through the side, with the side's normal.
        if (std::abs(side.value - cap.value) <= 1e-15 * (h + r)) return side.slope >= cap.slope ? side : cap;
        return side.value < cap.value ? side : cap;
    }
};

ConvexCastHit castRayCurved(const Ray& ray, const CurvedFaces& faces, const ConvexCastOptions& options) {
    ConvexCastHit hit;
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    const double tau = options.touchTolerance;
    if (!o.allFinite() || !d.allFinite() || d.isZero(0.0) || !(faces.h >= 0.0) || !(faces.r >= 0.0)) return hit;
    const auto f = [&](double t) { return faces.at(Vec3(o + t * d), d); };
    if (f(0.0).value >= -tau) {
        hit.hit = hit.inside = true;
        hit.point = o;
        return hit;
    }
    // The bracket: the ray inside the bounding sphere (inflated past rounding), within [0, maxT].
    const double dd = d.squaredNorm();
    const double radius = std::hypot(faces.h, faces.r) * (1.0 + 1e-12) + tau;
    const double tc = -o.dot(d) / dd;
    const double miss = (o + tc * d).norm();
    if (miss > radius) return hit;
    const double half = std::sqrt((radius - miss) * (radius + miss) / dd);
    double lo = std::max(0.0, tc - half), hi = std::min(options.maxT, tc + half);
    if (!(lo <= hi)) return hit;
    // The peak of the concave f: where its slope changes sign.
    double peak = lo;
    if (f(lo).slope > 0.0) {
        if (f(hi).slope >= 0.0) peak = hi;
        else {
            double a = lo, b = hi;
            for (int i = 0; i < 2200; ++i) {
                const double mid = 0.5 * (a + b);
                if (mid <= a || mid >= b) break;
                (f(mid).slope > 0.0 ? a : b) = mid;
            }
            peak = f(a).value >= f(b).value ? a : b;
        }
    }
    const double top = f(peak).value;
    if (top < -tau) return hit;
    // The entry: the first t at which f reaches min(0, top). A peak within f's rounding of 0 is a
    // tangent point: f is flat there (−κs² at a distance s), so the first t with f >= 0 in floating
    // point would come ~sqrt(u) early; the peak itself is exact.
    const double rounding = 8 * kMachineEpsilon * std::max(radius, Vec3(o + peak * d).norm());
    const double target = std::min(0.0, top);
    double a = lo, b = peak;
    if (f(a).value >= target) b = a;
    else if (top <= rounding) b = peak;
    else
        for (int i = 0; i < 2200; ++i) {
            const double mid = 0.5 * (a + b);
            if (mid <= a || mid >= b) break;
            (f(mid).value >= target ? b : a) = mid;
        }
    hit.hit = true;
    hit.t = b;
    hit.point = o + b * d;
    hit.normal = faces.at(hit.point, d).normal;
    return hit;
}

}  // namespace

ConvexCastHit castRayCylinder(const Ray& ray, double halfHeight, double radius, const ConvexCastOptions& options) {
    CurvedFaces faces;
    faces.h = halfHeight;
    faces.r = radius;
    return castRayCurved(ray, faces, options);
}

ConvexCastHit castRayCone(const Ray& ray, double halfHeight, double radius, const ConvexCastOptions& options) {
    CurvedFaces faces;
    faces.h = halfHeight;
    faces.r = radius;
    // A flat cone is its base disc: below ~1e-100 of the radius its height is under any rounding
    // of the radius, and k = r / 2h would overflow.
    if (!(halfHeight > 1e-100 * radius) || !(halfHeight > 0.0)) {
        faces.h = 0.0;
        return castRayCurved(ray, faces, options);
    }
    faces.cone = true;
    faces.k = radius / (2.0 * halfHeight);
    faces.secant = std::sqrt(1.0 + faces.k * faces.k);
    return castRayCurved(ray, faces, options);
}

}  // namespace cdlab
