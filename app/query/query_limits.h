// What one `cdlab query` line may ask for (README, Hardening): every quantity that multiplies the
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

/// Pairs of pieces one compound or mesh query may visit (boundary pieces of a x of b: a mesh's
/// triangles, a compound's shapes). Boxes cull most pairs, but every pair's boxes are compared
/// (~5 ns a pair): 10^8 pairs take ~0.5 s before any GJK.
constexpr double kMaxCompoundPairs = 1e8;

/// The work of a pair of pieces in pairs of boxes: GJK and EPA grow with the pieces' vertices (a
/// pair of 200-vertex polytopes costs ~25x a pair of boxes), so a pair counts (n_a + n_b) / 16 box
/// pairs, at least one (curved solids count 8 vertices).
constexpr double kBoxPairVertices = 16;

/// Work, in pairs of boxes (kBoxPairVertices), that `penetration` of a compound or mesh may hand to
/// EPA: the pairs of pieces whose boxes meet, counted before any EPA runs. EPA costs ~2.5-4.5 us a
/// pair of boxes (two 1000-box compounds, every pair overlapping: 10^6 pairs in 2.5-4.5 s), so the
/// limit runs in about a second. The search visits the pairs by an upper bound on their depth from
/// the boxes and stops when the bound is below the deepest depth found, so most queries run far
/// fewer (hostile_query_test "compound penetration: work bounded").
constexpr double kMaxCompoundDepthPairs = 2.5e5;

/// Work, in pairs of boxes, that `intersect`, `distance` and a separated `penetration` of a
/// compound or mesh may hand to GJK (counted as the pairs run; past it the line answers an error):
/// ~0.3-0.5 us a pair of boxes, so about a second too. The box culls leave most queries far below it.
constexpr double kMaxCompoundGjkPairs = 2e6;

/// Triangles of a mesh that `penetration` decomposes into convex pieces (the cells of its BSP
/// tree, 32 candidate planes per node): a 10 000-triangle torus takes 0.3 s and 41 MB.
constexpr std::size_t kMaxMeshTrianglesForPieces = 50000;

/// Fails at `node` when a shape for `op` has more vertices than kMaxHullVertices.
void requireHullVerticesWithinLimit(std::size_t vertices, const char* op, const JsonNode& node);
/// Fails at `node` when edgesA x edgesB exceeds kMaxSatEdgePairs.
void requireEdgePairsWithinLimit(int edgesA, int edgesB, const JsonNode& node);

}  // namespace cdlab::demos
