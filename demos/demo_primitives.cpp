// Primitive tests (ray casts, separating axes, point in polygon): renders golden/primitives/*.json
// (or the scene files given) into out/figures/primitives/.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("primitives", argc, argv); }
