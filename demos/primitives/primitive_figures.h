// Drawing pieces shared by the primitives demo's figures: an orthographic
// view that keeps the picture above the block of numbers, the block itself, trace numbers.
#pragma once

#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "demos/draw/convex_drawable.h"
#include "app/scene/json_reader.h"
#include "render/canvas.h"

namespace cdlab::demos {

/// Orthographic view along `viewDirection` of `points` (what is drawn), with `up` up, placed so that
/// their screen extents fill the picture's top `fraction` (below it: the numbers) under the title's
/// band, centred there; width and height in pixels.
render::Camera viewAbove(const std::vector<Vec3>& points, const Vec3& viewDirection, const Vec3& up, double fraction,
                         int width, int height);

/// `preferred` turned to lie across `line` (a gap, an axis): seen that way, a gap along the line
/// shows as a gap. A line along `preferred` gives any direction across it. Turned further about
/// the line (still across it) until it looks down at least 17° where some direction across the
/// line does: from below, a box reads as seen from above (the review's primitives/sphere_obb).
/// Test: tests/demos/draw/view_choice_test.cpp.
Vec3 viewAcross(const Vec3& preferred, const Vec3& line);

/// Lines of numbers, wrapped to the canvas width between their ";  "-separated phrases, whose last line ends `bottomMargin` pixels above the
/// canvas bottom (under them: the caption). Returns the pixel row of the block's top.
double drawNumberBlock(render::Canvas& canvas, const std::vector<std::string>& lines, double bottomMargin);

/// A finite number as itself, an infinite one as null (the trace holds no infinity).
Json finiteOrNull(double x);

constexpr double kNumberLineHeight = 26.0;
constexpr float kNumberTextPx = 18.0f;

}  // namespace cdlab::demos
