// V-Clip: closest features of two convex polyhedra by walking Voronoi regions.
//
// Source: B. Mirtich, "V-Clip: Fast and Robust Polyhedral Collision Detection", ACM Transactions
// on Graphics 17(3), 1998 (MERL TR-97-05). Feature / Voronoi-region vocabulary as in the paper.
//
// Outline:
//   - A VClipPolyhedron is built once per shape from a ConvexPolyhedron (half-edge mesh). Its
//     features are the vertices, edges and faces; the Voronoi region VR(X) of a feature X is the
//     set of points of space closer to X than to any other feature, bounded by planes:
//       vertex-edge (VE) plane between vertex V and incident edge E: through V, normal along E;
//       face-edge (FE) plane between face F and boundary edge E: contains E, perpendicular to F.
//     Each plane is stored ONCE, oriented so that its positive side is the edge's side
//     (edge e owns planes 4e .. 4e+3: VE at tail, VE at head, FE with left face, FE with right face).
//     A vertex's or face's region is the list of its planes with the NEGATIVE side inside.
//     (A face region is also bounded below by the face plane itself: handled by the states.)
//   - The walk keeps one feature on each body. Each step is one of the five states
//     V-V, V-E, V-F, E-E, E-F (the body order does not matter; F-F is never entered). A state
//     checks whether each feature's closest point lies in the other's Voronoi region; if not,
//     one feature is replaced by a neighbour (the update), else DONE. Edges are tested by
//     clipping (clipEdge: parameters lambdaMin, lambdaMax and the neighbours Nmin, Nmax of the
//     planes that clip them; simple and compound exclusion) and the sign of the derivative of
//     the distance at the clip points. A vertex below a face plane with no edge leading towards
//     it is a local minimum (handleLocalMin): the face is replaced by the face whose plane the
//     vertex is farthest above, or, if it is on or below every face plane, the bodies penetrate.
//     An edge that crosses a face plane inside the face's region pierces it: penetration.
//   - Inter-feature distance never increases: an update that lowers a feature's dimension keeps
//     it, one that raises it decreases it (strictly, except E-E edge -> face when the edge's
//     closest point is its endpoint: then equal; found by the tests, see vclip_walk.cpp). The walk
//     stops on a repeated pair and after (VA+EA+FA)(VB+EB+FB) updates; neither ever fires in the
//     test suite. handleLocalMin is the one jump outside this ordering (Mirtich §5.4).
//   - Work happens in body frames as in the paper: a feature of B is mapped into A's frame (and
//     vice versa) with the relative transform, so large world offsets cost no precision.
//
// Warm start (coherence): pass a VClipCache; the final feature pair of one call seeds the next.
// Typical coherent queries then take 1-3 steps.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

struct VClipBuild;

/// Kind of a polyhedron feature. None marks an absent neighbour (e.g. an unclipped end).
enum class VClipFeatureType : std::uint8_t { None, Vertex, Edge, Face };

/// A feature of one polyhedron: its type and its index into vertices(), edges() or faces().
struct VClipFeature {
    VClipFeatureType type = VClipFeatureType::None;
    int index = -1;

    static VClipFeature vertex(int i) { return {VClipFeatureType::Vertex, i}; }
    static VClipFeature edge(int i) { return {VClipFeatureType::Edge, i}; }
    static VClipFeature face(int i) { return {VClipFeatureType::Face, i}; }
    /// 0 vertex, 1 edge, 2 face, -1 none.
    int dimension() const { return static_cast<int>(type) - 1; }
    bool valid() const { return type != VClipFeatureType::None && index >= 0; }
    friend bool operator==(const VClipFeature&, const VClipFeature&) = default;
};

/// "vertex", "edge", "face", "none".
const char* nameOf(VClipFeatureType type);
/// "V3", "E12", "F0", "-".
std::string nameOf(const VClipFeature& feature);

/// A Voronoi plane (body frame): signedDistance(x) = normal · x - offset, unit normal, positive on
/// the side of `edge`. `other` is the vertex (VE plane) or face (FE plane) on the negative side.
struct VClipPlane {
    Vec3 normal = Vec3::UnitX();
    double offset = 0.0;
    VClipFeature edge;   ///< feature on the positive side (always an edge)
    VClipFeature other;  ///< feature on the negative side (vertex or face)
    double signedDistance(const Vec3& x) const { return normal.dot(x) - offset; }
};

enum class VClipBuildStatus {
    Ok,
    EmptyPolyhedron,  ///< no vertices
    InvalidMesh,      ///< ConvexPolyhedron::validate() failed (message names the defect)
    CoplanarFaces,    ///< two faces sharing an edge are coplanar: merge them first (convexHull does)
};

/// "Ok", "EmptyPolyhedron", ...
const char* nameOf(VClipBuildStatus status);

/// A convex polyhedron with its precomputed Voronoi regions (body frame). Build once, query often.
class VClipPolyhedron {
public:
    VClipPolyhedron() = default;

    const ConvexPolyhedron& mesh() const { return mesh_; }
    bool empty() const { return mesh_.empty(); }
    /// Number of features V + E + F.
    int featureCount() const { return mesh_.vertexCount() + mesh_.edgeCount() + mesh_.faceCount(); }

    /// All planes (4 per edge, see the header comment).
    const std::vector<VClipPlane>& planes() const { return planes_; }
    const VClipPlane& plane(int i) const { return planes_[i]; }
    /// Planes of edge e: indices 4e + k, k = 0 VE tail, 1 VE head, 2 FE left face, 3 FE right face.
    static int edgePlane(int e, int k) { return 4 * e + k; }
    /// Plane indices bounding VR(vertex v) (one VE plane per incident edge; inside = negative side).
    std::span<const int> vertexPlanes(int v) const {
        return {regionPlanes_.data() + vertexStart_[v], regionPlanes_.data() + vertexStart_[v + 1]};
    }
    /// Plane indices bounding VR(face f) sideways (one FE plane per boundary edge; inside = negative).
    std::span<const int> facePlanes(int f) const {
        return {regionPlanes_.data() + faceStart_[f], regionPlanes_.data() + faceStart_[f + 1]};
    }
    /// Tail and head vertex of edge e (origin and destination of edge(e).halfEdge).
    int edgeTail(int e) const { return edgeTail_[e]; }
    int edgeHead(int e) const { return edgeHead_[e]; }
    /// Left face (of edge(e).halfEdge) and right face (of its twin).
    int edgeLeftFace(int e) const { return edgeLeft_[e]; }
    int edgeRightFace(int e) const { return edgeRight_[e]; }

    /// Signed distance of a body-frame point from the region boundary plane `i`, positive inside
    /// VR(owner): owner = plane(i).edge gives +signedDistance, the other feature gives -.
    double regionDistance(int i, const VClipFeature& owner, const Vec3& x) const {
        const double d = planes_[i].signedDistance(x);
        return owner.type == VClipFeatureType::Edge ? d : -d;
    }

private:
    friend VClipBuild buildVClipPolyhedron(const ConvexPolyhedron& polyhedron);

    ConvexPolyhedron mesh_;
    std::vector<VClipPlane> planes_;
    std::vector<int> regionPlanes_;  // CSR lists for vertices then faces
    std::vector<int> vertexStart_, faceStart_;
    std::vector<int> edgeTail_, edgeHead_, edgeLeft_, edgeRight_;
};

/// Result of buildVClipPolyhedron: the regions (empty unless ok()) and why not.
struct VClipBuild {
    VClipBuildStatus status = VClipBuildStatus::EmptyPolyhedron;
    std::string message;  ///< one line; empty when Ok
    VClipPolyhedron polyhedron;
    bool ok() const { return status == VClipBuildStatus::Ok; }
};

/// Precomputes the Voronoi planes of a convex polyhedron (validate()d; adjacent faces must not be
/// coplanar: |n1 x n2| <= 1e-12 is rejected with CoplanarFaces). O(V + E + F) after validation.
VClipBuild buildVClipPolyhedron(const ConvexPolyhedron& polyhedron);

enum class VClipStatus {
    Separated,      ///< distance > 0; points, features and distance meaningful
    Penetrating,    ///< the bodies intersect or touch (distance 0); features say where it was found
    CycleDetected,  ///< a feature pair repeated (never expected on valid input: please report)
    StepLimit,      ///< more than maxSteps updates (never expected on valid input)
    InvalidInput,   ///< empty polyhedron, non-finite pose, or a seed feature out of range
};

/// "Separated", "Penetrating", ...
const char* nameOf(VClipStatus status);

/// How a penetration was found.
enum class VClipPenetration : std::uint8_t {
    None,
    EdgePiercesFace,  ///< E-F: the clipped edge crosses (or touches) the face plane inside VR(F)
    LocalMinimum,     ///< V-F: vertex on or below every face plane of the other body (dmax <= 0)
    Touching,         ///< a DONE state (or a clip point) with distance exactly 0
};

const char* nameOf(VClipPenetration how);

/// Feature pair kept between calls (coherence). Invalid (default) = cold start from vertex 0 / 0.
struct VClipCache {
    VClipFeature a;
    VClipFeature b;
};

struct VClipOptions {
    /// Update cap; <= 0 means (VA+EA+FA)(VB+EB+FB), the number of feature pairs (a walk that never repeats a pair ends
    /// within it).
    int maxSteps = 0;
    /// Stop with CycleDetected when a feature pair repeats (Brent's cycle detection: O(1) per step,
    /// found within ~2x the steps of the first repeat). Guards rounding; never fires in the tests.
    bool detectCycles = true;
};

struct VClipResult {
    VClipStatus status = VClipStatus::InvalidInput;
    VClipPenetration penetration = VClipPenetration::None;
    bool intersect = false;      ///< status == Penetrating
    double distance = 0.0;       ///< Separated: the distance (world units); else 0
    Vec3 pointA = Vec3::Zero();  ///< Separated: closest point on A, world frame. Penetrating: a
    Vec3 pointB = Vec3::Zero();  ///<   common point where found (E-F) or the vertex (V-F), both equal
    Vec3 normal = Vec3::Zero();  ///< Separated: unit (pointB - pointA) / distance, else zero
    VClipFeature featureA;       ///< final features (closest features when Separated)
    VClipFeature featureB;
    int steps = 0;        ///< number of updates made (0: the seed pair was already closest)
    std::string message;  ///< InvalidInput / CycleDetected / StepLimit: why
};

// ---------------------------------------------------------------------------------------------
// Trace (optional, recorded in every build type). Everything a demo draws is in WORLD frame.

/// The five states (body order ignored: V-E covers vertex on A / edge on B and the reverse).
enum class VClipState : std::uint8_t { VertexVertex, VertexEdge, VertexFace, EdgeEdge, EdgeFace };
/// "V-V", "V-E", "V-F", "E-E", "E-F".
const char* nameOf(VClipState state);

/// One Voronoi plane test: a point of one feature against one plane of the other's region.
struct VClipPlaneTest {
    int regionBody = 0;               ///< 0 = plane of A's region, 1 = B's
    VClipFeature owner;               ///< feature whose region the plane bounds
    VClipFeature neighbor;            ///< feature on the other side of the plane
    int plane = -1;                   ///< plane index in that body's planes()
    double signedDistance = 0.0;      ///< of the tested point, positive inside VR(owner)
    bool violated = false;            ///< signedDistance < 0
    bool maximal = false;             ///< V-F: the most violated plane (or handleLocalMin: the max face)
    Vec3 planePoint = Vec3::Zero();   ///< a point of the plane, world
    Vec3 planeNormal = Vec3::Zero();  ///< unit, pointing INTO VR(owner), world
    Vec3 testedPoint = Vec3::Zero();  ///< the point tested, world
};

/// clipEdge of an edge of one body against (part of) the Voronoi region of a feature of the other.
struct VClipClip {
    int edgeBody = 0;        ///< body of the clipped edge (0 = A)
    VClipFeature edge;       ///< the clipped edge
    VClipFeature region;     ///< the feature whose region clips it
    double lambdaMin = 0.0;  ///< clipped interval [lambdaMin, lambdaMax] of e(l) = tail + l (head - tail)
    double lambdaMax = 1.0;
    VClipFeature neighborMin;       ///< Nmin: neighbour of the plane that set lambdaMin (None: the tail)
    VClipFeature neighborMax;       ///< Nmax (None: the head)
    bool simplyExcluded = false;    ///< both ends outside one plane
    bool compoundExcluded = false;  ///< lambdaMin > lambdaMax without a simple exclusion
    VClipFeature excludedBy;        ///< simple exclusion: the neighbour of that plane
    int derivativeMin = 0;          ///< sign of D'(lambdaMin) (-1, 0, +1); 2 = not evaluated
    int derivativeMax = 0;          ///< sign of D'(lambdaMax); 2 = not evaluated
    Vec3 tail = Vec3::Zero(), head = Vec3::Zero();                ///< the edge, world
    Vec3 clippedTail = Vec3::Zero(), clippedHead = Vec3::Zero();  ///< e(lambdaMin), e(lambdaMax), world
};

/// What a step decided.
enum class VClipStepKind : std::uint8_t {
    Update,       ///< one feature replaced by a neighbour (or any feature: handleLocalMin, face search)
    Done,         ///< both closest points inside the other feature's region: Separated
    Penetration,  ///< see VClipResult::penetration
    Aborted,      ///< cycle / step limit
};
const char* nameOf(VClipStepKind kind);

struct VClipTraceStep {
    int step = 0;  ///< 0-based
    VClipState state = VClipState::VertexVertex;
    VClipFeature featureA, featureB;     ///< features at the start of the step
    std::vector<Vec3> featureAWorld;     ///< their geometry: 1 point, 2 endpoints or the face polygon
    std::vector<Vec3> featureBWorld;     ///<   (counter-clockwise from outside), world
    std::vector<VClipPlaneTest> planes;  ///< plane tests in the order made
    std::vector<VClipClip> clips;        ///< clipEdge calls in the order made
    VClipStepKind kind = VClipStepKind::Update;
    int updatedBody = -1;          ///< Update: 0 = A's feature replaced, 1 = B's
    VClipFeature from, to;         ///< Update: the replaced feature and its replacement
    std::string rule;              ///< short name of the rule applied, e.g. "V_B violates VE(E_A)"
    bool localMinimum = false;     ///< the update came from handleLocalMin (distance not monotone)
    double distanceBefore = 0.0;   ///< inter-feature distance of the pair before / after the update
    double distanceAfter = 0.0;    ///<   (0 when the features intersect), world units
    int distanceChange = 0;        ///< -1 decreased, 0 equal, +1 increased (sign of after - before)
    Vec3 closestA = Vec3::Zero();  ///< closest points of the pair before the update, world
    Vec3 closestB = Vec3::Zero();
};

struct VClipTrace {
    std::vector<VClipTraceStep> steps;
    VClipStatus status = VClipStatus::InvalidInput;
};

/// Closest features and distance of convex polyhedra A and B placed by poseA and poseB
/// (x_world = pose.apply(x_body)). cache: seed pair in, final pair out (nullptr: cold start from
/// vertex 0 of each). Outputs in world frame and units; see VClipResult for what is meaningful.
VClipResult vclip(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b, const Transform& poseB,
                  VClipCache* cache = nullptr, const VClipOptions& options = {}, VClipTrace* trace = nullptr);

/// World-frame geometry of a feature: 1 point (vertex), 2 (edge tail, head) or the face polygon.
std::vector<Vec3> featureGeometry(const VClipPolyhedron& p, const Transform& pose, const VClipFeature& f);

}  // namespace cdlab
