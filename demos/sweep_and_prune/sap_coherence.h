// Sweep and prune's cost as coherence falls (scene "figure": "coherence"): n unit cubes at a fixed
// density, each moving `speed` box sides per update in a fixed random direction and bouncing off
// the walls of their container; per n and speed,
// the adjacent swaps of insertion sort per update (core's SapResult::swaps) and the reported pairs.
// The swaps are the inversions between one frame's endpoint order and the next frame's values, so
// at fixed density and speed the swaps per object grow like speed * n^(2/3) (an axis holds 2n
// endpoints over a length ~n^(1/3)), until re-sorting from scratch (about 2n log2(2n) comparisons
// per axis, 6 log2(2n) per object) would be cheaper. Test: tests/demos/sweep_and_prune/sap_demo_test.cpp recounts the
// inversions and the overlapping pairs by brute force on the boxes coherenceBoxes gives.
#pragma once

#include <memory>
#include <vector>

#include "app/scene/demo.h"
#include "core/base/primitives.h"
#include "core/base/types.h"

namespace cdlab::demos {

struct CoherenceSettings {
    std::vector<int> counts = {16, 32, 64, 128, 256, 512, 1024};  ///< n, 2..kMaxCoherenceBoxes each
    std::vector<double> speeds = {0.05, 0.2, 0.8};                 ///< box sides per update, (0, 4]
    int updates = 5;                                               ///< 1..10
    double density = 0.1;                                          ///< cubes per unit volume, (0, 1]
    unsigned seed = 1;
};

/// Limits of a coherence scene, checked when it is read (the work is O(n * updates) plus the swaps,
/// which grow like speed * n^(5/3): their estimate is bounded by kMaxCoherenceSwapEstimate, about a
/// second of sorting).
constexpr int kMaxCoherenceBoxes = 4096;
constexpr int kMaxCoherenceCounts = 8;
constexpr int kMaxCoherenceSpeeds = 4;
/// The estimated swaps of a whole scene (readCoherenceScene's estimate; ~3 × 10⁸ swaps a second).
constexpr double kMaxCoherenceSwapEstimate = 3e8;

/// n unit cubes in a container cube [0, side]^3 that they bounce off (so the density stays fixed).
struct CoherenceBoxes {
    double side = 0;
    std::vector<Vec3> centres;     ///< frame 0
    std::vector<Vec3> velocities;  ///< per update
    /// The cubes at frame f: each centre moved by f * velocity, reflected at the container's walls
    /// (the centre stays in [0.5, side - 0.5] on every axis).
    std::vector<Aabb> at(int f) const;
};

/// The n moving cubes of one run: centres uniform in a cube of side cbrt(n / density) (> 1 by the
/// limits: n >= 2, density <= 1), directions uniform on the sphere. Depends only on (n, speed, density, seed) and is the same on every platform
/// (mt19937's raw output, no standard distribution).
CoherenceBoxes coherenceBoxes(int n, double speed, double density, unsigned seed);

struct CoherenceRun {
    int n = 0;
    double speed = 0;
    double side = 0;                   ///< of the container cube
    std::vector<long long> swaps;      ///< per update
    std::vector<long long> swapsAxis;  ///< per update and axis (3 per update, x y z)
    std::vector<int> pairs;            ///< reported after the build and after each update
    double swapsPerObject() const;     ///< mean over the updates, divided by n
};

/// Every (speed, n) of the settings, speeds outer, counts inner.
std::vector<CoherenceRun> runCoherence(const CoherenceSettings& s);

/// Reads the keys of a "figure": "coherence" scene (docs/scenes.md, sweep_and_prune) and finishes r.
std::unique_ptr<PreparedScene> readCoherenceScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
