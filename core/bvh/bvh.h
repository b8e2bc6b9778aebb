// Binary bounding-volume hierarchies (BVH) over the triangles of a TriangleMesh, with AABB or
// OBB nodes: construction (top-down median / SAH, bottom-up agglomerative), refitting after
// deformation, basic traversal (tree vs box / triangle / ray) and dual traversal (tree vs tree).
//
// Sources:
//  - C. Ericson, "Real-Time Collision Detection" (2005) §6.2.1 top-down construction (median of
//    the centroids on the longest axis), §6.2.3 bottom-up construction, §6.3.2 dual traversal
//    with the "descend larger" rule, §4.4.1 OBB-OBB separating axes.
//  - S. Gottschalk, M. Lin, D. Manocha, "OBBTree", SIGGRAPH 1996: OBB nodes fitted to the
//    triangles' covariance (core/bounding/bounding_volume_fit.h), split on the box's longest axis.
//  - I. Wald, "On fast construction of SAH-based bounding volume hierarchies", 2007: binned SAH.
//  - B. Walter, K. Bala, M. Kulkarni, K. Pingali, "Fast agglomerative clustering for rendering",
//    2008: bottom-up, repeatedly merge the pair of clusters whose union AABB has the smallest
//    surface area. Here in its plain form with cached nearest neighbours, O(n²) time on typical
//    input (O(n³) worst case), so it is limited to options.bottomUpMaxTriangles triangles
//    (status TooManyTrianglesForBottomUp above) instead of Walter's k-d tree search.
//  - G. van den Bergen, "Efficient collision detection of complex deformable models using AABB
//    trees", JGT 2(4), 1997: refit bottom-up keeping the topology.
//
// Layout: one flat node array; node 0 is the root; the two children of an inner node are
// adjacent (right == left + 1) and have larger indices than their parent (refit walks the array
// backwards). Each node covers a contiguous range [first, first + count) of triangleOrder
// (indices into the mesh's triangles). No per-node allocation.
//
// Frames: the tree is built in the mesh's body frame. Queries take the mesh's pose (Transform,
// core/base/types.h) and world-frame query objects. Leaf tests run on the WORLD triangles
// mesh.triangle(i, pose) (exact predicates of core/overlap/triangle_triangle.h / core/overlap/intersect_ray.h),
// so the set reported is exactly what a brute-force loop over the world triangles reports.
// Bounding-volume tests are conservative: every box is widened by a rounding margin (see
// bvh.cpp: kBvMarginRelative) so that rounding in transforms never prunes a touching pair.
// AABB nodes under a relative rotation are tested as OBBs (15-axis SAT of the two boxes); under
// no relative rotation (bitwise identity) as AABBs (3 axes).
#pragma once

#include <functional>
#include <vector>

#include "core/base/primitives.h"
#include "core/geometry/triangle_mesh.h"

namespace cdlab {

/// Bounding-volume type of the nodes.
enum class BvKind { Aabb, Obb };

/// How the topology is built.
enum class BvhBuildMethod {
    TopDownMedian,  ///< split at the median centroid on the longest axis (AABB: of the centroid
                    ///< box; OBB: the node box's longest axis, as Gottschalk's OBBTree)
    TopDownSah,     ///< binned SAH on the 3 coordinate axes (AABB surface areas, Wald 2007)
    BottomUp,       ///< agglomerative: merge the pair with the smallest union AABB surface area
};

/// Outcome of a build or refit. Only Ok trees may be traversed (others have no nodes).
enum class BvhStatus {
    Ok,                           ///< tree built (an empty mesh gives Ok with no nodes)
    InvalidMesh,                  ///< validateMesh failed (index out of range, NaN / inf vertex)
    TooManyTrianglesForBottomUp,  ///< BottomUp with more than options.bottomUpMaxTriangles
    TopologyMismatch,             ///< refit: the mesh's triangle count differs from the tree's
};

/// "ok", "invalid mesh", "too many triangles for bottom-up", "topology mismatch".
const char* nameOf(BvhStatus status);
/// "AABB", "OBB".
const char* nameOf(BvKind kind);
/// The scene spelling: "top_down_median", "top_down_sah", "bottom_up".
const char* nameOf(BvhBuildMethod method);

struct BvhBuildOptions {
    BvKind bvKind = BvKind::Obb;
    BvhBuildMethod method = BvhBuildMethod::TopDownMedian;
    /// A node with at most this many triangles is a leaf (>= 1). Every build splits until then.
    int maxLeafTriangles = 1;
    /// Bins per axis of the SAH build (>= 2).
    int sahBins = 16;
    /// BottomUp refuses larger meshes (its time is quadratic; see the header comment).
    int bottomUpMaxTriangles = 20000;
};

/// One node of the flat array.
struct BvhNode {
    int left = -1;    ///< first child, -1 for a leaf; the second child is left + 1
    int right = -1;   ///< second child (left + 1), -1 for a leaf
    int parent = -1;  ///< -1 for the root
    int depth = 0;    ///< root 0
    int first = 0;    ///< range [first, first + count) in Bvh::triangleOrder
    int count = 0;
    bool isLeaf() const { return left < 0; }
};

/// A BVH over one mesh (body frame). Build with buildBvh; refit with refitBvh.
struct Bvh {
    BvhStatus status = BvhStatus::Ok;
    BvKind kind = BvKind::Obb;
    BvhBuildMethod method = BvhBuildMethod::TopDownMedian;
    std::vector<BvhNode> nodes;      ///< nodes[0] is the root (when non-empty)
    std::vector<Aabb> aabbs;         ///< per node, when kind == Aabb (empty otherwise)
    std::vector<Obb> obbs;           ///< per node, when kind == Obb (empty otherwise)
    std::vector<int> triangleOrder;  ///< position in tree order -> mesh triangle index
    /// max |v| over the mesh's vertices (body frame): scales the rounding margin of BV tests.
    double vertexRadius = 0.0;

    bool empty() const { return nodes.empty(); }
    int triangleCount() const { return static_cast<int>(triangleOrder.size()); }
    /// The node's box in body frame as an OBB (an AABB node gives identity axes).
    Obb box(int node) const;
    /// Largest node depth (0 for a single leaf, -1 when empty).
    int height() const;
};

/// One node as the builder created it (top-down: parents before children; bottom-up: in merge
/// order, i.e. children before parents), for figures of the hierarchy levels.
struct BvhBuildStep {
    int node = -1;  ///< index in Bvh::nodes
    int depth = 0;
    int first = 0, count = 0;                               ///< triangle range in Bvh::triangleOrder
    Obb box{Vec3::Zero(), Vec3::Zero(), Mat3::Identity()};  ///< the node's box (AABB nodes: identity axes)
    /// Top-down inner nodes: the split. axis is the world axis (SAH, median on an AABB) or the
    /// index of the node box's axis (median on an OBB); position is the split coordinate along
    /// it (median: the median centroid's projection; SAH: the bin plane). -1 for leaves.
    int splitAxis = -1;
    double splitPosition = 0.0;
    /// SAH: the split's cost sum(area_child * count_child) / area_node; bottom-up: the merged
    /// AABB's surface area; 0 otherwise.
    double cost = 0.0;
    /// Traced SAH builds (nodes to BvhBuildTrace::candidatesToDepth): every bin plane with both
    /// sides non-empty, axis by axis, and the SAH cost the median split on the centroids' longest
    /// axis would have had (for comparison).
    struct SahCandidate {
        int axis = 0;
        double position = 0.0;  ///< the bin plane's coordinate
        int leftCount = 0, rightCount = 0;
        double leftArea = 0.0, rightArea = 0.0;  ///< child AABB surface area / the node's
        double cost = 0.0;                       ///< leftArea * leftCount + rightArea * rightCount
    };
    std::vector<SahCandidate> candidates;
    double medianCost = 0.0;
    int medianAxis = -1;
    double medianPosition = 0.0;
};
struct BvhBuildTrace {
    std::vector<BvhBuildStep> steps;
    /// SAH candidates are recorded for nodes of depth <= this only (each node has up to 3 (bins − 1);
    /// a 20000-triangle tree's every node would hold millions).
    int candidatesToDepth = 3;
};

/// Builds the hierarchy of options.bvKind over mesh's triangles (body frame) by options.method.
/// An invalid mesh gives status InvalidMesh and no nodes; an empty mesh status Ok, no nodes.
Bvh buildBvh(const TriangleMesh& mesh, const BvhBuildOptions& options = {}, BvhBuildTrace* trace = nullptr);

/// Refits every box bottom-up after the vertices of the mesh moved, keeping the topology (van
/// den Bergen 1997): AABB leaves from their triangles, AABB inner nodes as the union of the
/// children; OBB nodes keep their axes and get the extents of their triangles' vertices on
/// them. `deformed` must have the triangle count of the mesh the tree was built on
/// (TopologyMismatch otherwise, tree unchanged) and be valid (InvalidMesh, tree unchanged).
BvhStatus refitBvh(Bvh& bvh, const TriangleMesh& deformed);

/// Counters of one traversal (the AABB-vs-OBB comparison).
struct BvhQueryStats {
    long long bvTests = 0;        ///< bounding-volume overlap tests
    long long leafVisits = 0;     ///< leaves (or leaf pairs) whose boxes overlapped
    long long triangleTests = 0;  ///< exact primitive tests at the leaves
};

/// What one traversal step did.
enum class BvhTraversalAction {
    Prune,         ///< boxes disjoint: the subtree (pair) is skipped
    DescendA,      ///< boxes overlap; A's node is split (basic traversal: the node's children)
    DescendB,      ///< boxes overlap; B's node is split (dual traversal only)
    LeafTest,      ///< boxes overlap and both are leaves: the triangles are tested next
    TriangleTest,  ///< one exact triangle test (triangleA / triangleB, hit)
};

/// "prune", "descend A", "descend B", "leaf test", "triangle test".
const char* nameOf(BvhTraversalAction action);

/// One step of a traversal. Basic traversal: nodeB = -1, triangleB = -1.
struct BvhTraversalStep {
    int nodeA = -1, nodeB = -1;
    bool overlap = false;  ///< the BV test's answer (TriangleTest: unused, false)
    BvhTraversalAction action = BvhTraversalAction::Prune;
    int triangleA = -1, triangleB = -1;  ///< mesh triangle indices (TriangleTest only)
    bool triangleHit = false;            ///< TriangleTest: the exact test's answer
};
struct BvhTraversalTrace {
    std::vector<BvhTraversalStep> steps;
};

/// Result of a basic traversal: the mesh triangles in leaves whose box overlapped the query
/// (candidates, in traversal order) and those of them that pass the exact test (hits).
struct BvhQueryResult {
    std::vector<int> candidates;
    std::vector<int> hits;
    BvhQueryStats stats;
    /// Ray queries: the smallest t of the hits (world ray units) and its triangle (-1: none).
    double firstT = 0.0;
    int firstTriangle = -1;
};

/// Triangles of the mesh (under pose) overlapping the world box. Exact test per candidate:
/// testTriangleObb below (triangle taken to the box's frame, then Akenine-Möller).
BvhQueryResult queryBvhBox(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose, const Obb& box,
                           BvhTraversalTrace* trace = nullptr);

/// Triangles of the mesh (under pose) intersecting the world triangle (exact,
/// intersectTriangleTriangle on the world triangles).
BvhQueryResult queryBvhTriangle(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose,
                                const Triangle& triangle, BvhTraversalTrace* trace = nullptr);

/// Triangles of the mesh (under pose) hit by the world ray (exact decision, double-sided,
/// intersectRayTriangle on the world triangles), and the first hit (firstT, firstTriangle).
/// All hits are reported (no early termination at the first hit).
BvhQueryResult queryBvhRay(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose, const Ray& ray,
                           BvhTraversalTrace* trace = nullptr);

/// Closed triangle-OBB overlap: the triangle expressed in the box frame (axes^T (v - center)),
/// then testTriangleAabb against [-halfExtents, halfExtents] (core/overlap/sat_tests.h).
bool testTriangleObb(const Triangle& triangle, const Obb& box);

/// Called for each pair of overlapping leaves (node indices in A and B); return true to stop
/// the traversal (first-hit mode).
using BvhLeafPairCallback = std::function<bool(int leafA, int leafB)>;

/// Dual traversal of two trees under their poses (Ericson §6.3.2, iterative with a stack,
/// "descend larger": split A if B is a leaf or A's box is at least as large, by half
/// diagonal). Boxes are compared in A's body frame (B's boxes moved by the relative pose).
/// Calls onLeafPair for each overlapping leaf pair; returns the counters (triangleTests stays
/// 0: the callback does those). Both trees must be Ok; an empty tree gives no pairs.
BvhQueryStats traverseBvhPair(const Bvh& a, const Transform& poseA, const Bvh& b, const Transform& poseB,
                              const BvhLeafPairCallback& onLeafPair, BvhTraversalTrace* trace = nullptr);

}  // namespace cdlab
