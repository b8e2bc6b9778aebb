// demo_gjk: GJK step by step (van den Bergen §4.3; Ericson §9.5) — world space next to
// configuration space (A − B, the origin, the simplex, the search direction, the support point and
// the kept Voronoi region), in 3D and in the plane. Scene keys: docs/scenes.md, "gjk".
#pragma once

#include <string>
#include <vector>

#include "app/scene/demo.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab::demos {

const Demo& gjkDemo();

/// A vector the configuration panel draws from the origin, with the label it carries.
struct GjkDrawnVector {
    std::string label;
    Vec3 vector = Vec3::Zero();
    bool arrow = false;  ///< an arrow (a direction) or a segment to a point
};

/// What step `index` of `steps` draws from the origin: the search direction that iteration used —
/// "d = −v₁" (v of the iteration before: GJK searches along −v) or "d (start)" at the first — and
/// v after the iteration's reduction ("v₂"). Every label names the trace quantity drawn
/// (tests/demos/gjk/gjk_demo_test.cpp parses the labels and compares).
std::vector<GjkDrawnVector> gjkStepVectors(const std::vector<GjkTraceStep>& steps, int index);

/// "₁₂" for 12: subscript digits (the figure font has them).
std::string subscriptNumber(int n);

}  // namespace cdlab::demos
