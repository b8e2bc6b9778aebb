// Shared look of every figure: title and caption bars, label and line styles by role.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "render/canvas.h"

namespace cdlab::demos {

struct Frame;  // app/scene/demo.h

/// Title (bold, top left) and caption (bottom left) of a figure, in pixels, on top of everything.
void drawTitleAndCaption(render::Canvas& canvas, const std::string& title, const std::string& caption);
/// The end of a one-canvas figure: its title and caption drawn (drawTitleAndCaption), its pixels
/// read back into a frame named `name` with the gallery's one-line `frameCaption`.
Frame finishedFrame(render::Canvas& canvas, const std::string& title, const std::string& caption, const std::string& name,
                    const std::string& frameCaption);

/// One entry of a drawn key: a swatch of `color` and what that colour means.
struct KeyItem {
    render::Color color;
    std::string text;
    std::string swatch = "\u25A0";  // ■; "- -" for a dashed line
};
/// A key in one row from pixel (x, y) (top left): a colour swatch, then its meaning, for each item.
/// Figures name roles in their text and show the colour here, never a colour word.
void drawKey(render::Canvas& canvas, double x, double y, const std::vector<KeyItem>& items, float sizePx = 16.0f);

/// Greedy line filling: `pieces` joined by `separator`, a new line whenever the next piece would
/// make the line wider than `width` px in `style` (a piece wider than that gets a line of its own,
/// or with `cutWide` is cut between UTF-8 characters into lines that fit: text a user wrote, which
/// may hold no separator at all; figure_style_test "wrapAtSeparator").
std::vector<std::string> wrapPieces(const render::Canvas& measure, const std::vector<std::string>& pieces,
                                    const std::string& separator, const render::TextStyle& style, double width,
                                    bool cutWide = false);
/// `line` broken only at its `separator`s (a number block's "a = 1;  b = 2"), the pieces joined back
/// by wrapPieces into lines of at most `width`.
std::vector<std::string> wrapAtSeparator(const render::Canvas& measure, const std::string& line, const std::string& separator,
                                         const render::TextStyle& style, double width, bool cutWide = false);

render::LineStyle lineStyle(render::Role role, float widthPx, bool dashed = false, bool onTop = false);
render::TextStyle labelStyle(render::Role role, float sizePx = 22.0f, bool bold = true);

/// The colour of a triangle's Voronoi region, indexed by TriangleRegion (A, B, C, AB, BC, CA, ABC):
/// neighbouring regions get far-apart hues (A next to AB and CA, ..., ABC next to the three edge
/// regions). The voronoi_triangle figures and `cdlab check --figures` use the same.
render::Color triangleRegionColor(int regionIndex);
/// The colour of a Voronoi region by the dimension of its feature (0 vertex, 1 edge, 2 face, 3 the
/// inside): tetrahedron and box regions, the same four in every figure.
render::Color featureDimensionColor(int dimension);

/// "(0.5, -1, 2)" with up to 4 significant digits, for captions.
std::string formatPoint(const Vec3& p);
std::string formatNumber(double x);

/// Look-at camera that frames a bounding sphere (center, radius) from `viewDirection`.
render::Camera framingCamera(const Vec3& center, double radius, const Vec3& viewDirection, const Vec3& up,
                             bool perspective = true);

/// `view` turned towards `normal` as little as it takes for the two to be within acos(minCos) of
/// each other, kept within 72° of the vertical (framingCamera's up is +y): a step's face seen from
/// its front (the view rules FeatureEdgeOn and FeatureFromBehind, render/legibility.h). A view
/// that already sees it so is returned as it is. Test: tests/demos/draw/view_choice_test.cpp.
Vec3 viewTowards(const Vec3& view, const Vec3& normal, double minCos = 0.5);

}  // namespace cdlab::demos
