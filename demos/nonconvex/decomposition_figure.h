// How a body's convex pieces are made (nonconvex scenes, frame "decomposition"): core's
// decomposeIntoConvexPieces walks its BSP tree with a cell that every node's plane splits
// (core/spatial/convex_decomposition.h). Small multiples, one per tree depth: the cells still to
// split, the pieces kept so far (solid leaves) and what was thrown away (empty leaves: outside),
// each from the trace. Test: tests/demos/nonconvex/decomposition_test.cpp.
#pragma once

#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "core/spatial/convex_decomposition.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

/// The trace for trace.json: per step its node, depth, kind, piece and corner count.
Json decompositionJson(const DecompositionTrace& trace);

/// The frame: one panel per depth (at most 11, then the pieces), the cells of `trace` (world
/// frame) seen from `view`, `mesh` (world) outlined in each panel.
render::Image drawDecomposition(render::GlContext& gl, int width, int height, int scale, const std::string& title,
                                const std::string& bodyName, const DecompositionTrace& trace, const TriangleMesh& mesh,
                                const Vec3& view);

}  // namespace cdlab::demos
