// demo_epa: EPA step by step (van den Bergen, GDC 2001 / §4.3.8) after GJK — the expanding
// polytope in configuration space (closest face, support direction, visible faces, horizon), the
// penetration vector and witness points, and a plot of the depth bounds. 3D uses core/gjk_epa/epa.h; 2D
// scenes use the expanding polygon of core/gjk_epa/epa_2d.h. Scene keys: docs/scenes.md, "epa".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& epaDemo();

}  // namespace cdlab::demos
