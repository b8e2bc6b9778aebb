// Bounding-volume hierarchies over triangle meshes (see bvh.h for the sources and conventions).
#include "core/bvh/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/aabb_ops.h"
#include "core/bounding/bounding_volume_fit.h"
#include "core/overlap/intersect_ray.h"
#include "core/overlap/sat_tests.h"
#include "core/overlap/triangle_triangle.h"

namespace cdlab {

namespace {

// Rounding margin of every bounding-volume test, relative to the magnitude of the coordinates
// involved (vertex radius of both meshes, pose positions, query positions). Moving a box into
// another frame (rotation matrix from a quaternion, one matrix product, one translation)
// and the SAT projections are each accurate to a few ulp (~1e-15 relative); the world
// triangles of the leaf tests (Transform::apply) likewise. 1e-12 is ~1000 times that: never
// prunes a touching pair, and far below any box size that matters for culling.
constexpr double kBvMarginRelative = 1e-12;

// Slack added to every fitted OBB half extent, relative to |center| + largest half extent: the
// fit's projection onto the axes and back is accurate to a few ulp, and the containment check
// (axes^T (v - center) within halfExtents) rounds as well. 1e-13 makes containment hold in
// doubles for every vertex while staying negligible.
constexpr double kFitSlackRelative = 1e-13;

// Added to |R_ij| in the OBB-OBB test (Ericson §4.4.1): when two edges are (nearly) parallel
// their cross product is (nearly) zero and the axis test is dominated by rounding; the epsilon
// makes those axes conservative (never separating by noise). Same value as sat_tests.cpp.
constexpr double kParallelEpsilon = 1e-9;

Obb aabbToObb(const Aabb& b) { return Obb{0.5 * (b.min + b.max), 0.5 * (b.max - b.min), Mat3::Identity()}; }

Vec3 scaled(const Vec3& v, int k) {
    return v.unaryExpr([k](double x) { return std::ldexp(x, k); });
}

// Surface area of 2^k · b. The builders pass the k that brings the mesh's largest coordinate into
// [0.5, 1): the area of a box spanning 1e200 (or 1e308) is then no overflow (inf costs would leave
// no best split and no nearest cluster), and scaling by a power of two keeps every comparison of
// costs exactly as it is unscaled (the trace records areas scaled back, bit for bit).
double surfaceArea(const Aabb& b, int k) {
    const Vec3 d = (scaled(b.max, k) - scaled(b.min, k)).cwiseMax(0.0);
    return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

Aabb emptyAabb() {
    const double inf = std::numeric_limits<double>::infinity();
    return Aabb{Vec3::Constant(inf), Vec3::Constant(-inf)};
}

void grow(Aabb& b, const Vec3& p) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
}

Aabb triangleAabb(const Triangle& t) { return Aabb{t.a.cwiseMin(t.b).cwiseMin(t.c), t.a.cwiseMax(t.b).cwiseMax(t.c)}; }

Vec3 centroid(const Triangle& t) { return (t.a + t.b + t.c) / 3.0; }

void inflate(Obb& box) {
    box.halfExtents.array() +=
        kFitSlackRelative * (box.center.cwiseAbs().maxCoeff() + box.halfExtents.cwiseAbs().maxCoeff());
}

/// Boolean OBB-OBB separating-axis test, both boxes in one frame (Ericson §4.4.1, TestOBBOBB):
/// 15 axes, A's faces, B's faces, 9 edge-edge products. Closed boxes (touching overlaps).
bool obbOverlap(const Obb& a, const Obb& b) {
    const Vec3& ea = a.halfExtents;
    const Vec3& eb = b.halfExtents;
    const Mat3 R = a.axes.transpose() * b.axes;                 // R_ij = A_i . B_j
    const Vec3 t = a.axes.transpose() * (b.center - a.center);  // in A's box frame
    const Mat3 absR = R.cwiseAbs().array() + kParallelEpsilon;
    for (int i = 0; i < 3; ++i)  // axes A_i
        if (std::abs(t[i]) > ea[i] + eb.dot(absR.row(i))) return false;
    for (int j = 0; j < 3; ++j)  // axes B_j
        if (std::abs(t.dot(R.col(j))) > ea.dot(absR.col(j)) + eb[j]) return false;
    for (int i = 0; i < 3; ++i) {  // axes A_i x B_j
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double ra = ea[i1] * absR(i2, j) + ea[i2] * absR(i1, j);
            const double rb = eb[j1] * absR(i, j2) + eb[j2] * absR(i, j1);
            if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return false;
        }
    }
    return true;
}

/// Half diagonal of a node's box: the "size" of the descend-larger rule (robust for flat boxes,
/// whose volume is 0).
double nodeSize(const Bvh& bvh, int node) {
    if (bvh.kind == BvKind::Aabb) return 0.5 * (bvh.aabbs[node].max - bvh.aabbs[node].min).norm();
    return bvh.obbs[node].halfExtents.norm();
}

double maxVertexRadius(const TriangleMesh& mesh) {
    double r = 0.0;
    for (const std::array<int, 3>& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) r = std::max(r, mesh.vertices[t[k]].norm());
    return r;
}

// ---- construction ---------------------------------------------------------------------------

struct Builder {
    const TriangleMesh& mesh;
    const BvhBuildOptions& options;
    Bvh& bvh;
    std::vector<Vec3> centroids;    // per mesh triangle
    std::vector<Triangle> scratch;  // the current node's triangles, for the fits

    int areaExponent = 0;  // surface areas are those of 2^areaExponent · box

    Builder(const TriangleMesh& m, const BvhBuildOptions& o, Bvh& b) : mesh(m), options(o), bvh(b) {
        centroids.resize(mesh.triangles.size());
        for (int i = 0; i < mesh.triangleCount(); ++i) centroids[i] = centroid(mesh.triangle(i));
        double largest = 0.0;
        for (const Vec3& v : mesh.vertices) largest = std::max(largest, v.cwiseAbs().maxCoeff());
        if (largest > 0.0) std::frexp(largest, &areaExponent), areaExponent = -areaExponent;
    }
    double area(const Aabb& box) const { return surfaceArea(box, areaExponent); }
    double unscaledArea(double a) const { return std::ldexp(a, -2 * areaExponent); }

    /// Fits node i's box to its triangle range.
    void fit(int i) {
        const BvhNode& n = bvh.nodes[i];
        scratch.clear();
        for (int k = n.first; k < n.first + n.count; ++k) scratch.push_back(mesh.triangle(bvh.triangleOrder[k]));
        if (bvh.kind == BvKind::Aabb) {
            bvh.aabbs[i] = fitAabb(std::span<const Triangle>(scratch));  // exact (min / max): no slack
            return;
        }
        Obb box = fitObbTriangles(scratch);
        inflate(box);
        bvh.obbs[i] = box;
    }

    /// Room for the 2n - 1 nodes of a full binary tree over n triangles (no reallocation).
    void reserve(int n) {
        const size_t nodes = 2 * static_cast<size_t>(n);
        bvh.nodes.reserve(nodes);
        if (bvh.kind == BvKind::Aabb) bvh.aabbs.reserve(nodes);
        else bvh.obbs.reserve(nodes);
    }

    int addChildren(int parent) {
        const int left = static_cast<int>(bvh.nodes.size());
        BvhNode child;
        child.parent = parent;
        child.depth = bvh.nodes[parent].depth + 1;
        bvh.nodes.push_back(child);
        bvh.nodes.push_back(child);
        bvh.nodes[parent].left = left;
        bvh.nodes[parent].right = left + 1;
        if (bvh.kind == BvKind::Aabb) bvh.aabbs.resize(bvh.nodes.size());
        else bvh.obbs.resize(bvh.nodes.size());
        return left;
    }

    /// Median split (Ericson §6.2.1): returns the count of the left part.
    int splitMedian(const BvhNode& n, int node, BvhBuildStep& step) {
        int* begin = bvh.triangleOrder.data() + n.first;
        int* end = begin + n.count;
        int* mid = begin + n.count / 2;
        Vec3 dir;
        if (bvh.kind == BvKind::Obb) {
            // Gottschalk's OBBTree: the box's longest axis.
            int axis = 0;
            bvh.obbs[node].halfExtents.maxCoeff(&axis);
            dir = bvh.obbs[node].axes.col(axis);
            step.splitAxis = axis;
        } else {
            // Longest axis of the centroids' box.
            Aabb cb = emptyAabb();
            for (const int* p = begin; p != end; ++p) grow(cb, centroids[*p]);
            int axis = 0;
            (cb.max - cb.min).maxCoeff(&axis);
            dir = Vec3::Unit(axis);
            step.splitAxis = axis;
        }
        std::nth_element(begin, mid, end, [&](int x, int y) { return centroids[x].dot(dir) < centroids[y].dot(dir); });
        step.splitPosition = centroids[*mid].dot(dir);
        return n.count / 2;
    }

    /// The SAH cost of the median split on the centroids' longest axis, for a traced SAH build's
    /// comparison (a copy of the range is partitioned; the build's order is untouched).
    void recordMedianCost(const int* begin, const int* end, const Aabb& cb, double nodeArea, BvhBuildStep& step) {
        std::vector<int> order(begin, end);
        int axis = 0;
        (cb.max - cb.min).maxCoeff(&axis);
        auto mid = order.begin() + order.size() / 2;
        std::nth_element(order.begin(), mid, order.end(),
                         [&](int x, int y) { return centroids[x][axis] < centroids[y][axis]; });
        Aabb left = emptyAabb(), right = emptyAabb();
        for (auto it = order.begin(); it != order.end(); ++it)
            (it < mid ? left : right) = unionOf(it < mid ? left : right, triangleAabb(mesh.triangle(*it)));
        const double nl = double(mid - order.begin()), nr = double(order.end() - mid);
        step.medianAxis = axis;
        step.medianPosition = centroids[*mid][axis];
        step.medianCost = (area(left) * nl + area(right) * nr) / nodeArea;
    }

    /// Binned SAH split (Wald 2007): returns the count of the left part.
    int splitSah(const BvhNode& n, BvhBuildStep& step, bool record) {
        int* begin = bvh.triangleOrder.data() + n.first;
        int* end = begin + n.count;
        Aabb cb = emptyAabb();
        for (const int* p = begin; p != end; ++p) grow(cb, centroids[*p]);
        // Bins on the scaled centroids (as the areas): a centroid span beyond 1e308 cannot overflow.
        const Vec3 low = scaled(cb.min, areaExponent);
        const Vec3 extent = scaled(cb.max, areaExponent) - low;
        if (!(extent.maxCoeff() > 0.0)) {
            // All centroids coincide: no plane separates them; split the range in halves.
            step.splitAxis = 0;
            step.splitPosition = cb.min.x();
            return n.count / 2;
        }
        const int nb = std::max(2, options.sahBins);
        auto binOf = [&](int tri, int axis) {
            const double u = (std::ldexp(centroids[tri][axis], areaExponent) - low[axis]) / extent[axis];
            return std::clamp(static_cast<int>(u * nb), 0, nb - 1);
        };
        std::vector<Aabb> boxes(nb);
        std::vector<int> counts(nb);
        std::vector<double> rightArea(nb);
        std::vector<int> rightCount(nb);
        double bestCost = std::numeric_limits<double>::infinity();
        double nodeArea = 0.0;  // surface area of the union of the triangles' AABBs
        int bestAxis = -1, bestSplit = -1;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0)) continue;
            std::fill(boxes.begin(), boxes.end(), emptyAabb());
            std::fill(counts.begin(), counts.end(), 0);
            for (const int* p = begin; p != end; ++p) {
                const int b = binOf(*p, axis);
                ++counts[b];
                const Triangle t = mesh.triangle(*p);
                boxes[b] = unionOf(boxes[b], triangleAabb(t));
            }
            // Sweep from the right: area and count of bins k+1 .. nb-1.
            Aabb acc = emptyAabb();
            int c = 0;
            for (int k = nb - 1; k > 0; --k) {
                acc = unionOf(acc, boxes[k]);
                c += counts[k];
                rightArea[k - 1] = area(acc);
                rightCount[k - 1] = c;
            }
            nodeArea = area(unionOf(acc, boxes[0]));
            acc = emptyAabb();
            c = 0;
            for (int k = 0; k + 1 < nb; ++k) {  // split between bin k and k + 1
                acc = unionOf(acc, boxes[k]);
                c += counts[k];
                if (c == 0 || rightCount[k] == 0) continue;  // one side empty: not a split
                const double cost = area(acc) * c + rightArea[k] * rightCount[k];
                if (record)
                    step.candidates.push_back({axis, cb.min[axis] + std::ldexp(extent[axis], -areaExponent) * (k + 1) / nb, c,
                                               rightCount[k], area(acc), rightArea[k], cost});
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestSplit = k;
                }
            }
        }
        // The smallest and largest centroid on an axis with extent > 0 fall in bins 0 and nb - 1,
        // so some split has both sides non-empty.
        if (bestAxis < 0) {  // no finite cost (cannot happen with the scaled areas; kept as a guard)
            step.splitAxis = 0;
            step.splitPosition = cb.min.x();
            return n.count / 2;
        }
        if (record && nodeArea > 0.0) {  // (a node of points only has no area to compare with)
            for (auto& c : step.candidates)  // areas and costs relative to the node's
                c.leftArea /= nodeArea, c.rightArea /= nodeArea, c.cost /= nodeArea;
            recordMedianCost(begin, end, cb, nodeArea, step);
        }
        int* mid = std::partition(begin, end, [&](int tri) { return binOf(tri, bestAxis) <= bestSplit; });
        step.splitAxis = bestAxis;
        step.splitPosition = cb.min[bestAxis] + std::ldexp(extent[bestAxis], -areaExponent) * (bestSplit + 1) / nb;
        step.cost = nodeArea > 0.0 ? bestCost / nodeArea : unscaledArea(bestCost);
        return static_cast<int>(mid - begin);
    }

    void buildTopDown(BvhBuildTrace* trace) {
        const int n = mesh.triangleCount();
        reserve(n);
        BvhNode root;
        root.count = n;
        bvh.nodes.push_back(root);
        if (bvh.kind == BvKind::Aabb) bvh.aabbs.resize(1);
        else bvh.obbs.resize(1);
        const int maxLeaf = std::max(1, options.maxLeafTriangles);
        std::vector<int> stack{0};
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            // OBB: the box is needed now (its longest axis is the split direction); AABB boxes are
            // filled in bottom-up below (the union of the children's boxes equals the fit).
            if (bvh.kind == BvKind::Obb) fit(i);
            const BvhNode n = bvh.nodes[i];
            BvhBuildStep step;
            step.node = i;
            step.depth = n.depth;
            step.first = n.first;
            step.count = n.count;
            if (n.count > maxLeaf) {
                const int leftCount =
                    options.method == BvhBuildMethod::TopDownSah ? splitSah(n, step, trace && n.depth <= trace->candidatesToDepth)
                                                                 : splitMedian(n, i, step);
                const int left = addChildren(i);
                bvh.nodes[left].first = n.first;
                bvh.nodes[left].count = leftCount;
                bvh.nodes[left + 1].first = n.first + leftCount;
                bvh.nodes[left + 1].count = n.count - leftCount;
                stack.push_back(left + 1);
                stack.push_back(left);  // left first: depth-first, left to right
            }
            if (trace) trace->steps.push_back(step);
        }
        if (bvh.kind == BvKind::Aabb) fitAabbsBottomUp();
        if (trace)
            for (BvhBuildStep& step : trace->steps) step.box = bvh.box(step.node);
    }

    /// AABBs of all nodes: leaves fitted to their triangles, inner nodes the union of their
    /// children (children have larger indices, so a backward walk sees them first).
    void fitAabbsBottomUp() {
        for (int i = static_cast<int>(bvh.nodes.size()) - 1; i >= 0; --i) {
            const BvhNode& n = bvh.nodes[i];
            if (n.isLeaf()) fit(i);
            else bvh.aabbs[i] = unionOf(bvh.aabbs[n.left], bvh.aabbs[n.right]);
        }
    }

    /// Agglomerative clustering (Walter et al. 2008, plain form): every cluster caches its
    /// nearest neighbour (smallest union surface area). After merging a and b into k, only the
    /// clusters whose neighbour was a or b need a new search: for any other x,
    /// area(x u k) >= area(x u a) >= area(x u nn(x)) because k's box contains a's.
    void buildBottomUp(BvhBuildTrace* trace) {
        const int n = mesh.triangleCount();
        const int total = 2 * n - 1;
        std::vector<Aabb> box(total);
        std::vector<int> childA(total, -1), childB(total, -1), count(total, 1), nn(total, -1);
        std::vector<double> nnCost(total, std::numeric_limits<double>::infinity());
        std::vector<double> mergeArea(total, 0.0);
        for (int i = 0; i < n; ++i) box[i] = triangleAabb(mesh.triangle(i));
        std::vector<int> active(n);
        for (int i = 0; i < n; ++i) active[i] = i;
        auto findNearest = [&](int id) {
            nn[id] = -1;
            nnCost[id] = std::numeric_limits<double>::infinity();
            for (int other : active) {
                if (other == id) continue;
                const double c = area(unionOf(box[id], box[other]));
                if (nn[id] < 0 || c < nnCost[id] || (c == nnCost[id] && other < nn[id])) {
                    nnCost[id] = c;
                    nn[id] = other;
                }
            }
        };
        for (int id : active) findNearest(id);
        int next = n;
        while (active.size() > 1) {
            // The globally closest pair (smallest cached cost; ties: smallest id).
            size_t best = 0;
            for (size_t s = 1; s < active.size(); ++s) {
                const int id = active[s];
                if (nnCost[id] < nnCost[active[best]] || (nnCost[id] == nnCost[active[best]] && id < active[best]))
                    best = s;
            }
            const int a = active[best], b = nn[a];
            const int k = next++;
            box[k] = unionOf(box[a], box[b]);
            childA[k] = a;
            childB[k] = b;
            count[k] = count[a] + count[b];
            mergeArea[k] = area(box[k]);
            active.erase(std::remove_if(active.begin(), active.end(), [&](int id) { return id == a || id == b; }),
                         active.end());
            active.push_back(k);
            findNearest(k);
            for (int id : active)
                if (id != k && (nn[id] == a || nn[id] == b)) findNearest(id);
        }
        // Emit the flat tree: children in adjacent slots, ranges in depth-first order; a cluster of
        // at most maxLeafTriangles triangles becomes one leaf.
        const int maxLeaf = std::max(1, options.maxLeafTriangles);
        reserve(n);
        std::vector<int> clusterOfNode;
        clusterOfNode.reserve(2 * static_cast<size_t>(n));
        BvhNode root;
        root.count = n;
        bvh.nodes.push_back(root);
        clusterOfNode.push_back(total - 1);
        if (bvh.kind == BvKind::Aabb) bvh.aabbs.resize(1);
        else bvh.obbs.resize(1);
        std::vector<int> stack{0}, leafStack;
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            const int c = clusterOfNode[i];
            const BvhNode n = bvh.nodes[i];
            if (count[c] <= maxLeaf) {
                int pos = n.first;
                leafStack.assign(1, c);
                while (!leafStack.empty()) {
                    const int x = leafStack.back();
                    leafStack.pop_back();
                    if (childA[x] < 0) {
                        bvh.triangleOrder[pos++] = x;
                    } else {
                        leafStack.push_back(childB[x]);
                        leafStack.push_back(childA[x]);
                    }
                }
                continue;
            }
            const int left = addChildren(i);
            clusterOfNode.push_back(childA[c]);
            clusterOfNode.push_back(childB[c]);
            bvh.nodes[left].first = n.first;
            bvh.nodes[left].count = count[childA[c]];
            bvh.nodes[left + 1].first = n.first + count[childA[c]];
            bvh.nodes[left + 1].count = count[childB[c]];
            stack.push_back(left + 1);
            stack.push_back(left);
        }
        if (bvh.kind == BvKind::Aabb) fitAabbsBottomUp();
        else
            for (int i = 0; i < static_cast<int>(bvh.nodes.size()); ++i) fit(i);
        if (trace) {
            // Merge order: the nodes sorted by cluster id (triangles first, then each merge).
            std::vector<int> order(bvh.nodes.size());
            for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
            std::sort(order.begin(), order.end(), [&](int x, int y) { return clusterOfNode[x] < clusterOfNode[y]; });
            for (int i : order) {
                BvhBuildStep step;
                step.node = i;
                step.depth = bvh.nodes[i].depth;
                step.first = bvh.nodes[i].first;
                step.count = bvh.nodes[i].count;
                step.box = bvh.box(i);
                step.cost = unscaledArea(mergeArea[clusterOfNode[i]]);
                trace->steps.push_back(step);
            }
        }
    }
};

// ---- basic traversal ------------------------------------------------------------------------

/// Depth-first traversal of one tree: overlaps(node) is the BV test, leaf(node) handles the
/// triangles of an overlapping leaf.
template <class Overlaps, class Leaf>
void traverseOne(const Bvh& bvh, BvhQueryStats& stats, BvhTraversalTrace* trace, Overlaps&& overlaps, Leaf&& leaf) {
    if (bvh.status != BvhStatus::Ok || bvh.empty()) return;
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        ++stats.bvTests;
        const bool ov = overlaps(i);
        const BvhNode& n = bvh.nodes[i];
        BvhTraversalStep step;
        step.nodeA = i;
        step.overlap = ov;
        if (!ov) {
            step.action = BvhTraversalAction::Prune;
        } else if (n.isLeaf()) {
            step.action = BvhTraversalAction::LeafTest;
        } else {
            step.action = BvhTraversalAction::DescendA;
            stack.push_back(n.right);
            stack.push_back(n.left);
        }
        if (trace) trace->steps.push_back(step);
        if (ov && n.isLeaf()) {
            ++stats.leafVisits;
            for (int k = n.first; k < n.first + n.count; ++k) leaf(i, bvh.triangleOrder[k]);
        }
    }
}

void recordTriangle(BvhTraversalTrace* trace, int node, int tri, bool hit) {
    if (!trace) return;
    BvhTraversalStep step;
    step.nodeA = node;
    step.action = BvhTraversalAction::TriangleTest;
    step.triangleA = tri;
    step.triangleHit = hit;
    trace->steps.push_back(step);
}

/// The query box in the tree's body frame, widened by the rounding margin.
Obb toBody(const Obb& world, const Transform& pose, double margin) {
    const Mat3 Rt = pose.rotation.toRotationMatrix().transpose();
    Obb b{Rt * (world.center - pose.position), world.halfExtents, Rt * world.axes};
    b.halfExtents.array() += margin;
    return b;
}

}  // namespace

const char* nameOf(BvKind kind) { return kind == BvKind::Aabb ? "AABB" : "OBB"; }

const char* nameOf(BvhBuildMethod method) {
    switch (method) {
        case BvhBuildMethod::TopDownMedian: return "top_down_median";
        case BvhBuildMethod::TopDownSah: return "top_down_sah";
        case BvhBuildMethod::BottomUp: return "bottom_up";
    }
    return "?";
}

const char* nameOf(BvhStatus status) {
    switch (status) {
        case BvhStatus::Ok: return "ok";
        case BvhStatus::InvalidMesh: return "invalid mesh";
        case BvhStatus::TooManyTrianglesForBottomUp: return "too many triangles for bottom-up";
        case BvhStatus::TopologyMismatch: return "topology mismatch";
    }
    return "?";
}

const char* nameOf(BvhTraversalAction action) {
    switch (action) {
        case BvhTraversalAction::Prune: return "prune";
        case BvhTraversalAction::DescendA: return "descend A";
        case BvhTraversalAction::DescendB: return "descend B";
        case BvhTraversalAction::LeafTest: return "leaf test";
        case BvhTraversalAction::TriangleTest: return "triangle test";
    }
    return "?";
}

Obb Bvh::box(int node) const { return kind == BvKind::Aabb ? aabbToObb(aabbs[node]) : obbs[node]; }

int Bvh::height() const {
    int h = -1;
    for (const BvhNode& n : nodes) h = std::max(h, n.depth);
    return h;
}

Bvh buildBvh(const TriangleMesh& mesh, const BvhBuildOptions& options, BvhBuildTrace* trace) {
    Bvh bvh;
    bvh.kind = options.bvKind;
    bvh.method = options.method;
    if (validateMesh(mesh).status != MeshStatus::Valid) {
        bvh.status = BvhStatus::InvalidMesh;
        return bvh;
    }
    const int n = mesh.triangleCount();
    if (options.method == BvhBuildMethod::BottomUp && n > options.bottomUpMaxTriangles) {
        bvh.status = BvhStatus::TooManyTrianglesForBottomUp;
        return bvh;
    }
    if (n == 0) return bvh;
    bvh.vertexRadius = maxVertexRadius(mesh);
    bvh.triangleOrder.resize(n);
    for (int i = 0; i < n; ++i) bvh.triangleOrder[i] = i;
    Builder builder(mesh, options, bvh);
    if (options.method == BvhBuildMethod::BottomUp) builder.buildBottomUp(trace);
    else builder.buildTopDown(trace);
    return bvh;
}

BvhStatus refitBvh(Bvh& bvh, const TriangleMesh& deformed) {
    if (deformed.triangleCount() != bvh.triangleCount()) return BvhStatus::TopologyMismatch;
    if (validateMesh(deformed).status != MeshStatus::Valid) return BvhStatus::InvalidMesh;
    if (bvh.status != BvhStatus::Ok) return bvh.status;
    bvh.vertexRadius = maxVertexRadius(deformed);
    // Children have larger indices than their parents: walking backwards visits children first.
    for (int i = static_cast<int>(bvh.nodes.size()) - 1; i >= 0; --i) {
        const BvhNode& n = bvh.nodes[i];
        if (bvh.kind == BvKind::Aabb) {
            if (!n.isLeaf()) {
                bvh.aabbs[i] = unionOf(bvh.aabbs[n.left], bvh.aabbs[n.right]);
                continue;
            }
            Aabb b = emptyAabb();
            for (int k = n.first; k < n.first + n.count; ++k) {
                const Triangle t = deformed.triangle(bvh.triangleOrder[k]);
                grow(b, t.a);
                grow(b, t.b);
                grow(b, t.c);
            }
            bvh.aabbs[i] = b;
            continue;
        }
        // OBB: keep the axes, new extents of the node's vertices on them.
        Obb& box = bvh.obbs[i];
        const Mat3 At = box.axes.transpose();
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (int k = n.first; k < n.first + n.count; ++k) {
            const Triangle t = deformed.triangle(bvh.triangleOrder[k]);
            for (const Vec3* v : {&t.a, &t.b, &t.c}) {
                const Vec3 p = At * *v;
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
        }
        box.center = box.axes * (0.5 * (lo + hi));
        box.halfExtents = 0.5 * (hi - lo);
        inflate(box);
    }
    return BvhStatus::Ok;
}

bool testTriangleObb(const Triangle& triangle, const Obb& box) {
    const Mat3 At = box.axes.transpose();
    const Triangle local{At * (triangle.a - box.center), At * (triangle.b - box.center),
                         At * (triangle.c - box.center)};
    return testTriangleAabb(local, Aabb{-box.halfExtents, box.halfExtents}).hit;
}

BvhQueryResult queryBvhBox(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose, const Obb& box,
                           BvhTraversalTrace* trace) {
    BvhQueryResult result;
    const double margin =
        kBvMarginRelative * (bvh.vertexRadius + pose.position.norm() + box.center.norm() + box.halfExtents.norm());
    const Obb q = toBody(box, pose, margin);
    traverseOne(
        bvh, result.stats, trace, [&](int i) { return obbOverlap(bvh.box(i), q); },
        [&](int node, int tri) {
            result.candidates.push_back(tri);
            ++result.stats.triangleTests;
            const bool hit = testTriangleObb(mesh.triangle(tri, pose), box);
            if (hit) result.hits.push_back(tri);
            recordTriangle(trace, node, tri, hit);
        });
    return result;
}

BvhQueryResult queryBvhTriangle(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose,
                                const Triangle& triangle, BvhTraversalTrace* trace) {
    BvhQueryResult result;
    // The query triangle's AABB in the body frame, widened by the margin.
    Aabb qb = emptyAabb();
    for (const Vec3* v : {&triangle.a, &triangle.b, &triangle.c}) grow(qb, pose.applyInverse(*v));
    const double margin = kBvMarginRelative * (bvh.vertexRadius + pose.position.norm() + qb.min.norm() + qb.max.norm());
    qb.min.array() -= margin;
    qb.max.array() += margin;
    const Obb q = aabbToObb(qb);
    traverseOne(
        bvh, result.stats, trace,
        [&](int i) {
            if (bvh.kind == BvKind::Aabb) return testAabbAabb(bvh.aabbs[i], qb).hit;
            return obbOverlap(bvh.obbs[i], q);
        },
        [&](int node, int tri) {
            result.candidates.push_back(tri);
            ++result.stats.triangleTests;
            const bool hit = intersectTriangleTriangle(mesh.triangle(tri, pose), triangle).hit;
            if (hit) result.hits.push_back(tri);
            recordTriangle(trace, node, tri, hit);
        });
    return result;
}

BvhQueryResult queryBvhRay(const Bvh& bvh, const TriangleMesh& mesh, const Transform& pose, const Ray& ray,
                           BvhTraversalTrace* trace) {
    BvhQueryResult result;
    const Mat3 Rt = pose.rotation.toRotationMatrix().transpose();
    const Ray body{Rt * (ray.origin - pose.position), Rt * ray.direction};
    const double margin = kBvMarginRelative * (bvh.vertexRadius + pose.position.norm() + ray.origin.norm());
    traverseOne(
        bvh, result.stats, trace,
        [&](int i) {
            if (bvh.kind == BvKind::Aabb) {
                Aabb b = bvh.aabbs[i];
                b.min.array() -= margin;
                b.max.array() += margin;
                return intersectRayAabb(body, b).hit;
            }
            const Obb& o = bvh.obbs[i];
            const Mat3 At = o.axes.transpose();
            const Ray local{At * (body.origin - o.center), At * body.direction};
            const Vec3 h = o.halfExtents.array() + margin;
            return intersectRayAabb(local, Aabb{-h, h}).hit;
        },
        [&](int node, int tri) {
            result.candidates.push_back(tri);
            ++result.stats.triangleTests;
            const RayTriangleHit h = intersectRayTriangle(ray, mesh.triangle(tri, pose));
            if (h.hit) {
                result.hits.push_back(tri);
                if (result.firstTriangle < 0 || h.t < result.firstT) {
                    result.firstT = h.t;
                    result.firstTriangle = tri;
                }
            }
            recordTriangle(trace, node, tri, h.hit);
        });
    return result;
}

BvhQueryStats traverseBvhPair(const Bvh& a, const Transform& poseA, const Bvh& b, const Transform& poseB,
                              const BvhLeafPairCallback& onLeafPair, BvhTraversalTrace* trace) {
    BvhQueryStats stats;
    if (a.status != BvhStatus::Ok || b.status != BvhStatus::Ok || a.empty() || b.empty()) return stats;
    // B's body frame into A's: x_A = Rrel x_B + trel.
    const Mat3 Ra = poseA.rotation.toRotationMatrix();
    const Mat3 Rrel = Ra.transpose() * poseB.rotation.toRotationMatrix();
    const Vec3 trel = Ra.transpose() * (poseB.position - poseA.position);
    const bool noRotation = Rrel == Mat3::Identity();
    const double margin =
        kBvMarginRelative * (a.vertexRadius + b.vertexRadius + poseA.position.norm() + poseB.position.norm());
    auto overlaps = [&](int i, int j) {
        if (noRotation && a.kind == BvKind::Aabb && b.kind == BvKind::Aabb) {
            // AABB-AABB (Ericson §4.2.1) with B's box translated into A's frame.
            const Aabb& x = a.aabbs[i];
            const Aabb& y = b.aabbs[j];
            for (int k = 0; k < 3; ++k)
                if (x.min[k] > y.max[k] + trel[k] + margin || y.min[k] + trel[k] - margin > x.max[k]) return false;
            return true;
        }
        const Obb ob = b.box(j);
        Obb yb{Rrel * ob.center + trel, ob.halfExtents, Rrel * ob.axes};
        yb.halfExtents.array() += margin;
        return obbOverlap(a.box(i), yb);
    };
    std::vector<std::pair<int, int>> stack{{0, 0}};
    while (!stack.empty()) {
        const auto [i, j] = stack.back();
        stack.pop_back();
        ++stats.bvTests;
        const bool ov = overlaps(i, j);
        const BvhNode& na = a.nodes[i];
        const BvhNode& nb = b.nodes[j];
        BvhTraversalStep step;
        step.nodeA = i;
        step.nodeB = j;
        step.overlap = ov;
        if (!ov) {
            step.action = BvhTraversalAction::Prune;
            if (trace) trace->steps.push_back(step);
            continue;
        }
        if (na.isLeaf() && nb.isLeaf()) {
            step.action = BvhTraversalAction::LeafTest;
            if (trace) trace->steps.push_back(step);
            ++stats.leafVisits;
            if (onLeafPair(i, j)) return stats;
            continue;
        }
        // Descend larger (Ericson §6.3.2): split A if B is a leaf or A is at least as large.
        const bool descendA = nb.isLeaf() || (!na.isLeaf() && nodeSize(a, i) >= nodeSize(b, j));
        step.action = descendA ? BvhTraversalAction::DescendA : BvhTraversalAction::DescendB;
        if (trace) trace->steps.push_back(step);
        if (descendA) {
            stack.emplace_back(na.right, j);
            stack.emplace_back(na.left, j);
        } else {
            stack.emplace_back(i, nb.right);
            stack.emplace_back(i, nb.left);
        }
    }
    return stats;
}

}  // namespace cdlab
