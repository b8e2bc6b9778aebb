// demo_vclip: V-Clip step by step (Mirtich, ACM TOG 1998 / MERL TR-97-05) — both polyhedra with the
// current feature pair, the Voronoi-region planes under test (violated ones red), the clipped and the
// excluded parts of an edge, derivative signs, the update, the five-state diagram and the distance per
// update; the result frame checks Theorem 1. Motion scenes run one warm-started call per frame.
// Scene keys: docs/scenes.md, "vclip".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& vclipDemo();

}  // namespace cdlab::demos
