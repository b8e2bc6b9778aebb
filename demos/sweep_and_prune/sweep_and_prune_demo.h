// demo_sweep_and_prune: boxes moving over a few frames; per frame the 3D view with the reported
// pairs, the intervals on x, y and z with the endpoint order before and after insertion sort
// (the swaps of the frame highlighted) and the pairs added / removed.
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& sweepAndPruneDemo();

}  // namespace cdlab::demos
