#include "core/overlap/intersect_ray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/base/aabb_ops.h"
#include "core/base/accurate_cross.h"
#include "core/base/big_dyadic.h"
#include "core/base/exact_predicates.h"
#include "core/base/orient.h"
#include "core/overlap/polygon_tests.h"

namespace cdlab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// det[u1 - v1; u2 - v2; u3 - v3] = (u1 - v1) · ((u2 - v2) × (u3 - v3)) in number type T (Bounded:
// with a rigorous error bound; BigDyadic: exact), the differences taken in T.
template <class T>
T det3Rows(const Vec3* u, const Vec3* v) {
    T d[3][3];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) d[r][k] = T(u[r][k]) - T(v[r][k]);
    return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) + d[0][1] * (d[1][2] * d[2][0] - d[1][0] * d[2][2]) +
           d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

// A determinant whose double evaluation is within a relative 2^-44 of the exact value (a
// cancellation of at most ~64 against its permanent): the plain quotient of two such is within
// ~2^-43 of the exact quotient.
constexpr double kWellConditioned = 0x1p-44;
bool wellConditioned(const exact::Bounded& x) {
    return std::isfinite(x.value) && x.error <= kWellConditioned * std::abs(x.value);
}

// Quotients num / den of determinants of differences of the input doubles over one den (non-zero
// exactly): the plain quotient when both are well conditioned, else the exact quotient rounded
// once (a ray within rounding of a triangle's plane has a near-zero d · n whose double value has no
// correct digit: Möller-Trumbore's t was then anywhere, even negative and clamped to 0; issue 41
// class 3).
class DeterminantRatio {
public:
    DeterminantRatio(const Vec3* u, const Vec3* v) : u_(u), v_(v), den_(det3Rows<exact::Bounded>(u, v)) {}
    double of(const Vec3* nu, const Vec3* nv) {
        const exact::Bounded num = det3Rows<exact::Bounded>(nu, nv);
        if (wellConditioned(num) && wellConditioned(den_) && den_.value != 0.0) return num.value / den_.value;
        if (!exactDen_) exactDen_ = true, denExact_ = det3Rows<exact::BigDyadic>(u_, v_);
        return exact::quotient(det3Rows<exact::BigDyadic>(nu, nv), denExact_);
    }

private:
    const Vec3 *u_, *v_;
    exact::Bounded den_;
    bool exactDen_ = false;
    exact::BigDyadic denExact_;
};

// Clamp barycentric weights computed in doubles to the closed triangle: the exact decision has
// already put the point inside, so negative weights are rounding noise.
Vec3 clampBarycentric(Vec3 w) {
    if (!w.allFinite()) return Vec3::Constant(1.0 / 3.0);
    w = w.cwiseMax(0.0);
    const double sum = w.sum();
    return sum > 0.0 ? Vec3(w / sum) : Vec3::Constant(1.0 / 3.0);
}

// Barycentric weights of a point in the triangle's plane (Ericson §3.4, Cramer's rule).
Vec3 barycentricOf(const Triangle& tri, const Vec3& p) {
    const Vec3 v0 = tri.b - tri.a, v1 = tri.c - tri.a, v2 = p - tri.a;
    const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
    const double d20 = v2.dot(v0), d21 = v2.dot(v1);
    const double denom = d00 * d11 - d01 * d01;
    const double v = (d11 * d20 - d01 * d21) / denom;
    const double w = (d00 * d21 - d01 * d20) / denom;
    return clampBarycentric(Vec3(1.0 - v - w, v, w));
}

std::array<Vec2, 3> projectTriangle(const Triangle& tri, int axis) {
    return {dropAxis(tri.a, axis), dropAxis(tri.b, axis), dropAxis(tri.c, axis)};
}

// A ray / segment o + t d, t in [0, tMax], lying in the plane of a non-degenerate triangle:
// first contact by 2D clipping in the projection along `axis`.
RayTriangleHit coplanarHit(const Vec3& o, const Vec3& d, double tMax, const Triangle& tri, int axis, bool exactHit) {
    RayTriangleHit hit;
    const auto poly = projectTriangle(tri, axis);
    const LineClip2d clip = clipLineToConvexPolygon2d(poly, dropAxis(o, axis), dropAxis(d, axis), 0.0, tMax);
    if (!clip.hit && !exactHit) return hit;
    hit.hit = true;
    hit.coplanar = true;
    // When the exact test says hit but clipping lost it to rounding, the contact is at the
    // boundary within rounding error: take the nearest end, t = 0.
    hit.t = clip.hit ? clip.tEnter : 0.0;
    hit.point = o + hit.t * d;
    hit.barycentric = barycentricOf(tri, hit.point);
    return hit;
}

// Slab clipping of o + t d, t in [0, tMax] (Ericson §5.3.3, IntersectRayAABB).
RayBoxHit slabs(const Vec3& o, const Vec3& d, double tMax, const Aabb& box, SlabTrace* trace) {
    RayBoxHit hit;
    if (!isValidBox(box) || !o.allFinite() || !d.allFinite()) return hit;
    double tEnter = 0.0, tExit = tMax;
    int enterAxis = -1;
    for (int i = 0; i < 3; ++i) {
        SlabStep step;
        step.axis = i;
        if (d[i] == 0.0) {
            // Parallel to the slab (true for +0 and -0): no 1/d, which would give 0 * inf = NaN
            // for an origin on the slab plane. Inside the slab (closed) or never.
            step.parallel = true;
            step.rejected = o[i] < box.min[i] || o[i] > box.max[i];
        } else {
            // Divide instead of multiplying by 1/d: one rounding fewer, and t is exactly 0
            // for an origin on a slab plane.
            double tNear = (box.min[i] - o[i]) / d[i];
            double tFar = (box.max[i] - o[i]) / d[i];
            if (tNear > tFar) std::swap(tNear, tFar);
            step.tNear = tNear;
            step.tFar = tFar;
            if (tNear > tEnter) {
                tEnter = tNear;
                enterAxis = i;
            }
            tExit = std::min(tExit, tFar);
            step.rejected = tEnter > tExit;
        }
        step.tEnter = tEnter;
        step.tExit = tExit;
        if (trace) trace->steps.push_back(step);
        if (step.rejected) return hit;
    }
    hit.hit = true;
    hit.tEnter = tEnter;
    hit.tExit = tExit;
    hit.enterAxis = enterAxis;
    hit.point = o + tEnter * d;
    // The point lies on the box up to rounding; clamp so it is in the closed box.
    hit.point = hit.point.cwiseMax(box.min).cwiseMin(box.max);
    return hit;
}

RayHit linePlane(const Vec3& o, const Vec3& d, double tMax, const Plane& plane) {
    RayHit hit;
    if (!o.allFinite() || !d.allFinite() || !plane.normal.allFinite() || !std::isfinite(plane.offset) ||
        plane.normal.isZero(0.0))
        return hit;
    // n . (o + t d) = offset  =>  t = (offset - n . o) / (n . d)
    const double num = plane.offset - plane.normal.dot(o);
    const double den = plane.normal.dot(d);
    if (den == 0.0) {
        // Parallel: either in the plane (closed set: hit at once) or never.
        if (num != 0.0) return hit;
        hit.hit = true;
        hit.point = o;
        return hit;
    }
    const double t = num / den;
    if (!(t >= 0.0 && t <= tMax)) return hit;
    hit.hit = true;
    hit.t = t;
    hit.point = o + t * d;
    return hit;
}

RayHit lineSphere(const Vec3& o, const Vec3& d, double tMax, const Sphere& s, SphereQuadraticTrace* trace) {
    using Outcome = SphereQuadraticTrace::Outcome;
    SphereQuadraticTrace local;
    SphereQuadraticTrace& q = trace ? *trace : local;
    q = {};
    RayHit hit;
    if (!o.allFinite() || !d.allFinite() || !s.center.allFinite() || !(s.radius >= 0.0) || !std::isfinite(s.radius))
        return hit;
    // |m + t d|^2 = r^2 with m = o - c:  a t^2 + 2 b t + c = 0.
    const Vec3 m = o - s.center;
    const double a = d.dot(d);
    const double b = m.dot(d);
    const double c = m.dot(m) - s.radius * s.radius;
    q.a = a;
    q.b = b;
    q.c = c;
    // b² − a c written as a r² − |m × d|² (Lagrange: |m|²|d|² − (m·d)² = |m × d|²), |m × d| / |d|
    // the line's distance from the centre, with m × d from the exact m (core/base/accurate_cross.h).
    // b² − a c loses r² to the rounding of |m|² far from the centre (a unit sphere at 1e9 was hit
    // at its centre); this form's error is relative to r², not |m|²
    // (tests/core/overlap/intersect_ray_far_test.cpp).
    Vec3 w = accurateOffsetCross(s.center, o, d);
    if (!w.allFinite()) w = m.cross(d);  // beyond the error-free split's range (~2^996)
    q.discriminant = a * (s.radius * s.radius) - w.squaredNorm();
    if (a > 0.0 && q.discriminant >= 0.0) {  // the line's two crossings, for the figure
        const double root = std::sqrt(q.discriminant);
        // The root of larger magnitude without cancellation, the other from the product c / a.
        const double big = b <= 0.0 ? (-b + root) / a : (-b - root) / a;
        const double small = big != 0.0 ? c / (a * big) : 0.0;
        q.rootsValid = true;
        q.t0 = std::min(big, small);
        q.t1 = std::max(big, small);
    }
    if (c <= 0.0) {  // starts inside or on the sphere
        q.outcome = Outcome::StartsInside;
        hit.hit = true;
        hit.point = o;
        return hit;
    }
    if (a == 0.0 || b > 0.0) {  // a point outside, or moving away
        q.outcome = a == 0.0 ? Outcome::PointOutside : Outcome::PointsAway;
        return hit;
    }
    const double disc = q.discriminant;
    if (disc < 0.0) {
        q.outcome = Outcome::NoRealRoot;
        return hit;
    }
    // Smaller root (-b - sqrt(disc)) / a written as c / (-b + sqrt(disc)): -b >= 0 here, so
    // the denominator has no cancellation (the product of the roots is c / a).
    const double den = -b + std::sqrt(disc);
    const double t = den > 0.0 ? c / den : -b / a;
    if (!(t <= tMax)) {
        q.outcome = Outcome::BeyondEnd;
        return hit;
    }
    q.outcome = Outcome::Hit;
    hit.hit = true;
    hit.t = std::max(t, 0.0);
    hit.point = o + hit.t * d;
    return hit;
}

}  // namespace

RayHit intersectRayPlane(const Ray& ray, const Plane& plane) {
    if (ray.direction.isZero(0.0)) return {};
    return linePlane(ray.origin, ray.direction, kInf, plane);
}

RayHit intersectSegmentPlane(const Segment& segment, const Plane& plane) {
    return linePlane(segment.a, segment.b - segment.a, 1.0, plane);
}

const char* nameOf(SphereQuadraticTrace::Outcome outcome) {
    using Outcome = SphereQuadraticTrace::Outcome;
    switch (outcome) {
        case Outcome::Invalid: return "invalid input";
        case Outcome::StartsInside: return "starts inside";
        case Outcome::PointOutside: return "a point outside";
        case Outcome::PointsAway: return "points away";
        case Outcome::NoRealRoot: return "no real root";
        case Outcome::BeyondEnd: return "beyond the end";
        case Outcome::Hit: return "hit";
    }
    return "?";
}

RayHit intersectRaySphere(const Ray& ray, const Sphere& sphere, SphereQuadraticTrace* trace) {
    if (ray.direction.isZero(0.0)) {
        if (trace) *trace = {};
        return {};
    }
    return lineSphere(ray.origin, ray.direction, kInf, sphere, trace);
}

RayHit intersectSegmentSphere(const Segment& segment, const Sphere& sphere, SphereQuadraticTrace* trace) {
    return lineSphere(segment.a, segment.b - segment.a, 1.0, sphere, trace);
}

RayBoxHit intersectRayAabb(const Ray& ray, const Aabb& box, SlabTrace* trace) {
    if (ray.direction.isZero(0.0)) return {};
    return slabs(ray.origin, ray.direction, kInf, box, trace);
}

RayBoxHit intersectSegmentAabb(const Segment& segment, const Aabb& box, SlabTrace* trace) {
    return slabs(segment.a, segment.b - segment.a, 1.0, box, trace);
}

RayTriangleHit intersectRayTriangle(const Ray& ray, const Triangle& tri, const RayTriangleOptions& options) {
    RayTriangleHit hit;
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    const Vec3 zero = Vec3::Zero();
    if (!o.allFinite() || !d.allFinite() || !tri.allFinite() || d.isZero(0.0)) return hit;
    const int axis = projectionAxis(tri);
    if (axis < 0) return hit;  // zero-area triangle

    // Exact sign of d . n, n = (b - a) x (c - a).
    const int sDn = signDet3(d, zero, tri.b, tri.a, tri.c, tri.a);
    if (sDn == 0) {
        // Parallel to the plane: coplanar (closed set) or no hit.
        if (!options.doubleSided || orient3d(tri.a, tri.b, tri.c, o) != 0) return hit;
        return coplanarHit(o, d, kInf, tri, axis, false);
    }
    if (!options.doubleSided && sDn > 0) return hit;  // back face culled

    // Ericson §5.3.4: the line o + t d meets the closed triangle iff the triple products
    // [d, b-o, c-o], [d, c-o, a-o], [d, a-o, b-o] (= barycentric weights times d . n) all have
    // the sign of d . n or are zero.
    const int wa = signDet3(d, zero, tri.b, o, tri.c, o);
    const int wb = signDet3(d, zero, tri.c, o, tri.a, o);
    const int wc = signDet3(d, zero, tri.a, o, tri.b, o);
    if (wa * sDn < 0 || wb * sDn < 0 || wc * sDn < 0) return hit;
    // t = (a - o) . n / (d . n) >= 0.
    const int sNum = signDet3(tri.a, o, tri.b, tri.a, tri.c, tri.a);
    if (sNum * sDn < 0) return hit;

    // The numbers: t = [a - o, b - a, c - a] / [d, b - a, c - a] and the weights
    // [d, b - o, c - o] / [d, b - a, c - a], ... from the same determinants of the input doubles,
    // evaluated with an error bound: where d · n or the numerator cancels (a ray within rounding of
    // the plane), exactly and rounded once (ratioOfDeterminants), so the hit point is on the
    // triangle up to the rounding of o + t d, never before it.
    const Vec3 dRows[3] = {d, tri.b, tri.c}, dBase[3] = {zero, tri.a, tri.a};
    DeterminantRatio ratio(dRows, dBase);
    const Vec3 tRows[3] = {tri.a, tri.b, tri.c}, tBase[3] = {o, tri.a, tri.a};
    const double t = sNum == 0 ? 0.0 : ratio.of(tRows, tBase);
    const Vec3 ua[3] = {d, tri.b, tri.c}, ub[3] = {d, tri.c, tri.a}, uc[3] = {d, tri.a, tri.b};
    const Vec3 base[3] = {zero, o, o};
    const Vec3 w(wa == 0 ? 0.0 : ratio.of(ua, base), wb == 0 ? 0.0 : ratio.of(ub, base),
                 wc == 0 ? 0.0 : ratio.of(uc, base));
    hit.hit = true;
    // Exactly t = 0 for an origin on the plane; the exact decision put t >= 0 (the quotient keeps its sign).
    hit.t = std::isfinite(t) ? std::max(t, 0.0) : 0.0;
    hit.barycentric = clampBarycentric(w);
    hit.point = o + hit.t * d;
    hit.backFace = sDn > 0;
    return hit;
}

RayTriangleHit intersectSegmentTriangle(const Segment& segment, const Triangle& tri) {
    RayTriangleHit hit;
    const Vec3& p = segment.a;
    const Vec3& q = segment.b;
    if (!p.allFinite() || !q.allFinite() || !tri.allFinite()) return hit;
    const int axis = projectionAxis(tri);
    if (axis < 0) return hit;  // zero-area triangle

    const int sp = orient3d(tri.a, tri.b, tri.c, p);
    const int sq = orient3d(tri.a, tri.b, tri.c, q);
    if (sp * sq > 0) return hit;  // both ends strictly on one side
    if (sp == 0 && sq == 0) {
        // Segment in the plane (or a point on it): exact 2D decision in a projection that keeps
        // the triangle non-degenerate, then the first contact by clipping.
        const auto tri2 = projectTriangle(tri, axis);
        const Vec2 seg2[2] = {dropAxis(p, axis), dropAxis(q, axis)};
        if (!intersectConvexPolygons2d(tri2, seg2).hit) return hit;
        return coplanarHit(p, q - p, 1.0, tri, axis, true);
    }
    // The segment crosses the plane at one point. sign(d . n) for d = q - p:
    const int sDn = sq != 0 ? sq : -sp;
    // Ericson §5.3.4 / §5.3.6 with exact triple products of the input points:
    // [q - p, b - p, c - p] = orient3d(p, q, b, c), and cyclically.
    const int wa = orient3d(p, q, tri.b, tri.c);
    const int wb = orient3d(p, q, tri.c, tri.a);
    const int wc = orient3d(p, q, tri.a, tri.b);
    if (wa * sDn < 0 || wb * sDn < 0 || wc * sDn < 0) return hit;

    // t from the signed plane distances of the end points (same n for both).
    const Vec3 n = (tri.b - tri.a).cross(tri.c - tri.a);
    const double dp = n.dot(p - tri.a), dq = n.dot(q - tri.a);
    double t = sp == 0 ? 0.0 : (sq == 0 ? 1.0 : dp / (dp - dq));
    if (!std::isfinite(t)) t = 0.0;
    hit.hit = true;
    hit.t = std::clamp(t, 0.0, 1.0);
    hit.point = p + hit.t * (q - p);
    hit.barycentric = barycentricOf(tri, hit.point);
    hit.backFace = sDn > 0;
    return hit;
}

}  // namespace cdlab
