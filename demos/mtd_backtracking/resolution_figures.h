// The mtd_backtracking demo's frames (see resolution_figures.cpp).
#pragma once

#include <string>
#include <vector>

#include "demos/mtd_backtracking/resolution.h"
#include "app/scene/demo.h"
#include "render/canvas.h"

namespace cdlab::demos {

/// Every point drawn in any frame (A, and B at each pose), for one framing shared by the frames.
std::vector<Vec3> framedPoints(const ResolutionInput& input, const ResolutionRun& run);
/// A body's name at a point (or beside it when something is there).
void drawBodyNameAt(render::Canvas& canvas, const Vec3& at, const std::string& name);

Frame mtdFrame(render::GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& input,
               const ResolutionRun& run);
Frame backtrackFrame(render::GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& input,
                     const ResolutionRun& run);
Frame advanceFrame(render::GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& input,
                   const ResolutionRun& run);
Frame compareFrame(render::GlContext& gl, const SceneCommon& scene, int scale, const ResolutionInput& input,
                   const ResolutionRun& run);

}  // namespace cdlab::demos
