#include "core/broadphase/octree.h"

#include <algorithm>
#include <cmath>

#include "core/base/aabb_ops.h"

namespace cdlab {

Aabb Octree::loosen(const Aabb& cell) const {
    if (options_.looseness <= 1.0) return cell;
    const Vec3 c = 0.5 * (cell.min + cell.max);
    const Vec3 h = 0.5 * options_.looseness * (cell.max - cell.min);
    return {c - h, c + h};
}

Aabb Octree::childCell(const Aabb& cell, int octant) const {
    const Vec3 m = 0.5 * (cell.min + cell.max);
    Aabb child = cell;
    for (int i = 0; i < 3; ++i) {
        if (octant & (1 << i)) child.min[i] = m[i];
        else child.max[i] = m[i];
    }
    return child;
}

// Octant of the child that takes `box`, or -1 if it stays in `node`.
int Octree::childFor(const OctreeNode& node, const Aabb& box) const {
    const Vec3 m = 0.5 * (node.cell.min + node.cell.max);
    int octant = 0;
    if (options_.looseness <= 1.0) {
        // Classic: the box must lie strictly on one side of each split plane (a box touching the
        // plane stays here; see the header for why strictness keeps the pair query exact).
        for (int i = 0; i < 3; ++i) {
            if (box.max[i] < m[i]) continue;
            if (box.min[i] > m[i]) octant |= 1 << i;
            else return -1;
        }
        return octant;
    }
    // Loose: the box centre picks the octant; the box must fit the child's loose cell.
    const Vec3 c = 0.5 * (box.min + box.max);
    for (int i = 0; i < 3; ++i)
        if (c[i] > m[i]) octant |= 1 << i;
    return contains(loosen(childCell(node.cell, octant)), box) ? octant : -1;
}

void Octree::build(const std::vector<Aabb>& boxes, const OctreeOptions& options, OctreeTrace* trace) {
    options_ = options;
    options_.maxDepth = std::max(0, options_.maxDepth);
    options_.maxObjectsPerLeaf = std::max(0, options_.maxObjectsPerLeaf);
    if (!(options_.looseness >= 1.0) || !std::isfinite(options_.looseness)) options_.looseness = 1.0;
    boxes_ = boxes;
    rejected_.clear();
    nodes_.clear();
    nodeOf_.assign(boxes.size(), -1);
    if (trace) trace->steps.clear();

    std::vector<int> valid;
    Aabb bounds{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!isValidBox(boxes[i])) {
            rejected_.push_back(int(i));
            continue;
        }
        valid.push_back(int(i));
        bounds.min = bounds.min.cwiseMin(boxes[i].min);
        bounds.max = bounds.max.cwiseMax(boxes[i].max);
    }
    Aabb root;
    if (options_.useRootBounds && isValidBox(options_.rootBounds)) {
        root = options_.rootBounds;
    } else if (!valid.empty()) {
        // Fitted root: the cube around the input bounds (cubic cells read better in figures).
        const Vec3 c = 0.5 * (bounds.min + bounds.max);
        const double h = 0.5 * (bounds.max - bounds.min).maxCoeff();
        root = {c - Vec3::Constant(h), c + Vec3::Constant(h)};
        // Rounding of c +- h may clip the input bounds by an ulp: widen to contain them.
        root.min = root.min.cwiseMin(bounds.min);
        root.max = root.max.cwiseMax(bounds.max);
    } else {
        root = {Vec3::Zero(), Vec3::Zero()};
    }
    OctreeNode rootNode;
    rootNode.cell = root;
    rootNode.looseCell = loosen(root);
    nodes_.push_back(rootNode);
    status_ = valid.empty() ? OctreeStatus::Empty : rejected_.empty() ? OctreeStatus::Ok : OctreeStatus::SomeRejected;

    // Boxes not inside the root's (loose) cell stay in the root: the root is everyone's ancestor.
    std::vector<int> inside;
    for (int i : valid) {
        if (contains(nodes_[0].looseCell, boxes_[std::size_t(i)])) inside.push_back(i);
        else {
            nodes_[0].objects.push_back(i);
            nodeOf_[std::size_t(i)] = 0;
        }
    }
    insertAll(0, std::move(inside), trace);
}

// Top-down: keep the objects if the node is small enough or deep enough, otherwise push each
// object to the child that contains it (Ericson §7.3.2) and recurse.
void Octree::insertAll(int node, std::vector<int> objects, OctreeTrace* trace) {
    OctreeBuildStep step;
    step.node = node;
    step.depth = nodes_[std::size_t(node)].depth;
    step.objectsIn = int(objects.size()) + int(nodes_[std::size_t(node)].objects.size());
    std::array<std::vector<int>, 8> down;
    bool anyDown = false;
    const bool split = int(objects.size() + nodes_[std::size_t(node)].objects.size()) > options_.maxObjectsPerLeaf &&
                       nodes_[std::size_t(node)].depth < options_.maxDepth;
    for (int i : objects) {
        const int octant = split ? childFor(nodes_[std::size_t(node)], boxes_[std::size_t(i)]) : -1;
        if (octant < 0) {
            nodes_[std::size_t(node)].objects.push_back(i);
            nodeOf_[std::size_t(i)] = node;
        } else {
            down[std::size_t(octant)].push_back(i);
            anyDown = true;
        }
    }
    step.objectsKept = int(nodes_[std::size_t(node)].objects.size());
    step.split = anyDown;
    if (trace) trace->steps.push_back(step);
    if (!anyDown) return;
    for (int o = 0; o < 8; ++o) {
        if (down[std::size_t(o)].empty()) continue;  // children only where objects go (sparse octree)
        OctreeNode child;
        child.cell = childCell(nodes_[std::size_t(node)].cell, o);
        child.looseCell = loosen(child.cell);
        child.depth = nodes_[std::size_t(node)].depth + 1;
        child.parent = node;
        const int id = int(nodes_.size());
        nodes_.push_back(child);
        nodes_[std::size_t(node)].children[std::size_t(o)] = id;
        insertAll(id, std::move(down[std::size_t(o)]), trace);
    }
}

OctreeStats Octree::stats() const {
    OctreeStats s;
    s.nodeCount = int(nodes_.size());
    for (const OctreeNode& n : nodes_) {
        if (n.isLeaf()) ++s.leafCount;
        s.maxDepthReached = std::max(s.maxDepthReached, n.depth);
        if (int(s.objectsPerDepth.size()) <= n.depth) s.objectsPerDepth.resize(std::size_t(n.depth) + 1, 0);
        s.objectsPerDepth[std::size_t(n.depth)] += int(n.objects.size());
    }
    if (!nodes_.empty()) s.objectsAtRoot = int(nodes_[0].objects.size());
    return s;
}

std::vector<std::pair<int, int>> Octree::overlappingPairs(std::int64_t* pairTests) const {
    std::vector<std::pair<int, int>> pairs;
    std::int64_t tests = 0;
    auto test = [&](int a, int b) {
        ++tests;
        if (aabbOverlapClosed(boxes_[std::size_t(a)], boxes_[std::size_t(b)]))
            pairs.emplace_back(std::min(a, b), std::max(a, b));
    };
    if (options_.looseness <= 1.0) {
        // Classic octree: an overlapping pair always has one object in an ancestor-or-same node
        // of the other's. Depth-first with the objects of the current ancestors on a stack: each
        // object is tested against the later objects of its node and every ancestor object, so
        // each pair is tested exactly once (Ericson §7.3.2, TestAllCollisions).
        std::vector<int> ancestors;  // objects of the nodes on the current root path
        struct Item {
            int node;
            bool leave;
        };
        std::vector<Item> stack{{0, false}};
        while (!stack.empty()) {
            const Item it = stack.back();
            stack.pop_back();
            const OctreeNode& n = nodes_[std::size_t(it.node)];
            if (it.leave) {
                ancestors.resize(ancestors.size() - n.objects.size());
                continue;
            }
            for (std::size_t a = 0; a < n.objects.size(); ++a) {
                for (std::size_t b = a + 1; b < n.objects.size(); ++b) test(n.objects[a], n.objects[b]);
                for (int anc : ancestors) test(n.objects[a], anc);
            }
            ancestors.insert(ancestors.end(), n.objects.begin(), n.objects.end());
            stack.push_back({it.node, true});
            for (int c = 7; c >= 0; --c)
                if (n.children[std::size_t(c)] >= 0) stack.push_back({n.children[std::size_t(c)], false});
        }
    } else {
        // Loose octree: sibling loose cells overlap, so each object queries the tree with its own
        // box (descending into nodes whose loose cell it overlaps) and keeps partners j > i.
        std::vector<int> stack;
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            if (nodeOf_[i] < 0) continue;
            stack.assign(1, 0);
            while (!stack.empty()) {
                const OctreeNode& n = nodes_[std::size_t(stack.back())];
                stack.pop_back();
                for (int j : n.objects)
                    if (j > int(i)) test(int(i), j);
                for (int c : n.children)
                    if (c >= 0 && aabbOverlapClosed(nodes_[std::size_t(c)].looseCell, boxes_[i])) stack.push_back(c);
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    if (pairTests) *pairTests = tests;
    return pairs;
}

std::vector<int> Octree::query(const Aabb& box, int* nodesVisited) const {
    std::vector<int> hits;
    int visited = 0;
    if (!nodes_.empty() && isValidBox(box)) {
        // The root is always visited: it may hold boxes outside its cell.
        std::vector<int> stack{0};
        while (!stack.empty()) {
            const OctreeNode& n = nodes_[std::size_t(stack.back())];
            stack.pop_back();
            ++visited;
            for (int j : n.objects)
                if (aabbOverlapClosed(boxes_[std::size_t(j)], box)) hits.push_back(j);
            // A child's objects lie inside its (loose) cell: skip cells the query misses.
            for (int c : n.children)
                if (c >= 0 && aabbOverlapClosed(nodes_[std::size_t(c)].looseCell, box)) stack.push_back(c);
        }
    }
    std::sort(hits.begin(), hits.end());
    if (nodesVisited) *nodesVisited = visited;
    return hits;
}

}  // namespace cdlab
