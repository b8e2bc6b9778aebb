// BVH benchmark: build time (top-down median, binned SAH, bottom-up agglomerative where
// feasible) and query time (mesh vs mesh, mesh vs ray) against the triangle count (1k .. 1M; quick
// mode up to 100k), AABB vs OBB trees, refit vs rebuild after a deformation, on torus meshes
// (core/geometry/triangle_mesh.h torusMesh, R = 1, r = 0.3).
#pragma once

#include <ostream>
#include <string>

namespace cdlab::demos {

/// Runs the benchmark, prints a plain-text table to `table` and writes <outDir>/bvh_build.png,
/// bvh_query_mesh.png, bvh_query_ray.png and bvh_refit.png (log-log, demos/draw/plot.h; skipped
/// without a GL context).
/// Times are thread-CPU medians over repetitions, all configurations measured side by side in
/// one run. Checks on the way that every tree reports the same pairs (and, at 1k triangles,
/// the brute-force pairs); returns 0, or 1 when they differ. quick: sizes up to 100k (< 20 s).
int runBvhBench(bool quick, const std::string& outDir, std::ostream& table);

}  // namespace cdlab::demos
