// demo_nonconvex: non-convex bodies split into convex pieces and collided as pairs of pieces.
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& nonconvexDemo();

}  // namespace cdlab::demos
