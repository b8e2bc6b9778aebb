// The voronoi_triangle demo's polygon scenes: point vs a convex polygon in 3D, its n vertex, n edge
// regions and the face (polygon_regions.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "app/scene/demo.h"

namespace cdlab::demos {

std::unique_ptr<PreparedScene> makePolygonRegionsScene(SceneCommon common, std::vector<Vec3> polygon,
                                                       std::vector<Vec3> queries, double margin,
                                                       std::vector<std::string> views);

}  // namespace cdlab::demos
