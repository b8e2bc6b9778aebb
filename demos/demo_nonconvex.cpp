// Non-convex bodies as unions of convex pieces: renders golden/nonconvex/*.json (or the scene files
// given) into out/figures/nonconvex/.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("nonconvex", argc, argv); }
