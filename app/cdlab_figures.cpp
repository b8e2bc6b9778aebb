// cdlab-figures: the cdlab command line without the tools (query, check, bench, stress): figures,
// render, golden and demos. What `./cdlab figures`, `render` and `golden` build and run, so that a
// first `./cdlab figures` compiles only what rendering needs (BENCHMARKS.md, "First build").
#include "app/cli/cli.h"

int main(int argc, char** argv) { return cdlab::demos::cdlabMain(argc, argv); }
