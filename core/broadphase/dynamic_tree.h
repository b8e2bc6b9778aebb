// Dynamic AABB tree (the broad phase of Box2D v3's b2DynamicTree and Bullet's btDbvt): a binary
// tree of boxes, leaves inserted and removed one at a time, each internal node's box the union of
// its children's.
//
// Insertion (E. Catto, "Dynamic Bounding Volume Hierarchies", GDC 2019; J. Bittner, M. Hapala,
// V. Havran, "Incremental BVH construction for ray tracing", Computers & Graphics 2015):
//   1. Best sibling by the surface area heuristic, branch and bound. Pairing the new box L with a
//      node S costs area(S ∪ L) for the new parent plus the growth area(X ∪ L) - area(X) of every
//      ancestor X of S (the inherited cost). A subtree is skipped when even its best case — area(L)
//      plus the inherited cost down to its root — cannot beat the best cost found.
//   2. A new parent P = S ∪ L takes S's place.
//   3. Up from P's parent: refit each ancestor's box and height, then rotate it (below).
// Rotation (Catto 2019): at a node A with children B and C, swapping B with a grandchild under C
// (or C with one under B) changes only the box of the grandchild's parent; the swap that shrinks
// that box's area most is made, if any. This repairs the tree that insertion order alone would
// leave (boxes inserted along a line make a list without it).
// Removal: the leaf's sibling takes its parent's place; ancestors refitted.
// Query: depth-first over the nodes whose boxes overlap the query box (closed: touching counts).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/aabb_ops.h"
#include "core/base/primitives.h"

namespace cdlab {

struct DynamicTreeOptions {
    bool rotate = true;  ///< rotations on the way up (false: plain SAH insertion, for comparison)
};

/// Totals since construction.
struct DynamicTreeCounters {
    std::int64_t insertions = 0, removals = 0, rotations = 0;
    std::int64_t siblingCandidates = 0;  ///< nodes costed by the branch and bound
};

/// One rotation: at `node`, child `from` swapped with grandchild `to`; the area saved.
struct DynamicTreeRotation {
    int node = -1, from = -1, to = -1;
    double areaSaved = 0.0;
};

/// One insertion, for figures: the leaf, the sibling it was paired with, its cost, the nodes the
/// branch and bound costed (in order) and the rotations on the way up.
struct DynamicTreeInsertTrace {
    int leaf = -1, sibling = -1, parent = -1;
    double cost = 0.0;
    std::vector<int> costed;
    std::vector<DynamicTreeRotation> rotations;
};

class DynamicAabbTree {
public:
    static constexpr int kNull = -1;

    struct Node {
        Aabb box{Vec3::Zero(), Vec3::Zero()};
        int parent = kNull;
        int child1 = kNull, child2 = kNull;  ///< kNull for a leaf
        int height = 0;                      ///< 0 for a leaf; -1 for a free node
        int userId = -1;                     ///< leaves: the caller's id
        bool leaf() const { return child1 == kNull; }
    };

    explicit DynamicAabbTree(const DynamicTreeOptions& options = {}) : options_(options) {}

    /// Room for `leaves` leaves without allocation.
    void reserve(int leaves);
    /// Inserts a leaf holding `box` (finite, min <= max: checked by the caller) for `userId`;
    /// returns its node index, stable until removed.
    int insert(const Aabb& box, int userId, DynamicTreeInsertTrace* trace = nullptr);
    /// Removes leaf `leaf`.
    void remove(int leaf);
    /// New box for leaf `leaf` (removed and inserted again; the node index stays).
    void move(int leaf, const Aabb& box, DynamicTreeInsertTrace* trace = nullptr);

    /// Calls visit(userId, leaf) for every leaf whose box overlaps `box` (closed). Uses a scratch
    /// stack of the tree's: one query at a time per tree.
    template <class Visit>
    void query(const Aabb& box, Visit&& visit) const {
        if (root_ == kNull) return;
        std::vector<int>& stack = stack_;
        stack.clear();
        stack.push_back(root_);
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            const Node& n = nodes_[i];
            if (!overlaps(n.box, box)) continue;
            if (n.leaf()) {
                visit(n.userId, i);
            } else {
                stack.push_back(n.child1);
                stack.push_back(n.child2);
            }
        }
    }

    int root() const { return root_; }
    const Node& node(int i) const { return nodes_[i]; }
    int nodeCapacity() const { return static_cast<int>(nodes_.size()); }
    int leafCount() const { return leaves_; }
    int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
    /// Sum of the internal nodes' surface areas (the SAH cost up to a constant).
    double internalArea() const;
    const DynamicTreeCounters& counters() const { return counters_; }
    /// Empty when every invariant holds (parent links, boxes = unions of the children exactly,
    /// heights, leaf count), else the first one broken.
    std::string validate() const;

private:
    int allocate();
    void release(int i);
    int bestSibling(const Aabb& box, DynamicTreeInsertTrace* trace);
    void insertLeaf(int leaf, DynamicTreeInsertTrace* trace);
    void removeLeaf(int leaf);
    void refit(int i);
    void rotate(int a, DynamicTreeInsertTrace* trace);

    DynamicTreeOptions options_;
    std::vector<Node> nodes_;
    int root_ = kNull;
    int free_ = kNull;  ///< free list through Node::parent
    int leaves_ = 0;
    DynamicTreeCounters counters_;
    mutable std::vector<int> stack_;
    struct Candidate {
        double lowerBound;  ///< no pairing in the subtree costs less
        int node;
        double inherited;  ///< growth of the node's ancestors
    };
    std::vector<Candidate> candidates_;  ///< branch and bound's heap
};

}  // namespace cdlab
