#include "demos/draw/figure_canvas.h"

#include "app/scene/demo.h"
#include "app/scene/scene.h"

namespace cdlab::demos {

int figureScale(const SceneCommon& scene, const RunContext& context) {
    return context.scaleOverride > 0 ? context.scaleOverride : scene.image.scale;
}

render::CanvasOptions canvasOptions(int width, int height, int scale) {
    render::CanvasOptions o;
    o.width = width;
    o.height = height;
    o.scale = scale;
    return o;
}

render::CanvasOptions sceneCanvasOptions(const SceneCommon& scene, int scale) {
    return canvasOptions(scene.image.width, scene.image.height, scale);
}

}  // namespace cdlab::demos
