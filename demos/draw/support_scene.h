// What the GJK and EPA demos share: shapes read from the scene (support mappings placed by a pose,
// in 3D or in the z = 0 plane), their drawable outlines, the Minkowski difference A - B drawn as a
// hull (exact for polytopes: hull of {a_i - b_j}; from support samples for curved shapes), the
// two-panel frame layout (world space | configuration space), and JSON helpers for traces.
// Only geometry for drawing lives here; every algorithm answer comes from core.
#pragma once

#include <string>
#include <vector>

#include "core/shapes.h"
#include "core/types.h"
#include "demos/scene/demo.h"
#include "demos/scene/json_reader.h"
#include "render/canvas.h"

namespace cdlab::demos {

/// Convex hull of points in the xy plane (z ignored, kept from the input), counter-clockwise,
/// duplicates and collinear points dropped (Andrew's monotone chain). For 2D outlines in figures.
std::vector<Vec3> hull2d(std::vector<Vec3> points);

/// One convex shape of a GJK / EPA scene, world frame. 3D kinds: box, sphere, cylinder, cone,
/// polytope; 2D kinds (z = 0 plane, rotation about z): polygon, box, circle.
struct SceneShape {
    enum class Kind { Box, Sphere, Cylinder, Cone, Polytope };
    Kind kind = Kind::Box;
    bool planar = false;           ///< 2D scene: the shape lies in z = 0 (box: a rectangle, sphere: a disc)
    Transform pose;                ///< body -> world
    Vec3 halfExtents = Vec3::Ones();
    double radius = 0.5;
    double halfHeight = 0.5;
    PolytopeShape polytope;        ///< Polytope kind: body-frame vertices

    /// World-frame support point (core/support.h concept).
    Vec3 support(const Vec3& d) const;
    /// Exactly the convex hull of finitely many points (box, polytope, polygon)?
    bool isPolytope() const { return kind == Kind::Box || kind == Kind::Polytope; }
    /// Polytopes: the world vertices (a superset of the extreme points).
    std::vector<Vec3> worldVertices() const;
    std::string kindName() const;
};

/// Reads {"box": {...}} etc. (see docs/scenes.md, "gjk"). `planar`: the 2D forms.
SceneShape parseSceneShape(const JsonNode& node, bool planar);

/// A drawable convex body: triangles (3D) or a CCW outline (2D), plus feature edges worth drawing.
struct ConvexDrawable {
    bool planar = false;
    std::vector<Vec3> vertices;
    std::vector<Eigen::Vector3i> triangles;   // 3D
    std::vector<std::pair<int, int>> edges;   // 3D polytopes: hull edges; 2D: the outline loop
    std::vector<Vec3> outline;                // 2D: CCW polygon
    Vec3 center = Vec3::Zero();
    double radius = 0.0;                      // bounding sphere about center
    bool valid = false;
};

/// The shape as drawn: hull of its vertices (polytopes) or of support samples (curved shapes).
ConvexDrawable shapeDrawable(const SceneShape& shape);
/// A - B: hull of {a_i - b_j} when both are polytopes (exact), else of s_A(d) - s_B(-d) over
/// evenly spread directions d (inscribed in the true set).
ConvexDrawable minkowskiDrawable(const SceneShape& a, const SceneShape& b, bool* exact = nullptr);

/// Bounding sphere of points (centre of the bounding box, max distance).
void boundingSphere(const std::vector<Vec3>& points, Vec3& center, double& radius);

/// Layout of a two-panel frame: title band, two panels side by side, caption band.
struct TwoPanelLayout {
    int width = 1280, height = 640;
    int titleBand = 44, captionBand = 62;
    int panelWidth() const { return width / 2; }
    int panelHeight() const { return height - titleBand - captionBand; }
};

/// Camera for a panel: 2D (fits the sphere in the panel) or a perspective look-at from `view`.
render::Camera panelCamera(bool planar, const Vec3& center, double radius, const Vec3& view, const TwoPanelLayout& layout);

/// Draws a body translucent with its edges (3D) or a filled outline (2D).
void drawBody(render::Canvas& canvas, const ConvexDrawable& body, const render::Color& fill, float alpha,
              const render::Color& edge, float edgeWidth);

/// Draws the little "O" origin marker with a cross.
void drawOrigin(render::Canvas& canvas, double size, bool planar);

/// Text next to `at`, pushed `px` output pixels away from `from` on screen (so labels fan out
/// from a centre instead of piling onto the point they name).
void drawLabelAway(render::Canvas& canvas, const Vec3& at, const Vec3& from, const std::string& text,
                   render::TextStyle style, double px = 16.0);

/// Panel heading (top left, bold) and an optional second line underneath.
void drawPanelHeading(render::Canvas& canvas, const std::string& heading, const std::string& sub);

/// Assembles the frame: title (top), left and right panels, up to two caption lines (bottom).
render::Image composeTwoPanel(render::GlContext& gl, const TwoPanelLayout& layout, int supersample,
                              const std::string& title, const render::Image& left, const render::Image& right,
                              const std::vector<std::string>& captionLines);

/// Which of n steps get a frame when at most `maxFrames` may be drawn: the first maxFrames - 1
/// and the last (all when n <= maxFrames).
std::vector<int> framedSteps(int n, int maxFrames);

/// "step_03".
std::string stepFrameName(int i);

Json vec3Json(const Vec3& v);
/// Tail of the scene reader shared by both demos: "dimension", "shapes" [A, B], "view".
struct PairScene {
    int dimension = 3;
    SceneShape a, b;
    Vec3 view = Vec3(1.0, 0.8, 1.7);
    int maxStepFrames = 6;
    bool gif = true;
};
PairScene readPairScene(ObjectReader& reader);

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

/// The animated GIF of the step frames (render/gif_writer.h), appended to out.files as
/// "animation.gif"; frames are box-downsampled by `downscale`.
void addGif(DemoOutput& out, const std::vector<const Frame*>& frames, int downscale);

}  // namespace cdlab::demos
