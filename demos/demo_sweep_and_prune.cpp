// Sweep and prune frame by frame: renders golden/sweep_and_prune/*.json (or the scene files given)
// into out/figures/sweep_and_prune/, one figure per frame, and trace.json (swaps, pairs).
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("sweep_and_prune", argc, argv); }
