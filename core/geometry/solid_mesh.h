// Closed triangle meshes as solids: the edge check that makes a triangle soup the boundary of a
// solid, the solid's signed volume, and point containment by the generalised winding number.
//
// Closed and consistently oriented (a closed oriented 2-manifold, de Berg et al. ch. 2.2 on
// doubly-connected edge lists): every directed edge (i, j) of a triangle occurs exactly once, and
// its twin (j, i) exactly once, in another triangle. A soup that passes bounds a solid whose
// signed volume (divergence theorem: the sum of the tetrahedra from a reference point to each
// triangle) is positive when the triangles are counter-clockwise seen from outside.
//
// Winding number (Jacobson, Kavan & Sorkine-Hornung, "Robust inside-outside segmentation using
// generalized winding numbers", SIGGRAPH 2013): w(p) = sum over triangles of the signed solid angle
// they subtend at p, over 4π; the solid angle of one triangle is Van Oosterom & Strackee's (1983)
// closed form 2·atan2(a·(b×c), |a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|). For a closed mesh w is
// exactly 1 inside and 0 outside (−1 inside an inward-facing mesh), and the sum is continuous away
// from the surface, so rounding cannot flip a point that is not within rounding of a triangle.
//
// Frame: whatever frame the mesh's vertices are in. Requires validateMesh(mesh) == Valid.
#pragma once

#include <array>

#include "core/geometry/triangle_mesh.h"

namespace cdlab {

enum class SolidMeshStatus {
    Closed,                   ///< every directed edge once, its twin once: the boundary of a solid
    TooFewTriangles,          ///< fewer than 4 triangles cannot close a volume
    RepeatedVertex,           ///< a triangle names one vertex twice
    OpenEdge,                 ///< an edge whose twin is missing: a hole in the surface
    InconsistentOrientation,  ///< a directed edge occurs twice: neighbours disagree on the orientation
                              ///< (or more than two triangles meet at the edge)
};

/// Outcome of checkSolidMesh: the status and, when not Closed, the first offending triangle and edge.
struct SolidMeshCheck {
    SolidMeshStatus status = SolidMeshStatus::Closed;
    int triangle = -1;                ///< the triangle holding the offending edge
    std::array<int, 2> edge{-1, -1};  ///< the offending directed edge (vertex indices)
};

/// Checks that the triangles close up into a consistently oriented surface (the header's rule).
SolidMeshCheck checkSolidMesh(const TriangleMesh& mesh);

/// Human-readable name of a status ("closed", "open edge", ...).
const char* nameOf(SolidMeshStatus status);

/// Signed volume enclosed by the triangles: positive when they are counter-clockwise seen from
/// outside. Tetrahedra are summed from the centre of the vertices' bounds, so a mesh far from the
/// origin keeps its precision.
double signedVolume(const TriangleMesh& mesh);

/// Generalised winding number of p with respect to the mesh: 1 inside, 0 outside a closed
/// outward-facing mesh (rounded; meaningful when p is not within rounding of the surface).
double windingNumber(const TriangleMesh& mesh, const Vec3& p);

}  // namespace cdlab
