#include "demos/draw/figure_canvas.h"

#include "demos/scene/demo.h"
#include "demos/scene/scene.h"

namespace cdlab::demos {

int runSupersample(const SceneCommon& scene, const RunContext& context) {
    return context.scaleOverride > 0 ? context.scaleOverride : scene.image.scale;
}

render::CanvasOptions canvasOptions(int width, int height, int supersample) {
    render::CanvasOptions o;
    o.width = width;
    o.height = height;
    o.supersample = supersample;
    return o;
}

render::CanvasOptions sceneCanvasOptions(const SceneCommon& scene, int supersample) {
    return canvasOptions(scene.image.width, scene.image.height, supersample);
}

}  // namespace cdlab::demos
