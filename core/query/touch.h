// The touching tolerance of two query shapes (core/base/touch_rule.h: kTouchRelative times the
// extent of the cores' Minkowski difference plus the radii), and of a plane and a shape.
#pragma once

#include "core/base/touch_rule.h"
#include "core/query/shape.h"

namespace cdlab {

/// Distances at or below this are touching, for two bounded shapes (conv(vertices) ⊕ ball(radius)).
double touchTolerance(const QueryShape& a, const QueryShape& b);

/// The same for a plane n̂·x = d̂ (|n̂| = 1) and a shape whose largest |coordinate| (plus radius) is
/// `magnitude`: n̂·x − d̂ is rounded relative to both.
double planeTouchTolerance(double unitOffset, double magnitude);

/// Largest |coordinate| of a shape's vertices (a cylinder's or cone's: of its bounding box).
double largestCoordinate(const QueryShape& s);

/// n̂·x = d̂ with |n̂| = 1 (a plane's normal has its largest coordinate in [0.5, 1), so its norm is in
/// [0.5, sqrt 3]: this neither under- nor overflows).
struct UnitPlane {
    Vec3 n;
    double d;
};
UnitPlane unitPlane(const QueryShape& plane);

/// A plane against a bounded shape in closed form: the span of the shape's signed distances to the
/// plane (its support values along ±n̂).
struct PlaneSpan {
    double lo, hi;             ///< min / max of (n·x − d)/|n| over the shape
    Vec3 lowPoint, highPoint;  ///< shape points attaining them
    double touch;              ///< the touching tolerance of this plane and shape
};
PlaneSpan planeSpan(const QueryShape& plane, const QueryShape& s);

}  // namespace cdlab
