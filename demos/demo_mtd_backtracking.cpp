// MTD correction, backtracking and conservative advancement: renders golden/mtd_backtracking/*.json
// (or the scene files given) into out/figures/mtd_backtracking/.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("mtd_backtracking", argc, argv); }
