// Box–box and box–plane contact manifolds without heap allocation: contactPolyhedra and
// contactPolyhedronPlane specialised to boxes, with their answers (status, axis, normal, depth,
// features, manifold) at a fraction of their cost. For engines' hot loop; the general functions
// remain the reference and the traced path for figures.
//
// Box–box: the 15-axis separating axis test (Gottschalk, Lin & Manocha, "OBBTree", SIGGRAPH 1996;
// Ericson, "Real-Time Collision Detection" §4.4.1). With A's axes a_i, B's axes b_j (world), half
// extents hA, hB and t = c_B - c_A, the separation along a unit axis u oriented from A toward B is
//     u · t - rA(u) - rB(u),   rA(u) = Σ_i hA_i |u · a_i|,  rB(u) = Σ_j hB_j |u · b_j|
// (the gap between the boxes' projections). The axes are the face normals ±a_i, ±b_j (the face
// queries of contactPolyhedra) and the nine a_i x b_j: each is the normal of the Minkowski face of
// the two edges extreme along it, so these are exactly the edge pairs contactPolyhedra keeps after
// its Gauss-map pruning, with the same parallel test (|a_i x b_j| <= kParallelEdgeSine: skipped). The axis
// choice, the face clipping and the reduction are contactPolyhedra's own
// (core/contact/contact_stages.h). Exact depths: the depth is the chosen axis's overlap, with no
// fudge term (Bullet's btBoxBoxDetector inflates edge–edge depths).
//
// Box–plane: the eight corners from the rotation's columns (c ± hx x̂ ± hy ŷ ± hz ẑ), their signed
// distances, submerged corners, edge crossings and the reduction as contactPolyhedronPlane, in
// fixed buffers.
//
// Corners, edges and faces are numbered as presets::box (core/geometry/polyhedron_presets.h): corner
// k has bit 0 = +x, bit 1 = +y, bit 2 = +z; faces +x, -x, +y, -y, +z, -z. Features therefore name
// the same elements as contactPolyhedra on presets::box(h).
#pragma once

#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"

namespace cdlab {

/// Contact of box A (half extents ha, pose ta) and box B, world frame: as
/// contactPolyhedra(presets::box(ha), ta, presets::box(hb), tb, options), no heap allocation.
/// Half extents must be finite, > 0 and at most 1e150 (else InvalidInput with the reason).
SatContactResult contactBoxBox(const Vec3& ha, const Transform& ta, const Vec3& hb, const Transform& tb,
                               const SatContactOptions& options = {});

/// Box on a plane: what contactPolyhedronPlane(presets::box(h), ...) reports about the contact, without its
/// feature and polygon lists (which need the heap). message: "" or a static string.
struct BoxPlaneContact {
    PlaneContactStatus status = PlaneContactStatus::InvalidInput;
    const char* message = "";
    double signedDistance = 0.0;  ///< lowest corner's signed distance, world units
    double depth = 0.0;           ///< max(0, -signedDistance)
    Vec3 normal = Vec3::UnitX();  ///< unit, from the box toward the half-space: -n̂
    double tolerance = 0.0;       ///< tol used (world units)
    int deepestVertex = -1;       ///< a corner attaining signedDistance (first index)
    ContactManifold manifold;     ///< colliding: <= maxPoints points, deepest first
    bool colliding() const {
        return status == PlaneContactStatus::Touching || status == PlaneContactStatus::Penetrating;
    }
};

/// Box (half extents h, pose) against the solid half-space n · x <= d, as contactPolyhedronPlane;
/// options.maxPoints <= 0 keeps every candidate (submerged corners and edge crossings, deepest
/// first) where the general function keeps the polygon's corners.
BoxPlaneContact contactBoxPlane(const Vec3& h, const Transform& pose, const Plane& plane,
                                const PlaneContactOptions& options = {});

}  // namespace cdlab
