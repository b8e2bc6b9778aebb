// Step frames of the stepping demos: which steps get a frame, their names, and the animated GIF.
#pragma once

#include <string>
#include <vector>

#include "demos/scene/demo.h"

namespace cdlab::demos {

/// Which of n steps get a frame when at most `maxFrames` may be drawn: the first maxFrames - 1
/// and the last (all when n <= maxFrames).
std::vector<int> framedSteps(int n, int maxFrames);

/// "step_03".
std::string stepFrameName(int i);

/// The animated GIF of the step frames (render/gif_writer.h), appended to out.files as
/// "animation.gif"; frames are box-downsampled by `downscale`.
void addGif(DemoOutput& out, const std::vector<const Frame*>& frames, int downscale);

/// The end of a run that draws one frame per iteration (gjk, epa): the GIF of every frame so far
/// when `gif`, and with --steps a contact sheet of them titled "<scene title>: <algorithm>, one
/// iteration per frame".
void addAnimationAndSheet(render::GlContext& gl, const SceneCommon& common, const RunContext& ctx, bool gif,
                          const std::string& algorithm, DemoOutput& out);

}  // namespace cdlab::demos
