// Convex hull of a 3D point cloud: randomized incremental construction with a conflict graph
// (de Berg, Cheong, van Kreveld, Overmars, "Computational Geometry", 3rd ed., ch. 11.2), followed
// by merging of coplanar triangles into convex polygons (as Qhull does after construction:
// Barber, Dobkin, Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM TOMS 1996, §4).
//
// Outline:
//   1. Reject empty input and NaN/Inf coordinates; translate the cloud to its bounding-box centre.
//   2. Initial tetrahedron from extreme points: p0 = lowest x, p1 = farthest from p0,
//      p2 = farthest from line p0p1, p3 = farthest from plane p0p1p2 (each must clear eps, else
//      AllCoincident / AllCollinear / AllCoplanar).
//   3. Remaining points in a seeded random order (splitmix64 Fisher-Yates: deterministic on every
//      platform). Conflict graph: each point lists the faces it sees, each face the points that see it.
//   4. Insert p_r: the visible region is grown from its farthest conflict face over neighbours that
//      p_r sees by more than eps (depth-first, so the horizon comes out as an ordered loop); the
//      visible faces are deleted and a cone of triangles (horizon edge, p_r) is added. The conflicts
//      of a new face are found among the points of the two faces of its horizon edge (de Berg, lemma 11.6).
//   5. Merge adjacent triangles whose vertices lie within mergeTolerance of a seed triangle's plane
//      (largest seeds first) into polygons, then merge groups across concave edges; keep a merge only
//      if its boundary is one simple loop and convex within tolerance (else its triangles stay). Remove boundary
//      vertices with exactly two incident faces that are collinear with their neighbours (such a vertex is collinear in
//      both faces at once).
//
// Tolerance: eps = epsilonFactor * DBL_EPSILON * (max |coordinate| + bounding-box diagonal), default
// factor 4096 (eps ~ 9e-13 of the scale: far below any modelled feature, far above the rounding of
// the distance tests, whose planes come from exactly rounded cross products, core/geometry/polyhedron.h
// accurateCross). Points within eps of the hull are "not outside": duplicates and points
// perturbed off a face by up to ~eps are absorbed. Cone triangles that would fold under a
// neighbour g (r coplanar with g within eps, or r within eps of the horizon edge) make g part of
// the visible region, so no slivers or folds are built. Merging uses mergeTolerance = 4 eps; groups
// meeting at a concave edge (deeper than 2 * mergeTolerance, possible when input noise is just
// above eps) are merged too. Result: every input point is inside within a few eps, every face
// planar within ~2 mergeTolerance (validate() with its default tolerance passes), and every
// result vertex is an input point (exact coordinates; inputIndex says which).
// Known limitation: input noise of 2-10 eps off a plane (e.g. points scattered 1e-11 off cube faces)
// leaves faces accurate only to ~100 x the noise (~1e-9 of the scale); validate() then needs that
// tolerance. Raise epsilonFactor above the noise when the input is known to be noisy.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

enum class HullStatus {
    Ok,              ///< polyhedron, inputIndex and the counters are meaningful
    EmptyInput,      ///< no points
    NonFiniteInput,  ///< badIndex = first point with a NaN or Inf coordinate
    AllCoincident,   ///< every point within eps of the first: no extent
    AllCollinear,    ///< every point within eps of one line
    AllCoplanar,     ///< every point within eps of one plane: no volume
    InternalError,   ///< the final mesh failed its topology check (never expected; message says why)
};

/// Name of a status, e.g. "AllCoplanar".
const char* nameOf(HullStatus status);

struct HullOptions {
    double epsilonFactor = 4096.0;   ///< eps = epsilonFactor * DBL_EPSILON * (max|coord| + diagonal)
    std::optional<double> absoluteEpsilon = std::nullopt;  ///< set and > 0: this eps instead (length units); else automatic
    double mergeFactor = 4.0;        ///< merge tolerance = mergeFactor * eps (folds of eps can chain)
    bool mergeCoplanarFaces = true;  ///< false: output the triangulated hull
    bool removeCollinearVertices = true;
    bool shuffle = true;  ///< false: insert in input order (worst case O(n^2))
    std::uint64_t shuffleSeed = 0x9E3779B97F4A7C15ull;
};

struct HullResult {
    HullStatus status = HullStatus::EmptyInput;
    std::string message;          ///< one line; empty when Ok
    int badIndex = -1;            ///< NonFiniteInput: the offending point index
    ConvexPolyhedron polyhedron;  ///< Ok: the hull (input coordinates, faces CCW from outside)
    std::vector<int> inputIndex;  ///< Ok: polyhedron vertex i is points[inputIndex[i]]
    double epsilon = 0.0;         ///< visibility tolerance used (length units)
    double mergeTolerance = 0.0;  ///< coplanarity tolerance used for merging
    int triangleCount = 0;        ///< triangles before merging
    int droppedPoints = 0;        ///< points whose visible region was not a disc (they lie within
                                  ///< a few eps of the hull); normally 0
    bool ok() const { return status == HullStatus::Ok; }
};

/// A hull triangle in a trace: a stable id and its corners (input coordinates).
struct HullTraceFace {
    int id = -1;
    Triangle triangle;
};

/// One insertion of the incremental algorithm.
struct HullTraceStep {
    int pointIndex = -1;  ///< input index of the inserted point
    Vec3 point = Vec3::Zero();
    int eyeFaceId = -1;                   ///< farthest face the point sees
    double eyeDistance = 0.0;             ///< its distance above that face
    bool skipped = false;                 ///< visible region not a disc: point dropped, hull unchanged
    std::vector<int> visibleFaceIds;      ///< faces deleted by this step
    std::vector<Segment> horizon;         ///< ordered loop, counter-clockwise seen from the point
    std::vector<HullTraceFace> newFaces;  ///< the cone, one per horizon edge, same order
    int hullFaceCount = 0;                ///< triangles on the hull after the step
};

/// Everything the construction did, for demos (recorded in every build type when non-null).
struct HullTrace {
    std::array<int, 4> initialIndices{{-1, -1, -1, -1}};  ///< input indices of the tetrahedron
    std::vector<HullTraceFace> initialFaces;
    std::vector<HullTraceStep> steps;           ///< one per point that was outside when its turn came
    std::vector<HullTraceFace> finalTriangles;  ///< triangulated hull before merging
    int mergedGroups = 0;                       ///< polygons made of 2+ triangles
    int rejectedMerges = 0;                     ///< groups split back into triangles (not a convex disc)
    int removedCollinearVertices = 0;
};

/// Convex hull of points (any frame, length units). Never throws; status says what went wrong.
HullResult convexHull(std::span<const Vec3> points, const HullOptions& options = {}, HullTrace* trace = nullptr);

}  // namespace cdlab
