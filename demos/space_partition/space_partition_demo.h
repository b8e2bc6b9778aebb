// demo_space_partition: one object set under a uniform grid, an octree, a k-d tree and a BSP
// tree (top views), k-d nearest / range queries, and a solid-leaf BSP of a non-convex shape.
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& spacePartitionDemo();

}  // namespace cdlab::demos
