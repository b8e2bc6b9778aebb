// Number formatting shared by every answer of `cdlab query`: no negative zero, and no NaN or
// infinity (nlohmann would print them as null) in an answer.
#pragma once

#include "core/base/types.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// -0 prints as "-0.0": answers print +0 instead (docs/query.md: no answer prints -0).
inline double cleanZero(double x) { return x == 0 ? 0.0 : x; }

/// [x, y, z] with negative zeros cleaned.
inline Json vecJson(const Vec3& v) { return Json::array({cleanZero(v.x()), cleanZero(v.y()), cleanZero(v.z())}); }

/// Throws the query's overflow error when any number in the answer is NaN or infinite.
void requireFiniteAnswer(const Json& answer);

}  // namespace cdlab::demos
