// Contact manifolds shared by the contact generators (core/contact/contact_plane.h, core/contact/contact_sat.h):
// feature references of a ConvexPolyhedron, contact points with their penetration, and the
// reduction of a contact polygon to at most four points that keep its area.
//
// Reduction (as engines do it: D. Gregorius, "Robust Contact Creation for Physics Simulations",
// GDC 2015; Bullet btPersistentManifold::sortCachedPoints keeps the largest-area quad likewise):
//   0. points at depth 0 (edge crossings) within the deepest depth, in the plane, of a submerged
//      point are dropped: they are the rim of that corner and would displace full-depth corners;
//   1. the deepest point (largest depth; ties, to kManifoldTieRelative as in every rule: first in input order),
//   2. the point farthest from it (measured in the contact plane),
//   3. the point that makes the triangle with 1 and 2 of largest area,
//   4. the point that adds the most area to that triangle (largest area of the triangle it
//      forms with the hull edge it lies outside of), and 5, 6, ... the same on the hull of the
//      points kept so far while maxPoints allows: more points never gives fewer, and maxPoints at
//      or above the polygon's corner count gives every corner.
// Every distance and area is measured after projection onto the plane ⟂ normal, so depth
// differences do not count as "spread".
#pragma once

#include <span>
#include <vector>

#include "core/base/fixed_capacity_vector.h"
#include "core/base/types.h"
#include "core/geometry/polyhedron_feature.h"

namespace cdlab {

/// One contact point. Normal convention (as EPA, core/gjk_epa/epa.h): the manifold normal points from A
/// toward B and pointA - pointB = depth * normal: pointA is the point of A inside B, pointB its
/// projection onto B's surface (the plane / the reference face). World frame, world units.
struct ContactPoint {
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
    double depth = 0.0;  ///< penetration along the normal, >= 0 (0: on the surface of B)
};

/// The most points a manifold holds (a larger contact polygon is reduced to this many by the rules
/// above). Inline storage: a manifold needs no heap.
inline constexpr int kMaxContactPoints = 64;
using ContactManifold = FixedCapacityVector<ContactPoint, kMaxContactPoints>;
using ContactIndices = FixedCapacityVector<int, kMaxContactPoints>;

/// One step of reduceContactPolygon: which rule chose which polygon point and its score
/// (rule 1: depth; 2: distance; 3: twice the triangle area; 4: twice the added area).
struct ManifoldReductionStep {
    const char* rule = "";  ///< "deepest", "farthest", "max-area triangle", "max-area quad"
    int chosen = -1;        ///< index into the input points
    double score = 0.0;
};

/// Indices (into `polygon`: the contact points, any order; interior points allowed) of at most
/// maxPoints points chosen by the rules of the file comment, in the order chosen. maxPoints <= 0 keeps
/// every point (the deepest first) up to kMaxContactPoints; beyond that, and for maxPoints above
/// kMaxContactPoints, the rules reduce to kMaxContactPoints. maxPoints >= the count left by rule 0 keeps those
/// (the deepest first, then input order; no steps). A rule whose best score is 0 (all remaining
/// points coincide with or are collinear with the chosen ones) stops the reduction early. normal:
/// unit, any sign. No heap allocation when steps == nullptr (the steps are a std::vector) and the
/// polygon has at most kMaxContactPoints points (inline scratch; a larger one uses a stack arena).
ContactIndices reduceContactPolygon(std::span<const ContactPoint> polygon, const Vec3& normal, int maxPoints,
                                    std::vector<ManifoldReductionStep>* steps = nullptr);

/// Every point's index (at most kMaxContactPoints points), the deepest first — first of ties, by the
/// rules' kManifoldTieRelative tie rule — then input order: reduceContactPolygon's answer when nothing is
/// dropped (maxPoints <= 0, or a caller that applied rule 0 itself and kept no more than maxPoints).
ContactIndices deepestFirst(std::span<const ContactPoint> points);

}  // namespace cdlab
