// `cdlab bench`: run time against error for the core queries (BENCHMARKS.md).
#pragma once

namespace cdlab::demos {

/// argv[0] is "bench"; returns the exit status.
int runBench(int argc, char** argv);

}  // namespace cdlab::demos
