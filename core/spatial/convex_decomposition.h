// Convex decomposition of a closed non-convex polyhedron into the cells of its solid-leaf BSP tree
// (Thibault & Naylor, "Set operations on polyhedra using binary space partitioning trees",
// SIGGRAPH 1987; Ericson, Real-Time Collision Detection §8.2.3 and §12.5.x on convex pieces).
//
// Why BSP cells and not cuts at reflex edges: every cell of a BSP tree is the intersection of the
// half-spaces on its root path, so it is convex by construction, and for a closed, outward-facing
// mesh the solid leaves' cells tile the solid exactly (each input face bounds it on its own plane).
// Cutting at reflex edges needs the same plane clipping plus a choice of cut order whose pieces are
// fewer but whose correctness rests on that choice; the autopartition tree already made it, with
// Ericson's split / balance score (core/spatial/bsp_tree.h), and its thick planes absorb rounding.
// The price: more pieces than an optimal decomposition (an L-shaped prism: 2 to 3 pieces).
//
// Cells: the tree is walked from the root with the mesh's bounding box (grown by 1 %), split by
// each node's plane (Sutherland–Hodgman on every face, the cut closed by a cap polygon); a solid
// leaf's cell is a piece. Cell corners within the tree's thickness of an input vertex are snapped
// to it, so pieces meet the surface at the mesh's own points. A cell thinner than the thickness
// (a sliver of the thick planes) encloses no volume and is dropped.
//
// Frame: the mesh's. Requires validateMesh(mesh) == Valid and, for meaningful pieces,
// checkSolidMesh(mesh) == Closed with a positive signed volume (core/geometry/solid_mesh.h).
#pragma once

#include <vector>

#include "core/geometry/triangle_mesh.h"
#include "core/spatial/bsp_tree.h"

namespace cdlab {

struct ConvexDecomposition {
    std::vector<std::vector<Vec3>> pieces;  ///< the corners of each convex piece (mesh frame)
    BspStatus status = BspStatus::Empty;    ///< of the BSP build (DepthLimit: pieces may be missing)
    int droppedSlivers = 0;                 ///< solid cells with no volume above the thickness
    int treeNodes = 0;
};

/// One node of the walk, in walk order (a node before its front, then its back subtree): the cell
/// the node splits (inner) or keeps (solid leaf: a piece, unless a sliver) or discards (empty leaf).
struct DecompositionStep {
    int node = -1;
    int parent = -1;  ///< the node whose plane made this cell (-1: the root, the starting box)
    int depth = 0;
    BspNodeKind kind = BspNodeKind::EmptyLeaf;
    Plane plane{Vec3::UnitZ(), 0.0};  ///< inner nodes: the splitting plane (mesh frame)
    std::vector<Vec3> cell;           ///< the cell's corners (mesh frame, not snapped)
    int piece = -1;                   ///< solid leaves: the index in pieces (-1: dropped as a sliver)
    double volume = 0.0;              ///< of the cell: a node's is its two children's
};
struct DecompositionTrace {
    std::vector<DecompositionStep> steps;
};

/// Splits the solid bounded by the mesh into convex pieces whose union is the solid. `trace`, when
/// given, gets every node the walk visits with its cell.
ConvexDecomposition decomposeIntoConvexPieces(const TriangleMesh& mesh, const BspOptions& options = {},
                                              DecompositionTrace* trace = nullptr);

}  // namespace cdlab
