// Convex polyhedron vs plane: boolean test, signed distance, closest feature and the contact
// manifold.
//
// The plane n · x = d bounds the SOLID half-space n · x <= d (a ground): the body collides when
// some point of it has n · x <= d. Every quantity comes from the signed vertex distances
// s_i = n̂ · x_i - d̂ (n̂ = n / |n|, d̂ = d / |n|, x_i the world vertices), because a linear function
// on a convex polytope takes its extremes at vertices (Ericson, "Real-Time Collision Detection"
// §5.2.3 "Testing box against plane" generalised; van den Bergen 2003 §4.3 support mappings):
//   signed distance  s_min = min_i s_i                 (support point of the body in -n̂)
//   closest feature  the vertices with s_i <= s_min + tol: 1 → vertex, 2 adjacent → edge, more →
//                    the face holding them (the support set of -n̂ is a vertex, edge or face)
//   contact polygon  (s_min <= tol) vertices with s_i <= tol, plus the points where edges with
//                    s_i < -tol < tol < s_j cross the plane (depth 0), projected onto the plane,
//                    convex hull in the plane (counter-clockwise about n̂)
//   manifold         the candidates (submerged vertices and crossings) reduced to <= maxPoints by
//                    reduceContactPolygon (core/contact/contact_manifold.h): deepest, farthest, max-area
//                    triangle, max-area quad. The deepest point is always kept even when it projects
//                    inside the polygon (a corner pushed into the ground).
// A face resting on the plane within tol (face-on) gives that face's vertices; edge-on gives the
// edge's two endpoints: never one arbitrary vertex of a tie.
//
// Normal convention (as EPA, core/gjk_epa/epa.h): A = the body, B = the half-space; normal = -n̂ points
// from A toward B; translating the body by -depth * normal = depth * n̂ separates it (touching);
// each ContactPoint has pointA = the body point (below the plane), pointB = its projection on the
// plane, pointA - pointB = depth * normal.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/contact/contact_manifold.h"
#include "core/contact/contact_tolerances.h"
#include "core/geometry/polyhedron.h"
#include "core/geometry/shapes.h"

namespace cdlab {

enum class PlaneContactStatus {
    Separated,     ///< s_min > tol: distance = s_min, closest feature / points meaningful, no manifold
    Touching,      ///< |s_min| <= tol: depth = max(0, -s_min), manifold = the touching feature
    Penetrating,   ///< s_min < -tol: depth = -s_min, manifold meaningful
    InvalidInput,  ///< empty polyhedron, zero / non-finite plane normal or offset, NaN pose: see message
};

const char* nameOf(PlaneContactStatus status);

struct PlaneContactOptions {
    /// Feature tolerance tol (world units): vertices within tol of the extreme form the closest
    /// feature, and |s_min| <= tol counts as touching. std::nullopt (or a negative value): automatic,
    /// relativeTolerance * body diameter + 64 ulps of the coordinates.
    std::optional<double> tolerance = std::nullopt;
    /// Default tolerance relative to the body's bounding-box diagonal: kTouchingBandRelative (1e-9)
    /// is ~1e7 ulps of the coordinates (far above the rounding of s_i, ~4 ulps of |x| + |d|, for
    /// offsets up to 1e6 x the size) and far below any modelled tilt. A simulation resting on the
    /// ground wants a larger, absolute value (a "contact slop", e.g. 1e-3 of the size).
    double relativeTolerance = kTouchingBandRelative;
    /// Manifold size: 1 = deepest point only, 4 = engine-style quad; <= 0 keeps the full polygon.
    int maxPoints = 4;
};

struct PlaneContactResult {
    PlaneContactStatus status = PlaneContactStatus::InvalidInput;
    std::string message;                     ///< InvalidInput: why
    double signedDistance = 0.0;             ///< s_min, world units (< 0: below the plane)
    double depth = 0.0;                      ///< max(0, -s_min)
    Vec3 normal = Vec3::UnitX();             ///< unit, from the body toward the half-space: -n̂
    double tolerance = 0.0;                  ///< tol actually used (world units)
    int deepestVertex = -1;                  ///< a vertex attaining s_min (first index)
    FeatureRef feature;                      ///< closest (separated) / deepest (colliding) feature of the body
    std::vector<Vec3> featurePoints;         ///< its vertices, world frame (face: counter-clockwise from outside)
    std::vector<Vec3> featurePointsOnPlane;  ///< their projections on the plane (closest points of the plane)
    std::vector<ContactPoint> polygon;       ///< colliding: full contact polygon (see file comment), CCW about n̂
    ContactManifold manifold;                ///< colliding: <= maxPoints points, deepest first (maxPoints <= 0:
                                             ///< the polygon, plus the deepest point if it projects inside it,
                                             ///< reduced to kMaxContactPoints when larger)

    bool colliding() const {
        return status == PlaneContactStatus::Touching || status == PlaneContactStatus::Penetrating;
    }
};

/// Every intermediate of contactPolyhedronPlane, for figures.
struct PlaneContactTrace {
    Vec3 unitNormal = Vec3::UnitZ();      ///< n̂
    double unitOffset = 0.0;              ///< d̂
    std::vector<Vec3> worldVertices;      ///< x_i
    std::vector<double> vertexDistances;  ///< s_i
    std::vector<int> featureVertices;     ///< vertices within tol of s_min
    struct Crossing {
        int edge = -1;
        int below = -1, above = -1;  ///< vertex ids (s_below < -tol, s_above > tol)
        double t = 0.0;              ///< point = x_below + t (x_above - x_below)
        Vec3 point = Vec3::Zero();
    };
    std::vector<Crossing> crossings;
    std::vector<ContactPoint> candidates;          ///< submerged vertices then crossings, before the hull
    std::vector<int> candidateVertex;              ///< vertex id of each candidate, -1 for a crossing
    std::vector<int> hull;                         ///< candidates on the polygon, CCW about n̂
    std::vector<ManifoldReductionStep> reduction;  ///< reduction choices (indices into candidates)
};

/// Boolean, brute force: some world vertex has n · x <= d. O(V). Invalid input (NaN, n = 0): false.
bool intersectPolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane);

/// Boolean by one support query: s_{body}(-n) (PolytopeShape hill climbing over the vertex
/// adjacency when the polytope is large, O(sqrt V) typical) lies on or below the plane. The
/// polytope is in body frame; `hint` (optional) warm-starts the climb and receives the vertex.
bool intersectPolytopePlane(const PolytopeShape& body, const Transform& pose, const Plane& plane, int* hint = nullptr);

/// Signed distance s_min = min over the body of (n · x - d) / |n| (world units; < 0: the deepest
/// vertex is that far below). NaN for invalid input.
double signedDistancePolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane);

/// Full contact query (see the file comment): status, signed distance / depth, normal, closest or
/// deepest feature, contact polygon and reduced manifold. World frame.
PlaneContactResult contactPolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane,
                                          const PlaneContactOptions& options = {}, PlaneContactTrace* trace = nullptr);

}  // namespace cdlab
