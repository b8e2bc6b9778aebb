// cdlab's core in one include: `#include <cdlab/core/cdlab.h>` (installed: find_package(cdlab) and
// target_link_libraries(x cdlab::core); C++20, Eigen 3.3 or later). The headers of one job each:
// core/<layer>/<name>.h, the layers from the bottom up in core/CMakeLists.txt.
#pragma once

#include "core/base/types.h"
#include "core/cast/ray_cast.h"
#include "core/cast/time_of_impact.h"
#include "core/contact/contact_box.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/margins.h"
#include "core/query/cast.h"
#include "core/query/compound.h"
#include "core/query/contact.h"
#include "core/query/feature_walk.h"
#include "core/query/mass.h"
#include "core/query/pair.h"
#include "core/query/shape.h"
#include "core/world/world.h"
