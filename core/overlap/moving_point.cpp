#include "core/overlap/moving_point.h"

#include <algorithm>
#include <cmath>

#include "core/base/accurate_cross.h"
#include "core/base/orient.h"
#include "core/overlap/intersect_ray.h"
#include "core/overlap/polygon_tests.h"

namespace cdlab {

namespace {

bool validMotion(const MovingPoint& m) {
    return m.position.allFinite() && m.velocity.allFinite() && std::isfinite(m.tBegin) && std::isfinite(m.tEnd) &&
           m.tBegin <= m.tEnd;
}

// The path as a segment: s in [0, 1] maps to t = tBegin + s (tEnd - tBegin).
Segment pathOf(const MovingPoint& m) { return Segment{m.at(m.tBegin), m.at(m.tEnd)}; }

MovingPointHit makeHit(const MovingPoint& m, double s, const Vec3& point) {
    MovingPointHit hit;
    hit.hit = true;
    hit.t = std::min(m.tBegin + s * (m.tEnd - m.tBegin), m.tEnd);
    hit.point = point;
    return hit;
}

Vec3 unitOrZero(const Vec3& v) {
    const double len = v.norm();
    return len > 0.0 && std::isfinite(len) ? Vec3(v / len) : Vec3(Vec3::Zero());
}

// Parameter on segment ab of the point closest to p, in [0, 1] (0 for a == b).
double closestParameter(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    return len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

// Radius 0: the path segment pq and the segment ab meet (exactly). They must be coplanar,
// and then they meet iff they meet in all three coordinate projections (at least one of them
// is one-to-one on their common plane; meeting in 3D implies meeting in each).
bool segmentsMeetExactly(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
    if (orient3d(p, q, a, b) != 0) return false;
    for (int axis = 0; axis < 3; ++axis)
        if (!segmentsIntersect2d(dropAxis(p, axis), dropAxis(q, axis), dropAxis(a, axis), dropAxis(b, axis)))
            return false;
    return true;
}

MovingPointHit capsuleZeroRadius(const MovingPoint& m, const Segment& path, const Capsule& c) {
    const Vec3& p = path.a;
    const Vec3& q = path.b;
    if (!segmentsMeetExactly(p, q, c.a, c.b)) return {};
    // First contact parameter s on the path, computed in doubles.
    double s = 0.0;
    if (!segmentsMeetExactly(p, p, c.a, c.b)) {
        const Vec3 d = q - p, e = c.b - c.a;
        const Vec3 n = d.cross(e);
        if (n.squaredNorm() > 0.0) {
            // Crossing lines: p + s d = a + u e  =>  s = ((a - p) x e) . n / |n|^2.
            s = (c.a - p).cross(e).dot(n) / n.squaredNorm();
        } else {
            // Collinear overlap: the first end of ab met along the path.
            s = std::min(closestParameter(c.a, p, q), closestParameter(c.b, p, q));
        }
        if (!std::isfinite(s)) s = 0.0;
        s = std::clamp(s, 0.0, 1.0);
    }
    return makeHit(m, s, p + s * (q - p));
}

}  // namespace

MovingPointHit intersectMovingPointSphere(const MovingPoint& m, const Sphere& sphere) {
    if (!validMotion(m)) return {};
    const RayHit h = intersectSegmentSphere(pathOf(m), sphere);
    if (!h.hit) return {};
    MovingPointHit hit = makeHit(m, h.t, h.point);
    if (h.t > 0.0 || (h.point - sphere.center).squaredNorm() >= sphere.radius * sphere.radius)
        hit.normal = unitOrZero(h.point - sphere.center);
    return hit;
}

MovingPointHit intersectMovingPointCapsule(const MovingPoint& m, const Capsule& c) {
    if (!validMotion(m) || !c.a.allFinite() || !c.b.allFinite() || !(c.radius >= 0.0) || !std::isfinite(c.radius))
        return {};
    const Segment path = pathOf(m);
    if (c.radius == 0.0) return capsuleZeroRadius(m, path, c);

    const double r2 = c.radius * c.radius;
    const Vec3 p = path.a, d = path.b - path.a;
    auto axisPoint = [&](const Vec3& x) { return c.a + closestParameter(x, c.a, c.b) * (c.b - c.a); };
    // Starts inside or on the capsule.
    if ((p - axisPoint(p)).squaredNorm() <= r2) return makeHit(m, 0.0, p);

    double best = 2.0;  // > 1: none yet
    // Cylinder side (Ericson §5.3.7): |(m + s n) - axial part|^2 = r^2, with m = p - a,
    // n = d, D = b - a:  A s^2 + 2 B s + C = 0,
    //   A = (D.D)(n.n) - (n.D)^2,  B = (D.D)(m.n) - (n.D)(m.D),  C = (D.D)(m.m - r^2) - (m.D)^2,
    // computed by Lagrange's identity as A = |D x n|^2, B = (D x m).(D x n), C = |D x m|^2 - (D.D) r^2
    // and B^2 - A C = (D.D) (A r^2 - [D, m, n]^2), with D x m and m x n from the exact m
    // (core/base/accurate_cross.h). The expanded forms lost r^2 to the rounding of |m|^2 far from
    // the capsule; these err relative to r times the distance from the axis
    // (tests/core/overlap/intersect_ray_far_test.cpp).
    const Vec3 D = c.b - c.a, mv = p - c.a;
    const double dd = D.dot(D), md = mv.dot(D), nd = d.dot(D);
    Vec3 Dm = -accurateOffsetCross(c.a, p, D), mn = accurateOffsetCross(c.a, p, d);
    if (!Dm.allFinite() || !mn.allFinite()) Dm = D.cross(mv), mn = mv.cross(d);  // past the split's range
    const Vec3 Dn = D.cross(d);
    const double triple = D.dot(mn);  // [D, m, n]
    const double A = Dn.squaredNorm();
    const double B = Dm.dot(Dn);
    const double C = Dm.squaredNorm() - dd * r2;
    // C > 0: outside the infinite cylinder (else the entry is through an end sphere);
    // B < 0: approaching its axis; A > 0: not moving parallel to the axis.
    if (dd > 0.0 && A > 0.0 && C > 0.0 && B < 0.0) {
        const double disc = dd * (A * r2 - triple * triple);
        if (disc >= 0.0) {
            // Smaller root (-B - sqrt(disc)) / A = C / (-B + sqrt(disc)): no cancellation.
            const double s = C / (-B + std::sqrt(disc));
            const double axial = md + s * nd;  // (D.D) times the axis parameter of the contact
            if (s >= 0.0 && s <= 1.0 && axial >= 0.0 && axial <= dd) best = s;
        }
    }
    // End spheres: their entries cover the flat cylinder ends as well.
    for (const Vec3& center : {c.a, c.b}) {
        const RayHit h = intersectSegmentSphere(path, Sphere{center, c.radius});
        if (h.hit && h.t < best) best = h.t;
    }
    if (best > 1.0) return {};
    const Vec3 point = p + best * d;
    MovingPointHit hit = makeHit(m, best, point);
    hit.normal = unitOrZero(point - axisPoint(point));
    return hit;
}

MovingPointHit intersectMovingPointTriangle(const MovingPoint& m, const Triangle& tri) {
    if (!validMotion(m)) return {};
    const Segment path = pathOf(m);
    const RayTriangleHit h = intersectSegmentTriangle(path, tri);
    if (!h.hit) return {};
    MovingPointHit hit = makeHit(m, h.t, h.point);
    if (!h.coplanar) {
        const Vec3 n = unitOrZero((tri.b - tri.a).cross(tri.c - tri.a));
        // Face the side the point comes from (back face: flip).
        hit.normal = h.backFace ? Vec3(-n) : n;
        if (orient3d(tri.a, tri.b, tri.c, path.a) == 0) hit.normal = Vec3::Zero();  // started on it
    }
    return hit;
}

}  // namespace cdlab
