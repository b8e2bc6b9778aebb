// A zoomed inset for a quantity a figure names (a gap, a depth) that its picture draws too short
// to see: the review rule QuantityTooSmall (render/legibility.h) asks for kMinQuantityPx, or an
// inset that draws it larger with its zoom marked where it is taken from.
#pragma once

#include <functional>
#include <string>

#include "core/base/types.h"
#include "render/canvas.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

/// The quantity, from p to q in world units, and how to draw the scene about it.
struct ZoomTarget {
    std::string name;     // as the inset records it (Canvas::noteQuantity)
    std::string heading;  // after "zoom ×Z: " in the inset's heading strip, e.g. "gap 0.0048"
    Vec3 p = Vec3::Zero(), q = Vec3::Zero();
    /// Draws the geometry about p–q on the inset's canvas (its camera is the picture's, moved to
    /// frame 3 |p − q| about the middle): the bodies, the quantity's segment, point names.
    std::function<void(render::Canvas&)> draw;
};

/// The inset's heading strip, px (output pixels at scale 1).
constexpr int kZoomHeadingPx = 28;

/// The picture of `canvas` (everything drawn on it), with `target` magnified when the canvas draws
/// p–q shorter than render::kMinQuantityPx; otherwise (or when `within` is too small for an inset,
/// under 240 x 232 px) exactly canvas.readPixels(). The inset sits
/// in a corner of `within` (px in the canvas), 9/20 of it each way or smaller down to 1/4, wide
/// enough for its heading: the one that hides least of what the picture draws (label and marker
/// area, strokes in Canvas::layout(); never p or q), a smaller one costing more. Its heading
/// strip names the zoom (the ratio of the two pictures' scales at the quantity) and `heading`;
/// its picture marks p–q in ink with a tick across each end. On the canvas a square marks where the
/// inset is taken from, with a connector to it; the layout loses what the inset hides
/// (FigureLayout::cover) and gains the inset's own, its border as strokes. Test: zoom_inset_test.
render::Image readPixelsZoomed(render::GlContext& gl, render::Canvas& canvas, int scale, const ZoomTarget& target,
                               const render::Box& within);

/// The camera `camera` moved to look at `mid` from the same direction, framing 2 `radius` in height.
render::Camera zoomedCamera(const render::Camera& camera, const Vec3& mid, double radius);

}  // namespace cdlab::demos
