#include "core/overlap/polygon_tests.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/orient.h"

namespace cdlab {

namespace {

// p lies in the axis-aligned bounding box of a and b; for p collinear with a, b this is
// "p on the closed segment ab".
bool inBox(const Vec2& a, const Vec2& b, const Vec2& p) {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
           p.y() <= std::max(a.y(), b.y());
}

// Winding of a convex polygon: the sign of the first nonzero orient2d(v0, v_i, v_i+1),
// 0 for zero area.
int winding(std::span<const Vec2> poly) {
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
        const int s = orient2d(poly[0], poly[i], poly[i + 1]);
        if (s != 0) return s;
    }
    return 0;
}

// Exact test for polygons of which at least one has zero area: convex sets meet iff one holds a
// vertex of the other or their boundaries cross.
bool intersectByFeatures(std::span<const Vec2> a, std::span<const Vec2> b) {
    for (const Vec2& v : a)
        if (pointInConvexPolygon2d(b, v)) return true;
    for (const Vec2& v : b)
        if (pointInConvexPolygon2d(a, v)) return true;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (segmentsIntersect2d(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    return false;
}

// Edge i of `poly` (winding w) separates it from `other` iff every vertex of other lies
// strictly on the outer side of the edge's line: the SAT axis is the edge's outward normal
// and poly's extent along it ends exactly on that line.
bool edgeSeparates(std::span<const Vec2> poly, int w, std::size_t i, std::span<const Vec2> other) {
    const Vec2& e0 = poly[i];
    const Vec2& e1 = poly[(i + 1) % poly.size()];
    for (const Vec2& v : other)
        if (orient2d(e0, e1, v) * w >= 0) return false;
    return true;
}

}  // namespace

bool segmentsIntersect2d(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
    const int o1 = orient2d(p0, p1, q0), o2 = orient2d(p0, p1, q1);
    const int o3 = orient2d(q0, q1, p0), o4 = orient2d(q0, q1, p1);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
    // Touching / collinear cases: an endpoint on the other segment.
    if (o1 == 0 && inBox(p0, p1, q0)) return true;
    if (o2 == 0 && inBox(p0, p1, q1)) return true;
    if (o3 == 0 && inBox(q0, q1, p0)) return true;
    if (o4 == 0 && inBox(q0, q1, p1)) return true;
    return false;
}

bool pointInConvexPolygon2d(std::span<const Vec2> polygon, const Vec2& p) {
    if (polygon.empty() || !allFinite(polygon) || !p.allFinite()) return false;
    const int w = winding(polygon);
    if (w == 0) {
        // Zero area: the polygon is the segment between its two extreme vertices (or a point).
        // p is in it iff collinear with every edge and inside the vertices' bounding box.
        Vec2 lo = polygon[0], hi = polygon[0];
        for (const Vec2& v : polygon) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
            if (orient2d(polygon[0], v, p) != 0) return false;
        }
        return inBox(lo, hi, p);
    }
    // Ericson §5.4.1 for convex polygons: p is inside iff it is on the inner (closed) side of
    // every edge.
    for (std::size_t i = 0; i < polygon.size(); ++i)
        if (orient2d(polygon[i], polygon[(i + 1) % polygon.size()], p) * w < 0) return false;
    return true;
}

PolygonOverlapResult intersectConvexPolygons2d(std::span<const Vec2> a, std::span<const Vec2> b) {
    PolygonOverlapResult result;
    if (a.empty() || b.empty() || !allFinite(a) || !allFinite(b)) return result;
    const int wa = winding(a), wb = winding(b);
    if (wa == 0 || wb == 0) {
        result.hit = intersectByFeatures(a, b);
        return result;
    }
    // 2D SAT (Ericson §5.2.1): two convex polygons are disjoint iff an edge normal of one of
    // them separates them.
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (edgeSeparates(a, wa, i, b)) {
            result.separatingPolygon = 0;
            result.separatingEdge = static_cast<int>(i);
            return result;
        }
    }
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (edgeSeparates(b, wb, i, a)) {
            result.separatingPolygon = 1;
            result.separatingEdge = static_cast<int>(i);
            return result;
        }
    }
    result.hit = true;
    return result;
}

LineClip2d clipLineToConvexPolygon2d(std::span<const Vec2> polygon, const Vec2& p, const Vec2& d, double tMin,
                                     double tMax) {
    LineClip2d clip;
    const int w = winding(polygon);
    if (w == 0 || !(tMin <= tMax)) return clip;
    // Cyrus-Beck: inside edge i  <=>  w * cross(e, p + t d - v_i) >= 0, linear in t.
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2& v = polygon[i];
        const Vec2 e = polygon[(i + 1) % polygon.size()] - v;
        const Vec2 m = p - v;
        const double c0 = w * (e.x() * m.y() - e.y() * m.x());
        const double c1 = w * (e.x() * d.y() - e.y() * d.x());
        if (c1 == 0.0) {
            if (c0 < 0.0) return clip;  // parallel to the edge and outside it
        } else if (c1 > 0.0) {
            tMin = std::max(tMin, -c0 / c1);
        } else {
            tMax = std::min(tMax, -c0 / c1);
        }
        if (tMin > tMax) return clip;
    }
    clip.hit = true;
    clip.tEnter = tMin;
    clip.tExit = tMax;
    return clip;
}

Vec3 polygonNormal(std::span<const Vec3> polygon) {
    // Newell's method (Ericson §12.3.4): robust for nearly collinear vertices.
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec3& u = polygon[i];
        const Vec3& v = polygon[(i + 1) % polygon.size()];
        n.x() += (u.y() - v.y()) * (u.z() + v.z());
        n.y() += (u.z() - v.z()) * (u.x() + v.x());
        n.z() += (u.x() - v.x()) * (u.y() + v.y());
    }
    const double len = n.norm();
    return len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3(Vec3::Zero());
}

namespace {

std::vector<Vec2> project(std::span<const Vec3> polygon, int axis) {
    std::vector<Vec2> out;
    out.reserve(polygon.size());
    for (const Vec3& v : polygon) out.push_back(dropAxis(v, axis));
    return out;
}

// Exact test for p on the segment / point spanned by collinear 3D vertices: collinear in all
// three coordinate projections and inside the bounding box.
bool onDegeneratePolygon3d(std::span<const Vec3> polygon, const Vec3& p) {
    for (int axis = 0; axis < 3; ++axis) {
        const std::vector<Vec2> poly = project(polygon, axis);
        if (!pointInConvexPolygon2d(poly, dropAxis(p, axis))) return false;
    }
    return true;
}

}  // namespace

bool pointInConvexPolygon3d(std::span<const Vec3> polygon, const Vec3& p, double planeTolerance) {
    if (polygon.empty() || !p.allFinite()) return false;
    for (const Vec3& v : polygon)
        if (!v.allFinite()) return false;
    const Vec3 n = polygonNormal(polygon);
    if (n.isZero(0.0)) return onDegeneratePolygon3d(polygon, p);
    if (!(std::abs(n.dot(p - polygon[0])) <= planeTolerance)) return false;
    const int axis = dominantAxis(n);
    return pointInConvexPolygon2d(project(polygon, axis), dropAxis(p, axis));
}

PolygonOverlapResult intersectCoplanarConvexPolygons3d(std::span<const Vec3> a, std::span<const Vec3> b,
                                                       double planeTolerance) {
    PolygonOverlapResult result;
    if (a.empty() || b.empty()) return result;
    Vec3 n = polygonNormal(a);
    if (n.isZero(0.0)) n = polygonNormal(b);
    if (n.isZero(0.0)) {
        // Both have zero area (segments or points) in a common plane. Meeting in 3D implies
        // meeting in every coordinate projection; conversely at least one coordinate axis is
        // not parallel to the common plane, and that projection is one-to-one on it. So the
        // exact 2D test on all three projections decides it.
        for (int axis = 0; axis < 3; ++axis)
            if (!intersectConvexPolygons2d(project(a, axis), project(b, axis)).hit) return result;
        result.hit = true;
        return result;
    }
    const Vec3& origin = polygonNormal(a).isZero(0.0) ? b[0] : a[0];
    for (const Vec3& v : a)
        if (!(std::abs(n.dot(v - origin)) <= planeTolerance)) return result;
    for (const Vec3& v : b)
        if (!(std::abs(n.dot(v - origin)) <= planeTolerance)) return result;
    const int axis = dominantAxis(n);
    return intersectConvexPolygons2d(project(a, axis), project(b, axis));
}

}  // namespace cdlab
