// A captioned grid of frames in one image (for step-through demos and galleries).
#pragma once

#include <string>
#include <vector>

#include "app/scene/demo.h"
#include "render/gl_context.h"

namespace cdlab::demos {

struct ContactSheetOptions {
    int cellWidth = 384;  // each frame is box-downsampled to fit this width
    int columns = 0;      // 0: ceil(sqrt(n))
    std::string title;    // drawn above the grid
    std::string caption;  // the scene's caption, under the title
};

/// Lays frames out left to right, top to bottom, each with its caption underneath.
render::Image makeContactSheet(render::GlContext& gl, const std::vector<const Frame*>& frames,
                               const ContactSheetOptions& options);

/// The scene's "contact_sheet" frame: makeContactSheet of `frames`, captioned "<sceneTitle> — contact sheet".
Frame contactSheetFrame(render::GlContext& gl, const std::vector<const Frame*>& frames, const std::string& sceneTitle,
                        const ContactSheetOptions& options);

}  // namespace cdlab::demos
