#include "core/spatial/kd_tree.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

void KdTree::build(const std::vector<Vec3>& points, const KdTreeOptions& options) {
    options_ = options;
    options_.maxPointsPerLeaf = std::max(1, options_.maxPointsPerLeaf);
    points_ = points;
    rejected_.clear();
    order_.clear();
    nodes_.clear();
    Aabb bounds{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].allFinite()) {
            rejected_.push_back(int(i));
            continue;
        }
        order_.push_back(int(i));
        bounds.min = bounds.min.cwiseMin(points[i]);
        bounds.max = bounds.max.cwiseMax(points[i]);
    }
    status_ = order_.empty() ? KdTreeStatus::Empty : rejected_.empty() ? KdTreeStatus::Ok : KdTreeStatus::SomeRejected;
    if (order_.empty()) return;
    buildNode(0, int(order_.size()), 0, bounds);
}

// Median split (Ericson §7.3.7): nth_element puts the median point at mid, smaller-or-equal
// coordinates before it, greater-or-equal after; the halves become the children.
int KdTree::buildNode(int begin, int end, int depth, const Aabb& cell) {
    const int id = int(nodes_.size());
    KdNode node;
    node.begin = begin;
    node.end = end;
    node.depth = depth;
    node.cell = cell;
    nodes_.push_back(node);
    if (end - begin <= options_.maxPointsPerLeaf) return id;
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (int k = begin; k < end; ++k) {
        lo = lo.cwiseMin(points_[std::size_t(order_[std::size_t(k)])]);
        hi = hi.cwiseMax(points_[std::size_t(order_[std::size_t(k)])]);
    }
    if (lo == hi) return id;  // all points equal: no plane separates them, keep a leaf
    int axis = 0;
    if (options_.rule == KdSplitRule::Cycle) {
        axis = depth % 3;
        // A flat axis cannot split; take the next one with extent (lo != hi somewhere).
        while (lo[axis] == hi[axis]) axis = (axis + 1) % 3;
    } else {
        (hi - lo).maxCoeff(&axis);
    }
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
        const double ca = points_[std::size_t(a)][axis], cb = points_[std::size_t(b)][axis];
        return ca < cb || (ca == cb && a < b);  // index tie-break: a deterministic tree
    });
    const double split = points_[std::size_t(order_[std::size_t(mid)])][axis];
    Aabb leftCell = cell, rightCell = cell;
    leftCell.max[axis] = split;
    rightCell.min[axis] = split;
    nodes_[std::size_t(id)].axis = axis;
    nodes_[std::size_t(id)].split = split;
    const int left = buildNode(begin, mid, depth + 1, leftCell);
    const int right = buildNode(mid, end, depth + 1, rightCell);
    nodes_[std::size_t(id)].left = left;
    nodes_[std::size_t(id)].right = right;
    return id;
}

int KdTree::depth() const {
    int d = 0;
    for (const KdNode& n : nodes_) d = std::max(d, n.depth);
    return d;
}

int KdTree::leafCount() const {
    int c = 0;
    for (const KdNode& n : nodes_) c += n.isLeaf() ? 1 : 0;
    return c;
}

std::vector<int> KdTree::rangeQuery(const Aabb& box, KdQueryTrace* trace) const {
    std::vector<int> hits;
    const bool valid = box.min.allFinite() && box.max.allFinite() && (box.min.array() <= box.max.array()).all();
    if (nodes_.empty() || !valid) return hits;
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const int id = stack.back();
        stack.pop_back();
        const KdNode& n = nodes_[std::size_t(id)];
        if (trace) trace->visited.push_back(id);
        if (n.isLeaf()) {
            for (int k = n.begin; k < n.end; ++k) {
                const Vec3& p = points_[std::size_t(order_[std::size_t(k)])];
                if (trace) ++trace->distanceTests;
                if ((box.min.array() <= p.array()).all() && (p.array() <= box.max.array()).all())
                    hits.push_back(order_[std::size_t(k)]);
            }
            continue;
        }
        // Left points have coordinate <= split, right ones >= split: closed comparisons.
        if (box.min[n.axis] <= n.split) stack.push_back(n.left);
        else if (trace) trace->pruned.push_back(n.left);
        if (box.max[n.axis] >= n.split) stack.push_back(n.right);
        else if (trace) trace->pruned.push_back(n.right);
    }
    std::sort(hits.begin(), hits.end());
    return hits;
}

KdNearestResult KdTree::nearest(const Vec3& q, KdQueryTrace* trace) const {
    KdNearestResult best;
    if (nodes_.empty() || !q.allFinite()) return best;
    nearestNode(0, q, best, trace);
    return best;
}

void KdTree::nearestNode(int id, const Vec3& q, KdNearestResult& best, KdQueryTrace* trace) const {
    const KdNode& n = nodes_[std::size_t(id)];
    if (trace) trace->visited.push_back(id);
    if (n.isLeaf()) {
        for (int k = n.begin; k < n.end; ++k) {
            const int i = order_[std::size_t(k)];
            const double d2 = (points_[std::size_t(i)] - q).squaredNorm();
            if (trace) ++trace->distanceTests;
            if (d2 < best.distanceSquared || (d2 == best.distanceSquared && i < best.index)) {
                best.index = i;
                best.distanceSquared = d2;
                if (trace) trace->bestSoFar.push_back(i);
            }
        }
        return;
    }
    const double diff = q[n.axis] - n.split;
    const int nearChild = diff <= 0 ? n.left : n.right;
    const int farChild = diff <= 0 ? n.right : n.left;
    nearestNode(nearChild, q, best, trace);
    // Every far-side point p has |q_axis - p_axis| >= |diff|, and rounding is monotone, so
    // fl(|q - p|^2) >= fl(diff^2): skipping when diff^2 > best is safe; equality is visited so
    // that the smallest index among equally near points wins.
    if (diff * diff <= best.distanceSquared) nearestNode(farChild, q, best, trace);
    else if (trace) trace->pruned.push_back(farChild);
}

}  // namespace cdlab
