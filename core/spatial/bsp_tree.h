// Solid-leaf BSP tree by autopartition of a polygon soup (Fuchs, Kedem & Naylor, "On visible
// surface generation by a priori tree structures", SIGGRAPH 1980; Thibault & Naylor, "Set
// operations on polyhedra using binary space partitioning trees", SIGGRAPH 1987; Ericson,
// Real-Time Collision Detection ch. 8: §8.2.3 solid-leaf trees, §8.3.2 evaluating dividing planes,
// §8.3.3 classifying polygons, §8.3.4 polygon splitting, §8.4.1 point containment, §8.4.2 ray
// intersection).
//
// Build: every inner node's plane is the plane of one of the input polygons (autopartition),
// chosen by Ericson's score K * straddling + (1 - K) * |front - back| over the candidates. The
// polygons of a node are classified against its plane: in front, behind, coplanar or straddling;
// straddling polygons are split in two (front and back fragments). Coplanar polygons facing the
// same way as the plane lie on the boundary it represents and are stored at the node (they are
// the "fragments" of the figures); coplanar polygons facing the other way go behind. A front
// side with no polygons left becomes an empty (outside) leaf, a back side a solid leaf.
//
// Input: convex planar polygons (triangles are fine), vertices counter-clockwise seen from
// outside, i.e. normals pointing out of the solid. For inside/outside to be meaningful the
// polygons must bound a closed solid (a closed, consistently oriented mesh); for any other soup
// the tree is still a valid partition (figures), only the solid/empty labels mean little.
//
// Thick planes (Ericson §8.3.3): a point is ON a plane when its distance is within
// thickness() = options.planeThickness * L + 8 ulp(M), L = the largest extent of the input
// bounds, M = the largest |coordinate| (the input itself is rounded to ulp(M)). WHY:
// polygon planes are fitted in floating point, so a polygon's own vertices, or a vertex shared
// by two polygons, are off a plane by rounding noise (~1e-16 L); without a thick plane they
// would be classified as in front or behind at random, splitting polygons into slivers and
// making point classification flip. kBspPlaneThickness (1e-9) L sits far above that noise and far below any feature
// a figure or test uses. Geometry is stored relative to the centre of the input bounds (origin),
// so large offsets (1e6) do not add rounding to the plane distances.
//
// Frame: world; any length unit. Degenerate input: NaN / inf vertices -> status InvalidInput
// and an empty tree; polygons with fewer than 3 vertices or (near-)zero area (|Newell normal| <=
// 1e-12 L^2) are skipped (status SomeDegenerate); an empty soup gives a single empty leaf.
// Termination: a node consumes every fragment of its splitter polygon's plane in its region,
// so a root-to-leaf path uses each input polygon's plane at most once (depth <= polygon count;
// maxDepth caps it further, status DepthLimit, the leaf then being marked empty).
#pragma once

#include <vector>

#include "core/base/primitives.h"

namespace cdlab {

/// Default planeThickness, relative to the input size L (see the file comment): far above the
/// ~1e-16 L rounding of fitted planes, far below any feature a figure or test uses.
inline constexpr double kBspPlaneThickness = 1e-9;
/// Zero-area polygons: |Newell normal| at most this times L^2 (its rounding is ~1e-16 L^2; below
/// it a polygon has no reliable plane).
inline constexpr double kBspDegenerateArea = 1e-12;

/// A convex planar polygon, counter-clockwise seen from the front (outside).
struct BspPolygon {
    std::vector<Vec3> vertices;
};

struct BspOptions {
    double planeThickness = kBspPlaneThickness;  ///< relative to the input size (see the header)
    double splitWeight = 0.8;      ///< K of Ericson §8.3.2: weight of splits vs imbalance (0.8 as there)
    int maxCandidates = 0;  ///< 0: every polygon of a node is a candidate; else at most this many (evenly spaced)
    int maxDepth = 1000;    ///< root depth 0 (a 5k-triangle torus needs ~220)
};

enum class BspStatus {
    Ok,
    Empty,           ///< no usable polygon: one empty leaf, every point outside
    InvalidInput,    ///< NaN / inf in the input: empty tree (every point outside)
    SomeDegenerate,  ///< some polygons skipped (fewer than 3 vertices or zero area); the tree uses the rest
    DepthLimit,      ///< maxDepth reached: leaves there were marked empty, classification may be wrong there
};

enum class BspNodeKind { Inner, SolidLeaf, EmptyLeaf };

enum class BspPointClass { Inside, Outside, OnBoundary };

/// A piece of an input polygon after splitting; stored at the node whose plane it lies on.
struct BspFragment {
    std::vector<Vec3> vertices;  ///< world frame
    int source = -1;             ///< input polygon index
    bool split = false;          ///< true if cut by at least one plane (a piece, not the whole polygon)
    int node = -1;               ///< the node that stores it
};

/// One node. plane (world frame, unit normal, front = normal side) is meaningful for Inner
/// nodes; front / back are child node indices. splitter is the input polygon whose plane it is.
struct BspNode {
    BspNodeKind kind = BspNodeKind::EmptyLeaf;
    Plane plane{Vec3::UnitZ(), 0.0};
    int front = -1, back = -1;
    int parent = -1;
    int depth = 0;
    int splitter = -1;
    std::vector<int> fragments;  ///< indices into BspTree::fragments(): the polygons on this plane
};

/// One candidate splitter scored at a node: its plane against the node's polygons (coplanar ones
/// counted in front, as in Ericson's code).
struct BspCandidateScore {
    int source = -1;  ///< input polygon
    int front = 0, back = 0, straddling = 0;
    double score = 0.0;  ///< K * straddling + (1 - K) * |front - back|
};

/// One plane choice during the build (Ericson §8.3.2), in build order (parent before children).
struct BspSplitStep {
    int node = -1;
    int depth = 0;
    int splitter = -1;        ///< input polygon whose plane was chosen
    int candidates = 0;       ///< polygons scored
    int polygons = 0;         ///< fragments reaching the node
    int front = 0, back = 0;  ///< sent to each side whole
    int coplanar = 0;         ///< stored at the node (same facing)
    int straddling = 0;       ///< split in two
    double score = 0.0;       ///< K * straddling + (1 - K) * |front - back| of the chosen plane
    /// Every candidate in the order scored; the chosen one is the first of the lowest score.
    std::vector<BspCandidateScore> scores;
};
struct BspTrace {
    std::vector<BspSplitStep> steps;
};

/// Result of a segment / ray query: the first point where it is in the solid (closed).
struct BspRayResult {
    bool hit = false;
    double t = 0.0;  ///< parameter of the first solid point (segment: 0..1; ray: units of |direction|)
    Vec3 point = Vec3::Zero();
    bool startsInside = false;  ///< the start point is already in the solid (t = 0)
    int leaf = -1;              ///< the solid leaf hit
};

struct BspStats {
    int nodeCount = 0, innerCount = 0, solidLeaves = 0, emptyLeaves = 0;
    int depth = 0;
    int splits = 0;  ///< polygons cut in two during the build
    int fragmentCount = 0;
};

class BspTree {
public:
    /// Builds the tree over polygons (world frame). trace gets one step per inner node.
    void build(const std::vector<BspPolygon>& polygons, const BspOptions& options = {}, BspTrace* trace = nullptr);

    BspStatus status() const { return status_; }
    const std::vector<BspNode>& nodes() const { return nodes_; }
    const std::vector<BspFragment>& fragments() const { return fragments_; }
    double thickness() const { return thickness_; }
    const BspStats& stats() const { return stats_; }

    /// Point containment (Ericson §8.4.1): descend by the side of each plane; a point within
    /// thickness() of a plane goes down both sides and is OnBoundary when they disagree.
    BspPointClass classifyPoint(const Vec3& p) const;
    /// First solid point of the segment a -> b (Ericson §8.4.2), t in [0, 1]; closed solid
    /// (touching a face counts). A non-finite segment gives no hit.
    BspRayResult segmentQuery(const Segment& segment) const;
    /// The same for a ray origin + t * direction, t in [0, tMax].
    BspRayResult rayQuery(const Ray& ray, double tMax = 1e30) const;

private:
    struct Work;
    int buildNode(std::vector<int> polys, int depth, int parent, Work& work, BspTrace* trace);
    // Ericson §8.3.2 PickSplittingPlane: the source polygon whose plane scores best; step gets
    // the candidate count and the score.
    // With `record`, step.scores gets every candidate.
    int pickSplitter(const std::vector<int>& polys, const Work& work, BspSplitStep& step, bool record) const;
    // The node's polygons sorted against the splitter's plane: coplanar ones stored at node id,
    // straddling ones split, the rest into front / back.
    void partition(const std::vector<int>& polys, int id, Work& work, BspSplitStep& step, std::vector<int>& frontList,
                   std::vector<int>& backList);
    // A child: a leaf of the given kind when no polygon is left, else the subtree.
    int buildChild(std::vector<int> polys, BspNodeKind leafKind, int depth, int parent, Work& work, BspTrace* trace);
    BspPointClass classifyFrom(int node, const Vec3& local) const;
    bool firstSolid(int node, const Vec3& p, const Vec3& d, double t0, double t1, double& tHit, int& leaf) const;
    double localDistance(const BspNode& n, const Vec3& local) const;

    BspOptions options_;
    BspStatus status_ = BspStatus::Empty;
    Vec3 origin_ = Vec3::Zero();
    double thickness_ = 0.0;
    std::vector<BspNode> nodes_;
    std::vector<double> localOffset_;  ///< per node: plane offset relative to origin_
    std::vector<BspFragment> fragments_;
    BspStats stats_;
};

}  // namespace cdlab
