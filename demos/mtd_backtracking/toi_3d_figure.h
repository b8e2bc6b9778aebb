// Time of impact in 3D (mtd_backtracking scenes with "figure": "toi_3d"): two convex shapes
// (boxes, polytopes, spheres) translating by their motions over t in [0, 1]. core's
// translationalTimeOfImpact answers with one ray cast from the origin along motion_A − motion_B
// against B − A (van den Bergen 2004); beside it, backtracking by bisection in time: the bracket
// [separated, overlapping] halved by a GJK intersection test at its midpoint, step by step. Frames:
// "cast" (world: the shapes at t = 0 and at the time of impact, the motions, the contact; configuration
// space: B − A, the ray and its hit), "bisection" (the bracket per step against the cast's t).
// Test: tests/demos/mtd_backtracking/toi_3d_test.cpp.
#pragma once

#include <memory>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Reads the keys of a toi_3d scene (docs/scenes.md, mtd_backtracking) and finishes r.
std::unique_ptr<PreparedScene> readToi3dScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
