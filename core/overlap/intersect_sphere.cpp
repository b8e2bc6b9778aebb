#include "core/overlap/intersect_sphere.h"

#include <algorithm>
#include <cmath>

#include "core/base/aabb_ops.h"
#include "core/base/orient.h"

namespace cdlab {

namespace {

bool validSphere(const Sphere& s) {
    // Comparison order matters: a NaN radius fails >= 0.
    return s.center.allFinite() && s.radius >= 0.0 && std::isfinite(s.radius);
}

// Closest point of segment ab to p (Ericson §5.1.2); a == b gives a.
Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    if (len2 == 0.0) return a;
    const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    return a + t * ab;
}

// Closest point of a non-degenerate triangle to p (Ericson §5.1.5, ClosestPtPointTriangle):
// the Voronoi regions of the vertices, then the edges, then the face.
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;  // vertex region a
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;  // vertex region b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;  // edge region ab
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;  // vertex region c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;  // edge region ac
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)  // edge region bc
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    // Face region: p = a + v ab + w ac with v, w from the barycentric area ratios.
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

SphereShapeResult finish(const Sphere& sphere, const Vec3& closest) {
    SphereShapeResult r;
    r.closestPoint = closest;
    r.distanceSquared = (closest - sphere.center).squaredNorm();
    r.hit = r.distanceSquared <= sphere.radius * sphere.radius;
    return r;
}

}  // namespace

SphereSphereResult intersectSphereSphere(const Sphere& a, const Sphere& b) {
    SphereSphereResult r;
    if (!validSphere(a) || !validSphere(b)) return r;
    const Vec3 d = b.center - a.center;
    const double dist2 = d.squaredNorm();
    const double radiusSum = a.radius + b.radius;
    r.hit = dist2 <= radiusSum * radiusSum;
    r.distance = std::sqrt(dist2);
    r.depth = radiusSum - r.distance;
    if (r.distance > 0.0) r.normal = d / r.distance;
    // Surface points a.center + ra n and b.center - rb n; their midpoint.
    r.point = 0.5 * ((a.center + a.radius * r.normal) + (b.center - b.radius * r.normal));
    return r;
}

SphereShapeResult intersectSphereAabb(const Sphere& sphere, const Aabb& box) {
    if (!validSphere(sphere) || !isValidBox(box)) return {};
    // Ericson §5.1.3: clamp the center to the box per axis.
    return finish(sphere, sphere.center.cwiseMax(box.min).cwiseMin(box.max));
}

SphereShapeResult intersectSphereObb(const Sphere& sphere, const Obb& box) {
    if (!validSphere(sphere) || !box.center.allFinite() || !box.axes.allFinite() || !box.halfExtents.allFinite() ||
        !(box.halfExtents.array() >= 0.0).all())
        return {};
    // Ericson §5.1.4: clamp the center's box coordinates to the half extents.
    const Vec3 local = box.axes.transpose() * (sphere.center - box.center);
    const Vec3 clamped = local.cwiseMax(-box.halfExtents).cwiseMin(box.halfExtents);
    return finish(sphere, box.center + box.axes * clamped);
}

SphereShapeResult intersectSphereTriangle(const Sphere& sphere, const Triangle& tri) {
    if (!validSphere(sphere) || !tri.a.allFinite() || !tri.b.allFinite() || !tri.c.allFinite()) return {};
    const Vec3& p = sphere.center;
    if (projectionAxis(tri) >= 0) return finish(sphere, closestOnTriangle(p, tri.a, tri.b, tri.c));
    // Zero-area triangle: the closest of its three edges.
    Vec3 best = closestOnSegment(p, tri.a, tri.b);
    for (const Vec3& q : {closestOnSegment(p, tri.b, tri.c), closestOnSegment(p, tri.c, tri.a)})
        if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return finish(sphere, best);
}

}  // namespace cdlab
