// Back-to-front drawing order for translucent meshes, including meshes that cut through each other
// (a slab through a box, a sphere sunk into a box): a binary space partition built for one viewer
// and walked as it is built (Fuchs, Kedem & Naylor, "On visible surface generation by a priori tree
// structures", SIGGRAPH 1980; Ericson, Real-Time Collision Detection §8.1–8.3). A face that crosses
// another's plane is cut there, so each piece can be drawn wholly behind or in front of it: the
// painter's sort by face depth, which this replaces, has no right order for two faces that cross.
//
// Kept cheap for tessellated spheres and cones (thousands of triangles): a convex mesh stays one
// item that is never partitioned against itself (its faces turned away from the viewer, then those
// turned towards it, is the right order for a convex surface); items whose bounding boxes are apart
// along an axis are separated by that axis's plane without cutting anything; otherwise a face of the
// smallest item is the splitting plane, or a plane across the middle where faces would only peel
// one at a time (a curved sheet). Walked with an explicit stack; budgets on cuts and work fall back
// to the depth sort for what is left (pathological input only).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

namespace cdlab::render {

/// One translucent triangle mesh (indices into `vertices`; NaN triangles already removed).
struct TranslucentMesh {
    std::span<const Eigen::Vector3d> vertices;
    std::span<const Eigen::Vector3i> triangles;
};

/// Where the picture is seen from: a point (perspective), or a direction towards the viewer
/// (orthographic: the viewer is at infinity).
struct Viewer {
    Eigen::Vector3d eye;
    Eigen::Vector3d towardsEye;  // unit
    bool orthographic = false;
};

/// A convex planar piece of input triangle `triangle` of mesh `mesh` (the whole triangle, or the
/// part of it on one side of a cut), corners in the triangle's winding.
struct OrderedPiece {
    std::vector<Eigen::Vector3d> corners;
    int mesh = 0;
    int triangle = 0;
};

struct TranslucentOrderStats {
    int items = 0;          // convex meshes, plus one per triangle of a non-convex mesh
    int convexMeshes = 0;
    int cuts = 0;           // pieces cut in two
    bool budgetHit = false; // too many cuts or too much work: the rest ordered by depth alone
};

/// Every triangle of `meshes`, cut where needed, in an order in which each piece is drawn after every
/// piece behind it as seen by `viewer`. Pieces in one plane keep their input order (mesh, then
/// triangle), so coplanar faces of touching bodies blend the same way in every frame.
std::vector<OrderedPiece> backToFront(std::span<const TranslucentMesh> meshes, const Viewer& viewer,
                                      TranslucentOrderStats* stats = nullptr);

/// Whether a triangle mesh bounds (part of) a convex body: every triangle faces away from the mean
/// of the vertices and every edge shared by two triangles folds outwards. A flat mesh counts.
bool isConvexSurface(const TranslucentMesh& mesh);

}  // namespace cdlab::render
