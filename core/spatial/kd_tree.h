// k-d tree over points in 3D (Bentley, "Multidimensional binary search trees used for
// associative searching", CACM 1975; Ericson, Real-Time Collision Detection §7.3.7): each inner
// node cuts its points at the median along one axis (cycling x, y, z by depth, or the widest
// axis of the node's point bounds), with a range query (closed AABB) and a nearest-neighbour
// query (Friedman, Bentley & Finkel 1977: near child first, far child only if the split plane
// is not farther than the best distance so far).
//
// Split convention: after nth_element on the node's axis, the left child holds the points
// before the median position (coordinate <= split), the right child the median and after
// (coordinate >= split). Points equal to the split value may be on both sides, so both
// queries treat the plane as closed (ties visit both children).
//
// Frame: world; any length unit. Degenerate input: points with NaN / inf are not inserted
// (rejected()); duplicate points are fine (a node whose points are all equal is a leaf);
// the depth is at most ~log2(n) because every split halves the point count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/base/primitives.h"

namespace cdlab {

enum class KdSplitRule {
    Cycle,       ///< axis = depth mod 3 (Bentley 1975)
    WidestAxis,  ///< axis of the largest extent of the node's points (better for uneven clouds)
};

struct KdTreeOptions {
    KdSplitRule rule = KdSplitRule::WidestAxis;
    int maxPointsPerLeaf = 1;  ///< nodes with more points are split (values < 1 count as 1)
};

enum class KdTreeStatus {
    Ok,
    SomeRejected,  ///< some points had NaN / inf coordinates: see rejected()
    Empty,         ///< no valid point
};

/// One node. Points of the subtree are order_[begin, end) (indices into the input). Inner
/// nodes have axis >= 0, split (the median coordinate), left and right; leaves have axis -1.
/// cell is the region the node covers (root: the points' bounds), for drawing split lines.
struct KdNode {
    int axis = -1;
    double split = 0.0;
    int left = -1, right = -1;
    int begin = 0, end = 0;
    int depth = 0;
    Aabb cell;
    bool isLeaf() const { return axis < 0; }
};

/// What a query did, for figures: nodes whose subtree was entered, and nodes skipped because
/// the split plane was farther than the best distance (nearest) / missed the range.
struct KdQueryTrace {
    std::vector<int> visited;
    std::vector<int> pruned;
    int distanceTests = 0;       ///< point tests done
    std::vector<int> bestSoFar;  ///< nearest: every improvement of the best point
};

struct KdNearestResult {
    int index = -1;  ///< input index of the nearest point; -1 if the tree is empty / query invalid
    double distanceSquared = INFINITY;
};

class KdTree {
public:
    /// Builds the tree over points (world frame); indices in every result refer to `points`.
    void build(const std::vector<Vec3>& points, const KdTreeOptions& options = {});

    KdTreeStatus status() const { return status_; }
    const std::vector<int>& rejected() const { return rejected_; }
    const std::vector<KdNode>& nodes() const { return nodes_; }
    const std::vector<Vec3>& points() const { return points_; }
    /// Input indices in tree order: node n holds order()[n.begin .. n.end).
    const std::vector<int>& order() const { return order_; }
    int depth() const;  ///< deepest node's depth (root 0)
    int leafCount() const;

    /// Indices (sorted) of the points inside the closed box. An invalid box gives none.
    std::vector<int> rangeQuery(const Aabb& box, KdQueryTrace* trace = nullptr) const;
    /// The point nearest to q (Euclidean); among points at the same squared distance the
    /// smallest input index. A non-finite q gives index -1.
    KdNearestResult nearest(const Vec3& q, KdQueryTrace* trace = nullptr) const;

private:
    int buildNode(int begin, int end, int depth, const Aabb& cell);
    void nearestNode(int node, const Vec3& q, KdNearestResult& best, KdQueryTrace* trace) const;

    KdTreeOptions options_;
    KdTreeStatus status_ = KdTreeStatus::Empty;
    std::vector<Vec3> points_;
    std::vector<int> rejected_;
    std::vector<int> order_;
    std::vector<KdNode> nodes_;
};

}  // namespace cdlab
