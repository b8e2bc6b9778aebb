// The canvas a demo's figure is drawn on: its size in output pixels and its supersampling.
#pragma once

#include "render/canvas.h"

namespace cdlab::demos {

struct SceneCommon;
struct RunContext;

/// The print scale of a run: the command line's --scale when given, else the scene's "image.scale"
/// (a 2x figure has twice the pixels, text and line widths of the 1x one, and looks the same).
int figureScale(const SceneCommon& scene, const RunContext& context);

/// Options of a width x height canvas (layout units: the pixels of the scale-1 figure) whose picture
/// is `scale` times larger in pixels, text and lines included.
render::CanvasOptions canvasOptions(int width, int height, int scale);

/// Options of a canvas as large as the scene's image.
render::CanvasOptions sceneCanvasOptions(const SceneCommon& scene, int scale);

}  // namespace cdlab::demos
