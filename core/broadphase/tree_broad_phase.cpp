#include "core/broadphase/tree_broad_phase.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

void TreeBroadPhase::reserve(int objects, int pairs) {
    tree_.reserve(objects);
    leaf_.reserve(objects);
    fat_.reserve(objects);
    moved_.reserve(objects);
    movedList_.reserve(objects);
    fatSet_.reserve(static_cast<std::size_t>(pairs));
    fatPairs_.reserve(static_cast<std::size_t>(pairs));
    pairs_.reserve(static_cast<std::size_t>(pairs));
}

TreeBroadPhaseResult TreeBroadPhase::update(const std::vector<Aabb>& boxes) {
    TreeBroadPhaseResult r;
    const int n = static_cast<int>(boxes.size());
    for (int i = 0; i < n; ++i) {
        r.status = checkBox(boxes[i]);
        if (r.status != BoxStatus::Ok) {
            r.object = i;
            return r;
        }
    }
    for (int id = static_cast<int>(leaf_.size()) - 1; id >= n; --id) tree_.remove(leaf_[id]);
    const int kept = std::min(n, static_cast<int>(leaf_.size()));
    leaf_.resize(static_cast<std::size_t>(n), DynamicAabbTree::kNull);
    fat_.resize(static_cast<std::size_t>(n));
    last_.resize(static_cast<std::size_t>(n));
    moved_.assign(static_cast<std::size_t>(n), 0);
    movedList_.clear();
    for (int id = 0; id < n; ++id) {
        if (id >= kept) {
            insertOrMove(id, boxes[id], Vec3::Zero());
        } else if (!contains(fat_[id], boxes[id])) {
            insertOrMove(id, boxes[id], boxes[id].min - last_[id].min);
        } else {
            // Still inside, but a fat box far larger than a fresh one (it was stretched along a
            // motion that has stopped) would keep pairs that a tight one drops: shrink it. Slack:
            // 4 margins, and on each axis the stretch a body moving as now has (behind it the old
            // fat box trails by the frames since it was made).
            const Vec3 displacement = boxes[id].min - last_[id].min;
            const Aabb fresh = fatAbout(boxes[id], displacement);
            const Vec3 slack = Vec3::Constant(4.0 * margin_) + predictFrames_ * displacement.cwiseAbs();
            if (!contains(Aabb{fresh.min - slack, fresh.max + slack}, fat_[id]))
                insertOrMove(id, boxes[id], displacement);
        }
        last_[id] = boxes[id];
    }
    queryMoved();
    filterPairs(boxes);
    r.moved = static_cast<int>(movedList_.size());
    r.fatPairs = static_cast<std::int64_t>(fatPairs_.size());
    r.pairs = static_cast<int>(pairs_.size());
    return r;
}

// The box grown by the margin and stretched along predictFrames times the displacement. The
// stretch is capped at 4 margins plus the box's own extent on that axis: a teleport is not a
// velocity (stretched 4 jumps ahead, one frame's fat box would meet half the scene).
Aabb TreeBroadPhase::fatAbout(const Aabb& box, const Vec3& displacement) const {
    const Vec3 m = Vec3::Constant(margin_);
    Aabb fat{box.min - m, box.max + m};
    for (int k = 0; k < 3; ++k) {
        const double cap = 4.0 * margin_ + (box.max[k] - box.min[k]);
        const double ahead = std::clamp(predictFrames_ * displacement[k], -cap, cap);
        if (!std::isfinite(ahead)) continue;  // a jump across the double range: no prediction
        if (ahead < 0) fat.min[k] += ahead;
        else fat.max[k] += ahead;
    }
    return fat;
}

// Stage 1: a new fat box about the box; the leaf inserted or moved.
void TreeBroadPhase::insertOrMove(int id, const Aabb& box, const Vec3& displacement) {
    fat_[id] = fatAbout(box, displacement);
    if (leaf_[id] == DynamicAabbTree::kNull) leaf_[id] = tree_.insert(fat_[id], id);
    else tree_.move(leaf_[id], fat_[id]);
    moved_[id] = 1;
    movedList_.push_back(id);
}

// Stage 2: the fat pairs of the moved objects. A pair of two moved objects is found by both
// queries: the one of the larger id skips it.
void TreeBroadPhase::queryMoved() {
    for (int p : movedList_)
        tree_.query(fat_[p], [&](int q, int) {
            if (q == p || (moved_[q] && q < p)) return;
            const BoxPair pair = BoxPair::make(p, q);
            if (fatSet_.insert(pair)) fatPairs_.push_back(pair);
        });
}

// Stage 3: fat pairs apart dropped (only a moved object's fat box changed, but one pass over
// the set also filters the reported pairs); objects beyond n are gone.
void TreeBroadPhase::filterPairs(const std::vector<Aabb>& boxes) {
    const int n = static_cast<int>(boxes.size());
    pairs_.clear();
    for (std::size_t i = 0; i < fatPairs_.size();) {
        const BoxPair pair = fatPairs_[i];
        if (pair.b >= n || !overlaps(fat_[pair.a], fat_[pair.b])) {
            fatSet_.erase(pair);
            fatPairs_[i] = fatPairs_.back();
            fatPairs_.pop_back();
            continue;
        }
        if (overlaps(boxes[pair.a], boxes[pair.b])) pairs_.push_back(pair);
        ++i;
    }
}

}  // namespace cdlab
