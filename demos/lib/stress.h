// `cdlab stress`: families of hard inputs checked against independent oracles (README, "cdlab stress").
#pragma once

namespace cdlab::demos {

/// argv[0] is "stress"; returns the exit status.
int runStress(int argc, char** argv);

}  // namespace cdlab::demos
