#include "demos/draw/step_frames.h"

#include <algorithm>
#include <cstdio>

#include "demos/draw/contact_sheet.h"
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

std::string iterationCoverage(int iterations, const std::vector<int>& framed, const std::string& noun, int first) {
    if (iterations <= 0) return "no " + noun + " ran";
    std::vector<bool> shown(std::size_t(iterations), false);
    for (int i : framed)
        if (i >= 0 && i < iterations) shown[std::size_t(i)] = true;
    std::string skipped;
    for (int i = 0; i < iterations;) {
        if (shown[std::size_t(i)]) {
            ++i;
            continue;
        }
        int j = i;
        while (j + 1 < iterations && !shown[std::size_t(j + 1)]) ++j;
        skipped += (skipped.empty() ? "" : ", ") + std::to_string(i + first) + (j > i ? "–" + std::to_string(j + first) : "");
        i = j + 1;
    }
    if (skipped.empty()) return "one frame per " + noun;
    return noun + (skipped.find_first_of(",–") == std::string::npos ? " " : "s ") + skipped + " not shown";
}

void addAnimationAndSheet(render::GlContext& gl, const SceneCommon& common, const RunContext& ctx, bool gif,
                          const std::string& algorithm, int iterations, const std::vector<int>& framed,
                          DemoOutput& out) {
    std::vector<const Frame*> all;
    for (const Frame& f : out.frames) all.push_back(&f);
    if (gif) addGif(out, all, 1);
    if (common.steps || ctx.stepsOverride) {
        ContactSheetOptions o;
        o.caption = common.caption;
        o.title = common.title + ": " + algorithm + ", " + iterationCoverage(iterations, framed);
        o.cellWidth = 320;
        o.columns = std::min<int>(3, int(all.size()));
        out.frames.push_back(contactSheetFrame(gl, all, common.title, o));
    }
}

void addQueryFramesAndSheet(GlContext& gl, const SceneCommon& common, int count, const std::function<Frame(int)>& draw,
                            DemoOutput& out) {
    const std::size_t first = out.frames.size();
    for (int i = 0; i < count; ++i) out.frames.push_back(draw(i));
    std::vector<const Frame*> steps;
    for (std::size_t i = first; i < out.frames.size(); ++i) steps.push_back(&out.frames[i]);
    ContactSheetOptions o;
    o.caption = common.caption;
    o.title = common.title + ": one query point per frame";
    out.frames.push_back(contactSheetFrame(gl, steps, common.title, o));
}

}  // namespace cdlab::demos
