// Internal to the BVH demo (bvh_demo*.cpp): drawing pieces only — boxes (AABB and OBB) as
// wireframes coloured by tree level, triangle meshes, a small binary-tree diagram with the current
// node lit, legends and the panel-grid frame layout. Every number drawn comes from core's BVH
// traces (core/bvh/bvh.h); these files add drawing geometry (box corners, tree layout) only.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "core/base/types.h"
#include "app/scene/demo.h"
#include "render/canvas.h"

namespace cdlab::demos::bvhdemo {

/// A triangle soup to draw (world frame).
struct MeshView {
    std::vector<Vec3> vertices;
    std::vector<Eigen::Vector3i> triangles;
};

/// The 8 corners of a box, corner k = center + Σ_i (bit i of k ? +1 : −1) · h_i · axis_i.
std::array<Vec3, 8> boxCorners(const Obb& box);
/// The same box as an OBB with world axes.
Obb obbFromAabb(const Aabb& box);

/// Colour of tree level `depth` (0 = root): a fixed sequence that stays apart from the mesh colour.
render::Color levelColor(int depth);

/// Wireframe box (12 edges).
void drawBoxWire(render::Canvas& canvas, const Obb& box, const render::LineStyle& style);
/// Translucent box faces (12 triangles, unlit).
void drawBoxFill(render::Canvas& canvas, const Obb& box, const render::Color& color);

/// The mesh surface (lit, `fill` with alpha) and, when edgeWidth > 0, its triangle edges.
void drawMesh(render::Canvas& canvas, const MeshView& mesh, const render::Color& fill, float edgeWidth,
              const render::Color& edge);
/// A subset of the mesh's triangles (indices into mesh.triangles), opaque, with outlines on top.
void drawTriangleSubset(render::Canvas& canvas, const MeshView& mesh, const std::vector<int>& which,
                        const render::Color& fill, const render::Color& outline, float outlineWidth, bool lit = true);

/// Bounding sphere of a mesh's vertices (and optional extra points).
void meshSphere(const std::vector<const MeshView*>& meshes, Vec3& center, double& radius,
                const std::vector<Vec3>& extra = {});

// ---- tree diagram (pixel space)

/// How a node of the diagram is drawn.
struct TreeNodeLook {
    render::Color color;
    float radius = 4.0f;  // px
    bool ring = false;    // black outline ring (the current node)
};

/// A binary tree to draw: children[i] = {left, right} (both −1 for a leaf), node 0 the root.
/// Nodes deeper than maxDepth are not drawn; a node at maxDepth with children gets a short stub
/// ("more below"). Leaves take one slot each, so the drawing is the tree's real shape.
struct TreeDiagramInput {
    std::vector<std::array<int, 2>> children;
    std::vector<TreeNodeLook> look;  // per node; empty: every node muted
    int maxDepth = 5;
    std::string heading, sub;
    bool levelLabels = true;     // "level 0", "level 1", ... at the left
    std::vector<int> litLevels;  // levels whose row label is highlighted
    /// Edges from parent to these nodes drawn thick in their node colour (e.g. the traversal path).
    std::vector<int> litEdges;
    /// Per node, a name drawn under it (a leaf's box letter; empty: none).
    std::vector<std::string> names;
};
/// Draws the diagram into a W × H image (background, heading top-left).
render::Image drawTreeDiagram(render::GlContext& gl, int width, int height, int scale,
                              const TreeDiagramInput& in);

// ---- a grouped bar chart (pixel space)

struct BarSeries {
    std::string label;
    render::Color color;
    std::vector<double> values;  // one per group
};
struct BarChartInput {
    std::string heading, sub;
    std::vector<std::string> groups;  // labels under the groups
    std::vector<BarSeries> series;
    std::string valueFormat = "%.3g";  // printf format of the value printed over each bar ("": none)
    bool logY = false;                 // log10 axis (values <= 0 drawn at the floor)
};
render::Image drawBarChart(render::GlContext& gl, int width, int height, int scale, const BarChartInput& in);

// ---- legends and frames

/// One legend entry: a swatch (line, dashed line, dot or filled square) and its text.
struct LegendItem {
    enum class Swatch { Line, Dashed, Dot, Fill };
    Swatch swatch = Swatch::Line;
    render::Color color;
    std::string text;
};

/// A frame: title band, a grid of equally sized panels (row-major, `columns` per row), a legend
/// row under the panels and up to three caption lines.
struct GridLayout {
    int width = 1024, height = 768;
    int columns = 2, rows = 1;
    int titleBand = 40;
    int legendBand = 30;  // 0: no legend row
    int captionBand = 76;
    std::vector<int> columnWidths;  // empty: width / columns each
    int panelWidth(int column = 0) const { return columnWidths.empty() ? width / columns : columnWidths[column]; }
    int columnX(int column) const {
        int x = 0;
        for (int k = 0; k < column; ++k) x += panelWidth(k);
        return x;
    }
    int panelHeight() const { return (height - titleBand - legendBand - captionBand) / rows; }
};

render::Image composeGrid(render::GlContext& gl, const GridLayout& layout, int scale, const std::string& title,
                          const std::vector<render::Image>& panels, const std::vector<LegendItem>& legend,
                          const std::vector<std::string>& captionLines);

/// Heading (bold) and an optional second line at the top left of a panel.
void drawHeading(render::Canvas& canvas, const std::string& heading, const std::string& sub);
/// Small text lines at the bottom left of a panel (last line lowest).
void drawFooter(render::Canvas& canvas, const std::vector<std::string>& lines, const render::Color& color);

/// Perspective camera looking at a sphere from `view` (z up when the view is not along z).
render::Camera sphereCamera(const Vec3& center, double radius, const Vec3& view, int width, int height);

}  // namespace cdlab::demos::bvhdemo
