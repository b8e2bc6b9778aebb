// Closest point of a solid oriented box to a point, with its Voronoi region: the box's 8 vertex, 12
// edge and 6 face regions and the inside, 27 in all (Ericson, Real-Time Collision Detection §5.1.4,
// ClosestPtPointOBB). In the box's frame the regions are the cells of a 3 × 3 × 3 grid: along each
// axis the point's coordinate u = (p − center)·axis is below −e, between, or above +e (the slabs'
// tests); the axes where it lies outside name the feature (three: a vertex, two: an edge, one: a
// face, none: inside), and the closest point clamps u to [−e, e] on each axis.
// Ties: a coordinate exactly at ±e counts as inside the slab (the face wins over the edge, the edge
// over the vertex: the closest point is the same there). NaN / inf or negative half extents: invalid.
#pragma once

#include <array>
#include <string>

#include "core/base/primitives.h"

namespace cdlab {

/// One axis's slab test: the point's coordinate in the box frame against ±halfExtent.
struct BoxAxisTest {
    double coordinate = 0.0;  ///< u_i = (p − center) · axis_i
    double halfExtent = 0.0;
    int side = 0;             ///< −1: u < −e, 0: within [−e, e], +1: u > e
};

struct BoxRegionResult {
    bool valid = false;
    std::array<BoxAxisTest, 3> tests{};
    int dimension = 3;           ///< of the feature: 0 vertex, 1 edge, 2 face, 3 inside
    Vec3 point = Vec3::Zero();   ///< the closest point of the solid box (p itself inside)
    double distance = 0.0;
    /// The feature's corners by box corner index (bit i set: the + side of axis i): 1 for a vertex, 2
    /// for an edge, 4 for a face, none inside.
    std::vector<int> corners;
};

/// The region's name: "vertex +x−y+z", "edge +x+y", "face −z", "inside".
std::string regionName(const BoxRegionResult& result);

BoxRegionResult closestPointOnBox(const Vec3& p, const Obb& box);

}  // namespace cdlab
