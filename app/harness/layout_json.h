// A frame's layout (render/figure_layout.h) as manifest.json records it under the frame's entry:
// {"width", "height", "panels": [[x0,y0,x1,y1], ...], "labels": [{"text", "box", "anchor"}, ...],
//  "markers": [{"box", "label"}, ...]} in pixels of the written PNG, origin top-left.
#pragma once

#include "app/scene/json_reader.h"
#include "render/image.h"

namespace cdlab::demos {

Json layoutJson(const render::Image& image);

}  // namespace cdlab::demos
