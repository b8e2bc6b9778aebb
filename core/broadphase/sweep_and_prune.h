// Sweep and prune (sort and sweep) over n moving axis-aligned boxes: Baraff, "Dynamic
// Simulation of Non-Penetrating Rigid Bodies", PhD thesis, Cornell 1992, §6.2 ("Bounding
// boxes: coherence"); Cohen, Lin, Manocha, Ponamgi, "I-COLLIDE", Symposium on Interactive 3D
// Graphics 1995, §4; Ericson, Real-Time Collision Detection §7.5.2.
//
// Each axis keeps the 2n interval endpoints of the boxes sorted. Two closed boxes overlap iff
// their intervals overlap on all three axes, and on one axis intervals [a0, a1], [b0, b1] overlap
// iff a0 comes before b1 and b0 before a1 in the sorted list. When the boxes move a little, the
// lists are almost sorted: insertion sort repairs them in O(n + s), s = the number of adjacent
// swaps (= inversions between the old order and the new values). Only a swap of a min with a
// max endpoint changes whether two intervals overlap on that axis, so the overlapping-pair set
// is maintained from the swaps alone: a min moving left past a max starts an axis overlap (the
// pair is added when the other two axes overlap too), a max moving left past a min ends one (the
// pair is removed if it was reported). Update cost O(n + s + pair changes); with coherent motion
// s is small and a frame costs O(n + k), k = pair changes. Caveat (measured in cdlab bench): s
// counts endpoints crossed on each axis, so at constant 3D density and speed s / n grows like
// n^(2/3) (the 1D projections get denser); s = O(n) when motion per frame shrinks accordingly.
//
// Per-pair axis count: I-COLLIDE keeps an n x n matrix of per-axis overlap flags; here the
// "number of overlapping axes" of a pair is read from the endpoint RANKS on the three axes
// (positions in the sorted arrays, O(1)), so memory is O(n + pairs reported), not O(pairs that
// overlap on any one axis) (~8e7 pairs for the 100k boxes of cdlab bench). Ranks, not
// coordinates, are compared: while axis x is being repaired, axis y still holds last frame's
// order, and the reported set is always exactly {pairs whose ranks overlap on all three axes};
// after all three axes are sorted, that is the set of overlapping boxes.
//
// Ties (closed boxes): at equal coordinates a min endpoint sorts before a max endpoint, so
// touching boxes (a1 == b0) overlap, as in testAabbAabb (core/overlap/sat_tests.h). Equal endpoints of the
// same kind are never swapped (the order among them does not change any overlap).
//
// Ids are stable: an object keeps its id until removed; a removed id may be reused by add().
// Steady state: update() allocates nothing (arrays and the pair hash set are reused) unless the
// pair set outgrows its capacity or a trace is recorded. Not thread-safe.
#pragma once

#include <cstdint>
#include <vector>

#include "core/broadphase/box_pair.h"

namespace cdlab {

enum class SapStatus {
    Ok,
    NonFiniteBox,   ///< a live box has a NaN / inf coordinate: nothing was changed
    EmptyBox,       ///< a live box has min > max on some axis: nothing was changed
    WrongBoxCount,  ///< update(): boxes.size() != idCapacity(): nothing was changed
    UnknownId,      ///< remove(): the id is not a live object
};

/// One endpoint in an axis list: a coordinate and which object's min or max it is.
struct SapEndpoint {
    double value = 0.0;
    std::uint32_t tag = 0;  ///< 2 * object + (1 for a max endpoint)

    int object() const { return static_cast<int>(tag >> 1); }
    bool isMax() const { return (tag & 1u) != 0; }
};

enum class SapPairEvent {
    None,     ///< the swap changed an axis overlap but not the reported set
    Added,    ///< the pair now overlaps on all three axes: reported
    Removed,  ///< the pair stopped overlapping on this axis: no longer reported
};

/// "none", "added", "removed".
const char* nameOf(SapPairEvent event);

/// One adjacent swap of insertion sort: `moving` (the endpoint being inserted) jumps left over
/// `passed`, which moves one slot right. Values are this update's coordinates.
struct SapSwap {
    int axis = 0;
    int movingObject = 0;
    bool movingIsMax = false;
    double movingValue = 0.0;
    int passedObject = 0;
    bool passedIsMax = false;
    double passedValue = 0.0;
    int position = 0;  ///< index of the moving endpoint after the swap (passed is at position + 1)
    SapPairEvent event = SapPairEvent::None;
    int axesOverlapping = 0;  ///< after the swap: on how many axes the two objects' ranks overlap (0..3)
};

/// build()'s sweep met `other` in the active list: their x intervals overlap; the pair is added
/// iff their ranks overlap on y and on z too.
struct SapSweepTest {
    int other = 0;
    bool overlapY = false, overlapZ = false;
};

/// One endpoint of build()'s sweep along x, in sorted order. A min endpoint meets every box in
/// the active list (tests, in list order) and joins it; a max endpoint leaves it.
struct SapSweepStep {
    SapEndpoint endpoint;
    std::vector<SapSweepTest> tests;  ///< empty for a max endpoint
    std::vector<int> active;          ///< the active list after this step, in list order
};

/// Everything one call did, in order (cleared at the start of each call that takes it).
struct SapTrace {
    std::vector<SapSweepStep> sweep;  ///< build() only: its sweep along x, one step per x endpoint
    std::vector<SapSwap> swaps;  ///< axis x first, then y, then z
    int swapsPerAxis[3] = {0, 0, 0};
    std::vector<BoxPair> added;  ///< pair events in order; a pair may be added and removed in one update
    std::vector<BoxPair> removed;
};

/// Outcome of build / update / add / remove.
struct SapResult {
    SapStatus status = SapStatus::Ok;
    int object = -1;         ///< the offending id when status is a box error; the new id for add()
    std::int64_t swaps = 0;  ///< adjacent swaps of this call (all three axes)
    std::int64_t swapsPerAxis[3] = {0, 0, 0};
    int pairsAdded = 0;  ///< pair events of this call
    int pairsRemoved = 0;
};

/// Totals since construction (or the last build).
struct SapCounters {
    std::int64_t updates = 0, swaps = 0, pairsAdded = 0, pairsRemoved = 0;
};

class SweepAndPrune {
public:
    /// Presizes the endpoint arrays for `objects` and the pair set for `pairs` so that updates
    /// allocate nothing.
    void reserve(int objects, int pairs);

    /// Drops everything and inserts boxes[i] as object i: sort per axis (O(n log n)), then one
    /// sweep along x for the initial pairs. Rejects non-finite or empty boxes (nothing changed).
    SapResult build(const std::vector<Aabb>& boxes, SapTrace* trace = nullptr);

    /// New coordinates for every object: boxes[id] for each live id (entries of free ids are
    /// ignored; boxes.size() must be idCapacity()). Insertion sort per axis, pairs from the swaps.
    SapResult update(const std::vector<Aabb>& boxes, SapTrace* trace = nullptr);

    /// Inserts one box (O(n + swaps)): its endpoints enter at the end of each list and are
    /// insertion-sorted into place. result.object is the new id (-1 if rejected).
    SapResult add(const Aabb& box, SapTrace* trace = nullptr);

    /// Removes object `id` and every pair it is in (reported in trace->removed); O(n + k).
    SapResult remove(int id, SapTrace* trace = nullptr);

    /// The reported pairs (a < b), in no particular order.
    const std::vector<BoxPair>& pairs() const { return pairs_; }
    /// True when the pair (a, b) is reported.
    bool reported(int a, int b) const;
    /// The sorted endpoint list of axis 0, 1 or 2 (x, y, z).
    const std::vector<SapEndpoint>& endpoints(int axis) const { return endpoints_[axis]; }
    /// Index of object id's min (or max) endpoint in endpoints(axis).
    int rank(int axis, int id, bool isMax) const { return static_cast<int>(ranks_[id].of[axis][isMax ? 1 : 0]); }
    int objectCount() const { return liveCount_; }
    /// One past the largest id ever handed out (the size update() expects).
    int idCapacity() const { return static_cast<int>(boxes_.size()); }
    bool alive(int id) const { return id >= 0 && id < idCapacity() && alive_[id]; }
    /// The coordinates last given for `id`.
    const Aabb& box(int id) const { return boxes_[id]; }
    const SapCounters& counters() const { return counters_; }

private:
    void sortAxis(int axis, std::size_t from, SapTrace* trace, SapResult& result);
    void sortAxisUntraced(int axis, std::size_t from, SapResult& result);
    void swapped(int axis, const SapEndpoint& moving, const SapEndpoint& passed, std::size_t position, SapTrace* trace,
                 SapResult& result);
    bool overlapOnAxis(int axis, int a, int b) const {
        const std::uint32_t* ra = ranks_[a].of[axis];
        const std::uint32_t* rb = ranks_[b].of[axis];
        return ra[0] < rb[1] && rb[0] < ra[1];
    }
    void addPair(int a, int b, SapTrace* trace, SapResult& result);
    bool removePair(int a, int b, SapTrace* trace, SapResult& result);
    void growSet(std::size_t capacity);
    std::size_t findSlot(std::uint64_t key) const;

    std::vector<SapEndpoint> endpoints_[3];
    /// Where one object's endpoints are in the three sorted lists, [axis][0 = min, 1 = max]; the
    /// six together in one cache line, as a swap reads or writes both objects' entries.
    struct alignas(32) Ranks {
        std::uint32_t of[3][2];
    };
    std::uint32_t& rankOf(int axis, std::uint32_t tag) { return ranks_[tag >> 1].of[axis][tag & 1u]; }
    std::vector<Ranks> ranks_;  ///< by object id
    std::vector<Aabb> boxes_;
    std::vector<char> alive_;
    std::vector<int> freeIds_;
    int liveCount_ = 0;
    // Reported pairs: a dense array (for iteration) and an open-addressing hash set with linear
    // probing (key -> index into pairs_), backward-shift deletion, so no tombstones accumulate.
    std::vector<BoxPair> pairs_;
    std::vector<std::uint64_t> slotKey_;
    std::vector<int> slotIndex_;
    SapCounters counters_;
    std::vector<int> active_, activeAt_;  ///< build(): the sweep's active list
};

}  // namespace cdlab
