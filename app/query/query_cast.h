// The cast ops of `cdlab query`: "raycast" (a ray against a shape) and "time_of_impact" (two shapes
// translating over t in [0, 1]). Formats in docs/query.md.
#pragma once

#include <string>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Answers op "raycast" or "time_of_impact" from the rest of the query line.
Json answerCastQuery(const std::string& op, ObjectReader& r);

}  // namespace cdlab::demos
