// demo_primitives: the basic primitive tests, each figure showing the test's own geometry and the
// numbers that decide it — ray and segment casts (sphere quadratic, AABB slabs, triangle
// barycentrics), separating-axis tests (segment-box 6 axes, triangle-box 13, box-box 15) and
// point in polygon three ways.
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& primitivesDemo();

}  // namespace cdlab::demos
