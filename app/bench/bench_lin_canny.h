// `cdlab bench` section: Lin–Canny (core/feature_walk/lin_canny.h) against V-Clip (core/feature_walk/vclip.h) and
// warm-started GJK (core/gjk_epa/gjk.h) on coherent motion, and both feature walks on degenerate families.
//
// Coherent motion: A and B (same shape: cube, icosahedron, 60-gon disk) rotate by `level` degrees
// per call about fixed random axes while B orbits A by level / 2 degrees; every method carries its
// warm start (feature pair / simplex) from call to call. Rows "feature_walk_coherent", input
// "<shape>, <level> deg/call", iterations = steps (walks) or GJK iterations, error vs the
// Minkowski-hull oracle (verification/minkowski_hull_oracle.h).
// Degenerate families (after Mirtich, "V-Clip" 1998, §7: 10^5 trials): axis-aligned boxes with
// offsets on a 1/4 grid (coplanar faces, parallel edges, vertices exactly on Voronoi planes, exact
// touching, penetration), 90-degree rotations, random seed pairs; exact answer = the box gap.
// Rows "feature_walk_degenerate" per method: boolean error = "cycle or wrong answer"; the
// DegenerateCount out-parameter splits it.
#pragma once

#include <vector>

#include "app/bench/bench_measure.h"

namespace cdlab::demos {

/// Counts over the degenerate trials (last repetition) of one method.
struct DegenerateCount {
    const char* method = "";
    int trials = 0;
    int cycles = 0;         ///< CycleDetected or StepLimit
    int wrongDistance = 0;  ///< Separated with |d - exact| > 1e-9 (size ~1), or Separated when they meet
    int wrongVerdict = 0;   ///< Penetrating although the gap is > 1e-9
};

/// Runs the section; appends the counts of the degenerate families to `counts` when given.
/// Progress lines on stderr (settings.progress). Rows as documented above.
std::vector<Row> benchLinCanny(const Settings& settings, std::vector<DegenerateCount>* counts = nullptr);

}  // namespace cdlab::demos
