// The shape-pair ops of `cdlab query`: intersect, distance, penetration (README, "cdlab query").
#pragma once

#include <string>

#include "core/base/types.h"
#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Reads "a", "b", "method", "trace" from the query object and answers `op`. Throws InputError.
Json answerShapeQuery(const std::string& op, ObjectReader& reader);

/// The "penetration" op's answer for two shapes, in the query's units: overlapping, depth, normal
/// (from a toward b) and deepest points; separated, distance, normal and closest points.
struct ShapePairAnswer {
    bool intersect = false;
    double distance = 0, depth = 0;
    Vec3 normal = Vec3::UnitX(), pointA = Vec3::Zero(), pointB = Vec3::Zero();
};
ShapePairAnswer penetrationOf(QueryShape a, QueryShape b);
/// The same answer for any two shapes (normalised by a power of two first, as every op is); with
/// wantDepth false an overlapping pair answers only `intersect` (no EPA run).
ShapePairAnswer shapePairAnswer(QueryShape a, QueryShape b, bool wantDepth);

}  // namespace cdlab::demos
