#include "core/broadphase/dynamic_tree.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

void DynamicAabbTree::reserve(int leaves) {
    nodes_.reserve(static_cast<std::size_t>(2 * std::max(leaves, 1)));
    stack_.reserve(256);
    candidates_.reserve(256);
}

int DynamicAabbTree::allocate() {
    if (free_ != kNull) {
        const int i = free_;
        free_ = nodes_[i].parent;
        nodes_[i] = Node{};
        return i;
    }
    nodes_.emplace_back();
    return static_cast<int>(nodes_.size()) - 1;
}

void DynamicAabbTree::release(int i) {
    nodes_[i] = Node{};
    nodes_[i].height = -1;
    nodes_[i].parent = free_;
    free_ = i;
}

int DynamicAabbTree::insert(const Aabb& box, int userId, DynamicTreeInsertTrace* trace) {
    const int leaf = allocate();
    nodes_[leaf].box = box;
    nodes_[leaf].userId = userId;
    nodes_[leaf].height = 0;
    ++leaves_;
    insertLeaf(leaf, trace);
    return leaf;
}

void DynamicAabbTree::remove(int leaf) {
    removeLeaf(leaf);
    release(leaf);
    --leaves_;
}

void DynamicAabbTree::move(int leaf, const Aabb& box, DynamicTreeInsertTrace* trace) {
    removeLeaf(leaf);
    nodes_[leaf].box = box;
    insertLeaf(leaf, trace);
}

// Stage 1: the sibling of least SAH cost, branch and bound over the tree (file comment), best
// first: the candidate of least lower bound is costed next, and the search ends when no candidate's
// lower bound beats the best cost found (Bittner et al. 2015, §3.1).
int DynamicAabbTree::bestSibling(const Aabb& box, DynamicTreeInsertTrace* trace) {
    const double leafArea = surfaceArea(box);
    int best = root_;
    double bestCost = INFINITY;
    candidates_.clear();
    candidates_.push_back({leafArea, root_, 0.0});
    const auto later = [](const Candidate& x, const Candidate& y) { return x.lowerBound > y.lowerBound; };
    while (!candidates_.empty()) {
        std::pop_heap(candidates_.begin(), candidates_.end(), later);
        const Candidate c = candidates_.back();
        candidates_.pop_back();
        if (c.lowerBound >= bestCost) break;  // every other candidate's bound is at least this
        const Node& n = nodes_[c.node];
        const double unionArea = surfaceArea(unionOf(n.box, box));
        const double cost = unionArea + c.inherited;
        ++counters_.siblingCandidates;
        if (trace) trace->costed.push_back(c.node);
        if (cost < bestCost) {
            bestCost = cost;
            best = c.node;
        }
        if (n.leaf()) continue;
        // Below n every candidate's ancestors grow by at least what n grows by, and its own new
        // parent is at least as large as the leaf.
        const double childInherited = c.inherited + unionArea - surfaceArea(n.box);
        const double bound = leafArea + childInherited;
        if (bound < bestCost) {
            for (int child : {n.child1, n.child2}) {
                candidates_.push_back({bound, child, childInherited});
                std::push_heap(candidates_.begin(), candidates_.end(), later);
            }
        }
    }
    if (trace) trace->cost = bestCost;
    return best;
}

// Stages 2 and 3: a new parent takes the sibling's place; ancestors refitted and rotated.
void DynamicAabbTree::insertLeaf(int leaf, DynamicTreeInsertTrace* trace) {
    ++counters_.insertions;
    if (trace) *trace = DynamicTreeInsertTrace{leaf, -1, -1, 0.0, {}, {}};
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }
    const int sibling = bestSibling(nodes_[leaf].box, trace);
    const int parent = allocate();  // before taking references: nodes_ may grow
    const int oldParent = nodes_[sibling].parent;
    Node& p = nodes_[parent];
    p.parent = oldParent;
    p.box = unionOf(nodes_[leaf].box, nodes_[sibling].box);
    p.height = nodes_[sibling].height + 1;
    p.child1 = sibling;
    p.child2 = leaf;
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    if (oldParent == kNull) {
        root_ = parent;
    } else if (nodes_[oldParent].child1 == sibling) {
        nodes_[oldParent].child1 = parent;
    } else {
        nodes_[oldParent].child2 = parent;
    }
    if (trace) trace->sibling = sibling, trace->parent = parent;
    for (int i = oldParent; i != kNull; i = nodes_[i].parent) {
        refit(i);
        if (options_.rotate) rotate(i, trace);
    }
}

void DynamicAabbTree::removeLeaf(int leaf) {
    ++counters_.removals;
    if (leaf == root_) {
        root_ = kNull;
        return;
    }
    const int parent = nodes_[leaf].parent;
    const int grand = nodes_[parent].parent;
    const int sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    nodes_[sibling].parent = grand;
    if (grand == kNull) {
        root_ = sibling;
    } else {
        if (nodes_[grand].child1 == parent) nodes_[grand].child1 = sibling;
        else nodes_[grand].child2 = sibling;
        for (int i = grand; i != kNull; i = nodes_[i].parent) refit(i);
    }
    release(parent);
    nodes_[leaf].parent = kNull;
}

void DynamicAabbTree::refit(int i) {
    Node& n = nodes_[i];
    n.box = unionOf(nodes_[n.child1].box, nodes_[n.child2].box);
    n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
}

// Catto's tree rotation at node a (file comment): of the four swaps of a child with a grandchild
// on the other side, make the one that shrinks the grandchild's parent the most.
void DynamicAabbTree::rotate(int a, DynamicTreeInsertTrace* trace) {
    const int b = nodes_[a].child1, c = nodes_[a].child2;
    if (nodes_[a].height < 2) return;
    int bestFrom = kNull, bestTo = kNull, bestUnder = kNull;
    double bestDelta = 0.0;
    // Child `from` of a swapped with grandchild `to` under `under` (a's other child), whose other
    // child is `kept`: under's box becomes from ∪ kept.
    const auto consider = [&](int from, int under, int to, int kept) {
        const double delta = surfaceArea(unionOf(nodes_[from].box, nodes_[kept].box)) - surfaceArea(nodes_[under].box);
        if (delta < bestDelta) bestDelta = delta, bestFrom = from, bestTo = to, bestUnder = under;
    };
    if (!nodes_[c].leaf()) {
        consider(b, c, nodes_[c].child1, nodes_[c].child2);
        consider(b, c, nodes_[c].child2, nodes_[c].child1);
    }
    if (!nodes_[b].leaf()) {
        consider(c, b, nodes_[b].child1, nodes_[b].child2);
        consider(c, b, nodes_[b].child2, nodes_[b].child1);
    }
    if (bestFrom == kNull) return;
    Node& A = nodes_[a];
    Node& U = nodes_[bestUnder];
    if (A.child1 == bestFrom) A.child1 = bestTo;
    else A.child2 = bestTo;
    if (U.child1 == bestTo) U.child1 = bestFrom;
    else U.child2 = bestFrom;
    nodes_[bestTo].parent = a;
    nodes_[bestFrom].parent = bestUnder;
    refit(bestUnder);
    refit(a);
    ++counters_.rotations;
    if (trace) trace->rotations.push_back({a, bestFrom, bestTo, -bestDelta});
}

double DynamicAabbTree::internalArea() const {
    double sum = 0.0;
    for (const Node& n : nodes_)
        if (n.height > 0) sum += surfaceArea(n.box);
    return sum;
}

std::string DynamicAabbTree::validate() const {
    if (root_ == kNull) return leaves_ == 0 ? "" : "no root but leaves counted";
    if (nodes_[root_].parent != kNull) return "the root has a parent";
    int leaves = 0;
    std::vector<int> stack{root_};
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        const Node& n = nodes_[i];
        if (n.leaf()) {
            if (n.height != 0) return "leaf " + std::to_string(i) + " has height " + std::to_string(n.height);
            ++leaves;
            continue;
        }
        for (int c : {n.child1, n.child2}) {
            if (c < 0 || c >= nodeCapacity() || nodes_[c].parent != i) return "node " + std::to_string(i) + ": child link";
            stack.push_back(c);
        }
        const Aabb u = unionOf(nodes_[n.child1].box, nodes_[n.child2].box);
        if (u.min != n.box.min || u.max != n.box.max) return "node " + std::to_string(i) + ": box is not its children's union";
        if (n.height != 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height))
            return "node " + std::to_string(i) + ": height";
    }
    return leaves == leaves_ ? "" : "reachable leaves " + std::to_string(leaves) + " != " + std::to_string(leaves_);
}

}  // namespace cdlab
