#include "demos/draw/step_frames.h"

#include <cstdio>

#include "render/gif_writer.h"
#include "render/image.h"

namespace cdlab::demos {

using namespace render;

std::vector<int> framedSteps(int n, int maxFrames) {
    std::vector<int> out;
    if (n <= maxFrames) {
        for (int i = 0; i < n; ++i) out.push_back(i);
        return out;
    }
    for (int i = 0; i < maxFrames - 1; ++i) out.push_back(i);
    out.push_back(n - 1);
    return out;
}

std::string stepFrameName(int i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "step_%02d", i);
    return buf;
}

void addGif(DemoOutput& out, const std::vector<const Frame*>& frames, int downscale) {
    std::vector<Image> images;
    for (const Frame* f : frames) images.push_back(downscale > 1 ? downsample(f->image, downscale) : f->image);
    if (images.empty()) return;
    out.files.emplace_back("animation.gif", encodeGif(images));
}

}  // namespace cdlab::demos
