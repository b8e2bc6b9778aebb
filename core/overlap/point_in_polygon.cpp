#include "core/overlap/point_in_polygon.h"

#include <cmath>
#include <numbers>

#include "core/base/orient.h"

namespace cdlab {

namespace {

bool usable(std::span<const Vec2> polygon, const Vec2& p) {
    if (polygon.size() < 3 || !p.allFinite()) return false;
    for (const Vec2& v : polygon)
        if (!v.allFinite()) return false;
    return true;
}

/// p lies on the closed segment ab (exact: collinear, and inside the segment's bounding box).
bool onSegment(const Vec2& a, const Vec2& b, const Vec2& p) {
    return orient2d(a, b, p) == 0 && p.x() >= std::min(a.x(), b.x()) && p.x() <= std::max(a.x(), b.x()) &&
           p.y() >= std::min(a.y(), b.y()) && p.y() <= std::max(a.y(), b.y());
}

bool onBoundary(std::span<const Vec2> polygon, const Vec2& p) {
    for (std::size_t i = 0; i < polygon.size(); ++i)
        if (onSegment(polygon[i], polygon[(i + 1) % polygon.size()], p)) return true;
    return false;
}

/// Sign of the polygon's signed area: the shoelace sum taken about the first corner (so a polygon
/// far from the origin keeps its digits), trusted unless it is within its rounding bound of zero.
int orientationOf(std::span<const Vec2> polygon) {
    const Vec2 o = polygon[0];
    double twiceArea = 0.0, scale = 0.0;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
        const Vec2 a = polygon[i] - o, b = polygon[i + 1] - o;
        twiceArea += a.x() * b.y() - a.y() * b.x();
        scale += std::abs(a.x() * b.y()) + std::abs(a.y() * b.x());
    }
    // The differences are rounded by <= 2^-53 relative, each term by a few more, the sum by n more.
    const double bound = double(polygon.size() + 4) * 2.3e-16 * scale;
    return twiceArea > bound ? 1 : twiceArea < -bound ? -1 : 0;
}

}  // namespace

EdgeSideResult sameSideOfEveryEdge(std::span<const Vec2> polygon, const Vec2& p) {
    EdgeSideResult r;
    if (!usable(polygon, p)) return r;
    r.orientation = orientationOf(polygon);
    bool outer = r.orientation == 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const int side = orient2d(polygon[i], polygon[(i + 1) % polygon.size()], p) * r.orientation;
        r.sides.push_back(side);
        if (side < 0 && r.firstOuterEdge < 0) r.firstOuterEdge = int(i);
        if (side < 0) outer = true;
    }
    r.inside = !outer;
    // On the boundary: inside, and on some edge's line within that edge.
    r.onBoundary = r.inside && onBoundary(polygon, p);
    return r;
}

AngleSumResult angleSummation(std::span<const Vec2> polygon, const Vec2& p) {
    AngleSumResult r;
    if (!usable(polygon, p)) return r;
    if (onBoundary(polygon, p)) {
        r.onBoundary = r.inside = true;
        return r;
    }
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2 u = polygon[i] - p, w = polygon[(i + 1) % polygon.size()] - p;
        const double angle = std::atan2(u.x() * w.y() - u.y() * w.x(), u.dot(w));
        r.angles.push_back(angle);
        r.total += angle;
    }
    // Off the boundary the total is a multiple of 2π up to n roundings of atan2: rounding it is exact.
    r.winding = int(std::lround(r.total / (2.0 * std::numbers::pi)));
    r.inside = r.winding != 0;
    return r;
}

CrossingNumberResult crossingNumber(std::span<const Vec2> polygon, const Vec2& p) {
    CrossingNumberResult r;
    if (!usable(polygon, p)) return r;
    if (onBoundary(polygon, p)) {
        r.onBoundary = r.inside = true;
        return r;
    }
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2& a = polygon[i];
        const Vec2& b = polygon[(i + 1) % polygon.size()];
        const bool aAbove = a.y() > p.y(), bAbove = b.y() > p.y();
        if (aAbove == bAbove) continue;  // both on one side of the ray's line (half-open rule)
        // The edge crosses the line y = p.y; the crossing is right of p iff p is left of the
        // upward-directed edge: orient2d(lower, upper, p) > 0 (exact; 0 is the boundary, excluded above).
        const int side = bAbove ? orient2d(a, b, p) : orient2d(b, a, p);
        if (side <= 0) continue;
        r.crossingEdges.push_back(int(i));
        r.crossingX.push_back(a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    r.inside = r.crossingEdges.size() % 2 == 1;
    return r;
}

}  // namespace cdlab
