// Boxes in coherent motion, the input of the broad-phase benchmarks (bench_broadphase.cpp,
// bench_tree.cpp): n boxes with centres uniform in a cube of side (n / 0.05)^(1/3) (0.05 boxes per
// unit volume), half extents per axis uniform in [minHalf, maxHalf] (or log-uniform: sizes spanning
// maxHalf / minHalf), constant velocities uniform in [-speed, speed] per axis per frame, bouncing
// off the cube's walls. Also the pair set those benchmarks compare between methods.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/base/primitives.h"
#include "core/broadphase/box_pair.h"

namespace cdlab::demos {

/// Largest velocity component per frame of the uniform workload: 5% of the mean box size
/// (coherent motion).
constexpr double kBoxSpeed = 0.05;

struct BoxMotion {
    std::vector<Vec3> center, half, velocity;
    double side = 1.0;

    BoxMotion(int n, std::uint64_t seed, double speed, double minHalf = 0.25, double maxHalf = 0.75,
              bool logUniform = false) {
        std::mt19937_64 rng(seed);
        side = std::cbrt(n / 0.05);
        const auto halfExtent = [&] {
            return logUniform ? minHalf * std::pow(maxHalf / minHalf, uniform(rng, 0, 1)) : uniform(rng, minHalf, maxHalf);
        };
        for (int i = 0; i < n; ++i) {
            center.emplace_back(uniform(rng, 0, side), uniform(rng, 0, side), uniform(rng, 0, side));
            // One statement per axis: the draws keep their order (x, y, z).
            Vec3 h;
            for (int k = 0; k < 3; ++k) h[k] = halfExtent();
            half.push_back(h);
            velocity.emplace_back(uniform(rng, -speed, speed), uniform(rng, -speed, speed), uniform(rng, -speed, speed));
        }
    }
    /// Moves every box one frame and writes the boxes.
    void step(std::vector<Aabb>& boxes) {
        boxes.resize(center.size());
        for (std::size_t i = 0; i < center.size(); ++i) {
            for (int k = 0; k < 3; ++k) {
                center[i][k] += velocity[i][k];
                if (center[i][k] < 0 || center[i][k] > side) velocity[i][k] = -velocity[i][k];
            }
            boxes[i] = Aabb{center[i] - half[i], center[i] + half[i]};
        }
    }

private:
    static double uniform(std::mt19937_64& rng, double lo, double hi) {
        return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1p-53);
    }
};

/// A broad phase's pairs as sorted 64-bit keys (a < b in each pair): sets compare as vectors.
inline std::vector<std::uint64_t> pairKeys(const std::vector<BoxPair>& pairs) {
    std::vector<std::uint64_t> keys;
    keys.reserve(pairs.size());
    for (const BoxPair& p : pairs) keys.push_back(BoxPair::make(p.a, p.b).key());
    std::sort(keys.begin(), keys.end());
    return keys;
}

}  // namespace cdlab::demos
