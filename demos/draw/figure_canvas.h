// The canvas a demo's figure is drawn on: its size in output pixels and its supersampling.
#pragma once

#include "render/canvas.h"

namespace cdlab::demos {

struct SceneCommon;
struct RunContext;

/// The supersampling factor of a run: the command line's --scale when given, else the scene's "image.scale".
int runSupersample(const SceneCommon& scene, const RunContext& context);

/// Options of a width x height canvas (output pixels) rendered `supersample` times larger.
render::CanvasOptions canvasOptions(int width, int height, int supersample);

/// Options of a canvas as large as the scene's image.
render::CanvasOptions sceneCanvasOptions(const SceneCommon& scene, int supersample);

}  // namespace cdlab::demos
