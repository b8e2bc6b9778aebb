// Test-only oracles and motion generators for the broad phases (core/broadphase/sweep_and_prune.h,
// core/broadphase/uniform_grid.h). The pair oracle is the O(n^2) loop over testAabbAabb (core/overlap/sat_tests.h,
// tested on its own); the swap oracle counts inversions of the old endpoint order under the new
// coordinates by brute force. Neither shares code with the code under test.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "core/base/primitives.h"
#include "core/overlap/sat_tests.h"

namespace broad_oracle {

using cdlab::Aabb;
using cdlab::Vec3;

struct IdPair {
    int a, b;
    bool operator==(const IdPair& o) const { return a == o.a && b == o.b; }
    bool operator<(const IdPair& o) const { return a < o.a || (a == o.a && b < o.b); }
};

/// Every pair i < j of live boxes that testAabbAabb says overlap, sorted.
inline std::vector<IdPair> bruteForcePairs(const std::vector<Aabb>& boxes, const std::vector<char>* alive = nullptr) {
    std::vector<IdPair> out;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
        if (alive && !(*alive)[i]) continue;
        for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j) {
            if (alive && !(*alive)[j]) continue;
            if (cdlab::testAabbAabb(boxes[i], boxes[j]).hit) out.push_back({i, j});
        }
    }
    return out;
}

/// Sorted copy of any container of pairs with members a, b.
template <class P>
std::vector<IdPair> sortedPairs(const std::vector<P>& pairs) {
    std::vector<IdPair> out;
    for (const P& p : pairs) out.push_back({std::min(p.a, p.b), std::max(p.a, p.b)});
    std::sort(out.begin(), out.end());
    return out;
}

/// Endpoint (object, isMax) in an old order.
struct End {
    int object;
    bool isMax;
};

/// Number of pairs i < j of the old order whose new keys (value, max after min) are strictly
/// out of order: the minimum number of adjacent swaps that sort it (ties never swap).
inline std::int64_t inversions(const std::vector<End>& oldOrder, const std::vector<Aabb>& boxes, int axis) {
    auto key = [&](const End& e) {
        return std::make_pair(e.isMax ? boxes[e.object].max[axis] : boxes[e.object].min[axis], e.isMax ? 1 : 0);
    };
    std::int64_t n = 0;
    for (std::size_t i = 0; i < oldOrder.size(); ++i)
        for (std::size_t j = i + 1; j < oldOrder.size(); ++j) n += key(oldOrder[j]) < key(oldOrder[i]) ? 1 : 0;
    return n;
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1p-53);
}

/// Boxes moving with constant velocities in a cube, bouncing off its walls.
struct Motion {
    std::vector<Vec3> center, half, velocity;
    double extent = 10.0;

    static Motion random(std::mt19937_64& rng, int n, double extent, double minHalf, double maxHalf, double speed) {
        Motion m;
        m.extent = extent;
        for (int i = 0; i < n; ++i) {
            m.center.push_back(Vec3(uniform(rng, 0, extent), uniform(rng, 0, extent), uniform(rng, 0, extent)));
            m.half.push_back(
                Vec3(uniform(rng, minHalf, maxHalf), uniform(rng, minHalf, maxHalf), uniform(rng, minHalf, maxHalf)));
            m.velocity.push_back(
                Vec3(uniform(rng, -speed, speed), uniform(rng, -speed, speed), uniform(rng, -speed, speed)));
        }
        return m;
    }
    void step() {
        for (std::size_t i = 0; i < center.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                center[i][k] += velocity[i][k];
                if (center[i][k] < 0 || center[i][k] > extent) velocity[i][k] = -velocity[i][k];
            }
    }
    std::vector<Aabb> boxes(const Vec3& offset = Vec3::Zero()) const {
        std::vector<Aabb> out;
        for (std::size_t i = 0; i < center.size(); ++i)
            out.push_back(Aabb{offset + center[i] - half[i], offset + center[i] + half[i]});
        return out;
    }
};

/// Integer-coordinate boxes (min in [0, extent), size 0..maxSize per axis) for exact ties.
inline Aabb integerBox(std::mt19937_64& rng, int extent, int maxSize) {
    Aabb b;
    for (int k = 0; k < 3; ++k) {
        b.min[k] = static_cast<double>(rng() % extent);
        b.max[k] = b.min[k] + static_cast<double>(rng() % (maxSize + 1));
    }
    return b;
}

}  // namespace broad_oracle
