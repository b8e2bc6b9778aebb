// The one touching rule of `cdlab query`: every op (intersect, distance, penetration, contact,
// and the vclip / lin_canny methods) decides "touching or overlapping" versus "separated" by
// comparing its computed distance with the same tolerance of the same pair of shapes.
//
// Why the tolerance is relative to the extent of A − B and not to the coordinates: every
// distance method works on differences of the shapes' points (GJK on w = a − b, V-Clip and SAT in a
// frame local to the bodies), and fl(a − b) has an error below u·|a − b| whatever |a| and |b| are.
// So the computed distance is right to a few ulps of W = max |a − b| over the two shapes (plus the
// radii that are added in closed form) — not of the coordinates. Two unit boxes 5e-5 apart at
// x = 1e9 have W ≈ 2, and their gap is 1e11 times larger than the rounding: they are separated.
// kTouchRelative = 1e-13 (~450 ulps) is well above the errors measured for GJK / EPA, V-Clip,
// Lin–Canny and the SAT (a few to ~64 ulps of W) and far below any gap a user means.
//
// A plane is the exception: n̂·x − d̂ is computed from the coordinates themselves, so its rounding
// is relative to the coordinates and to the plane's offset (planeTouchTolerance).
#pragma once

#include <vector>

#include "core/base/types.h"

namespace cdlab::demos {

struct QueryShape;

constexpr double kTouchRelative = 1e-13;

/// max over the axes of |a_i − b_i| for a in conv(a), b in conv(b): a bound on the coordinates of
/// every point of A − B (the bounding box of the Minkowski difference).
double minkowskiExtent(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

/// Distances at or below this are touching, for two bounded shapes (conv(vertices) ⊕ ball(radius)).
double touchTolerance(const QueryShape& a, const QueryShape& b);

/// The same for a plane n̂·x = d̂ (|n̂| = 1) and a shape whose largest |coordinate| (plus radius) is
/// `magnitude`: n̂·x − d̂ is rounded relative to both.
double planeTouchTolerance(double unitOffset, double magnitude);

/// Largest |coordinate| of a shape's vertices (a cylinder's or cone's: of its bounding box).
double largestCoordinate(const QueryShape& s);

}  // namespace cdlab::demos
