// Cylinders in `cdlab bench` (section "queries"): a sphere against a cylinder, whose distance and
// depth have closed forms (the sphere's centre against the cylinder's side, cap or rim), by GJK
// and EPA on the support mappings alone and by the query's path — the same runs with the
// direction polished on the curved patch (core/gjk_epa/direction_refinement.h) — so the rows show
// what the polish costs and what it buys.
#pragma once

#include <vector>

#include "app/bench/bench_measure.h"

namespace cdlab::demos {

/// Appends the cylinder rows to `rows`.
void benchCylinders(const Settings& settings, std::vector<Row>& rows);

}  // namespace cdlab::demos
