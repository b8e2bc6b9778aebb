// Dynamic AABB tree benchmark: the fat-box tree broad phase (core/broadphase/tree_broad_phase.h)
// beside sweep and prune, the uniform grid and Bullet's btDbvtBroadphase (when installed), on a
// uniform-size and a mixed-size (100x) workload in coherent motion, n = 1k, 10k, 100k.
#pragma once

#include <ostream>

namespace cdlab::demos {

/// Runs the benchmark and prints its table to `table`: per workload and n, mean pairs, median
/// thread-CPU ms per frame of each method, tree / Bullet, leaves moved per frame, fat pairs,
/// Bullet's cached pairs, grid entries per box, the tree's first-frame build time. quick: n <= 10k,
/// fewer frames. Returns 0, or 1 when SAP, grid and tree ever report different pair sets.
int runTreeBench(bool quick, std::ostream& table);

}  // namespace cdlab::demos
