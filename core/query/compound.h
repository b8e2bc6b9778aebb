// Pair queries of non-convex bodies: a union of convex query shapes (a compound) or the solid
// bounded by a closed, consistently oriented triangle mesh — `cdlab query`'s {"compound": ...} and
// {"mesh": ...} (docs/query.md, "Compounds and meshes"), answered with core's one pair query on pieces
// (pairQuery, core/query/pair.h).
//
//   intersect: some pair of boundary pieces intersects (touching counts), or one body is a mesh
//     that holds a piece of the other (its generalised winding number at the piece's first core
//     point, core/geometry/solid_mesh.h).
//   distance: the smallest distance over the pairs of boundary pieces (a mesh's triangles, a
//     compound's shapes) with its witness points — the true distance of the two unions.
//   penetration: the deepest pair of convex pieces (a mesh's pieces are the cells of its
//     solid-leaf BSP tree, core/spatial/convex_decomposition.h) — not the union's true depth, which
//     may need a longer translation; separated, the distance answer with its normal.
//
// Pairs of pieces are culled by their bounding boxes; every quantity that multiplies the work has a
// limit (CompoundOptions, defaults below), checked where the work is counted: past it the query
// stops with CompoundStatus::WorkLimit and no answer. Tests: tests/app/query/query_compound_test.cpp
// (answers, traces, errors) and tests/app/query/hostile_query_test.cpp (the limits).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/triangle_mesh.h"
#include "core/query/pair.h"
#include "core/query/shape.h"

namespace cdlab {

/// Pairs of pieces one compound or mesh query may visit (boundary pieces of a x of b: a mesh's
/// triangles, a compound's shapes). Boxes cull most pairs, but every pair's boxes are compared
/// (~5 ns a pair): 10^8 pairs take ~0.5 s before any GJK.
constexpr double kMaxCompoundPairs = 1e8;

/// The work of a pair of pieces in pairs of boxes: GJK and EPA grow with the pieces' vertices (a
/// pair of 200-vertex polytopes costs ~25x a pair of boxes), so a pair counts (n_a + n_b) / 16 box
/// pairs, at least one (curved solids count 8 vertices).
constexpr double kBoxPairVertices = 16;

/// Work, in pairs of boxes (kBoxPairVertices), that `penetration` of a compound or mesh may hand to
/// EPA: the pairs of pieces whose boxes meet, counted before any EPA runs. EPA costs ~2.5-4.5 us a
/// pair of boxes (two 1000-box compounds, every pair overlapping: 10^6 pairs in 2.5-4.5 s), so the
/// limit runs in about a second. The search visits the pairs by an upper bound on their depth from
/// the boxes and stops when the bound is below the deepest depth found, so most queries run far
/// fewer (hostile_query_test "penetration of compounds: EPA only where the box bound can beat the
/// deepest pair, capped").
constexpr double kMaxCompoundDepthPairs = 2.5e5;

/// Work, in pairs of boxes, that `intersect`, `distance` and a separated `penetration` of a
/// compound or mesh may hand to GJK (counted as the pairs run; past it the query stops):
/// ~0.3-0.5 us a pair of boxes, so about a second too. The box culls leave most queries far below it.
constexpr double kMaxCompoundGjkPairs = 2e6;

/// Triangles of a mesh that `penetration` decomposes into convex pieces (the cells of its BSP
/// tree, 32 candidate planes per node): a 10 000-triangle torus takes 0.3 s and 41 MB.
constexpr std::size_t kMaxMeshTrianglesForPieces = 50000;

/// One side of a compound query. The closest points of two disjoint bodies lie on their boundary
/// pieces; the deepest pair is sought among their convex pieces; a mesh also answers "is this point
/// inside". Build one with shape(), compound() or solidMesh().
struct CompoundBody {
    enum class Kind { Shape, Compound, Mesh };
    Kind kind = Kind::Shape;
    std::vector<QueryShape> boundary;  ///< a compound's shapes, a mesh's triangles, or the one shape
    /// Convex pieces: a shape's or compound's = boundary; a mesh's: empty until computed
    /// (compoundPairQuery computes them when a penetration needs them: meshConvexPieces).
    std::vector<QueryShape> pieces;
    std::optional<TriangleMesh> mesh;  ///< world frame, outward-facing
    TriangleMesh unitMesh;             ///< the mesh times 2^unitExponent (exact): size ~1 (containment tests)
    int unitExponent = 0;

    /// One shape of any kind (a plane or a ray too).
    static CompoundBody shape(QueryShape s);
    /// A union of bounded convex shapes (non-empty: the caller checks, as for every constructor).
    static CompoundBody compound(std::vector<QueryShape> shapes);
    /// The solid bounded by `mesh`: world frame, finite vertices, checkSolidMesh(mesh) == Closed.
    /// An inward-facing mesh is turned outward (it bounds the same solid). std::nullopt when it
    /// encloses no volume (all its triangles flat against each other), measured on the mesh scaled
    /// by a power of two to size ~1 so that 1e-300 or 1e300 meshes neither underflow nor overflow.
    static std::optional<CompoundBody> solidMesh(TriangleMesh mesh);
};

/// A mesh body's convex pieces: the solid cells of the BSP tree of its unit mesh (32 candidate
/// planes a node), scaled back to the world frame. Takes any number of triangles; compoundPairQuery
/// calls it only below CompoundOptions::maxMeshTrianglesForPieces.
std::vector<QueryShape> meshConvexPieces(const CompoundBody& mesh);

enum class CompoundOp { Intersect, Distance, Penetration };

/// The work limits (the defaults are `cdlab query`'s; docs/limits.md).
struct CompoundOptions {
    double maxPiecePairs = kMaxCompoundPairs;      ///< pieces of a x pieces of b, checked before each search
    double maxGjkWork = kMaxCompoundGjkPairs;      ///< intersect / distance searches, box-pair work
    double maxDepthWork = kMaxCompoundDepthPairs;  ///< penetration's EPA candidates, box-pair work
    std::size_t maxMeshTrianglesForPieces = kMaxMeshTrianglesForPieces;
};

enum class CompoundStatus {
    Ok,
    WorkLimit,    ///< a work limit was passed (CompoundPairResult::limitHit): no answer
    PairFailed,   ///< a pair query of two pieces failed (CompoundPairResult::pairStatus): no answer
    NoPiecePair,  ///< penetration: the bodies intersect, but no pair of their convex or boundary
                  ///< pieces does (a piece lost to rounding): no answer
};

enum class CompoundLimit {
    PiecePairs,     ///< piecesA x piecesB > maxPiecePairs (boundary pieces first, then convex pieces)
    GjkWork,        ///< the GJK searches' work passed maxGjkWork (before the pair past it ran)
    DepthWork,      ///< the EPA candidates' work passed maxDepthWork (before any EPA ran)
    MeshTriangles,  ///< penetration: a mesh has more triangles than maxMeshTrianglesForPieces
};

/// Which limit stopped a query, and the counts its message names.
struct CompoundLimitHit {
    CompoundLimit which = CompoundLimit::PiecePairs;
    int body = 0;                          ///< MeshTriangles: the mesh's side (0: a, 1: b)
    std::size_t piecesA = 0, piecesB = 0;  ///< PiecePairs: the pieces multiplied
    std::size_t triangles = 0;             ///< MeshTriangles: the mesh's triangles
    long long pairs = 0;                   ///< DepthWork: the pairs of pieces whose boxes meet
    double work = 0;                       ///< GjkWork / DepthWork: the work counted
    double limit = 0;                      ///< the limit passed (from CompoundOptions)
};

enum class CompoundPieces { Boundary, Convex };

/// The answer (the fields of pairQuery's PairResult) and what found it.
struct CompoundPairResult {
    CompoundStatus status = CompoundStatus::Ok;
    PairStatus pairStatus = PairStatus::Ok;  ///< PairFailed: the failed pair's status
    CompoundLimitHit limitHit;               ///< WorkLimit

    bool intersect = false;
    double distance = 0.0;        ///< separated: the closest pair's (> 0); intersecting: 0
    double depth = 0.0;           ///< penetration of intersecting bodies: the deepest pair's
    Vec3 normal = Vec3::UnitX();  ///< from A toward B (separated, or penetration)
    Vec3 pointA = Vec3::Zero();   ///< separated: closest points; penetration: deepest points
    Vec3 pointB = Vec3::Zero();
    bool hasWitness = false;  ///< pointA, pointB and normal are set (distance or penetration op)

    /// The pair of pieces that answered: found (intersect: the first pair met, none when only a
    /// mesh's inside test found the overlap), the list it is from and its indices in each.
    bool paired = false;
    CompoundPieces among = CompoundPieces::Boundary;
    int pieceA = -1, pieceB = -1;
    long long pairsTested = 0;  ///< pair queries run, over every search
    std::array<std::size_t, 2> boundaryPieces{0, 0};
    std::array<std::size_t, 2> convexPieces{0, 0};  ///< a mesh's: 0 unless its pieces were computed
};

/// Intersect, distance or penetration of two bodies (see the file comment). Stops at the first
/// failure, in the order the work runs: the piece-pairs limit on the boundaries, the intersect
/// search (GJK work limit, failed pairs), the closest-pair search, then penetration's mesh pieces
/// (a's triangle limit and pieces, then b's), the piece-pairs limit on the convex pieces and the
/// deepest-pair searches (EPA work limit, failed pairs).
CompoundPairResult compoundPairQuery(const CompoundBody& a, const CompoundBody& b, CompoundOp op,
                                     const CompoundOptions& options = {});

}  // namespace cdlab
