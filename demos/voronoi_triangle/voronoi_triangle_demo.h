// demo_voronoi_triangle: point vs triangle (7 Voronoi regions) and point vs tetrahedron (15).
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& voronoiDemo();

}  // namespace cdlab::demos
