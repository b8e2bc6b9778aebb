// Sort and sweep in columns: sweep and prune without coherence, for many boxes at once.
//
// Sort and sweep (Baraff 1992 §6.2; Ericson, Real-Time Collision Detection §7.5.2): sort the boxes
// by their min on one axis, then for each box walk the ones after it while their min is below its
// max, testing the other two axes. Alone, its cost is the number of pairs that overlap on the sweep
// axis, which at constant 3D density grows like n^(5/3): every box's interval meets ~n^(2/3) others.
// Cutting space into slabs along a second axis (the multi-SAP of Terdiman, "Sweep-and-prune", 2007;
// Bullet's btMultiSapBroadphase) leaves each sweep only the boxes of one slab; cutting along the
// third axis as well leaves columns, and a box meets ~1 candidate that shares its column and overlaps
// it on the sweep axis (measured 28 per box with slabs alone, 1 with columns, at 100k boxes): the
// sweep replaces the grid's third dimension and its hash table. O(n log(n / columns) + candidates)
// per frame, no state between frames (unlike SweepAndPrune's insertion sort, whose swaps per box
// grow like n^(2/3) at constant speed), so coherent and incoherent motion cost the same.
//
// Axes: the sweep axis is the one along which the box centres spread most, then the two others;
// each is cut every 2 mean box extents (a typical box lies in 1..2 slabs along each, ~2.25 columns),
// at most ~2n columns in all. Exactly-once rule: a pair shares every column of its overlap; it is
// reported only in the column that holds the overlap's start (max of the two mins on each of the
// two cut axes), whose indices are computed by the same floor as the boxes' column ranges, so it is
// always one of the shared columns. Touching boxes overlap (closed boxes, as testAabbAabb in
// core/overlap/sat_tests.h).
//
// Steady state: run() allocates nothing once its buffers have grown. Not thread-safe.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/broadphase/box_pair.h"

namespace cdlab {

struct ColumnSweepResult {
    BoxStatus status = BoxStatus::Ok;
    int object = -1;              ///< the offending box when status is not Ok
    int sweepAxis = 0;            ///< the axis sorted and swept; the two others are cut into columns
    int columns = 0;
    std::int64_t entries = 0;     ///< (column, box) entries: sum over boxes of columns spanned
    std::int64_t candidates = 0;  ///< pairs overlapping on the sweep axis within a column, tested
    int pairs = 0;
};

class ColumnSweep {
public:
    /// Every pair of overlapping boxes, each once (ids are indices into `boxes`). On a bad box
    /// (NaN / inf, or min > max) nothing is reported and the status says which.
    ColumnSweepResult run(const std::vector<Aabb>& boxes);
    const std::vector<BoxPair>& pairs() const { return pairs_; }

private:
    // A box in one column: its three intervals, the sweep axis first, copied so the sweep reads one
    // column's entries sequentially.
    struct Entry {
        double lo[3], hi[3];
        int id;
    };
    std::vector<Entry> entries_;
    std::vector<std::int64_t> columnStart_;  // counting sort by column: first entry of each column (64-bit:
                                             // counted before the entry budget is checked)
    std::vector<std::int64_t> cursor_;       // the next free entry of each column while filling
    std::vector<std::pair<std::uint64_t, std::uint32_t>> byMin_, scratch_;  // (min's key, box), radix sorted
    std::vector<BoxPair> pairs_;
};

}  // namespace cdlab
