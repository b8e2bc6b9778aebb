// Point in a simple or self-intersecting polygon, three ways (Ericson, Real-Time Collision
// Detection §5.4.1; Haines, "Point in Polygon Strategies", Graphics Gems IV, 1994):
//  - same side of every edge: n orientation tests, right only for convex polygons;
//  - angle summation: the signed angles the edges subtend at p add up to 2π times the winding
//    number (n atan2 calls: the slow one, and the one that counts windings);
//  - crossing number: a ray from p toward +x crosses the boundary an odd number of times iff p
//    is inside (even-odd rule; n cheap edge tests, right for any polygon).
// Edges run v[i] -> v[i+1 mod n]. Every side and crossing decision is exact for the double inputs
// (orient2d of core/base/orient.h); the polygon's orientation (for the edge-side test) comes from its
// area in doubles, zero when within rounding of zero. A point on the boundary is reported as such by
// the angle and crossing tests (closed polygon), and by the edge-side test when it says inside.
// Degenerate input (fewer than 3 vertices, NaN / inf) gives inside == false, onBoundary == false.
#pragma once

#include <span>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// Same side of every edge: orient2d(v_i, v_{i+1}, p) per edge, compared with the polygon's
/// orientation (the sign of its area). inside: no edge has p strictly on its outer side.
struct EdgeSideResult {
    bool inside = false;
    bool onBoundary = false;
    int orientation = 0;          ///< +1 counterclockwise, -1 clockwise, 0 zero area (never inside)
    std::vector<int> sides;       ///< per edge: orient2d sign times orientation (+1 inner side, -1 outer, 0 on the line)
    int firstOuterEdge = -1;      ///< the first edge with p strictly outside (where the test stops), or -1
};
EdgeSideResult sameSideOfEveryEdge(std::span<const Vec2> polygon, const Vec2& p);

/// Angle summation: per edge the signed angle from v_i - p to v_{i+1} - p in (-π, π]; the sum
/// is 2π * winding. inside: winding != 0 (the nonzero rule). When p is on the boundary the
/// angles are not defined there: onBoundary, angles empty.
struct AngleSumResult {
    bool inside = false;
    bool onBoundary = false;
    std::vector<double> angles;   ///< radians, per edge
    double total = 0.0;           ///< radians
    int winding = 0;              ///< round(total / 2π)
};
AngleSumResult angleSummation(std::span<const Vec2> polygon, const Vec2& p);

/// Crossing number: edges crossing the ray p + t (1, 0), t > 0, counted with the half-open rule
/// (an edge counts when exactly one end point is strictly above p's line), so a ray through a
/// vertex counts it once for a crossing and 0 or 2 times for a touch.
struct CrossingNumberResult {
    bool inside = false;
    bool onBoundary = false;
    std::vector<int> crossingEdges;   ///< edge indices, in edge order
    std::vector<double> crossingX;    ///< x of each crossing (floating point, for drawing)
};
CrossingNumberResult crossingNumber(std::span<const Vec2> polygon, const Vec2& p);

}  // namespace cdlab
