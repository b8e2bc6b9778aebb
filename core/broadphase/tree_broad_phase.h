// Broad phase on a dynamic AABB tree with fat boxes (Box2D's b2BroadPhase, Bullet's
// btDbvtBroadphase; Catto, "Dynamic Bounding Volume Hierarchies", GDC 2019): each object's leaf
// (core/broadphase/dynamic_tree.h) holds its box grown by a margin and stretched along its last
// displacement (Box2D v2.4's b2DynamicTree::MoveProxy: predictFrames frames of the motion since the
// previous frame), so a body in steady motion is re-inserted every few frames, not every frame.
// A frame
//   1. re-inserts only the objects whose box left its fat box, or whose fat box has become much
//      larger than a new one would be (a body that stopped), with a new fat box about it,
//   2. queries the tree with the fat box of each of those, adding the pairs of overlapping fat boxes
//      to a set kept between frames (core/broadphase/pair_set.h),
//   3. drops the pairs whose fat boxes no longer overlap and reports those whose own boxes overlap
//      (closed: touching counts) — the same pairs as sweep and prune and the uniform grid.
// Per frame: O(moved · log n) tree work plus O(fat pairs) filtering; nothing allocated once the
// buffers have grown. A larger margin moves fewer leaves but keeps more fat pairs.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/broadphase/box_pair.h"
#include "core/broadphase/dynamic_tree.h"
#include "core/broadphase/pair_set.h"

namespace cdlab {

struct TreeBroadPhaseOptions {
    double margin = 0.1;  ///< fat box = box grown by this on every side (world units; NaN or < 0: 0)
    /// The fat box also reaches this many frames of the last displacement ahead (0: no prediction;
    /// NaN or < 0: 0), at most 4 margins plus the box's size on each axis.
    double predictFrames = 4.0;
    DynamicTreeOptions tree;
};

struct TreeBroadPhaseResult {
    BoxStatus status = BoxStatus::Ok;
    int object = -1;             ///< the offending box when status is not Ok (nothing changed then)
    int moved = 0;               ///< objects re-inserted (or inserted) this frame
    std::int64_t fatPairs = 0;   ///< pairs of overlapping fat boxes kept
    int pairs = 0;
};

class TreeBroadPhase {
public:
    explicit TreeBroadPhase(const TreeBroadPhaseOptions& options = {})
        : options_(options),
          tree_(options.tree),
          margin_(options.margin >= 0 && options.margin < INFINITY ? options.margin : 0.0),
          predictFrames_(options.predictFrames >= 0 && options.predictFrames < INFINITY ? options.predictFrames : 0.0) {}

    /// Room for `objects` objects and `pairs` fat pairs without allocation.
    void reserve(int objects, int pairs);
    /// The boxes of objects 0..n-1 this frame; n may change between frames (objects n.. removed,
    /// new ones inserted). A non-finite or empty box is refused (status, object) and nothing changes.
    TreeBroadPhaseResult update(const std::vector<Aabb>& boxes);

    /// Pairs whose boxes overlap (a < b), each once, in no particular order.
    const std::vector<BoxPair>& pairs() const { return pairs_; }
    const DynamicAabbTree& tree() const { return tree_; }
    const Aabb& fatBox(int id) const { return fat_[id]; }
    int leafOf(int id) const { return leaf_[id]; }
    const TreeBroadPhaseOptions& options() const { return options_; }

private:
    void insertOrMove(int id, const Aabb& box, const Vec3& displacement);
    Aabb fatAbout(const Aabb& box, const Vec3& displacement) const;
    void queryMoved();
    void filterPairs(const std::vector<Aabb>& boxes);

    TreeBroadPhaseOptions options_;
    DynamicAabbTree tree_;
    double margin_, predictFrames_;  ///< the options, NaN and negative values as 0
    std::vector<int> leaf_;
    std::vector<Aabb> fat_, last_;  ///< fat boxes; the boxes of the previous frame
    std::vector<char> moved_;
    std::vector<int> movedList_;
    PairSet fatSet_;
    std::vector<BoxPair> fatPairs_, pairs_;
};

}  // namespace cdlab
