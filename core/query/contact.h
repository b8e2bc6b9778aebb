// The contact query of two shapes of core/query/shape.h — the answers `cdlab query`'s "contact" op
// prints (docs/query.md): the contact manifold of a polytope (polytope / aabb / obb) against
// a plane (core/contact/contact_plane.h) or another polytope (SAT with face clipping,
// core/contact/contact_sat.h), of a sphere or capsule against any of them ("Spheres and capsules"
// below), and of a cylinder or cone against a plane or a polytope (core/query/curved_contact.h);
// separated pairs answer the distance and the closest features.
//
// Conventions (the same as the penetration of core/query/pair.h): normal n is a unit vector from A
// toward B; translating B by depth·n leaves the shapes touching; each contact point has
// pointA − pointB = depth·n (pointA: the point of A inside B, pointB: its projection on B's
// surface). Two polytopes' depth is the least overlap or a face axis's overlap at most
// faceBiasRelative (2 %) above it: least overlap <= depth <= least overlap · 1.02 + tolerance
// (core/contact/contact_sat.h, step 3). A plane here is the solid half-space n·x <= d (a ground): a body below the plane is
// deep inside it. Features name the input vertices of the shape (face vertices counter-clockwise
// seen from outside; aabb/obb corners numbered with bit k of the index choosing the + side of axis
// k); the plane's feature is Plane.
//
// Touching or separated is decided by the touching rule of every query (core/base/touch_rule.h):
// for two polytopes by the GJK distance, for a polytope and a plane by the lowest signed vertex
// distance. The manifold itself (which vertices form the touching feature, which clipped points are
// kept) uses core/contact's feature tolerance, widened to the rule's when the rule says touching and
// the feature tolerance does not. Polytope pairs are computed in a frame local to the bodies
// (ContactFrame: translated to the first body's first vertex, then scaled by a power of two), so the
// rounding is relative to the bodies' extent, not to how far they are from the origin; the result
// is in the input's units. Two bodies whose answer depends on how that translation rounded their
// vertices (a hull failed: a 2e-9 cube 1e3 from the origin vertex; or the SAT met nearly parallel
// edges, whose axis amplifies vertex rounding by 1 / sine) are computed again in the exact frame:
// origin 0 on each axis where the translation rounded some vertex (issue 41 (b), (e)). A hull the
// default tolerance (4096 ulps) finds flat is tried again at 64 ulps, so a needle ~1e-12 of its
// length wide is a solid here as for the other ops; exactly flat bodies stay refused.
//
// Spheres and capsules (a point or segment core ⊕ ball(r)), in the input's units (issue 21 §2):
//   sphere – anything: one point, the penetration query's deepest pair (a plane: the half-space);
//   capsule – plane: each end of the segment whose sphere reaches the half-space (up to two points);
//   capsule – polytope: when the contact normal is a face normal of the polytope, the segment clipped
//     to that face's side planes, each clipped end whose sphere reaches the face a point (a capsule
//     lying on a face: both ends); otherwise one point;
//   capsule – sphere or capsule: one point.
// A sphere's feature is its centre, Vertex [0]; a capsule's the end ([0] = a, [1] = b) or the
// segment (Edge [0, 1]) holding its contact points.
// Cylinders and cones, in the input's units: on the plane and on a polytope face that the contact
// normal is the normal of, their rims clipped to it (curvedOnFace); against anything else one point,
// the penetration query's deepest pair. A sphere or capsule against them: the rules above.
//
// Tests (through `cdlab query`): tests/app/query/query_contact_test.cpp (polytope–plane depths
// against long-double vertex depths, polytope pairs against the Minkowski facet oracle, box stacks,
// tiny and huge scales, errors), query_contact_rounded_test.cpp, query_contact_curved_test.cpp,
// hostile_query_test.cpp (a plane at offset 1e300, the hull-vertex and SAT edge-pair limits).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/contact/contact_manifold.h"
#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/query/curved_contact.h"
#include "core/query/pair.h"
#include "core/query/shape.h"

namespace cdlab {

struct ContactOptions {
    /// Manifold size (1 to 64: the manifold rules of core/contact/contact_manifold.h reduce to it).
    int maxPoints = 4;
    /// Input vertices a shape may have (the query builds the convex hull of polytopes): past it the
    /// query answers HullVerticesOverLimit before any work.
    std::size_t maxHullVertices = SIZE_MAX;
    /// Edge pairs (edges of A x edges of B) the SAT of two polytopes may test, checked before the
    /// SAT runs (it is quadratic in the edge count): past it EdgePairsOverLimit.
    double maxSatEdgePairs = INFINITY;
};

/// Which computation answered (and the trace's "algorithm").
enum class ContactMethod {
    Rounded,        ///< a sphere or capsule against anything
    Curved,         ///< a cylinder or cone against a plane, polytope, cylinder or cone
    PolytopePlane,  ///< a polytope against a plane: core/contact/contact_plane.h
    Sat,            ///< two polytopes: GJK decides, the SAT of core/contact/contact_sat.h builds the manifold
};
/// "rounded", "curved", "polytope-plane", "sat".
const char* nameOf(ContactMethod method);

/// Why a contact query has no answer. The checks run in this order: per shape (a, then b) its kind
/// then its vertex count; two planes; then whichever the computation meets first.
enum class ContactStatus {
    Ok,
    UnsupportedShape,       ///< `shape` is a point, segment, ray or triangle (contact takes polytope,
                            ///<   aabb, obb, sphere, capsule, cylinder, cone and plane)
    HullVerticesOverLimit,  ///< `shape` has more than options.maxHullVertices vertices
    TwoPlanes,              ///< both shapes are planes (`shape` = 1: b)
    PairFailed,             ///< a pair query failed (pairStatus): the penetration of a rounded or curved
                            ///<   pair, or GJK of two polytopes (NonFiniteSupport)
    HullFailed,             ///< the convex hull of `shape` failed (flat or degenerate): `message`
    PlaneTooFar,            ///< the plane (`shape`) is farther from the body than double precision
                            ///<   spans in the bodies' local frame (offset / body size above ~1e308)
    EdgePairsOverLimit,     ///< edgesA x edgesB > options.maxSatEdgePairs (`shape` = 1: b)
    ContactFailed,          ///< core/contact rejected the pair (its InvalidInput): `message`
};

/// The feature of one shape holding the contact (or closest) points.
struct ContactFeature {
    enum class Type { None, Vertex, Edge, Face, Plane, Curved };
    Type type = Type::None;
    /// None, Vertex, Edge, Face: the input vertices of the feature (a polytope's: indices into its
    /// vertices, face counter-clockwise from outside; a sphere's centre [0], a capsule's ends [0], [1]).
    std::vector<int> vertices;
    CurvedFeature curved;  ///< Curved: the cylinder's or cone's cap, side, rim or apex
};
/// "none", "vertex", "edge", "face", "plane", "curved".
const char* nameOf(ContactFeature::Type type);

/// A polytope pair's local frame: world = 2^-exponent · local + origin.
struct ContactFrame {
    Vec3 origin = Vec3::Zero();
    int exponent = 0;
    Vec3 toWorld(const Vec3& p) const { return Vec3(scaled(p, -exponent) + origin); }
    double length(double x) const { return std::ldexp(x, -exponent); }
};

struct ContactResult {
    ContactStatus status = ContactStatus::Ok;
    int shape = -1;                          ///< the shape a status is about: 0 = a, 1 = b
    PairStatus pairStatus = PairStatus::Ok;  ///< PairFailed: why
    std::string message;                     ///< HullFailed, ContactFailed: core's reason
    int edgesA = 0, edgesB = 0;              ///< EdgePairsOverLimit: the hulls' edge counts

    ContactMethod method = ContactMethod::Rounded;
    bool colliding = false;
    double depth = 0.0;     ///< colliding: >= 0
    double distance = 0.0;  ///< separated: > the touching tolerance
    Vec3 normal = Vec3::UnitX();
    /// Colliding: the contact points (at most maxPoints, the deepest first), each with its depth.
    /// Separated: the closest points (their depth 0).
    std::vector<ContactPoint> points;
    ContactFeature featureA, featureB;
    std::optional<SatAxisKind> axis;  ///< two colliding polytopes: the SAT axis of the normal
};

/// The algorithms' traces of one contact query (PolytopePlane: `plane`; Sat: `sat`, also for a
/// separated pair). They ran in `frame`: their lengths times 2^-exponent (frame.length) are in the
/// input's units, their points need frame.toWorld.
struct ContactTrace {
    ContactFrame frame;
    PlaneContactTrace plane;
    SatContactTrace sat;
};

/// The contact of a and b (see the file comment). With a trace, a separated pair of polytopes also
/// runs the SAT (to record it); without one GJK alone answers it, in linear time.
ContactResult contactQuery(QueryShape a, QueryShape b, const ContactOptions& options = {}, ContactTrace* trace = nullptr);

}  // namespace cdlab
