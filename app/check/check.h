// `cdlab check`: your implementation's answers (and, optionally, your GJK trace) against cdlab's,
// one JSON Lines query at a time (docs/check.md).
//
// A line is a `cdlab query` line plus "answer" (your answer, the same keys as cdlab's), optionally
// "tolerance" (this line's, relative to the shapes' size) and "trace" (yours: an object, not the
// query's `"trace": true`). cdlab answers the query and compares: verdicts exactly; numbers
// within the tolerance; and where an answer is not unique (witness points, normals at an edge,
// the region of a point on a region boundary, a support point among ties) yours is checked for
// being *a* right answer — a point on its shape, a normal whose support gap is the depth — not for
// being cdlab's.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// The largest tolerance `--tolerance` (CheckOptions::tolerance) may set: 1e-3 of the shapes' size
/// already passes answers no double implementation needs; a looser one would pass wrong answers.
constexpr double kMaxCheckTolerance = 1e-3;

struct CheckOptions {
    /// Relative to the size of the problem L (the largest extent of the shapes, at least their
    /// coordinates' rounding): numbers may differ by tolerance * L. cdlab itself meets 1e-12 L on
    /// distances and 1e-10 L on depths (docs/accuracy.md); 1e-9 leaves your double code room.
    /// In (0, kMaxCheckTolerance]; it caps every line's own "tolerance" (a line may only tighten
    /// it: a larger one fails the line).
    double tolerance = 1e-9;
    /// Non-empty: each failing line of two convex shapes gets a figure DIR/line_<n>.png
    /// (app/check/check_figure.h), named at the end of its verdict line.
    std::string figuresDir;
};

struct CheckResult {
    Json id;
    bool pass = false;
    std::vector<std::string> reasons;  ///< why it failed, in plain words (empty when it passed)
    Json query, yours, cdlab;          ///< the line's query (without answer), the two answers (when read)
    Json trace;                        ///< your trace (null when none)
    int traceDivergence = -1;          ///< the index of the first step of your trace that breaks a rule
    std::string traceAlgorithm;        ///< the algorithm of that trace ("gjk", "epa", "ericson_regions")
};

/// Checks one line (lineNumber counts from 1 and names the line in errors). Never throws: a line
/// that cannot be read or checked (malformed JSON, "op" not a string, a key of the wrong type, out
/// of memory, longer than kMaxQueryLineBytes) fails with its reason.
CheckResult checkLine(const std::string& line, std::size_t lineNumber, const CheckOptions& options) noexcept;

/// Reads lines until EOF and prints one verdict line each, then "N passed, M failed". Returns 0
/// when every line passed, 1 otherwise. Blank lines are skipped. A line longer than
/// kMaxQueryLineBytes (app/query/query_limits.h, `cdlab query`'s limit) fails naming its length
/// and is not held in memory; every verdict line is escaped (printable) so that it stays one
/// line whatever the answers hold.
int runCheck(std::istream& in, std::ostream& out, const CheckOptions& options);

/// A fuzz property: cdlab's own answer to the query line, fed back to checkLine as the line's
/// "answer", passes. True when it does, and for lines cdlab answers with an error (nothing to feed
/// back); else false with the reasons in *why (when given).
bool selfCheckPasses(const std::string& queryLine, std::string* why);

}  // namespace cdlab::demos
