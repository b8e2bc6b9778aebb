// Space partitioning: renders golden/space_partition/*.json (uniform grid / octree / k-d / BSP
// panels, k-d queries, a solid-leaf BSP of a non-convex shape) into out/figures/space_partition/.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("space_partition", argc, argv); }
