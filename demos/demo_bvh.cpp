// Bounding-volume hierarchies: renders golden/bvh/*.json (or the scene files given) into
// out/figures/bvh/ (hierarchy levels, AABB vs OBB trees, dual traversal steps, refit) and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("bvh", argc, argv); }
