// The shape-pair ops of `cdlab query`: intersect, distance, penetration (docs/query.md).
#pragma once

#include <string>

#include "core/base/types.h"
#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Reads "a", "b", "method", "trace" from the query object and answers `op`. Throws InputError.
Json answerShapeQuery(const std::string& op, ObjectReader& reader);

}  // namespace cdlab::demos
