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

}  // namespace cdlab::demos
