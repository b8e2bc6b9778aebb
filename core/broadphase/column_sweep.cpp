#include "core/broadphase/column_sweep.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace cdlab {

namespace {

// The sweep axis (centres spread most), then the two cut axes: variances of the box centres, taken
// about the first centre (no cancellation for boxes far from the origin).
void chooseAxes(const std::vector<Aabb>& boxes, int& sweep, int& cut1, int& cut2) {
    const Vec3 origin = 0.5 * (boxes[0].min + boxes[0].max);
    Vec3 sum = Vec3::Zero(), sumSq = Vec3::Zero();
    for (const Aabb& b : boxes) {
        const Vec3 c = 0.5 * (b.min + b.max) - origin;
        sum += c;
        sumSq += c.cwiseProduct(c);
    }
    const double n = static_cast<double>(boxes.size());
    const Vec3 variance = sumSq / n - (sum / n).cwiseProduct(sum / n);
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return variance[i] > variance[j] || (variance[i] == variance[j] && i < j); });
    sweep = order[0], cut1 = order[1], cut2 = order[2];
}

// Slab index of coordinate x along one cut axis: floor((x - lo) / width), clamped. Monotone in x,
// and the same expression for the boxes' ranges and for the exactly-once rule.
struct SlabIndex {
    double lo = 0.0, width = 1.0;
    int count = 1;
    int operator()(double x) const {
        const double s = std::floor((x - lo) / width);
        if (!(s > 0.0)) return 0;
        return s >= count - 1 ? count - 1 : static_cast<int>(s);
    }
};

// Slabs 2 mean extents wide along `axis` (at most maxSlabs; one slab when every box is flat along it).
SlabIndex makeSlabs(const std::vector<Aabb>& boxes, int axis, double maxSlabs) {
    double lo = boxes[0].min[axis], hi = boxes[0].max[axis], extent = 0.0;
    for (const Aabb& b : boxes) {
        lo = std::min(lo, b.min[axis]);
        hi = std::max(hi, b.max[axis]);
        extent += b.max[axis] - b.min[axis];
    }
    SlabIndex s;
    s.lo = lo;
    const double width = 2.0 * extent / static_cast<double>(boxes.size());
    const double range = hi - lo;
    if (!(width > 0.0) || !(range > width) || !std::isfinite(range)) return s;  // one slab
    s.count = static_cast<int>(std::min(std::ceil(range / width), std::max(1.0, std::floor(maxSlabs))));
    s.width = range / s.count;
    return s;
}

// Unsigned 64-bit keys that order like the doubles (IEEE-754: flip all bits of a negative, the sign
// bit of a positive; -0 sorts just below +0, which only reorders equal values).
std::uint64_t orderedKey(double x) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    return (bits >> 63) ? ~bits : bits | (std::uint64_t(1) << 63);
}

// LSD radix sort of (key, index) by key, 8 bits a pass, a pass skipped when every key shares its
// byte (coordinates in one range share their sign and most exponent bits). Stable.
void radixSort(std::vector<std::pair<std::uint64_t, std::uint32_t>>& items,
               std::vector<std::pair<std::uint64_t, std::uint32_t>>& scratch) {
    scratch.resize(items.size());
    for (int shift = 0; shift < 64; shift += 8) {
        std::size_t count[257] = {};
        for (const auto& item : items) ++count[((item.first >> shift) & 0xff) + 1];
        if (*std::max_element(count + 1, count + 257) == items.size()) continue;
        for (int b = 0; b < 256; ++b) count[b + 1] += count[b];
        for (const auto& item : items) scratch[count[(item.first >> shift) & 0xff]++] = item;
        items.swap(scratch);
    }
}

}  // namespace

ColumnSweepResult ColumnSweep::run(const std::vector<Aabb>& boxes) {
    ColumnSweepResult r;
    pairs_.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        r.status = checkBox(boxes[i]);
        if (r.status != BoxStatus::Ok) {
            r.object = static_cast<int>(i);
            return r;
        }
    }
    if (boxes.empty()) return r;
    int cut1 = 1, cut2 = 2;
    chooseAxes(boxes, r.sweepAxis, cut1, cut2);
    const int axis[3] = {r.sweepAxis, cut1, cut2};
    // Columns: slabs along the two cut axes, at most ~2n columns in all.
    const double maxColumns = 2.0 * static_cast<double>(boxes.size()) + 1.0;
    SlabIndex slab1 = makeSlabs(boxes, cut1, maxColumns), slab2 = makeSlabs(boxes, cut2, maxColumns);
    if (static_cast<double>(slab1.count) * slab2.count > maxColumns) {
        const double shrink = std::sqrt(maxColumns / (static_cast<double>(slab1.count) * slab2.count));
        slab1 = makeSlabs(boxes, cut1, std::max(1.0, slab1.count * shrink));
        slab2 = makeSlabs(boxes, cut2, std::max(1.0, slab2.count * shrink));
    }
    r.columns = slab1.count * slab2.count;
    const auto columnOf = [&](int i1, int i2) { return i1 * slab2.count + i2; };
    const auto forColumns = [&](const Aabb& b, auto&& f) {
        const int s1 = slab1(b.min[cut1]), e1 = slab1(b.max[cut1]);
        const int s2 = slab2(b.min[cut2]), e2 = slab2(b.max[cut2]);
        for (int i1 = s1; i1 <= e1; ++i1)
            for (int i2 = s2; i2 <= e2; ++i2) f(columnOf(i1, i2));
    };

    // Entries by column (a counting sort), then by their min on the sweep axis within each column.
    // A few boxes far larger than the mean span every column: then the columns coarsen (both cuts
    // halved) until the entries stay within 8n, so memory stays O(n) whatever the size mix.
    const std::int64_t entryBudget = 8 * static_cast<std::int64_t>(boxes.size()) + 64;
    for (;;) {
        columnStart_.assign(static_cast<std::size_t>(r.columns) + 1, 0);
        r.entries = 0;
        for (const Aabb& b : boxes) {
            const int s1 = slab1(b.min[cut1]), e1 = slab1(b.max[cut1]), s2 = slab2(b.min[cut2]), e2 = slab2(b.max[cut2]);
            r.entries += std::int64_t(e1 - s1 + 1) * (e2 - s2 + 1);
            if (r.entries > entryBudget && r.columns > 1) break;  // coarsen first: no use counting on
            for (int i1 = s1; i1 <= e1; ++i1)
                for (int i2 = s2; i2 <= e2; ++i2) ++columnStart_[columnOf(i1, i2) + 1];
        }
        if (r.entries <= entryBudget || r.columns == 1) break;
        slab1 = makeSlabs(boxes, cut1, std::max(1, slab1.count / 2));
        slab2 = makeSlabs(boxes, cut2, std::max(1, slab2.count / 2));
        r.columns = slab1.count * slab2.count;
    }
    for (int c = 0; c < r.columns; ++c) columnStart_[c + 1] += columnStart_[c];
    // The boxes in the order of their min on the sweep axis (one radix sort), entered into their
    // columns in that order: each column comes out sorted (measured 1.5x faster at 100k boxes than
    // sorting the 4096 columns one by one).
    byMin_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
        byMin_[i] = {orderedKey(boxes[i].min[r.sweepAxis]), static_cast<std::uint32_t>(i)};
    radixSort(byMin_, scratch_);
    entries_.resize(static_cast<std::size_t>(r.entries));
    cursor_.assign(columnStart_.begin(), columnStart_.end() - 1);
    constexpr std::size_t kAhead = 16;  // the boxes are read in sorted, not memory, order: prefetched
    for (std::size_t j = 0; j < byMin_.size(); ++j) {
        if (j + kAhead < byMin_.size()) __builtin_prefetch(&boxes[byMin_[j + kAhead].second]);
        const std::uint32_t i = byMin_[j].second;
        const Aabb& b = boxes[i];
        Entry entry;
        for (int k = 0; k < 3; ++k) entry.lo[k] = b.min[axis[k]], entry.hi[k] = b.max[axis[k]];
        entry.id = static_cast<int>(i);
        forColumns(b, [&](int c) { entries_[cursor_[c]++] = entry; });
    }

    // Sweep each column: the entries after A whose min on the sweep axis is <= A's max overlap it on
    // that axis; test the other two, and report the pair in the column of its overlap's start.
    // The four comparisons are combined without branches: a branch per test mispredicts where the
    // outcome is near even (with slabs alone it measured 1.3x slower at 100k boxes).
    std::int64_t candidates = 0;
    for (int c = 0; c < r.columns; ++c) {
        const Entry* first = entries_.data() + columnStart_[c];
        const Entry* last = entries_.data() + columnStart_[c + 1];
        for (const Entry* a = first; a != last; ++a) {
            const Entry* b = a + 1;
            for (; b != last && b->lo[0] <= a->hi[0]; ++b) {
                const bool overlap = (b->lo[1] <= a->hi[1]) & (a->lo[1] <= b->hi[1]) & (b->lo[2] <= a->hi[2]) &
                                     (a->lo[2] <= b->hi[2]);
                if (!overlap) continue;
                if (columnOf(slab1(std::max(a->lo[1], b->lo[1])), slab2(std::max(a->lo[2], b->lo[2]))) != c)
                    continue;  // reported in another column
                pairs_.push_back(BoxPair::make(a->id, b->id));
            }
            candidates += b - (a + 1);
        }
    }
    r.candidates = candidates;
    r.pairs = static_cast<int>(pairs_.size());
    return r;
}

}  // namespace cdlab
