// `cdlab check`'s trace checks (docs/check.md): your GJK steps, EPA steps and Voronoi-region tests,
// each step against the rule every correct run follows, so that ties (several extreme points,
// several nearest sub-simplices, a value of 0 on a region boundary) are not divergences. The first
// step that breaks a rule is reported with its numbers.
#pragma once

#include <string>
#include <vector>

#include "demos/scene/json_reader.h"

namespace cdlab::demos {

/// Checks `trace` (yours) for the query `op`: {"algorithm": "gjk" | "epa" | "ericson_regions", ...}
/// (no "algorithm": gjk) or {"algorithms": [...]} (each in turn). Appends a reason and sets
/// `divergence` to the failing step's index (and `algorithm` to its name) on the first break; leaves
/// divergence at -1 when every step follows the rules.
void checkTrace(const std::string& op, const Json& query, const Json& trace, double tol,
                std::vector<std::string>& reasons, int& divergence, std::string& algorithm);

}  // namespace cdlab::demos
