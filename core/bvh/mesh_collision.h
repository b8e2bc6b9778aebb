// Mesh-mesh collision of triangle soups through bounding-volume hierarchies: the dual
// traversal of core/bvh/bvh.h (Ericson, Real-Time Collision Detection §6.3.2) with the exact
// triangle-triangle test of core/overlap/triangle_triangle.h at the leaves (Gottschalk et al.,
// "OBBTree", SIGGRAPH 1996, §5).
//
// The leaf test runs on the world triangles mesh.triangle(i, pose), and the bounding-volume
// tests are conservative (bvh.h), so the pairs reported are exactly those of a brute-force loop
// over all pairs of world triangles with intersectTriangleTriangle (touching counts; zero-area
// triangles never hit).
#pragma once

#include <vector>

#include "core/bvh/bvh.h"
#include "core/geometry/triangle_mesh.h"

namespace cdlab {

/// A pair of intersecting triangles: index a in mesh A, index b in mesh B.
struct TrianglePair {
    int a = -1;
    int b = -1;
    bool operator==(const TrianglePair&) const = default;
};

enum class MeshCollisionStatus {
    Ok,
    InvalidTree,       ///< a tree's status is not Ok (invalid mesh, bottom-up limit)
    TreeMeshMismatch,  ///< a tree's triangle count differs from its mesh's
};

struct MeshCollisionOptions {
    /// Stop at the first intersecting pair (pairs then has at most one element).
    bool firstHitOnly = false;
};

/// Result: hit iff some pair intersects; pairs in traversal order (all of them unless
/// firstHitOnly); stats = BV tests, overlapping leaf pairs, triangle tests.
struct MeshCollisionResult {
    MeshCollisionStatus status = MeshCollisionStatus::Ok;
    bool hit = false;
    std::vector<TrianglePair> pairs;
    BvhQueryStats stats;
};

/// All intersecting triangle pairs of mesh A under poseA and mesh B under poseB, with their
/// trees (built on the same meshes, body frame; any BV kinds, any build methods). The trace
/// receives the traversal steps followed, after each LeafTest, by its TriangleTest steps.
MeshCollisionResult collideMeshes(const TriangleMesh& meshA, const Bvh& bvhA, const Transform& poseA,
                                  const TriangleMesh& meshB, const Bvh& bvhB, const Transform& poseB,
                                  const MeshCollisionOptions& options = {}, BvhTraversalTrace* trace = nullptr);

/// The O(n m) reference: every pair of world triangles (for benchmarks; meshes must be valid).
/// stats.triangleTests = n m (or fewer with firstHitOnly). Pairs in order (a, then b).
MeshCollisionResult collideMeshesBruteForce(const TriangleMesh& meshA, const Transform& poseA,
                                            const TriangleMesh& meshB, const Transform& poseB,
                                            const MeshCollisionOptions& options = {});

}  // namespace cdlab
