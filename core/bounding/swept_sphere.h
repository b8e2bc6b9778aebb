// Swept-sphere volumes (SSVs): a core primitive (point, segment, rectangle) swept by a sphere of
// radius r, i.e. the points within r of the core. PSS = point swept sphere (a sphere), LSS =
// line swept sphere (a capsule), RSS = rectangle swept sphere.
//
// Source: E. Larsen, S. Gottschalk, M. Lin, D. Manocha, "Fast Distance Queries with Rectangular
// Swept Sphere Volumes", ICRA 2000 (§3: the SSV family; §4: fitting from the principal axes of
// the covariance, as for OBBs: the core spans the major axes, the radius covers the thin one).
// Ericson, "Real-Time Collision Detection" (2005) §4.5 (sphere-swept volumes).
// Overlap tests: core/bounding/swept_sphere_overlap.h.
//
// Frame and units: the caller's (world) frame and length unit; volumes in units^3.
// Containment: every fit ends with radius = max distance from the points to the final core
// (measured in double against the stored core), padded by a few ulp of the magnitudes involved,
// so every finite input point is inside. Non-finite points are skipped; no finite point gives
// radius -1 and a NaN core (no hit in every test).
#pragma once

#include <span>

#include "core/base/primitives.h"
#include "core/bounding/bounding_volume_fit.h"

namespace cdlab {

/// Rectangle swept sphere: the points within radius of the rectangle
/// { center + axes.col(0) u + axes.col(1) v : |u| <= halfLengths[0], |v| <= halfLengths[1] }.
/// axes is a rotation matrix; axes.col(2) is the rectangle's normal. halfLengths >= 0 (0 makes
/// the rectangle a segment or a point); radius < 0 is empty.
struct Rss {
    Vec3 center = Vec3::Zero();
    Mat3 axes = Mat3::Identity();
    Vec2 halfLengths = Vec2::Zero();
    double radius = 0.0;
};

/// What a swept-sphere fit computed (recorded in every build type when non-null).
struct SweptSphereFitTrace {
    /// covariance OBB of the points (its axes are the SSV's axes)
    Obb principalBox{Vec3::Zero(), Vec3::Zero(), Mat3::Identity()};
    ObbFitTrace covariance;   ///< the covariance and its eigenvalues
    double coreRadius = 0.0;  ///< radius from the first pass (LSS: the points' minimum circle
                              ///< across the axis; RSS: half the thickness along the normal)
    int cornerFixes = 0;      ///< RSS: rectangle ends pushed out for points off a corner
};

/// PSS: the minimum enclosing sphere (Welzl; see core/bounding/bounding_sphere.h).
Sphere fitPss(std::span<const Vec3> points);

/// LSS (Larsen et al. 2000 §4): capsule whose segment lies along the major principal axis of the
/// point covariance. The axis line passes through the center of the minimum circle of the points
/// projected on the plane across it, whose radius is the capsule radius; the segment's ends are
/// then pulled in as far as every point stays within the radius (a point at axial coordinate t
/// and distance d from the line needs an end beyond t -+ sqrt(r^2 - d^2)).
Capsule fitLss(std::span<const Vec3> points, SweptSphereFitTrace* trace = nullptr);

/// RSS (Larsen et al. 2000 §4): rectangle in the plane of the two major principal axes, at the
/// middle of the points' spread along the minor axis, radius = half that spread; the rectangle's
/// sides are pulled in as far as every point stays within the radius, and pushed back out for
/// points beyond a corner (where both sides count).
Rss fitRss(std::span<const Vec3> points, SweptSphereFitTrace* trace = nullptr);

/// Capsule volume pi r^2 |b - a| + 4/3 pi r^3 (units^3); 0 for a negative radius.
double volume(const Capsule& capsule);

/// RSS volume: slab 8 a b r + half-cylinders along the perimeter 2 pi r^2 (a + b) + corner
/// spheres 4/3 pi r^3, with (a, b) = halfLengths (units^3); 0 for a negative radius.
double volume(const Rss& rss);

/// Distance from p to the capsule's segment (double); the point is inside iff it is <= radius.
double coreDistance(const Capsule& capsule, const Vec3& p);

/// Distance from p to the RSS's rectangle (double); the point is inside iff it is <= radius.
double coreDistance(const Rss& rss, const Vec3& p);

}  // namespace cdlab
