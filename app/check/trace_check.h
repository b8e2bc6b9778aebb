// `cdlab check`'s trace checks (docs/check.md): your GJK steps, EPA steps and Voronoi-region tests,
// each step against the rule every correct run follows, so that ties (several extreme points,
// several nearest sub-simplices, a value of 0 on a region boundary) are not divergences. The first
// step that breaks a rule is reported with its numbers.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/check/check_values.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Steps (GJK, EPA) or region tests one trace may list. cdlab's own GJK stops within 128
/// iterations and its EPA within 120; a longer trace fails unread, so the check of a line stays
/// linear in a bounded count (tests/app/check/check_test.cpp, "step limit").
constexpr std::size_t kMaxTraceSteps = 10000;
/// Traces one {"algorithms": [...]} may hold (not nested): a GJK run, an EPA run and region tests.
constexpr std::size_t kMaxTraceAlgorithms = 4;

/// Checks `trace` (yours) for the query `op`: {"algorithm": "gjk" | "epa" | "ericson_regions", ...}
/// (no "algorithm": gjk) or {"algorithms": [...]} (each in turn). Appends a reason and sets
/// `divergence` to the failing step's index (and `algorithm` to its name) on the first break; leaves
/// divergence at -1 when every step follows the rules. a and b: the query's shapes "a" and "b",
/// read once for the line (support values at every step).
void checkTrace(const std::string& op, const Json& query, const Json& trace, double tol, const ShapeModel& a,
                const ShapeModel& b, std::vector<std::string>& reasons, int& divergence, std::string& algorithm);

}  // namespace cdlab::demos
