// `cdlab query` distance / penetration with method "lin_canny" (Lin & Canny 1991, core/lin_canny.h),
// on polyhedral shapes (polytope, aabb, obb), beside "vclip" (demos/lib/query_vclip.h).
#pragma once

#include <string>

#include "demos/lib/json_reader.h"
#include "demos/lib/query_shapes.h"

namespace cdlab::demos {

/// Answers `op` ("distance" or "penetration") for the parsed shapes a and b with one cold
/// Lin–Canny walk on their convex hulls. Answer keys as GJK's / V-Clip's: separated
/// {"intersect":false,"distance","point_a","point_b"} (+ "normal" for penetration); a detected
/// penetration {"intersect":true,"distance":0} ("distance" only for op distance). A cycle (the
/// walk would loop: Lin–Canny on penetrating bodies) throws InputError
/// "lin_canny: cycle detected (penetrating?)" rather than guess. Optional "trace" key
/// {"unit", "algorithms":[{"algorithm":"lin_canny","status","steps":[...]}]}. Errors name the
/// JSON node (non-polyhedral or flat shapes). Throws InputError.
Json answerLinCannyQuery(const std::string& op, const QueryShape& a, const QueryShape& b, const JsonNode& aNode,
                         const JsonNode& bNode, bool wantTrace);

}  // namespace cdlab::demos
