// demo_bounding_volumes: every bounding-volume type fitted to the same shape, one panel each
// (Ritter and Welzl spheres, AABB, covariance OBB, k-DOPs, LSS capsule, RSS), with its tightness
// (BV volume / volume of the shape's convex hull) on the panel and in the trace.
// Core: bounding_volume_fit.h, bounding_sphere.h, kdop.h, swept_sphere.h.
// Scene keys: docs/scenes.md, "bounding_volumes".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& boundingVolumesDemo();

}  // namespace cdlab::demos
