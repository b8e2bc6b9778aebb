// What one `cdlab query` line may ask for (docs/limits.md): every quantity that multiplies the
// work or memory of an answer has a limit, checked before the work starts, and past it the line
// answers one error naming the JSON path and the limit (the other lines are still answered).
#pragma once

#include <cstddef>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Longest query line read (bytes, newline excluded). A 10^6-vertex polytope written with 17
/// significant digits is ~60 MB; parsing holds ~8 bytes of DOM per input byte, so a line at the
/// limit costs ~0.5 GB and the whole process stays below ~1 GB.
constexpr std::size_t kMaxQueryLineBytes = std::size_t(64) << 20;

/// Input vertices of one shape for the ops that build its convex hull (contact, mass_properties,
/// method vclip / lin_canny). Measured with every vertex on the hull (points on a sphere):
/// 10^5 vertices take 1.5 s / 190 MB (mass_properties) to 3.1 s / 320 MB (vclip, whose feature
/// planes cost the most); 2·10^5 twice that. GJK ops (intersect, distance, penetration) read the
/// points directly (10^5 vertices: 0.3 s, 65 MB) and are limited by the line length only.
constexpr std::size_t kMaxHullVertices = 100000;

/// Edge pairs the SAT of a colliding `contact` may test (edges of A x edges of B): the Gauss-map
/// test is per pair, so the SAT is quadratic in the edge count (~8 ns a pair: two 2000-vertex
/// spheres, 3.6·10^7 pairs, take 0.3 s; 10^8 pairs ~1 s). Separated pairs need no SAT: GJK answers
/// them in linear time.
constexpr double kMaxSatEdgePairs = 1e8;

// The compound and mesh limits (piece pairs, GJK and EPA work, mesh triangles decomposed) multiply
// the work of core's compound query and live with it: core/query/compound.h (kMaxCompoundPairs,
// kMaxCompoundGjkPairs, kMaxCompoundDepthPairs, kMaxMeshTrianglesForPieces, CompoundOptions);
// app/query/query_compound.cpp turns a CompoundLimitHit into the error at the JSON path.

/// Fails at `node` when a shape for `op` has more vertices than kMaxHullVertices.
void requireHullVerticesWithinLimit(std::size_t vertices, const char* op, const JsonNode& node);
/// Fails at `node` when edgesA x edgesB exceeds kMaxSatEdgePairs.
void requireEdgePairsWithinLimit(int edgesA, int edgesB, const JsonNode& node);

}  // namespace cdlab::demos
