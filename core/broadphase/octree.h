// Octree over axis-aligned boxes, for broad-phase pair finding and box queries (Ericson,
// Real-Time Collision Detection §7.3.1 octrees, §7.3.2 object assignment and TestAllCollisions,
// §7.3.6 loose octrees; loose octree after Ulrich, "Loose
// Octrees", Game Programming Gems, 2000).
//
// Each node is a cubic-ish cell (the root is the given or fitted bounds, cut at its midpoint on
// all three axes). An object (a closed Aabb, touching counts as overlapping exactly as in
// testAabbAabb, core/overlap/sat_tests.h) is stored in the deepest node whose cell contains it with a
// gap on every split plane: a box that touches or crosses a child's split plane stays in the
// parent. That strictness is what makes the pair query exact: two objects in different
// subtrees of a node lie strictly on opposite sides of one of its split planes, so closed
// boxes in such subtrees can never touch, and every overlapping pair has one object in an
// ancestor-or-same node of the other.
//
// Loose octree (looseness k > 1): every cell is enlarged by the factor k about its centre and
// an object goes into the deepest node whose loose cell contains it; with k = 2 an object
// whose largest extent is <= half a cell's size always fits at that cell's depth (by its
// centre), so a small object on a split plane sits at its own size's depth, not at the root. Loose cells of
// siblings overlap, so pairs are then found by box queries against the loose cells.
//
// Frame: world; any length unit. Degenerate input: boxes with NaN / inf or min > max on an axis
// are not inserted (listed in OctreeResult::rejected); zero-size boxes are fine; boxes outside
// the given root bounds stay in the root (the root is an ancestor of everything, so pairs stay
// exact). Recursion is bounded by maxDepth; objects all on one point do not loop.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/aabb_ops.h"
#include "core/base/primitives.h"

namespace cdlab {

struct OctreeOptions {
    int maxDepth = 8;            ///< the root has depth 0; nodes at maxDepth are never split
    int maxObjectsPerLeaf = 4;   ///< a node with more objects than this (at its depth) is split
    double looseness = 1.0;      ///< k >= 1: cells enlarged by k about their centre (1 = classic)
    bool useRootBounds = false;  ///< true: rootBounds is the root cell; false: fitted to the input
    Aabb rootBounds{Vec3::Zero(), Vec3::Zero()};
};

enum class OctreeStatus {
    Ok,            ///< every box inserted
    SomeRejected,  ///< some boxes were invalid (NaN / inf / min > max): see rejected
    Empty,         ///< no valid box: the tree is a single empty root
};

/// One node. cell is the tight cell (the cut), looseCell the cell the objects fit in (== cell
/// for looseness 1). children[o] is the child for octant o (bit 0: +x half, bit 1: +y, bit 2:
/// +z) or -1. objects are input indices stored in this node.
struct OctreeNode {
    Aabb cell;
    Aabb looseCell;
    int depth = 0;
    int parent = -1;
    std::array<int, 8> children{-1, -1, -1, -1, -1, -1, -1, -1};
    std::vector<int> objects;
    bool isLeaf() const {
        for (int c : children)
            if (c >= 0) return false;
        return true;
    }
};

/// Construction trace for figures: the nodes in creation order (depth-first, parent before
/// children) with the objects that were pushed down vs kept at each split.
struct OctreeBuildStep {
    int node = -1;
    int depth = 0;
    int objectsIn = 0;    ///< objects that reached this node
    int objectsKept = 0;  ///< of those, stored here (straddling a split plane, or a leaf)
    bool split = false;   ///< children were created
};
struct OctreeTrace {
    std::vector<OctreeBuildStep> steps;
};

struct OctreeStats {
    int nodeCount = 0;
    int leafCount = 0;
    int maxDepthReached = 0;
    int objectsAtRoot = 0;
    std::vector<int> objectsPerDepth;  ///< index = depth
};

class Octree {
public:
    /// Builds the tree over boxes (world frame). Indices in every result refer to `boxes`.
    void build(const std::vector<Aabb>& boxes, const OctreeOptions& options = {}, OctreeTrace* trace = nullptr);

    OctreeStatus status() const { return status_; }
    const std::vector<int>& rejected() const { return rejected_; }
    const std::vector<OctreeNode>& nodes() const { return nodes_; }
    const std::vector<Aabb>& boxes() const { return boxes_; }
    /// Node that stores object i, -1 if rejected.
    int nodeOf(int i) const { return nodeOf_[std::size_t(i)]; }
    OctreeStats stats() const;

    /// Every pair (i < j) of inserted boxes that overlap (closed), each exactly once, sorted.
    /// pairTests (optional) receives the number of box-box tests done (brute force: n(n-1)/2).
    std::vector<std::pair<int, int>> overlappingPairs(std::int64_t* pairTests = nullptr) const;
    /// Indices (sorted) of inserted boxes that overlap the closed query box; nodesVisited
    /// (optional) receives the number of nodes whose objects were tested.
    std::vector<int> query(const Aabb& box, int* nodesVisited = nullptr) const;

private:
    void insertAll(int node, std::vector<int> objects, OctreeTrace* trace);
    int childFor(const OctreeNode& node, const Aabb& box) const;
    Aabb childCell(const Aabb& cell, int octant) const;
    Aabb loosen(const Aabb& cell) const;

    OctreeOptions options_;
    OctreeStatus status_ = OctreeStatus::Empty;
    std::vector<Aabb> boxes_;
    std::vector<int> rejected_;
    std::vector<int> nodeOf_;
    std::vector<OctreeNode> nodes_;
};

}  // namespace cdlab
