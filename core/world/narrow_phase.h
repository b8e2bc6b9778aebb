// The narrow phase of the many-body world (core/world/world.h): the contact manifold of one pair of
// world shapes, through core's contact generators, each pair kind by the one made for it:
//   box – box        contactBoxBox (core/contact/contact_box.h: SAT over the 15 axes, face clipping)
//   box – plane      contactBoxPlane
//   hull – hull/box  contactPolyhedra (core/contact/contact_sat.h: Gauss-map pruned SAT, clipping)
//   hull – plane     contactPolyhedronPlane (core/contact/contact_plane.h)
//   sphere or capsule – sphere or capsule
//                    closest points of the cores (a point or a segment); two nearly parallel
//                    capsules a point at each end of their overlap
//   sphere or capsule – plane
//                    each end of the core whose ball reaches the plane
//   sphere or capsule – box or hull
//                    GJK distance between the core and the polytope (core/gjk_epa/gjk.h); a core
//                    inside the polytope EPA (core/gjk_epa/epa.h); a capsule lying along a face
//                    its segment clipped to the face, two points
// Speculative contacts (Catto, "Speculative contacts", Box2D blog 2013 / GDC 2014 "Continuous
// collision"): a pair closer than `margin` is in contact already, each point with its separation
// s > 0, so the solver lets it approach by s in the step and no more. The polytope generators take
// `margin` as their touching band; a rounded pair is in contact when its cores are closer than
// the radii plus `margin`.
//
// Point identities (for warm starting, core/world/world.h): each point carries the vertex of A
// nearest to its point on A and the vertex of B nearest to its point on B, both in the bodies' own
// frames, so a point resting on a corner keeps its id while the bodies jiggle and a clipped point
// keeps the corner it is cut next to (tests/core/world/world_test.cpp).
#pragma once

#include <cstdint>

#include "core/base/fixed_capacity_vector.h"
#include "core/base/types.h"
#include "core/world/world_shape.h"

namespace cdlab {

/// The most points a world manifold keeps (the area-keeping reduction of
/// core/contact/contact_manifold.h picks them).
inline constexpr int kWorldManifoldPoints = 4;

/// One contact point, world frame, at the poses the narrow phase was given.
struct WorldContactPoint {
    Vec3 pointA = Vec3::Zero();  ///< on A's surface
    Vec3 pointB = Vec3::Zero();  ///< on B's surface
    /// (pointB − pointA) · normal: < 0 penetrating, > 0 a speculative gap.
    double separation = 0.0;
    std::uint32_t id = 0;  ///< (vertex of A) << 16 | (vertex of B); see the file comment
};

/// Which generator made a manifold.
enum class NarrowMethod { None, BoxBox, BoxPlane, HullHull, HullPlane, Rounded };
/// "none", "box-box", "box-plane", "hull-hull", "hull-plane", "rounded".
const char* nameOf(NarrowMethod method);

struct PairManifold {
    NarrowMethod method = NarrowMethod::None;
    Vec3 normal = Vec3::UnitZ();  ///< unit, from A toward B
    FixedCapacityVector<WorldContactPoint, kWorldManifoldPoints> points;
    /// The features the manifold lies on (SAT axis kind and both features; the plane's body
    /// vertex): a manifold whose key changed is a new configuration, its points are not matched.
    std::uint64_t featureKey = 0;
    /// The body whose frame the normal turns with while the bodies move (the face's body; 2: the
    /// line between two rounded shapes' cores, recomputed from them).
    int normalBody = 0;
    /// When collideShapes answers false because the shapes are apart: an axis (unit, A → B) along
    /// which they are separated (the SAT's or GJK's); zero when there is none to report.
    Vec3 separatingAxis = Vec3::Zero();
};

/// The gap between a and b along the unit axis d (A → B): min over B of d·x − max over A of d·x,
/// from the shapes' supports (> 0: d separates them by at least that much). A plane's is −∞.
double separationAlong(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb,
                       const Vec3& d);

/// The manifold of a at pose ta and b at pose tb, points with separation <= margin (world units,
/// >= 0). Returns false (points empty) when the shapes are farther apart than margin, when both are
/// planes, or when a generator refused the pair (non-finite poses). A plane's pose is ignored.
bool collideShapes(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                   PairManifold& out);

}  // namespace cdlab
