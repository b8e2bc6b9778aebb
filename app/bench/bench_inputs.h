// Random inputs shared by the sections of `cdlab bench` (queries, contact): polytope pairs and
// oriented box pairs, fixed seeds, each with its Minkowski-hull oracle
// (verification/minkowski_hull_oracle.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry/shapes.h"
#include "core/overlap/sat_tests.h"
#include "verification/minkowski_hull_oracle.h"

namespace cdlab::demos {

/// The support mapping of conv(v): its hull with adjacency (hill climbing on large hulls), or the
/// plain vertex list when the hull fails.
PolytopeShape polytopeOf(const std::vector<Vec3>& v);

/// A pair of convex vertex sets in world frame with their support mappings and oracle.
struct PolyPair {
    std::vector<Vec3> va, vb;
    PolytopeShape a, b;
    MinkowskiOracle oracle;
};

/// `count` pairs of n-vertex polytopes, B's centre at `offset` (in units of the size, ~1) along a
/// random direction. offset 2.2 > 1 + 1: always separated; 0.4: nearly always overlapping.
/// moveBy > 0: the same pairs with B moved by that much (the next frame of a warm start).
std::vector<PolyPair> polyPairs(int n, int count, double offset, std::uint64_t seed, double moveBy = 0.0);

/// Oriented boxes: half extents in [0.2, 1], random rotation, centre offset along a random
/// direction; `touching` puts two axis-aligned boxes face to face (distance exactly 0).
struct OrientedBoxPair {
    Transformed<BoxShape> a, b;
    std::vector<Vec3> va, vb;  ///< world corners
    MinkowskiOracle oracle;
    Obb obbA, obbB;
};

std::vector<OrientedBoxPair> boxPairs(int count, double offset, bool touching, std::uint64_t seed);

/// The eight world corners of a posed box, corner i with bit k of i picking +h_k (also the stress
/// families' box vertices).
std::vector<Vec3> boxCorners(const Transformed<BoxShape>& box);

}  // namespace cdlab::demos
