// The shapes of the `cdlab query` format (docs: the query format), read from JSON into core's
// QueryShape (core/query/shape.h); errors name the JSON path.
#pragma once

#include "app/scene/json_reader.h"
#include "core/query/shape.h"

namespace cdlab::demos {

/// Parses {"sphere": {...}} and friends. Plane normals (with their offsets) and ray directions are
/// rescaled by a power of two (QueryShape::plane / ray: the same plane or ray).
QueryShape parseQueryShape(const JsonNode& node);

}  // namespace cdlab::demos
