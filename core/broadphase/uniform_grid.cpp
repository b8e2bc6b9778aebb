// Hashed uniform grid, rebuilt per frame (see uniform_grid.h; Ericson §7.1).
#include "core/broadphase/uniform_grid.h"

#include <cmath>

#include "core/base/aabb_ops.h"

namespace cdlab {

namespace {

// Cell indices are formed in doubles first; beyond 2^53 consecutive cells are no longer
// distinct doubles, so such coordinates / h are refused.
constexpr double kMaxCellIndex = 9007199254740992.0;  // 2^53

std::uint64_t hashCell(const std::array<std::int64_t, 3>& c) {
    // Teschner et al. 2003 primes, then the splitmix64 finalizer (low bits well mixed for a
    // power-of-two table).
    std::uint64_t x = static_cast<std::uint64_t>(c[0]) * 73856093ull ^ static_cast<std::uint64_t>(c[1]) * 19349663ull ^
                      static_cast<std::uint64_t>(c[2]) * 83492791ull;
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

}  // namespace

std::vector<UniformGrid::RayCell> UniformGrid::cellsAlongSegment(const Vec3& p, const Vec3& q, double h, int maxCells) {
    std::vector<RayCell> out;
    if (!(h > 0) || !std::isfinite(h) || !p.allFinite() || !q.allFinite() || maxCells <= 0) return out;
    std::array<std::int64_t, 3> cell = cellOf(p, h);
    const std::array<std::int64_t, 3> last = cellOf(q, h);
    const Vec3 d = q - p;
    // Per axis: the step direction, the t of the next boundary crossed, the t between crossings.
    std::array<int, 3> step{};
    Vec3 tNext, tDelta;
    for (int k = 0; k < 3; ++k) {
        step[std::size_t(k)] = d[k] > 0 ? 1 : d[k] < 0 ? -1 : 0;
        if (step[std::size_t(k)] == 0) {
            tNext[k] = tDelta[k] = INFINITY;
            continue;
        }
        const double boundary = double(cell[std::size_t(k)] + (step[std::size_t(k)] > 0 ? 1 : 0)) * h;
        tNext[k] = (boundary - p[k]) / d[k];
        tDelta[k] = h / std::abs(d[k]);
    }
    out.push_back({cell, 0.0});
    while (cell != last && int(out.size()) < maxCells) {
        int k = 0;
        if (tNext[1] < tNext[k]) k = 1;
        if (tNext[2] < tNext[k]) k = 2;
        if (!(tNext[k] <= 1.0)) break;  // rounding left the last cell unreached: the segment ends here
        cell[std::size_t(k)] += step[std::size_t(k)];
        out.push_back({cell, tNext[k]});
        tNext[k] += tDelta[k];
    }
    return out;
}

std::array<std::int64_t, 3> UniformGrid::cellOf(const Vec3& p, double h) {
    return {static_cast<std::int64_t>(std::floor(p.x() / h)), static_cast<std::int64_t>(std::floor(p.y() / h)),
            static_cast<std::int64_t>(std::floor(p.z() / h))};
}

UniformGridResult UniformGrid::build(const std::vector<Aabb>& boxes, const UniformGridOptions& options) {
    UniformGridResult result;
    pairs_.clear();
    const double h = options.cellSize;
    if (!std::isfinite(h) || !(h > 0.0)) {
        result.status = GridStatus::BadCellSize;
        return result;
    }
    // 1. Validate and count the cells of every box.
    std::int64_t total = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const BoxStatus s = checkBox(boxes[i]);
        if (s != BoxStatus::Ok) {
            result.status = s == BoxStatus::NonFinite ? GridStatus::NonFiniteBox : GridStatus::EmptyBox;
            result.object = static_cast<int>(i);
            return result;
        }
        std::int64_t cells = 1;
        for (int k = 0; k < 3; ++k) {
            const double lo = std::floor(boxes[i].min[k] / h), hi = std::floor(boxes[i].max[k] / h);
            if (!(std::abs(lo) < kMaxCellIndex && std::abs(hi) < kMaxCellIndex) ||
                hi - lo + 1 > static_cast<double>(options.maxCellsPerBox)) {
                result.status = GridStatus::TooManyCells;
                result.object = static_cast<int>(i);
                return result;
            }
            cells *= static_cast<std::int64_t>(hi - lo) + 1;
            if (cells > options.maxCellsPerBox) break;
        }
        if (cells > options.maxCellsPerBox) {
            result.status = GridStatus::TooManyCells;
            result.object = static_cast<int>(i);
            return result;
        }
        total += cells;
    }
    // 2. Entries (cell, box, bucket): the bucket hashed once per entry. A table of >= entries
    //    buckets (a power of two): load factor <= 1, the buckets scanned in step 4 stay few.
    std::size_t buckets = 16;
    while (buckets < static_cast<std::size_t>(total)) buckets *= 2;
    const std::size_t mask = buckets - 1;
    entries_.resize(static_cast<std::size_t>(total));
    bucketStart_.assign(buckets + 1, 0);
    std::size_t w = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const auto lo = cellOf(boxes[i].min, h), hi = cellOf(boxes[i].max, h);
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
                    const auto bucket = static_cast<std::uint32_t>(hashCell({x, y, z}) & mask);
                    entries_[w++] = Entry{{x, y, z}, static_cast<int>(i), bucket};
                    ++bucketStart_[bucket + 1];
                }
    }
    result.entries = total;
    // 3. Counting sort by bucket.
    for (std::size_t b = 0; b < buckets; ++b) bucketStart_[b + 1] += bucketStart_[b];
    sorted_.resize(entries_.size());
    for (const Entry& e : entries_) sorted_[bucketStart_[e.bucket]++] = e;
    // bucketStart_[b] now holds the end of bucket b; the start of b is the end of b - 1.
    // 4. Test the boxes that share a cell; report a pair only in its intersection's min-corner cell.
    std::size_t begin = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
        const std::size_t end = bucketStart_[b];
        for (std::size_t i = begin; i < end; ++i)
            for (std::size_t j = i + 1; j < end; ++j) {
                const Entry& p = sorted_[i];
                const Entry& q = sorted_[j];
                if (p.cell != q.cell) continue;  // hash collision: another cell in this bucket
                ++result.pairTests;
                const Aabb& A = boxes[p.box];
                const Aabb& B = boxes[q.box];
                if (!overlaps(A, B)) continue;
                if (cellOf(A.min.cwiseMax(B.min), h) != p.cell) continue;  // reported in another cell
                pairs_.push_back(BoxPair::make(p.box, q.box));
            }
        begin = end;
    }
    result.pairs = static_cast<int>(pairs_.size());
    return result;
}

}  // namespace cdlab
