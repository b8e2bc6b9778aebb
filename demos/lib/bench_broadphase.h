// Broad phase benchmark (issue 9): sweep and prune update time per frame vs n (100 .. 100k boxes in
// coherent motion) beside a brute-force O(n^2) pair loop and a hashed uniform grid rebuilt every
// frame, on the same frames. Shows SAP's O(n + s + k) per frame (s swaps, k pairs) on a log-log
// plot with O(n) and O(n^2) reference slopes, and time / (n + k) vs n.
#pragma once

#include <ostream>
#include <string>

namespace cdlab::demos {

/// Runs the benchmark, writes <outDir>/broadphase_time.png and broadphase_per_item.png (when a GL
/// context can be made) and prints a plain-text table to `table`: per n, mean pairs k and swaps s per
/// frame, median thread-CPU ms per frame of SAP update, uniform grid rebuild and brute force (up to
/// 10k objects in quick mode, 30k otherwise; "-" beyond), ns per (n + k) and per (n + k + s), the
/// one-off SAP build time, and the log-log slopes against n.
/// quick: n <= 10k, fewer frames (< 20 s). Checks that the three report the same pair count every
/// frame; returns 0, or 1 if they ever differ.
int runBroadphaseBench(bool quick, const std::string& outDir, std::ostream& table);

}  // namespace cdlab::demos
