// Colours and the named-role palette. Figures use roles, never RGB literals, so one palette
// change restyles every demo. Default palette: Okabe & Ito (2008), colour-blind safe.
#pragma once

#include <cstdint>

namespace cdlab::render {

/// Linear 0..1 RGBA colour (no gamma handling: figures are flat-shaded diagrams).
struct Color {
    float r = 0, g = 0, b = 0, a = 1;
    Color withAlpha(float alpha) const { return {r, g, b, alpha}; }
    Color scaled(float k) const { return {r * k, g * k, b * k, a}; }  // darker / lighter
    Color mixed(const Color& o, float t) const {
        return {r + (o.r - r) * t, g + (o.g - g) * t, b + (o.b - b) * t, a + (o.a - a) * t};
    }
};

/// What a colour is used for in a figure.
enum class Role {
    Background,  // page
    Ink,         // text, axes, outlines
    Muted,       // grid, construction lines, inactive things
    ShapeA,      // first body
    ShapeB,      // second body
    Minkowski,   // configuration-space obstacle A - B
    Simplex,     // current GJK simplex / EPA polytope
    Origin,      // the origin of configuration space
    Direction,   // search direction, normals
    Support,     // new support point
    Highlight,   // the thing the caption talks about
    Query,       // query points
    Result,      // closest points, witnesses, answers
    Colliding,   // bodies that intersect (their outlines), never a point or a pair
};

Color roleColor(Role role);

/// The 8 Okabe-Ito colours (black excluded, repeats after 7) for categorical data such as
/// Voronoi regions: categorical(i) for i = 0, 1, 2, ...
Color categorical(int index);

}  // namespace cdlab::render
