// Separating-axis tests for boxes (Ericson, Real-Time Collision Detection §4.4.1 OBB-OBB,
// §5.3.3 segment-AABB, §5.2.9 triangle-AABB after Akenine-Möller, "Fast 3D Triangle-Box
// Overlap Testing", 2001).
//
// Two convex sets are disjoint iff their projections on some axis are disjoint; for these
// pairs a finite list of candidate axes suffices (face normals and edge-edge cross products).
// Every shape is closed: projections that touch (share an end point) do NOT separate, so
// touching counts as intersecting. World frame, any consistent length unit.
// Degenerate input: NaN / inf, empty boxes (min > max or negative half extents) give
// hit == false; a zero-length segment is a point, a zero-area triangle the segment or point it
// spans (a zero candidate axis is skipped: it never separates).
// The tests run in doubles; where noted an epsilon makes them conservative (a pair closer than
// that epsilon to touching may be reported as intersecting, never the reverse).
#pragma once

#include <vector>

#include "core/base/primitives.h"
#include "core/base/sat_axis_kind.h"

namespace cdlab {

/// One candidate axis, recorded for demos. Projections are onto the (not normalized) world axis,
/// measured from the box A's center: A covers [minA, maxA], B covers [minB, maxB].
struct SatAxisStep {
    SatAxisKind kind = SatAxisKind::FaceA;
    int indexA = -1;
    int indexB = -1;
    Vec3 axis = Vec3::Zero();
    double minA = 0.0, maxA = 0.0, minB = 0.0, maxB = 0.0;
    bool separating = false;
};
struct SatTrace {
    std::vector<SatAxisStep> steps;
};

/// Result of a SAT test. When !hit because an axis separates, separatingAxis is that step
/// (the last one in the trace); otherwise it is default.
struct SatResult {
    bool hit = false;
    SatAxisStep separatingAxis;
};

/// AABB-AABB overlap (Ericson §4.2.1): the three coordinate axes.
SatResult testAabbAabb(const Aabb& a, const Aabb& b, SatTrace* trace = nullptr);

/// Segment-AABB overlap (Ericson §5.3.3, TestSegmentAABB): the 3 box axes and the 3 products
/// box axis x segment direction. Conservative by kSatParallelEpsilon (see sat_tests.cpp) on the
/// cross-product axes, against rounding when the segment is nearly parallel to a box axis.
SatResult testSegmentAabb(const Segment& segment, const Aabb& box, SatTrace* trace = nullptr);

/// Segment-OBB overlap: testSegmentAabb in the box's frame (axes of the trace in world frame).
SatResult testSegmentObb(const Segment& segment, const Obb& box, SatTrace* trace = nullptr);

/// Triangle-AABB overlap (Akenine-Möller 2001; Ericson §5.2.9): 13 axes in the order 9 edge
/// cross products (box axis i x triangle edge j), 3 box face normals, 1 triangle normal.
SatResult testTriangleAabb(const Triangle& triangle, const Aabb& box, SatTrace* trace = nullptr);

/// OBB-OBB overlap (Ericson §4.4.1, after Gottschalk et al. 1996): 15 axes in the order A's 3
/// face normals, B's 3 face normals, 9 edge cross products A_i x B_j. Conservative by
/// kSatParallelEpsilon (see sat_tests.cpp) against rounding when edges are (nearly) parallel.
SatResult testObbObb(const Obb& a, const Obb& b, SatTrace* trace = nullptr);

}  // namespace cdlab
