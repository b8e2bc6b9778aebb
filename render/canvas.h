// A figure being drawn: an off-screen multisampled framebuffer plus a list of draw commands.
// Draw calls only record; readPixels() renders everything in a fixed order (opaque meshes,
// translucent meshes back-to-front, lines / points / arrows, then text on top) and returns the
// picture. Pixel sizes (line widths, point radii, text size) are in output pixels at scale 1
// and are multiplied by the supersampling factor internally.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "render/camera.h"
#include "render/color.h"
#include "render/figure_layout.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::render {

struct CanvasOptions {
    int width = 1024;  // output size in pixels
    int height = 1024;
    int supersample = 1;  // render at s times the output size, box-filter down (anti-aliasing)
    int msaaSamples = 4;  // 4x MSAA (llvmpipe supports 4, not 8); clamped to GL_MAX_SAMPLES
    int scale = 1;        // a print figure: width*scale x height*scale pixels, text, lines and points scaled
                          // with it; every coordinate of the API stays in units of the scale-1 figure
    bool text = true;     // false: texts are recorded but neither drawn nor laid out (a contact sheet's
                          // thumbnail carries no text of its own, only its tile caption)
};

struct LineStyle {
    float widthPx = 2.0f;
    Color color;
    float dashPx = 0.0f;  // > 0: dashed with this dash length (gap = dash)
    bool onTop = false;   // ignore depth (annotations); otherwise depth-tested in 3D
};

enum class Anchor { Center, Left, Right, Top, Bottom, TopLeft, TopRight, BottomLeft, BottomRight };

struct TextStyle {
    float sizePx = 18.0f;
    Color color;
    Anchor anchor = Anchor::Center;  // which point of the text box sits at the position
    bool halo = true;                // background-coloured outline for legibility over shapes
    bool bold = false;
    Eigen::Vector2d offsetPx{0, 0};  // moves the text by output pixels (x right, y down), e.g. off a point
    /// A point label: readPixels() places it (render/label_placement.h) around its point, off the other
    /// labels, markers and thick lines, preferring the side offsetPx points to; one that fits nowhere
    /// is not drawn and is listed in the layout's `unplaced`.
    bool place = false;
    /// The strokes this label names (Canvas::setStrokeOwner; 0: none): a body's name may cross its
    /// own outline (the rule LabelOnStroke exempts them, render/legibility.h).
    int names = 0;
};

/// A highlighted feature of a body (Canvas::noteFeature): its points (one: a vertex, two: an
/// edge, more: a face) and the outward normals of the faces holding it (a face: its own; an edge:
/// its two faces'; a vertex: its faces'), world frame.
struct FeatureNote {
    std::string name;
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector3d> normals;
    bool filled = false;  // drawn as a filled region
    bool step = false;    // what the frame's step changed (the feature the frame is built around)
    /// The colour the step's feature is drawn in, as its legend or label shows it (alpha 0: not
    /// judged). Where it faces the eye the picture must show it (StepFeatureFaded).
    Color color{0, 0, 0, 0};
};

/// Where readPixels() spends its time, summed over this thread's frames (each drawing thread keeps
/// its own; for `cdlab figures --profile`).
/// With `profiling` on, readPixels() waits for the GPU (glFinish) before reading back, so the
/// draw / read-back split is real; off (default), nothing waits and only totals are meaningful.
struct RenderStats {
    bool profiling = false;
    int frames = 0;
    double buildSeconds = 0;     // CPU: vertices for every recorded command
    double drawSeconds = 0;      // GL draw calls until the GPU is done (profiling only)
    double readbackSeconds = 0;  // MSAA resolve, glReadPixels, flip, supersample resolve
};
RenderStats& renderStats();  ///< this thread's (each drawing thread keeps its own)

/// Every string drawn by any Canvas of this thread since the last clear, in drawing order: what
/// a caller checks in the text of its frames (e.g. that no number printed as "nan" or "inf").
std::vector<std::string>& drawnTextLog();

/// Not thread-safe; a Canvas must not outlive its GlContext. Cheap to create: GL objects
/// (program, buffers, glyph atlases, framebuffers by size) are cached in the GlContext.
class Canvas {
public:
    Canvas(GlContext& context, const CanvasOptions& options);
    /// The same, looking through `camera` (the background stays the default).
    Canvas(GlContext& context, const CanvasOptions& options, const Camera& camera);
    ~Canvas();
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    void setCamera(const Camera& camera);
    const Camera& camera() const;
    void setBackground(const Color& color);  // default roleColor(Role::Background)
    int width() const;
    int height() const;

    /// Triangle mesh, flat shaded per triangle (+ simple directional light when `lit`).
    /// color.a < 1 draws it translucent (sorted back to front, no depth write).
    void drawMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
                  const Color& color, bool lit = true);
    /// Convex planar polygon (fan-triangulated), e.g. a face, a region or a translucent plane patch.
    void drawPolygon(const std::vector<Eigen::Vector3d>& corners, const Color& color, bool lit = false);
    /// Thick anti-aliased line as a screen-space quad (any width; dashed optional).
    /// Every stroke drawn from now on belongs to `owner` (0: none) until the next call: a body's
    /// outline, named by the label whose TextStyle::names is the same id.
    void setStrokeOwner(int owner);
    void drawLine(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style);
    void drawPolyline(const std::vector<Eigen::Vector3d>& points, bool closed, const LineStyle& style);
    /// Filled disc of `radiusPx` pixels, with an optional outline in `outline` colour.
    void drawPoint(const Eigen::Vector3d& p, float radiusPx, const Color& color, bool onTop = true,
                   float outlinePx = 1.0f, const Color& outline = Color{0, 0, 0, 1});
    /// Shaft from p to q with a triangular head at q (head size scales with width).
    void drawArrow(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style);
    /// Text at a 3D point (projected; skipped when behind the camera), always on top of everything ...
    void drawText(const Eigen::Vector3d& at, const std::string& text, const TextStyle& style);
    /// ... or naming any one of several points (a face or an edge by its points; TextStyle::place):
    /// the placement step takes the point with the cleanest spot, the first on a tie, and the
    /// label's layout anchor is that point. Test: canvas_test "a label naming any of several points".
    void drawTextAtAnyOf(const std::vector<Eigen::Vector3d>& at, const std::string& text, const TextStyle& style);
    /// ... or at pixel coordinates (x right, y down, output pixels at scale 1).
    void drawTextPx(double x, double y, const std::string& text, const TextStyle& style);
    /// A quantity the frame names, drawn from p to q (a gap, a depth): readPixels() records its
    /// length on the picture in the layout's `quantities` (the rule QuantityTooSmall).
    void noteQuantity(const std::string& name, const Eigen::Vector3d& p, const Eigen::Vector3d& q);
    /// A body the frame draws, by its points (a polytope's vertices, a curved body's samples):
    /// readPixels() records the convex hull of their projections in the layout's `bodies` (the
    /// rule BodyCutByPanel, render/legibility.h).
    /// `apartFrom`: the body (noted by that name) the trace says this one is separated from; their
    /// outlines on the picture must not overlap (SeparatedBodiesOverlap).
    void noteBody(const std::string& name, const std::vector<Eigen::Vector3d>& points,
                  const std::string& apartFrom = "");
    /// A feature the frame highlights: readPixels() records how the camera sees it in the layout's
    /// `features` (FeatureEdgeOn, FeatureFromBehind, HiddenFilled; render/legibility.h).
    void noteFeature(const FeatureNote& feature);
    /// A plot axis from p to q (log: a log scale; LogAxisWithoutValues) ...
    void noteAxis(const Eigen::Vector3d& p, const Eigen::Vector3d& q, bool log);
    /// ... and a series or reference line as the legend names it, drawn in `color` through `at`
    /// (SeriesShareColour).
    void noteSeries(const std::string& name, const Color& color, const Eigen::Vector3d& at);
    /// Width and height in output pixels that drawTextPx would use.
    Eigen::Vector2d measureText(const std::string& text, const TextStyle& style) const;

    /// Renders every recorded command, resolves MSAA and supersampling, reads back RGBA8, with the
    /// picture's layout (every text box, marker and the panel; output pixels) in Image::layout.
    /// The command list is kept; calling again re-renders identically.
    Image readPixels();
    /// The layout readPixels() would record (the same placement of every label), without drawing:
    /// for a caller that arranges the picture by it before reading it (demos/draw/zoom_inset.cpp).
    FigureLayout layout();
    /// Forgets recorded commands (camera and background stay).
    void clearCommands();
    /// MSAA samples actually used: msaaSamples clamped to GL_MAX_SAMPLES, halved further if the
    /// driver left the framebuffer incomplete (exact after the first readPixels()); 1 = none.
    int samples() const;
    /// Projects a world point to output pixels (x right, y down, scale 1); false when it is
    /// behind the camera. Lets demos place pixel-space annotations next to 3D things.
    bool project(const Eigen::Vector3d& p, Eigen::Vector2d& pixel) const;

    struct Impl;

private:
    Impl* impl_;
};

}  // namespace cdlab::render
