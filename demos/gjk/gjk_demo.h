// demo_gjk: GJK step by step (van den Bergen §4.3; Ericson §9.5) — world space next to
// configuration space (A − B, the origin, the simplex, the search direction, the support point and
// the kept Voronoi region), in 3D and in the plane. Scene keys: docs/scenes.md, "gjk".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& gjkDemo();

}  // namespace cdlab::demos
