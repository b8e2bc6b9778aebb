// Closest point of a convex planar polygon (an n-gon in 3D) to a point, with its Voronoi region: n
// vertex regions, n edge regions and the face (Ericson, Real-Time Collision Detection §5.1.5's
// region tests for a triangle, carried to n sides). In the polygon's plane, with its unit normal N
// (Newell's, counter-clockwise corners seen from +N) and the outward edge normals m_i = e_i × N of
// the edges e_i = v_{i+1} − v_i:
//   vertex i:  (p − v_i)·e_i <= 0  and  (p − v_i)·(v_{i−1} − v_i) <= 0   (behind both edges' ends);
//   edge i:    (p − v_i)·m_i > 0   and  0 < (p − v_i)·e_i < e_i·e_i         (outside the edge line, over it);
//   face:      otherwise (inside every edge line).
// Vertices are tested first, then edges (Ericson's order: ties go to the lower dimension). The
// tests run in doubles (the triangle's exact signs are core/closest/closest_point.h's); a point that
// rounding lets past every vertex and edge test while outside an edge line gets the nearest edge
// point. Degenerate input (fewer than 3 corners, zero area, a repeated or collinear corner — every
// corner must turn — NaN / inf): invalid.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// One region test as made: the candidate ("v2", "v2v3"), its two terms and whether it holds.
struct PolygonRegionTest {
    std::string candidate;
    double first = 0.0, second = 0.0;
    bool accepted = false;
};

struct ClosestPointPolygonResult {
    bool valid = false;
    int dimension = 2;   ///< of the feature: 0 vertex, 1 edge, 2 face
    int index = -1;      ///< vertex i, or edge i (v_i v_{i+1}); -1 for the face
    Vec3 point = Vec3::Zero();
    double distance = 0.0;
    Vec3 normal = Vec3::UnitZ();
    std::vector<PolygonRegionTest> tests;
};

/// "v2", "v2v3" or "face".
std::string regionName(const ClosestPointPolygonResult& result, int corners);

ClosestPointPolygonResult closestPointOnConvexPolygon(const Vec3& p, std::span<const Vec3> polygon);

/// The in-plane Voronoi regions, clipped `margin` beyond the polygon: a wedge per vertex, a strip per
/// edge (edge i: v_i, v_{i+1} and their offsets along m_i), and the face; each counter-clockwise
/// about N. Empty when the polygon is invalid.
struct PolygonVoronoiDiagram {
    std::vector<std::vector<Vec3>> vertexRegions, edgeRegions;
    std::vector<Vec3> face;
    Vec3 normal = Vec3::UnitZ();
};
PolygonVoronoiDiagram polygonVoronoiRegions(std::span<const Vec3> polygon, double margin);

}  // namespace cdlab
