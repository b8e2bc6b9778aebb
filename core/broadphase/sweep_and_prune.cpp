// Sweep and prune with incremental insertion sort (see sweep_and_prune.h; Baraff 1992 §6.2,
// Cohen et al. 1995 §4, Ericson §7.5.2).
#include "core/broadphase/sweep_and_prune.h"

#include <algorithm>

namespace cdlab {

const char* nameOf(SapPairEvent event) {
    switch (event) {
        case SapPairEvent::None: return "none";
        case SapPairEvent::Added: return "added";
        case SapPairEvent::Removed: return "removed";
    }
    return "?";
}

namespace {

constexpr std::uint64_t kEmptySlot = ~std::uint64_t{0};  // no pair has key (2^32-1, 2^32-1): a < b

/// Sort key of an endpoint: (coordinate, min before max). A min precedes a max at equal
/// coordinates so touching intervals overlap (closed boxes).
bool before(const SapEndpoint& p, const SapEndpoint& q) {
    return p.value < q.value || (p.value == q.value && !p.isMax() && q.isMax());
}

/// splitmix64 finalizer: spreads the (a, b) key over the table.
std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

BoxStatus firstBadBox(const std::vector<Aabb>& boxes, const std::vector<char>* alive, int& bad) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (alive && !(*alive)[i]) continue;
        const BoxStatus s = checkBox(boxes[i]);
        if (s != BoxStatus::Ok) {
            bad = static_cast<int>(i);
            return s;
        }
    }
    return BoxStatus::Ok;
}

SapStatus toSap(BoxStatus s) { return s == BoxStatus::NonFinite ? SapStatus::NonFiniteBox : SapStatus::EmptyBox; }

}  // namespace

void SweepAndPrune::reserve(int objects, int pairs) {
    for (int k = 0; k < 3; ++k) endpoints_[k].reserve(2 * static_cast<std::size_t>(objects));
    ranks_.reserve(objects);
    boxes_.reserve(objects);
    alive_.reserve(objects);
    pairs_.reserve(pairs);
    std::size_t capacity = 16;
    while (capacity < 2 * static_cast<std::size_t>(pairs)) capacity *= 2;  // load <= 1/2
    if (capacity > slotKey_.size()) growSet(capacity);
}

// ---- pair set ------------------------------------------------------------------------------------

std::size_t SweepAndPrune::findSlot(std::uint64_t key) const {
    const std::size_t mask = slotKey_.size() - 1;
    std::size_t i = mix(key) & mask;
    while (slotKey_[i] != key && slotKey_[i] != kEmptySlot) i = (i + 1) & mask;
    return i;
}

void SweepAndPrune::growSet(std::size_t capacity) {
    slotKey_.assign(capacity, kEmptySlot);
    slotIndex_.assign(capacity, -1);
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        const std::size_t s = findSlot(pairs_[i].key());
        slotKey_[s] = pairs_[i].key();
        slotIndex_[s] = static_cast<int>(i);
    }
}

bool SweepAndPrune::reported(int a, int b) const {
    if (slotKey_.empty() || a == b) return false;
    return slotKey_[findSlot(BoxPair::make(a, b).key())] != kEmptySlot;
}

void SweepAndPrune::addPair(int a, int b, SapTrace* trace, SapResult& result) {
    if (slotKey_.empty() || 2 * (pairs_.size() + 1) > slotKey_.size())
        growSet(std::max<std::size_t>(16, 2 * slotKey_.size()));
    const BoxPair p = BoxPair::make(a, b);
    const std::size_t s = findSlot(p.key());
    if (slotKey_[s] != kEmptySlot) return;  // already reported (cannot happen from a swap; defensive)
    slotKey_[s] = p.key();
    slotIndex_[s] = static_cast<int>(pairs_.size());
    pairs_.push_back(p);
    ++result.pairsAdded;
    ++counters_.pairsAdded;
    if (trace) trace->added.push_back(p);
}

bool SweepAndPrune::removePair(int a, int b, SapTrace* trace, SapResult& result) {
    if (slotKey_.empty()) return false;
    const BoxPair p = BoxPair::make(a, b);
    std::size_t i = findSlot(p.key());
    if (slotKey_[i] == kEmptySlot) return false;
    // Dense array: move the last pair into the hole and repoint its slot.
    const int hole = slotIndex_[i];
    const BoxPair last = pairs_.back();
    pairs_.pop_back();
    if (hole != static_cast<int>(pairs_.size())) {
        pairs_[hole] = last;
        slotIndex_[findSlot(last.key())] = hole;
    }
    // Backward-shift deletion (linear probing): pull later entries of the probe run into the
    // hole unless their home slot lies cyclically in (i, j].
    const std::size_t mask = slotKey_.size() - 1;
    std::size_t j = i;
    for (;;) {
        j = (j + 1) & mask;
        if (slotKey_[j] == kEmptySlot) break;
        const std::size_t home = mix(slotKey_[j]) & mask;
        const bool homeInRange = i < j ? (i < home && home <= j) : (i < home || home <= j);
        if (!homeInRange) {
            slotKey_[i] = slotKey_[j];
            slotIndex_[i] = slotIndex_[j];
            i = j;
        }
    }
    slotKey_[i] = kEmptySlot;
    slotIndex_[i] = -1;
    ++result.pairsRemoved;
    ++counters_.pairsRemoved;
    if (trace) trace->removed.push_back(p);
    return true;
}

// ---- sorting --------------------------------------------------------------------------------------

void SweepAndPrune::swapped(int axis, const SapEndpoint& moving, const SapEndpoint& passed, std::size_t position,
                            SapTrace* trace, SapResult& result) {
    ++result.swaps;
    ++result.swapsPerAxis[axis];
    ++counters_.swaps;
    const int a = moving.object(), b = passed.object();  // never equal: an object's min precedes its max
    const int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
    const bool others = overlapOnAxis(o1, a, b) && overlapOnAxis(o2, a, b);
    SapPairEvent event = SapPairEvent::None;
    bool overlapHere = false;
    if (!moving.isMax() && passed.isMax()) {
        // min of a now before max of b: the intervals start to overlap on this axis.
        overlapHere = true;
        if (others) {
            addPair(a, b, trace, result);
            event = SapPairEvent::Added;
        }
    } else if (moving.isMax() && !passed.isMax()) {
        // max of a now before min of b: they stop overlapping on this axis.
        if (others && removePair(a, b, trace, result)) event = SapPairEvent::Removed;
    } else {
        // min past min or max past max: the axis overlap is unchanged.
        overlapHere = overlapOnAxis(axis, a, b);
    }
    if (trace) {
        SapSwap s;
        s.axis = axis;
        s.movingObject = a;
        s.movingIsMax = moving.isMax();
        s.movingValue = moving.value;
        s.passedObject = b;
        s.passedIsMax = passed.isMax();
        s.passedValue = passed.value;
        s.position = static_cast<int>(position);
        s.event = event;
        s.axesOverlapping =
            (overlapHere ? 1 : 0) + (overlapOnAxis(o1, a, b) ? 1 : 0) + (overlapOnAxis(o2, a, b) ? 1 : 0);
        trace->swaps.push_back(s);
        ++trace->swapsPerAxis[axis];
    }
}

void SweepAndPrune::sortAxis(int axis, std::size_t from, SapTrace* trace, SapResult& result) {
    if (!trace) {
        sortAxisUntraced(axis, from, result);
        return;
    }
    std::vector<SapEndpoint>& e = endpoints_[axis];
    for (std::size_t i = std::max<std::size_t>(from, 1); i < e.size(); ++i) {
        const SapEndpoint cur = e[i];
        std::size_t j = i;
        // Insertion sort: strictly-before only, so equal keys never swap (O(n + inversions)).
        while (j > 0 && before(cur, e[j - 1])) {
            const SapEndpoint prev = e[j - 1];
            e[j] = prev;
            rankOf(axis, prev.tag) = static_cast<std::uint32_t>(j);
            --j;
            // Ranks on this axis stay consistent swap by swap (swapped() reads them for the trace).
            rankOf(axis, cur.tag) = static_cast<std::uint32_t>(j);
            e[j] = cur;
            swapped(axis, cur, prev, j, trace, result);
        }
    }
}

// The same insertion sort and pair events as the traced path, with less work per swap (the
// swaps are the cost at scale: ~158 per box per frame at 100k boxes in cdlab bench):
//  - the moving endpoint is written, with its rank, once where it lands: no event reads this
//    axis's ranks, only the other two axes', which do not change while this axis is sorted (the
//    moving object's are held in registers);
//  - no branch on the endpoint kinds: about half of the swaps pass an endpoint of the same kind
//    (min past min, max past max), which changes no overlap, in no predictable order. Each swap
//    evaluates the event condition (kinds differ and the ranks overlap on the other two axes)
//    without branches, reading the passed object's ranks from the cache line it has just
//    written; the one branch left is taken only for a pair event.
//  - the swap counts are summed in a local.
void SweepAndPrune::sortAxisUntraced(int axis, std::size_t from, SapResult& result) {
    SapEndpoint* e = endpoints_[axis].data();
    Ranks* ranks = ranks_.data();
    const std::size_t size = endpoints_[axis].size();
    const int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
    std::int64_t swaps = 0;
    for (std::size_t i = std::max<std::size_t>(from, 1); i < size; ++i) {
        const SapEndpoint cur = e[i];
        if (!before(cur, e[i - 1])) continue;
        const int a = cur.object();
        const std::uint32_t curKind = cur.tag & 1u;
        const Ranks& ra = ranks[a];
        const std::uint32_t aMin1 = ra.of[o1][0], aMax1 = ra.of[o1][1];
        const std::uint32_t aMin2 = ra.of[o2][0], aMax2 = ra.of[o2][1];
        std::size_t j = i;
        do {
            const SapEndpoint prev = e[j - 1];
            e[j] = prev;
            Ranks& rb = ranks[prev.tag >> 1];
            rb.of[axis][prev.tag & 1u] = static_cast<std::uint32_t>(j);
            --j;
            ++swaps;
            const bool event = ((prev.tag & 1u) != curKind) & (aMin1 < rb.of[o1][1]) & (rb.of[o1][0] < aMax1) &
                               (aMin2 < rb.of[o2][1]) & (rb.of[o2][0] < aMax2);
            if (event) [[unlikely]] {
                if (curKind == 0) addPair(a, prev.object(), nullptr, result);  // a's min passed b's max
                else removePair(a, prev.object(), nullptr, result);  // a's max passed b's min: apart on this axis
            }
        } while (j > 0 && before(cur, e[j - 1]));
        e[j] = cur;
        ranks[a].of[axis][curKind] = static_cast<std::uint32_t>(j);
    }
    result.swaps += swaps;
    result.swapsPerAxis[axis] += swaps;
    counters_.swaps += swaps;
}

// ---- public operations ----------------------------------------------------------------------------

SapResult SweepAndPrune::build(const std::vector<Aabb>& boxes, SapTrace* trace) {
    SapResult result;
    if (trace) *trace = SapTrace{};
    int bad = -1;
    const BoxStatus s = firstBadBox(boxes, nullptr, bad);
    if (s != BoxStatus::Ok) {
        result.status = toSap(s);
        result.object = bad;
        return result;
    }
    const std::size_t n = boxes.size();
    boxes_ = boxes;
    alive_.assign(n, 1);
    freeIds_.clear();
    liveCount_ = static_cast<int>(n);
    pairs_.clear();
    std::fill(slotKey_.begin(), slotKey_.end(), kEmptySlot);
    std::fill(slotIndex_.begin(), slotIndex_.end(), -1);
    counters_ = SapCounters{};
    ranks_.resize(n);
    for (int k = 0; k < 3; ++k) {
        std::vector<SapEndpoint>& e = endpoints_[k];
        e.resize(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            e[2 * i] = SapEndpoint{boxes[i].min[k], static_cast<std::uint32_t>(2 * i)};
            e[2 * i + 1] = SapEndpoint{boxes[i].max[k], static_cast<std::uint32_t>(2 * i + 1)};
        }
        // Full sort once; the tag breaks ties of equal keys so the initial order is deterministic.
        std::sort(e.begin(), e.end(), [](const SapEndpoint& p, const SapEndpoint& q) {
            return before(p, q) || (!before(q, p) && p.tag < q.tag);
        });
        for (std::size_t i = 0; i < 2 * n; ++i) rankOf(k, e[i].tag) = static_cast<std::uint32_t>(i);
    }
    // Initial pairs: sweep along x keeping the active intervals; a min meets every active box
    // (their x intervals overlap, min before max at ties) and is paired if y and z overlap too.
    active_.clear();
    activeAt_.assign(n, -1);
    for (const SapEndpoint& p : endpoints_[0]) {
        const int a = p.object();
        SapSweepStep* step = nullptr;
        if (trace) {
            trace->sweep.emplace_back();
            step = &trace->sweep.back();
            step->endpoint = p;
        }
        if (!p.isMax()) {
            for (int b : active_) {
                const bool y = overlapOnAxis(1, a, b), z = overlapOnAxis(2, a, b);
                if (step) step->tests.push_back(SapSweepTest{b, y, z});
                if (y && z) addPair(a, b, trace, result);
            }
            activeAt_[a] = static_cast<int>(active_.size());
            active_.push_back(a);
        } else {
            const int at = activeAt_[a];
            active_[at] = active_.back();
            activeAt_[active_[at]] = at;
            active_.pop_back();
        }
        if (step) step->active = active_;
    }
    return result;
}

SapResult SweepAndPrune::update(const std::vector<Aabb>& boxes, SapTrace* trace) {
    SapResult result;
    if (trace) *trace = SapTrace{};
    if (boxes.size() != boxes_.size()) {
        result.status = SapStatus::WrongBoxCount;
        return result;
    }
    int bad = -1;
    const BoxStatus s = firstBadBox(boxes, &alive_, bad);
    if (s != BoxStatus::Ok) {
        result.status = toSap(s);
        result.object = bad;
        return result;
    }
    ++counters_.updates;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!alive_[i]) continue;
        boxes_[i] = boxes[i];
        for (int k = 0; k < 3; ++k) {
            endpoints_[k][ranks_[i].of[k][0]].value = boxes[i].min[k];
            endpoints_[k][ranks_[i].of[k][1]].value = boxes[i].max[k];
        }
    }
    for (int k = 0; k < 3; ++k) sortAxis(k, 1, trace, result);
    return result;
}

SapResult SweepAndPrune::add(const Aabb& box, SapTrace* trace) {
    SapResult result;
    if (trace) *trace = SapTrace{};
    const BoxStatus s = checkBox(box);
    if (s != BoxStatus::Ok) {
        result.status = toSap(s);
        return result;
    }
    int id;
    if (!freeIds_.empty()) {
        id = freeIds_.back();
        freeIds_.pop_back();
        boxes_[id] = box;
        alive_[id] = 1;
    } else {
        id = idCapacity();
        boxes_.push_back(box);
        alive_.push_back(1);
        ranks_.resize(boxes_.size());
    }
    ++liveCount_;
    result.object = id;
    // Append on all three axes first: ranks at the end overlap nothing, so no pair is added until
    // the last axis is sorted in, when the other two hold their final ranks.
    const std::size_t at = endpoints_[0].size();
    for (int k = 0; k < 3; ++k) {
        endpoints_[k].push_back(SapEndpoint{box.min[k], static_cast<std::uint32_t>(2 * id)});
        endpoints_[k].push_back(SapEndpoint{box.max[k], static_cast<std::uint32_t>(2 * id + 1)});
        ranks_[id].of[k][0] = static_cast<std::uint32_t>(at);
        ranks_[id].of[k][1] = static_cast<std::uint32_t>(at + 1);
    }
    for (int k = 0; k < 3; ++k) sortAxis(k, at, trace, result);
    return result;
}

SapResult SweepAndPrune::remove(int id, SapTrace* trace) {
    SapResult result;
    if (trace) *trace = SapTrace{};
    if (!alive(id)) {
        result.status = SapStatus::UnknownId;
        result.object = id;
        return result;
    }
    result.object = id;
    for (std::size_t i = pairs_.size(); i-- > 0;) {
        if (i >= pairs_.size()) continue;
        const BoxPair p = pairs_[i];
        if (p.a == id || p.b == id) removePair(p.a, p.b, trace, result);
    }
    for (int k = 0; k < 3; ++k) {
        std::vector<SapEndpoint>& e = endpoints_[k];
        std::size_t w = 0;
        for (std::size_t i = 0; i < e.size(); ++i) {
            if (e[i].object() == id) continue;
            e[w] = e[i];
            rankOf(k, e[w].tag) = static_cast<std::uint32_t>(w);
            ++w;
        }
        e.resize(w);
    }
    alive_[id] = 0;
    freeIds_.push_back(id);
    --liveCount_;
    return result;
}

}  // namespace cdlab
