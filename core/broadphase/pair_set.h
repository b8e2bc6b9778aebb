// A set of unordered id pairs (BoxPair keys) with O(1) insert, erase and lookup: open addressing,
// linear probing, backward-shift deletion (Knuth, TAOCP vol. 3 §6.4, Algorithm R), so no tombstones
// accumulate over frames of inserts and erases. Grows by doubling at a load of 1/2; a reserved set
// allocates nothing until it outgrows the reservation.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/broadphase/box_pair.h"

namespace cdlab {

class PairSet {
public:
    /// Room for `pairs` pairs without growing.
    void reserve(std::size_t pairs) {
        std::size_t capacity = 16;
        while (capacity < 2 * pairs) capacity *= 2;
        if (capacity > slots_.size()) rehash(capacity);
    }
    /// Adds the pair; false when it was there already.
    bool insert(const BoxPair& p) {
        if (2 * (count_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : 2 * slots_.size());
        const std::uint64_t key = p.key() + 1;  // 0 marks an empty slot
        std::size_t i = slotOf(key);
        while (slots_[i] != 0) {
            if (slots_[i] == key) return false;
            i = (i + 1) & (slots_.size() - 1);
        }
        slots_[i] = key;
        ++count_;
        return true;
    }
    /// Removes the pair; false when it was not there.
    bool erase(const BoxPair& p) {
        if (slots_.empty()) return false;
        const std::uint64_t key = p.key() + 1;
        const std::size_t mask = slots_.size() - 1;
        std::size_t i = slotOf(key);
        while (slots_[i] != key) {
            if (slots_[i] == 0) return false;
            i = (i + 1) & mask;
        }
        // Backward shift: move later entries of the probe run into the hole when their home slot
        // does not lie cyclically in (hole, j].
        for (std::size_t j = (i + 1) & mask;; j = (j + 1) & mask) {
            if (slots_[j] == 0) break;
            const std::size_t home = slotOf(slots_[j]);
            const bool between = i <= j ? (i < home && home <= j) : (i < home || home <= j);
            if (between) continue;
            slots_[i] = slots_[j];
            i = j;
        }
        slots_[i] = 0;
        --count_;
        return true;
    }
    bool contains(const BoxPair& p) const {
        if (slots_.empty()) return false;
        const std::uint64_t key = p.key() + 1;
        for (std::size_t i = slotOf(key);; i = (i + 1) & (slots_.size() - 1)) {
            if (slots_[i] == key) return true;
            if (slots_[i] == 0) return false;
        }
    }
    std::size_t size() const { return count_; }
    void clear() {
        std::fill(slots_.begin(), slots_.end(), 0);
        count_ = 0;
    }

private:
    std::size_t slotOf(std::uint64_t key) const {
        key ^= key >> 33;  // murmur3's 64-bit finaliser: ids in both halves spread over the slots
        key *= 0xff51afd7ed558ccdull;
        key ^= key >> 33;
        return static_cast<std::size_t>(key) & (slots_.size() - 1);
    }
    void rehash(std::size_t capacity) {
        std::vector<std::uint64_t> old(capacity, 0);
        old.swap(slots_);
        count_ = 0;
        for (std::uint64_t key : old)
            if (key != 0) {
                std::size_t i = slotOf(key);
                while (slots_[i] != 0) i = (i + 1) & (slots_.size() - 1);
                slots_[i] = key;
                ++count_;
            }
    }

    std::vector<std::uint64_t> slots_;  ///< key + 1, or 0 for empty; size a power of two
    std::size_t count_ = 0;
};

}  // namespace cdlab
