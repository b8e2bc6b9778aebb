// Non-convex bodies in the shape-pair ops of `cdlab query` (docs/query.md, "Compounds and meshes"):
// {"compound":[S, ...]}, a union of convex shapes each with its own pose fields, and
// {"mesh":{"vertices", "triangles"[, "position", "rotation"]}}, the solid bounded by a closed,
// consistently oriented triangle mesh.
//
// intersect: some pair of pieces intersects, or one body holds a piece of the other (a mesh's
// inside by its winding number). distance: the smallest distance over the pairs of boundary
// pieces (a mesh's triangles, a compound's shapes) with its witness points — the true distance of
// the two unions. penetration: the deepest pair of convex pieces (a mesh's pieces are the cells
// of its solid-leaf BSP tree, core/spatial/convex_decomposition.h) — not the union's true depth,
// which may need a longer translation; separated, the distance answer with its normal.
//
// The geometry, searches and work limits are core's (core/query/compound.h: CompoundBody,
// compoundPairQuery); this file reads the JSON into CompoundBody and writes the result, trace and
// failures back (a work limit or failed pair as the error at its JSON node).
#pragma once

#include <string>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// True for {"compound": ...} and {"mesh": ...}.
bool isCompoundOrMesh(const JsonNode& shape);

/// Answers intersect, distance or penetration when a or b is a compound or a mesh (same answer
/// keys as for convex shapes). Reads the rest of the query ("method": gjk only, "trace").
Json answerCompoundQuery(const std::string& op, ObjectReader& reader, const JsonNode& a, const JsonNode& b);

}  // namespace cdlab::demos
