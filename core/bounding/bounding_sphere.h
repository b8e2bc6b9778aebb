// Bounding spheres of point sets: Ritter's approximate sphere and Welzl's exact minimum
// enclosing ball.
//
// Sources: C. Ericson, "Real-Time Collision Detection" (2005) §4.3.2 (Ritter: a sphere over the
// most separated pair of the six axis-extreme points, then grown over every point outside),
// §4.3.4 (Welzl, "Smallest enclosing disks (balls and ellipsoids)", 1991); the move-to-front
// variant of B. Gärtner, "Fast and Robust Smallest Enclosing Balls", ESA 1999 (a point found
// outside is moved to the front of the list, so that later passes meet it first).
// Overlap: intersectSphereSphere in core/overlap/intersect_sphere.h.
//
// Frame and units: the caller's frame and length unit; volumes in units^3.
// Containment: both fits end with radius = max |p - center| over the points (computed relative
// to a point near the data so that large offsets cancel), padded by a few ulp of the magnitudes
// involved, so every finite input point is inside the returned sphere when tested in double.
// Non-finite points are skipped (counted in the trace); no finite point gives radius -1 (the
// empty sphere: no hit in every test) and center NaN.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/base/primitives.h"

namespace cdlab {

/// Welzl's trace status: Exact while the farthest point exceeds the support ball's radius by at most
/// this, relative (rounding of a well-shaped support set is ~1e-15; a rejected, nearly dependent
/// support set leaves far more).
inline constexpr double kWelzlExactRelative = 1e-9;

/// One growth step of Ritter's pass: point `pointIndex` was outside the sphere (before), so the
/// sphere grew to just reach it (after), the far side of the old sphere staying on the new one.
struct RitterStep {
    int pointIndex = -1;
    Sphere before{Vec3::Zero(), 0.0};
    Sphere after{Vec3::Zero(), 0.0};
};

/// Trace of fitSphereRitter.
struct RitterTrace {
    std::array<int, 2> initialPair{-1, -1};  ///< most separated of the axis-extreme points
    Sphere initial{Vec3::Zero(), 0.0};       ///< sphere with that pair as diameter
    std::vector<RitterStep> steps;           ///< growth steps in input order
    int skippedNonFinite = 0;
};

/// Ritter's bounding sphere (Ericson §4.3.2): sphere over the most separated pair of the
/// min / max points along x, y, z, then one pass growing it over every point outside. O(n);
/// typically 5-20 % larger radius than the minimum ball. Points must be finite to count.
Sphere fitSphereRitter(std::span<const Vec3> points, RitterTrace* trace = nullptr);

/// How Welzl's recursion ended.
enum class WelzlStatus {
    Exact,        ///< minimum ball to rounding (every point within the support ball)
    Approximate,  ///< a nearly affinely dependent support set was rejected and the final
                  ///< radius (max distance) exceeds the support ball's by more than kWelzlExactRelative
                  ///< relative: still encloses every point, may be slightly larger than minimal
    Empty,        ///< no finite point
};

/// "Exact", "Approximate", "Empty".
const char* nameOf(WelzlStatus status);

/// One event of the move-to-front recursion: point `pointIndex` lay outside the current ball,
/// so it joins the support set (the points forced onto the boundary) and a new ball is the
/// smallest one with the whole support set on its boundary.
struct WelzlStep {
    int pointIndex = -1;
    int depth = 0;                   ///< support-set size before adding the point (0..3)
    std::vector<int> support;        ///< support set after adding it (input indices)
    Sphere ball{Vec3::Zero(), 0.0};  ///< the new ball (world frame); unchanged if !accepted
    bool accepted = true;            ///< false: support set + point nearly affinely dependent
};

/// Trace of fitSphereWelzl.
struct WelzlTrace {
    std::vector<WelzlStep> steps;
    std::vector<int> finalSupport;  ///< support set (2..4 input indices) of the returned ball
    WelzlStatus status = WelzlStatus::Empty;
    int skippedNonFinite = 0;
};

/// Welzl's minimum enclosing ball (Ericson §4.3.4) with Gärtner's move-to-front, on the points in
/// a fixed pseudo-random order (seeded constant: deterministic for a given input, expected O(n)).
/// The ball with a support set on its boundary has its center in the support set's affine hull
/// (Gram system); a support set that is (nearly) affinely dependent is rejected, which keeps
/// duplicates, collinear and coplanar sets well defined. Single point: radius 0.
Sphere fitSphereWelzl(std::span<const Vec3> points, WelzlTrace* trace = nullptr);

/// Volume 4/3 pi r^3 (units^3); 0 for a negative radius.
double volume(const Sphere& sphere);

}  // namespace cdlab
