// Stages shared by the contact generators: the SAT one for convex polyhedra
// (core/contact/contact_sat.h) and the box–box one (core/contact/contact_box.h). Internal to
// core/contact: the algorithm is described in contact_sat.h (Gregorius, GDC 2013 / 2015).
#pragma once

#include <memory_resource>
#include <span>
#include <string>

#include "core/contact/contact_sat.h"
#include "core/contact/contact_tolerances.h"

namespace cdlab::detail {

/// "" (a static string, as every message here) when the pose is usable: finite, and its quaternion
/// unit to kUnitQuaternionTolerance (~1e-6: a typo-level error, not rounding drift, which stays
/// ~1e-15 per multiplication); else why not.
const char* poseProblem(const Transform& pose);

/// Unit plane (n̂, d̂) of n · x = d without overflow or underflow (divides by the largest |n_i|
/// first). "" on success, else why the plane is invalid (not finite, zero normal).
const char* unitPlane(const Plane& plane, Vec3& n, double& d);

/// The touching band: the caller's tolerance (when set and >= 0), else kTouchingBandRelative of the
/// larger body diagonal plus 64 ulps of
/// the largest coordinate (support values are dot products of coordinates up to maxCoord, rounded
/// to a few ulps).
double satTolerance(const SatContactOptions& options, double size, double maxCoord);

/// The best axis of each family (separation -inf when the family is empty) and its index in the
/// order the axes were tested (the trace's numbering).
struct SatBestAxes {
    SatAxisRecord faceA{SatAxisKind::FaceA, -1, -1, Vec3::Zero(), -INFINITY};
    SatAxisRecord faceB{SatAxisKind::FaceB, -1, -1, Vec3::Zero(), -INFINITY};
    SatAxisRecord edge{SatAxisKind::EdgeEdge, -1, -1, Vec3::Zero(), -INFINITY};
    int faceAIndex = -1, faceBIndex = -1, edgeIndex = -1;
};

struct SatChosenAxis {
    SatAxisRecord best;
    int chosen = -1;      ///< its index in the test order
    double maxSep = 0.0;  ///< the largest separation over all axes
};

/// Step 3: separated → the axis of largest separation; otherwise the axis of least penetration,
/// faces preferred to edges and A's faces to B's unless the other is better by the bias.
SatChosenAxis chooseSatAxis(const SatBestAxes& best, double tol, const SatContactOptions& options);

/// The chosen axis into the result: separation (the largest over all axes), normal, axis kind,
/// depth along the axis, and the status by the touching band tol.
void recordChosenAxis(const SatChosenAxis& c, double tol, SatContactResult& r);

/// Step 4b: the incident polygon clipped by the side planes of the reference polygon (Sutherland–
/// Hodgman, Ericson §8.3.4), the points behind the reference plane nr · x = dRef (s <= tol) kept
/// with depth -s and reduced to options.maxPoints into r.manifold. Positions are relative to
/// `origin` (added back on output); the reference polygon is counter-clockwise about nr. When
/// clipping leaves nothing (the incident face only grazes the reference prism within rounding),
/// the incident body's deepest vertex (of incidentVertices) along -nr stands in. Records the
/// reference / incident polygons, clip steps, clipped points and reduction in the trace.
/// sidePlanes: the side plane of each reference edge (unit normal e_i x nr / |e_i x nr|, offset
/// through r_i) when the caller knows them cheaply (a box face); empty: computed here.
/// touchingFallback = false: a clip that keeps nothing only sets r.clipKeptNothing (no stand-in
/// point), for a caller that answers on another axis then (contactPolyhedra's least-overlap retry:
/// the exact touching pair costs a hull of |reference| x |incident| points).
void clipIncidentFace(std::span<const Vec3> reference, const Vec3& nr, double dRef, std::span<const Vec3> incident,
                      std::span<const Vec3> incidentVertices, std::span<const Vec3> referenceVertices,
                      bool referenceOnA, const Vec3& origin, double tol,
                      const SatContactOptions& options, SatContactResult& r, SatContactTrace* trace,
                      std::pmr::memory_resource* memory, std::span<const Plane> sidePlanes = {},
                      bool touchingFallback = true);

}  // namespace cdlab::detail
