// Broad phase benchmark: sweep and prune update time per frame vs n (100 .. 100k boxes in
// coherent motion) beside a brute-force O(n^2) pair loop, a hashed uniform grid and two octrees
// (classic and loose, core/broadphase/octree.h), all rebuilt every frame, on the same frames. Shows SAP's
// O(n + s + k) per frame (s swaps, k pairs) on a log-log plot with O(n) and O(n^2) reference
// slopes, and time / (n + k) vs n.
#pragma once

#include <ostream>
#include <string>

namespace cdlab::demos {

/// Runs the benchmark, writes <outDir>/broadphase_time.png and broadphase_per_item.png (when a GL
/// context can be made) and prints plain-text tables to `table`: per n, mean pairs k and swaps s per
/// frame, median thread-CPU ms per frame of SAP update, uniform grid rebuild, classic and loose
/// octree rebuild + pair query, and brute force (up to 10k objects in quick mode, 30k otherwise;
/// "-" beyond), ns per (n + k) and per (n + k + s), the one-off SAP build time, the log-log slopes
/// against n, and per octree the box tests per box, objects at the root and mean object depth.
/// quick: n <= 10k, fewer frames (< 20 s). Checks that all five report the same pair count every
/// frame and the same pair set as brute force on every brute-force frame; returns 0, or 1 if they
/// ever differ.
int runBroadphaseBench(bool quick, const std::string& outDir, std::ostream& table);

}  // namespace cdlab::demos
