// What the feature-walk demos (vclip, lin_canny) draw with: the scene's polyhedral bodies, the frame
// layout, the 3D panel pieces (feature_walk_figure.cpp), the state diagram and the small plots
// (feature_walk_state_diagram.cpp). Every number drawn comes from core's VClipTrace /
// VClipResult (core/feature_walk/vclip.h); these files only add drawing geometry (plane patches, cameras) and the
// Theorem-1 check, which re-evaluates the final closest points against the stored region planes.
#pragma once

#include <string>
#include <vector>

#include "core/feature_walk/vclip.h"
#include "core/geometry/polyhedron.h"
#include "app/scene/demo.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene_limits.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos::walkfigure {

/// One body of a scene: the mesh, its precomputed Voronoi regions and its pose (body -> world).
struct Body {
    std::string kind;  // "icosahedron", "box", ...
    VClipPolyhedron regions;
    Transform pose;
};

/// Reads {"icosahedron": {"radius": 1, "position": [...], "rotation": [w, x, y, z]}} etc.
Body parseBody(const JsonNode& node);
/// "V3" / "E12" / "F0" (checked against the body's feature counts).
VClipFeature parseFeature(const JsonNode& node, const Body& body);

/// The scene keys the V-Clip and Lin–Canny demos share, read into either demo's settings:
/// "bodies" [A, B], "seed" [featureA, featureB], "view", "max_step_frames", "gif".
template <class Settings>
void readWalkSceneKeys(ObjectReader& r, Settings& s) {
    JsonNode bodies = r.get("bodies");
    if (!bodies.isArray() || bodies.size() != 2) bodies.fail("expected [bodyA, bodyB]");
    s.a = parseBody(bodies.at(0));
    s.b = parseBody(bodies.at(1));
    if (auto seed = r.find("seed")) {
        if (!seed->isArray() || seed->size() != 2) seed->fail("expected [featureA, featureB], e.g. [\"V0\", \"F3\"]");
        s.seed = VClipCache{parseFeature(seed->at(0), s.a), parseFeature(seed->at(1), s.b)};
    }
    if (auto v = r.find("view")) {
        s.view = sceneVec3(*v);
        if (s.view.squaredNorm() == 0) v->fail("view direction must be non-zero");
    }
    if (auto m = r.find("max_step_frames")) s.maxStepFrames = m->asInt(2, 40);
    s.gif = r.boolOr("gif", true);
}

/// Frame layout: title band, the 3D panel on the left, the state diagram over the distance plot on
/// the right, a caption band: the scene's caption, then up to three lines about the frame.
struct Layout {
    int width = 1024, height = 768;
    int titleBand = 40, captionBand = 104;
    int columnWidth = 384;
    int mainWidth() const { return width - columnWidth; }
    int panelHeight() const { return height - titleBand - captionBand; }
    int diagramHeight() const { return panelHeight() * 45 / 100; }
    int plotHeight() const { return panelHeight() - diagramHeight(); }
};

render::Image composeFrame(render::GlContext& gl, const Layout& layout, int scale, const std::string& title,
                           const std::string& sceneCaption, const render::Image& main, const render::Image& diagram,
                           const render::Image& plot, const std::vector<std::string>& captionLines);

// ---- the 3D panel pieces (vclip_demo_draw.cpp)

/// A body placed at `pose`, translucent, with its edges; noted as `name`, apart from the body named
/// `apartFrom` ("" none; Canvas::noteBody).
void drawPolyhedron(render::Canvas& canvas, const Body& body, const Transform& pose, const render::Color& fill,
                    float alpha, const std::string& name, const std::string& apartFrom = "");
/// The outward normals (world frame) of the faces of `body` placed at `pose` that hold feature f:
/// a face's own, an edge's two, a vertex's ring (what Canvas::noteFeature judges the view by).
std::vector<Vec3> featureNormals(const Body& body, const Transform& pose, const VClipFeature& f);
/// A walk's bodies as its frames show them, for choosing their view: A and B at their poses, and
/// whether the walk found them apart (then they stay apart on the picture).
struct WalkBodies {
    const Body* a = nullptr;
    Transform poseA;
    const Body* b = nullptr;
    Transform poseB;
    bool apart = false;
};
/// One step's features: the pair (fa on A, fb on B) and, after an update of body `updated` (0: A,
/// 1: B, -1: none), its new feature `to`, the feature the frame is built around.
struct WalkStepFeatures {
    VClipFeature fa, fb;
    int updated = -1;
    VClipFeature to;
};
/// The view direction, within `maxTurnDegrees` of `view` and 72° of the vertical, that best shows
/// the steps: each new feature from its front (a face's normal within 63° of the view, an edge's or
/// a vertex's faces' nearest within 72°, an edge 20° off it: FeatureFromBehind, FeatureEdgeOn), no current feature
/// edge-on (the review: a current face turned to a dashed line), the bodies apart on the picture
/// when they are apart (SeparatedBodiesOverlap), and the least turn from `view`, in that order.
/// A view that shows all of that is returned as it is. Test: tests/demos/draw/view_choice_test.cpp.
Vec3 chooseWalkView(const WalkBodies& bodies, const Vec3& view, const std::vector<WalkStepFeatures>& steps,
                    double maxTurnDegrees);
/// Both bodies, translucent with their edges, noted apart when they are (drawPolyhedron), and with
/// `names` each body's name on its far side from the other, where the features are not.
void drawWalkBodies(render::Canvas& canvas, const WalkBodies& bodies, bool names);
/// The closest points pa, pb (dashed between them when more than 1e-3 `sceneRadius` apart); with
/// `named` labelled sideways on screen (p_A left, p_B right: the feature labels sit above / below),
/// one "p_A = p_B" where they meet.
void drawClosestPoints(render::Canvas& canvas, const Vec3& pa, const Vec3& pb, bool named, double sceneRadius);
/// A step's update: an arrow from the old feature's centre to the new one's, drawn beside that path
/// (0.05 `sceneRadius` to its side on the picture), not along it: from a vertex to an edge through
/// it the path is the edge itself, and the edge drawn over it hid the arrow (the review's walk
/// steps 3–5, edge_edge steps 0 and 2–4).
void drawUpdateArrow(render::Canvas& canvas, const Vec3& from, const Vec3& to, double sceneRadius);
/// The view of one step's frame: the walk's `sceneView` when it shows the step's new feature from
/// its front, else chooseWalkView for this step alone (the camera swings round to the feature).
Vec3 stepView(const WalkBodies& bodies, const Vec3& sceneView, const WalkStepFeatures& step);
/// The key of the plane tests: violated, satisfied, and the dashed distance from each tested point
/// to its plane (drawPlaneTest; the review found the dashes unexplained).
std::vector<KeyItem> planeKey();
/// A step's new feature (drawFeature with `step`, unnamed: its label goes with the update arrow),
/// in the pass its kind belongs to. A face in the first pass, before the current features, so their
/// strokes go over its fill and outline (it holds the current edge, which its outline painted over:
/// lin_canny/walk step 1); filled in its body's feature colour, saturated (StepFeatureFaded). An edge
/// or a vertex in the last pass, over the plane patches drawn along it, darker than the body's own
/// edges. Empty `geometry` (no update): nothing.
void drawNewFeature(render::Canvas& canvas, const std::vector<Vec3>& geometry, const std::vector<Vec3>& normals,
                    const render::Color& bodyFeature, const std::string& label, bool firstPass);
/// A feature highlighted: a vertex as a large dot, an edge as a thick line, a face filled; on the
/// far side of its body (every face in `normals` turned away from the eye) an edge dashed and a
/// face hollow with a dashed outline (hidden geometry is never filled). Labelled with `label`
/// pushed away from `awayFrom`; noted (Canvas::noteFeature) with `step`: what the frame's step
/// changed.
void drawFeature(render::Canvas& canvas, const std::vector<Vec3>& geometry, const std::vector<Vec3>& normals,
                 const render::Color& color, const std::string& label, const Vec3& awayFrom, bool labels,
                 bool step = false);
/// The body's vertices placed at `pose` (world frame).
std::vector<Vec3> worldVertices(const Body& body, const Transform& pose);
/// How far (px) a walk frame keeps its bodies from the panel's sides and bottom (the review found
/// a cube 7 px from the panel's edge).
constexpr double kSideMarginPx = 16.0;
/// Do the points project inside the canvas, `top` px below its top edge and kSideMarginPx from its
/// other edges, through its camera?
bool verticesInside(const render::Canvas& canvas, const std::vector<Vec3>& points, double top);
/// Mean of a feature's points.
Vec3 featureCenter(const std::vector<Vec3>& geometry);
/// The other points a feature's label may name it at (drawLabelAway's alsoAt): an edge's points a
/// quarter, a sixth and 0.4 from either end (not nearer its ends: a leader there reads as naming
/// the vertex), a face's halfway from its centre to each corner; none for a vertex.
std::vector<Vec3> featureLabelPoints(const std::vector<Vec3>& geometry);
/// A patch of a Voronoi plane of `body` placed at `pose`, world frame: FE planes are drawn as the edge extruded along
/// the face's outward normal, VE planes as a square about the vertex turned towards `toward`.
std::vector<Vec3> planePatch(const Body& body, const Transform& pose, int plane, const Vec3& toward, double size);
/// What a plane test is drawn as (regionBody placed at `pose`): the Voronoi plane's patch
/// (planePatch, turned towards `tested`); for the face-plane test (plane < 0) the `owner` face
/// enlarged ×1.2 about its centre; none for anything else.
std::vector<Vec3> planeTestPatch(const Body& regionBody, const Transform& pose, int plane, const VClipFeature& owner,
                                 const Vec3& tested, double sceneRadius);
/// Whether a step draws plane test p of its `tests`: all of them up to six; beyond that only the
/// violated ones and the maximal one, or with neither the one nearest to being violated (at eight
/// the patches buried vclip/penetration step_05's labels).
bool planeTestDrawn(const std::vector<VClipPlaneTest>& tests, const VClipPlaneTest& p);
/// The corners of the plane patches a step draws (planeTestDrawn, planeTestPatch; each region's body
/// at its pose in `bodies`): what the step's frame keeps whole in its panel.
std::vector<Vec3> drawnPatchPoints(const WalkBodies& bodies, const std::vector<VClipPlaneTest>& tests,
                                   double sceneRadius);
/// A plane test: its patch (red and solid when violated, faint green when satisfied, thick when
/// maximal), the tested point and its offset to the plane along `normalIntoOwner`.
void drawPlaneTest(render::Canvas& canvas, const Body& regionBody, const Transform& pose, int plane,
                   const VClipFeature& owner, const Vec3& tested, double signedDistance, const Vec3& normalIntoOwner,
                   bool violated, bool maximal, double sceneRadius);
/// "V3 (A)".
std::string featureLabel(const VClipFeature& f, int body);
/// The scene's world bounding sphere.
void sceneSphere(const std::vector<const Body*>& bodies, Vec3& center, double& radius);

/// Theorem 1 (Mirtich 1998): the point x (world) lies in VR(feature) of `body` placed at `pose`. Returns the planes
/// tested (index, signed distance, positive inside); the face plane itself is reported as index -1.
struct RegionCheck {
    struct Test {
        int plane = -1;       // index into body.regions.planes(); -1 = the face's own plane
        double distance = 0;  // positive inside
    };
    std::vector<Test> tests;
    double minDistance = 0;  // smallest signed distance (the margin of the check)
};
RegionCheck checkInRegion(const Body& body, const Transform& pose, const VClipFeature& feature, const Vec3& x);

// ---- state diagram and plots (vclip_state_diagram.cpp)

/// What the diagram lights: the current state, the transition just taken (from -> to, -1 = none),
/// how often each state was visited so far, and a terminal note ("DONE", "penetration").
struct DiagramInput {
    int current = -1;        // VClipState as int, -1 none
    int from = -1, to = -1;  // transition taken by this step's update (to may equal from: self loop)
    int visits[5] = {0, 0, 0, 0, 0};
    std::string terminal;  // drawn under the current state
    std::string heading = "V-Clip states";
};
render::Image drawStateDiagram(render::GlContext& gl, int width, int height, int scale, const DiagramInput& in);

/// One curve of a small plot: x, y points with a per-point colour.
struct PlotSeries {
    std::vector<double> x, y;
    std::vector<render::Color> pointColors;
    render::Color lineColor;
    bool bars = false;  // draw as bars from 0 instead of a polyline
};
struct PlotInput {
    std::string heading, xLabel;
    std::vector<PlotSeries> series;
    double marker = -1;  // x of a vertical "now" marker (< 0: none)
    std::vector<std::pair<render::Color, std::string>> legend;
    bool integerY = false;
};
/// A line / bar chart in pixel space.
render::Image drawPlot(render::GlContext& gl, int width, int height, int scale, const PlotInput& in);

/// Colours of the walk.
render::Color violatedColor();   // red: violated plane / excluded part
render::Color satisfiedColor();  // green: satisfied plane
render::Color clipColor();       // the clipped part of an edge

}  // namespace cdlab::demos::walkfigure
