// An AABB under rotation (bounding_volumes scenes with "figure": "aabb_refit"): a polygon in the
// plane z = 0 turned about its box's centre by each of the scene's angles; per angle the AABB
// refitted to the turned points (core's fitAabb) against the AABB of the turned old box (core's
// transformAabb, |R| h: no point revisited), with both areas. Test:
// tests/demos/bounding_volumes/aabb_refit_test.cpp.
#pragma once

#include <memory>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Reads the keys of an aabb_refit scene (docs/scenes.md, bounding_volumes) and finishes r.
std::unique_ptr<PreparedScene> readAabbRefitScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
