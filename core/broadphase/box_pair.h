// The answer of every broad phase (sweep and prune, uniform grid): pairs of box ids whose closed
// AABBs overlap (touching counts, as in testAabbAabb of core/overlap/sat_tests.h).
#pragma once

#include <cstdint>

#include "core/base/primitives.h"

namespace cdlab {

/// Unordered pair of object ids, stored with a < b.
struct BoxPair {
    int a = 0;
    int b = 0;

    static BoxPair make(int i, int j) { return i < j ? BoxPair{i, j} : BoxPair{j, i}; }
    /// One 64-bit key per unordered pair (for sets and sorting): a in the high half.
    std::uint64_t key() const {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
    }
    friend bool operator==(const BoxPair& p, const BoxPair& q) { return p.a == q.a && p.b == q.b; }
    friend bool operator<(const BoxPair& p, const BoxPair& q) { return p.key() < q.key(); }
};

/// Why a broad phase refused its input.
enum class BoxStatus {
    Ok,
    NonFinite,  ///< a coordinate is NaN or +-inf: no order, no cell
    Empty,      ///< min > max on some axis (an empty box has no interval to sort)
};

/// Ok, or why `box` cannot enter a broad phase (flat boxes, min == max, are fine).
inline BoxStatus checkBox(const Aabb& box) {
    if (!box.min.allFinite() || !box.max.allFinite()) return BoxStatus::NonFinite;
    if (!(box.min.array() <= box.max.array()).all()) return BoxStatus::Empty;
    return BoxStatus::Ok;
}

}  // namespace cdlab
