// Overlap tests between bounding volumes (bounding_volumes scenes with "figure": "bv_overlap"): two
// polygons in the plane z = 0, each bounded by its minimum circle (core's fitSphereWelzl), its AABB
// (fitAabb) and its 18-DOP (fitKdop<18>, an 8-DOP in the plane); one panel per test with its numbers
// — centre distance against the radius sum (intersectSphereSphere), the x and y intervals
// (testAabbAabb), the four in-plane slab intervals (testKdopKdop). Tighter volumes reject more
// pairs. Test: tests/demos/bounding_volumes/bv_overlap_test.cpp.
#pragma once

#include <memory>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Reads the keys of a bv_overlap scene (docs/scenes.md, bounding_volumes) and finishes r.
std::unique_ptr<PreparedScene> readBvOverlapScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
