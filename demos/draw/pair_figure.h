// The two-panel frame of the gjk and epa demos: world space | configuration space, with the bodies,
// A − B and the framing spheres every frame draws from.
#pragma once

#include <string>
#include <vector>

#include "demos/draw/convex_drawable.h"
#include "app/scene/pair_scene.h"
#include "render/canvas.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

/// Layout of a two-panel frame: title band, two panels side by side, caption band.
struct TwoPanelLayout {
    int width = 1280, height = 640;
    int titleBand = 44, captionBand = 62;
    int panelWidth() const { return width / 2; }
    int panelHeight() const { return height - titleBand - captionBand; }
};
/// The layout of a width x height frame; a scene caption takes one more line under the panels.
TwoPanelLayout twoPanelLayout(int width, int height, const std::string& sceneCaption);

/// Camera for a panel: 2D (fits the sphere in the panel) or a perspective look-at from `view`.
render::Camera panelCamera(bool planar, const Vec3& center, double radius, const Vec3& view,
                           const TwoPanelLayout& layout);

/// Panel heading (top left, bold) and an optional second line underneath.
void drawPanelHeading(render::Canvas& canvas, const std::string& heading, const std::string& sub);

/// Assembles the frame: title (top), left and right panels, up to two caption lines (bottom).
render::Image composeTwoPanel(render::GlContext& gl, const TwoPanelLayout& layout, int scale,
                              const std::string& title, const std::string& sceneCaption, const render::Image& left,
                              const render::Image& right, const std::vector<std::string>& captionLines);

/// What every GJK and EPA frame draws from: both bodies, A − B (only when `drawMinkowski`), and
/// the framing spheres of the world panel and of the configuration-space panel.
struct PairDrawing {
    bool planar = false, exact = false;  // exact: A − B is the exact hull (polytopes), not sampled
    ConvexDrawable a, b, c;
    Vec3 cCenter = Vec3::Zero(), wCenter = Vec3::Zero();
    double cRadius = 1, wRadius = 1;
};
/// Builds the drawing; `csPoints` are the algorithm's configuration-space points (simplices,
/// support points, polytopes) framed together with A − B and the origin. Records in `skipped`
/// what was not computed.
PairDrawing makePairDrawing(const PairScene& pair, bool drawMinkowski, std::vector<Vec3> csPoints,
                            std::vector<std::string>& skipped);

/// A support point of `body`, in the support colour; on the body's far side (seen through it from
/// the camera) faded, as hidden edges are dashed (the review: gjk/box_box's s_B(−d) at B's hidden
/// corner drawn as a visible dot).
void drawSupportPoint(render::Canvas& canvas, const ConvexDrawable& body, const Vec3& point, float radiusPx);

/// The two bodies in world space, translucent (`alpha3d` in 3D), named when `labels`; when they
/// intersect their outlines take Role::Colliding, with a key where outlines are drawn. `apart`: the
/// trace says the bodies are separated (noted as such: SeparatedBodiesOverlap, render/legibility.h).
void drawPairBodies(render::Canvas& world, const PairDrawing& d, float alpha3d, bool colliding, bool labels,
                    bool apart = false);

/// The world panel's camera for a separated 3D pair (closest points pa on A, pb on B): `base`
/// when the bodies are apart on its picture, else the same framing looking across the gap, the
/// eye in the plane midway between the closest points, where the two bodies' pictures cannot
/// overlap (the view rule SeparatedBodiesOverlap; gjk/sliver's 0.005 gap overlapped 29 px).
/// Test: tests/demos/draw/view_choice_test.cpp.
render::Camera acrossGapCamera(render::GlContext& gl, const render::CanvasOptions& options,
                               const render::Camera& base, const PairDrawing& d, const Vec3& pa, const Vec3& pb);

/// The name under which a pair figure records the witness distance it draws (Canvas::noteQuantity).
inline const std::string kDistanceQuantity = "distance |p_A − p_B|";

}  // namespace cdlab::demos
