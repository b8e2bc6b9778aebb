// Contact model figures: polyhedron vs plane manifolds, the six contact types, SAT face clipping;
// renders golden/polyhedron_plane/*.json (or the scene files given) into out/figures/polyhedron_plane/.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("polyhedron_plane", argc, argv); }
