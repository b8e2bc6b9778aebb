// The voronoi_triangle demo's box scenes: point vs box, its 27 Voronoi regions (box_regions.cpp).
#pragma once

#include <memory>
#include <vector>

#include "core/base/primitives.h"
#include "app/scene/demo.h"

namespace cdlab::demos {

std::unique_ptr<PreparedScene> makeBoxRegionsScene(SceneCommon common, const Obb& box, std::vector<Vec3> queries,
                                                   double margin);

}  // namespace cdlab::demos
