// The feature-walk methods of `cdlab query` distance/penetration: "vclip" (Mirtich 1998) and
// "lin_canny" (Lin & Canny 1991), on polyhedral shapes (docs/query.md).
#pragma once

#include <string>

#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Answers `op` ("distance" or "penetration") with `method` ("vclip" or "lin_canny") for the
/// parsed shapes a and b (their JSON nodes name errors). Throws InputError.
Json answerFeatureWalkQuery(const std::string& op, const std::string& method, const QueryShape& a, const QueryShape& b,
                            const JsonNode& aNode, const JsonNode& bNode, bool wantTrace);

}  // namespace cdlab::demos
