#include "core/overlap/triangle_triangle.h"

#include <array>

#include "core/base/orient.h"
#include "core/overlap/intersect_ray.h"
#include "core/overlap/polygon_tests.h"

namespace cdlab {

namespace {

// Signs of the vertices of `t` relative to the plane of `p`; true when all three are strictly
// on the same side (no intersection possible).
bool strictlyOneSide(const Triangle& p, const Triangle& t, bool& allZero) {
    const int s0 = orient3d(p.a, p.b, p.c, t.a);
    const int s1 = orient3d(p.a, p.b, p.c, t.b);
    const int s2 = orient3d(p.a, p.b, p.c, t.c);
    allZero = s0 == 0 && s1 == 0 && s2 == 0;
    return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

// Contact points of the edges of `edges` with triangle `t`, appended to points.
void edgeContacts(const Triangle& edges, const Triangle& t, std::array<Vec3, 12>& points, int& count) {
    const Vec3 v[3] = {edges.a, edges.b, edges.c};
    for (int i = 0; i < 3; ++i) {
        const Segment s{v[i], v[(i + 1) % 3]};
        const RayTriangleHit hit = intersectSegmentTriangle(s, t);
        if (!hit.hit) continue;
        points[count++] = hit.point;
        if (hit.coplanar) {
            // The edge lies in t's plane: its overlap with t is a segment; its far end is the
            // first contact of the reversed edge.
            const RayTriangleHit back = intersectSegmentTriangle(Segment{s.b, s.a}, t);
            if (back.hit) points[count++] = back.point;
        }
    }
}

}  // namespace

TriangleTriangleResult intersectTriangleTriangle(const Triangle& a, const Triangle& b) {
    TriangleTriangleResult result;
    if (!a.allFinite() || !b.allFinite()) return result;
    const int axisA = projectionAxis(a);
    if (axisA < 0 || projectionAxis(b) < 0) return result;  // zero-area triangle

    // Möller / Guigue-Devillers rejection: one triangle strictly on one side of the other's
    // plane.
    bool bOnPlaneA = false, aOnPlaneB = false;
    if (strictlyOneSide(a, b, bOnPlaneA)) return result;
    if (strictlyOneSide(b, a, aOnPlaneB)) return result;

    if (bOnPlaneA) {
        // Coplanar: exact 2D SAT in the projection that keeps a non-degenerate (b lies in the
        // same plane, so that projection keeps it non-degenerate too).
        const std::array<Vec2, 3> a2 = {dropAxis(a.a, axisA), dropAxis(a.b, axisA), dropAxis(a.c, axisA)};
        const std::array<Vec2, 3> b2 = {dropAxis(b.a, axisA), dropAxis(b.b, axisA), dropAxis(b.c, axisA)};
        result.coplanar = true;
        result.hit = intersectConvexPolygons2d(a2, b2).hit;
        return result;
    }

    // Non-coplanar: the common set is a segment of the line where the planes meet, and each of
    // its end points is where an edge of one triangle meets the other. Collect those contacts.
    std::array<Vec3, 12> points;
    int count = 0;
    edgeContacts(a, b, points, count);
    edgeContacts(b, a, points, count);
    if (count == 0) return result;
    result.hit = true;
    result.hasSegment = true;
    // All contacts lie on the segment (up to rounding); its ends are the farthest pair.
    int best0 = 0, best1 = 0;
    double bestDist = -1.0;
    for (int i = 0; i < count; ++i) {
        for (int j = i; j < count; ++j) {
            const double d = (points[i] - points[j]).squaredNorm();
            if (d > bestDist) {
                bestDist = d;
                best0 = i;
                best1 = j;
            }
        }
    }
    result.segmentStart = points[best0];
    result.segmentEnd = points[best1];
    return result;
}

}  // namespace cdlab
