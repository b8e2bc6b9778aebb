// V-Clip against GJK under frame coherence: cold and warm-started queries on a cube,
// an icosahedron, a 60-gon disk and a 642-vertex geodesic sphere, at 0, 1, 5, 10 and 25 degrees
// of relative rotation per call.
#pragma once

#include <ostream>

namespace cdlab::demos {

/// Runs the benchmark and prints a Markdown table to `out`: median thread-CPU ns per query (over
/// repetitions of a whole sequence of queries) and mean steps (V-Clip updates / GJK iterations)
/// per query, for V-Clip cold (seeded at vertex 0 / 0), V-Clip warm (the previous call's
/// feature pair), GJK cold and GJK warm (the previous simplex). quick: fewer queries and
/// repetitions (a smoke run of ~1 s). Checks on the way that all four agree on the distance
/// (1e-9 relative); returns 0, or 1 if they do not.
int runVclipBench(bool quick, std::ostream& out);

}  // namespace cdlab::demos
