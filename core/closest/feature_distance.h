// Closest points between two polyhedron features and the contact normal rule: the six contact
// types V–V, V–E, V–F, E–E, E–F, F–F (a vertex is a point, an edge a segment, a face a convex
// planar polygon, all closed).
//
// Closest points (Ericson, "Real-Time Collision Detection" §5.1: point-segment §5.1.2 and
// segment-segment §5.1.9 come from core/closest/closest_point.h):
//   point–polygon    projection onto the plane if it falls inside every edge line, else the
//                    nearest boundary point (point–segment over the edges).
//   segment–polygon  0 where the segment pierces the polygon (plane crossing inside it, or an
//                    endpoint inside it when coplanar); else the best of: each endpoint vs the
//                    polygon, the segment vs each polygon edge. For a convex planar polygon the
//                    minimum of the distance (a convex function) over segment × polygon lies at a
//                    segment endpoint or on the polygon boundary unless the segment meets the
//                    polygon, so these candidates are complete.
//   polygon–polygon  0 where an edge of one pierces the other; else the best of every edge of one
//                    against the other polygon (same argument, both ways).
// Parallel edges (and parallel faces / an edge parallel to a face) have a continuum of closest
// pairs: one is returned and `parallel` is set.
//
// Contact normal (unit, from A toward B):
//   V–F, E–F, F–F: the face normal (outward normal of A's face, or minus B's outward normal; F–F
//                  uses A's face: A is the reference), stable under small motions.
//   V–V, V–E, E–E: the line between the closest points, (pointB - pointA) / distance. This is
//                  UNSTABLE: as the features approach each other its direction is rounding noise
//                  and at contact it is undefined (0/0). normalUnstable flags distances below
//                  kUnstableNormalRelative of the features' size; at distance 0 the E–E normal falls
//                  back to the edge cross product (sign: toward B's edge midpoint, a heuristic; the
//                  bodies would decide), V–V and V–E have no normal at all (normal = 0, normalDefined = false). Engines
//                  avoid this by taking the normal from SAT (core/contact/contact_sat.h) or the face of a neighbouring
//                  feature.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron_feature.h"

namespace cdlab {

/// Parallel tests of featureDistance, relative: a segment is parallel to a polygon's plane when its
/// end heights differ by at most this times its length, two polygons when |n_a x n_b| is at most this
/// times |n_a| |n_b|; ~4500 ulps, above the rounding of a Newell normal, below any modelled tilt.
inline constexpr double kFeatureParallelRelative = 1e-12;
/// How far (times the features' size) a closest point may sit off a vertex or edge and still be
/// realized on it: far above the points' rounding (~1e-16), far below any modelled feature.
inline constexpr double kFeatureSnapRelative = 1e-12;
/// The closest-point direction's own rounding, as a sine: the floor of the slope below which a
/// feature's direction and the closest-point direction count as parallel (or perpendicular) when
/// the realized feature is decided; the points' offset tol / distance is added to it.
inline constexpr double kFeatureDirectionSlope = 1e-9;
/// normalUnstable: a closest-point line shorter than this times the features' size carries fewer
/// than ~7 correct digits of direction (the points have ~1e-16 relative rounding each).
inline constexpr double kUnstableNormalRelative = 1e-9;

enum class ContactType { VV, VE, VF, EE, EF, FF };

/// "V-V", "V-E", "V-F", "E-E", "E-F", "F-F" (the lower-dimensional feature first).
const char* nameOf(ContactType type);

/// A feature as geometry, world frame: Vertex = 1 point, Edge = 2 points, Face = >= 3 points of a
/// convex planar polygon counter-clockwise seen from outside (right-hand rule gives the outward
/// normal).
struct FeatureGeometry {
    FeatureType type = FeatureType::Vertex;
    std::vector<Vec3> points;
};

struct FeatureDistanceResult {
    bool valid = false;  ///< false: wrong point count or non-finite input (see message)
    std::string message;
    /// The pair's type by the features that hold the closest points: a face whose closest point is
    /// on its boundary counts as that edge (or corner), an edge whose closest point is an endpoint
    /// as that vertex; so type, normal rule and closest points always agree. A parallel pair (a
    /// continuum of closest pairs) keeps the given features' type.
    ContactType type = ContactType::VV;
    FeatureType realizedA = FeatureType::Vertex;  ///< the sub-feature of A holding pointA
    FeatureType realizedB = FeatureType::Vertex;
    double distance = 0.0;       ///< |pointA - pointB|, world units (0: the features meet)
    Vec3 pointA = Vec3::Zero();  ///< closest point on feature A
    Vec3 pointB = Vec3::Zero();  ///< closest point on feature B
    Vec3 normal = Vec3::Zero();  ///< unit contact normal from A toward B (0 if !normalDefined)
    bool normalDefined = false;
    const char* normalRule = "";  ///< "face A", "face B", "closest points", "edge cross product", "none"
    bool normalUnstable = false;  ///< normal from the closest-point line below kUnstableNormalRelative x size
    bool parallel = false;        ///< parallel edges / faces: one of many closest pairs
};

/// Closest point of the convex planar polygon (>= 3 points, any orientation; collinear points
/// allowed: then the polyline) to p. distanceSquared in units^2.
struct PointPolygonResult {
    Vec3 point = Vec3::Zero();
    double distanceSquared = 0.0;
    bool interior = false;  ///< the projection fell inside (point on the face, not its boundary)
};
PointPolygonResult closestPointOnPolygon(const Vec3& p, const std::vector<Vec3>& polygon);

/// Closest pair of a segment and a convex planar polygon (see the file comment).
struct FeaturePairPoints {
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
    double distanceSquared = 0.0;
    bool parallel = false;
};
FeaturePairPoints closestPointsSegmentPolygon(const Segment& s, const std::vector<Vec3>& polygon);

/// Closest pair of two convex planar polygons (A first).
FeaturePairPoints closestPointsPolygonPolygon(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

/// Closest points, distance and contact normal of two features (either order of dimensions;
/// `type` names the pair with the lower dimension first, the points stay A's and B's).
FeatureDistanceResult featureDistance(const FeatureGeometry& a, const FeatureGeometry& b);

}  // namespace cdlab
