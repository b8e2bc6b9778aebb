// demo_lin_canny: Lin–Canny closest-feature tracking step by step (Lin & Canny, ICRA 1991; Lin,
// PhD thesis 1993, ch. 3) on the same polyhedra and Voronoi planes as V-Clip — both bodies, the
// current feature pair, the applicability test's planes (violated ones red), the pair's closest
// points and the update; a side-by-side figure of the Lin–Canny and V-Clip walks on one scene; and
// a cycling figure (a cycle forced with a negative applicability tolerance, beside V-Clip's verdict).
// Scene keys: docs/scenes.md, "lin_canny".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& linCannyDemo();

}  // namespace cdlab::demos
