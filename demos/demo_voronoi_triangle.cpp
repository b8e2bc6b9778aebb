// Point vs triangle (and tetrahedron) Voronoi regions: renders golden/voronoi_triangle/*.json
// (or the scene files given) into out/figures/voronoi_triangle/. `--steps` adds one frame per query.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("voronoi_triangle", argc, argv); }
