// Scratch memory for one call: a buffer on the stack behind a std::pmr::monotonic_buffer_resource.
// Containers built on it (std::pmr::vector) make no heap allocation while the buffer lasts and
// fall back to operator new beyond it, so inputs of any size still work; everything is released
// when the arena goes out of scope. Reserve sizes up front: a monotonic resource does not reuse
// the blocks a growing vector leaves behind.
#pragma once

#include <cstddef>
#include <memory_resource>

namespace cdlab {

template <std::size_t Bytes>
class StackArena {
public:
    StackArena() = default;
    StackArena(const StackArena&) = delete;
    StackArena& operator=(const StackArena&) = delete;
    std::pmr::memory_resource* resource() { return &resource_; }

private:
    alignas(std::max_align_t) std::byte buffer_[Bytes];
    std::pmr::monotonic_buffer_resource resource_{buffer_, Bytes};
};

}  // namespace cdlab
