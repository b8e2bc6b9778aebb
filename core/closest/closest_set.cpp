#include "core/closest/closest_set.h"

#include <algorithm>
#include <cmath>

#include "core/closest/voronoi_regions.h"

namespace cdlab {

namespace {

/// The distinct points (closer than tol merged), ordered counter-clockwise about their centroid in
/// the plane ⟂ n (n toward the viewer). Points of one face of a convex polytope are in convex position.
std::vector<Vec3> orderedFace(std::vector<Vec3> pts, const Vec3& n, double tol) {
    std::vector<Vec3> out;
    for (const Vec3& p : pts)
        if (std::none_of(out.begin(), out.end(), [&](const Vec3& q) { return (q - p).norm() <= tol; })) out.push_back(p);
    if (out.size() < 3) return out;
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : out) c += p;
    c /= double(out.size());
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    std::sort(out.begin(), out.end(), [&](const Vec3& p, const Vec3& q) {
        return std::atan2((p - c).dot(v), (p - c).dot(u)) < std::atan2((q - c).dot(v), (q - c).dot(u));
    });
    // Points on an edge between two corners (collinear) are kept: the clip below handles them.
    return out;
}

/// `shape` clipped by the prism over the convex polygon `face` (>= 3 points, counter-clockwise
/// about n): the half-spaces through its edges with outward in-plane normals.
std::vector<Vec3> clipByFace(std::vector<Vec3> shape, const std::vector<Vec3>& face, const Vec3& n) {
    for (std::size_t i = 0; i < face.size() && !shape.empty(); ++i) {
        const Vec3 e = face[(i + 1) % face.size()] - face[i];
        const Vec3 outward = e.cross(n);  // counter-clockwise about n: e × n points out
        if (!(outward.norm() > 0)) continue;
        shape = clipConvexPolygon(shape, HalfSpace{face[i], outward});
    }
    return shape;
}

}  // namespace

ClosestSet closestSetOfPolytopes(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& axis, double distance,
                                 double tolerance, const Vec3& fallback) {
    ClosestSet set;
    if (!(distance > 0) || a.empty() || b.empty()) return set;
    const Vec3 n = axis.normalized();
    set.offset = distance * n;
    double maxA = -INFINITY, minB = INFINITY;
    for (const Vec3& p : a) maxA = std::max(maxA, n.dot(p));
    for (const Vec3& p : b) minB = std::min(minB, n.dot(p));
    std::vector<Vec3> fa, fb;
    for (const Vec3& p : a)
        if (n.dot(p) >= maxA - tolerance) fa.push_back(p);
    for (const Vec3& p : b)
        if (n.dot(p) <= minB + tolerance) fb.push_back(p - set.offset);  // moved onto A's plane
    fa = orderedFace(fa, n, tolerance);
    fb = orderedFace(fb, n, tolerance);
    std::vector<Vec3> onA;
    if (fa.size() >= 3) onA = clipByFace(fb.size() == 2 ? std::vector<Vec3>{fb[0], fb[1]} : fb, fa, n);
    else if (fb.size() >= 3) onA = clipByFace(fa, fb, n);
    else if (fa.size() == 2 && fb.size() == 2 && std::abs((fa[1] - fa[0]).normalized().dot((fb[1] - fb[0]).normalized())) >
                                                     1 - 1e-12) {
        // Parallel edges: their overlap along the common direction.
        const Vec3 dir = (fa[1] - fa[0]).normalized();
        const double a0 = std::min(dir.dot(fa[0]), dir.dot(fa[1])), a1 = std::max(dir.dot(fa[0]), dir.dot(fa[1]));
        const double b0 = std::min(dir.dot(fb[0]), dir.dot(fb[1])), b1 = std::max(dir.dot(fb[0]), dir.dot(fb[1]));
        const double lo = std::max(a0, b0), hi = std::min(a1, b1);
        const Vec3 base = fa[0] - dir.dot(fa[0]) * dir;
        if (hi >= lo) onA = {base + lo * dir, base + hi * dir};
    }
    // Merge what the clip left (duplicates at shared corners); nothing left (skew edges, a vertex,
    // rounding): GJK's one pair.
    set.onA = orderedFace(onA, n, tolerance);
    if (set.onA.empty()) set.onA = {fallback};
    return set;
}

}  // namespace cdlab
