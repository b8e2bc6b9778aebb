// A vector of at most N elements stored inline: no heap, elements constructed only up to size()
// (a 64-point manifold costs nothing until points are added). The contact generators return their
// manifolds in it so that a contact query makes no allocation (Jolt keeps its manifold points in a
// StaticArray for the same reason). push_back past N is refused (returns false), never undefined.
#pragma once

#include <cassert>
#include <cstddef>
#include <new>
#include <span>
#include <type_traits>

namespace cdlab {

template <class T, int N>
class FixedCapacityVector {
    static_assert(N > 0);
    static_assert(std::is_trivially_destructible_v<T>, "elements are dropped without a destructor call");

public:
    FixedCapacityVector() = default;
    FixedCapacityVector(const FixedCapacityVector& other) { copyFrom(other); }
    FixedCapacityVector& operator=(const FixedCapacityVector& other) {
        if (this != &other) copyFrom(other);
        return *this;
    }

    static constexpr int capacity() { return N; }
    std::size_t size() const { return static_cast<std::size_t>(count_); }
    bool empty() const { return count_ == 0; }
    bool full() const { return count_ == N; }
    void clear() { count_ = 0; }

    /// Appends `value` unless the vector is full (then returns false and changes nothing).
    bool push_back(const T& value) {
        if (count_ == N) return false;
        ::new (static_cast<void*>(slot(count_))) T(value);
        ++count_;
        return true;
    }
    void pop_back() {
        assert(count_ > 0);
        --count_;
    }
    /// Shrinks to n elements (n <= size()).
    void truncate(std::size_t n) {
        assert(n <= size());
        count_ = static_cast<int>(n);
    }

    // Laundered only when an element lives there ([ptr.launder] needs an object at the address).
    T* data() {
        T* p = reinterpret_cast<T*>(storage_);
        return count_ ? std::launder(p) : p;
    }
    const T* data() const {
        const T* p = reinterpret_cast<const T*>(storage_);
        return count_ ? std::launder(p) : p;
    }
    T& operator[](std::size_t i) {
        assert(i < size());
        return data()[i];
    }
    const T& operator[](std::size_t i) const {
        assert(i < size());
        return data()[i];
    }
    T& front() { return (*this)[0]; }
    const T& front() const { return (*this)[0]; }
    T& back() { return (*this)[size() - 1]; }
    const T& back() const { return (*this)[size() - 1]; }
    T* begin() { return data(); }
    T* end() { return data() + count_; }
    const T* begin() const { return data(); }
    const T* end() const { return data() + count_; }
    operator std::span<const T>() const { return {data(), size()}; }

private:
    void* slot(int i) { return storage_ + static_cast<std::size_t>(i) * sizeof(T); }
    void copyFrom(const FixedCapacityVector& other) {
        count_ = 0;
        for (const T& x : other) push_back(x);
    }

    alignas(T) unsigned char storage_[N * sizeof(T)];
    int count_ = 0;
};

}  // namespace cdlab
