// Contact manifold of two convex polyhedra by the separating axis test and face clipping.
//
// D. Gregorius, "The Separating Axis Test between Convex Polyhedra" (GDC 2013) and "Robust
// Contact Creation for Physics Simulations" (GDC 2015); Ericson, "Real-Time Collision Detection"
// §5.2.1 (SAT) and §8.3.4 (Sutherland–Hodgman clipping). Outline:
//   1. Face axes: for every face f of A (outward n, plane n · x = d) the separation is
//      n · s_B(-n) - d (s_B = support point of B); likewise for the faces of B against A.
//   2. Edge axes: for an edge pair (e_A, e_B) the axis e_A x e_B is a face of the Minkowski
//      difference A - B only if the arcs of the two edges on the Gauss map intersect (arc of e_A
//      from the normal of its one face to the other's; arc of e_B negated). Gregorius' test with
//      the arcs' four normals a, b (A) and c = -n_B1, d = -n_B2:
//         c · (b x a) * d · (b x a) < 0,  a · (d x c) * b · (d x c) < 0,  c · (b x a) * b · (d x c) > 0.
//      Pairs failing it are pruned (their axis is no face of A - B, so it cannot be the least
//      penetration axis); parallel edges are skipped (their axis is a face axis). A surviving
//      pair's axis, oriented away from A's centre, has separation axis · (p_B - p_A).
//   Untraced calls find the same axes faster: each support in step 1 by steepest descent over the
//   other body's vertex graph, started at the support of an adjacent face (faces visited breadth
//   first); the pairs of step 2 by walking each arc of A through the vertex regions of B's Gauss
//   map from the support of its first face to that of its second, each region boundary crossed
//   being one B edge whose arc crosses it (O(crossings) per edge of A instead of O(|E_B|)). Traced
//   calls test every vertex and every pair in index order, so the trace can count the pruning.
//   3. Max separation > tol: separated (a separating axis; the separation is a lower bound of the
//      distance). Otherwise the axis of least penetration, preferring faces (an edge axis must be
//      better by faceBias, a B face better than the A face by faceBias too: stable manifolds
//      under rounding, as Box2D's b2CollidePolygons does with k_tol). The contract (issue 41 (a)):
//      the depth is not always the least overlap; it is bounded by
//         least overlap <= depth <= least overlap · (1 + faceBiasRelative) + faceBiasAbsolute + tol
//      (2 % with the defaults; tol the touching band, kTouchingBandRelative = 1e-9 of the larger
//      bounding-box diagonal + 64 ulps, unless options.tolerance sets it), and it is the overlap of
//      the projections on the reported normal (cdlab stress "contact manifolds").
//      faceBiasRelative = 0 asks for the least overlap (within tol). Nearly parallel edges (sine
//      below kPreciseEdgeSine) have their axis computed in long double, so the bound holds for them
//      too (their double cross product is off by ~1e-16 / sine).
//   4. Face axis: reference face = that face, incident face = the other body's face most
//      anti-parallel to it; the incident polygon is clipped by the reference face's side planes
//      (Sutherland–Hodgman), points behind the reference plane or up to tol above it (s <= tol)
//      are kept with depth -s (negative within the band), reduced to <= maxPoints
//      (core/contact/contact_manifold.h); when none is kept, the touching pair of the two bodies.
//      Edge axis: one point, the closest points of the two edges (their common perpendicular in
//      double-double when it lies on both).
// Normal convention (as EPA, core/gjk_epa/epa.h): normal points from A toward B; pointA - pointB =
// depth * normal; translating B by depth * normal separates the bodies (touching). Vertices are
// taken relative to A's position so large offsets cost no precision in differences.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/base/sat_axis_kind.h"
#include "core/base/types.h"
#include "core/contact/contact_manifold.h"
#include "core/contact/contact_tolerances.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

enum class SatContactStatus {
    Separated,     ///< separation > tol: normal = separating axis (A→B), no manifold
    Touching,      ///< |separation| <= tol: manifold of the touching features, depth ~0
    Penetrating,   ///< separation < -tol: depth, normal, manifold meaningful
    InvalidInput,  ///< empty polyhedron or non-finite / non-unit pose: see message
};
const char* nameOf(SatContactStatus status);

/// "face A", "face B", "edge-edge".
const char* nameOf(SatAxisKind kind);

struct SatContactOptions {
    /// Touching tolerance (world units); std::nullopt (or a negative value): automatic,
    /// kTouchingBandRelative x the larger body diagonal + 64 ulps of the coordinates.
    std::optional<double> tolerance = std::nullopt;
    /// Axis preference: a candidate replaces the current best only if its separation exceeds it
    /// by faceBiasRelative * |best| + faceBiasAbsolute (order: face A, face B, edges): the depth is
    /// then at most least overlap · (1 + faceBiasRelative) + faceBiasAbsolute + tolerance.
    double faceBiasRelative = 0.02;
    double faceBiasAbsolute = 0.0;  ///< world units; < 0 not allowed (treated as 0)
    int maxPoints = 4;              ///< manifold size (<= 0: every clipped point, up to kMaxContactPoints)
    /// Untraced query: skip the edges of A whose every edge pair is bounded below the face axes'
    /// best by more than the preference and the tolerance (an edge pair on the arc of A's edge e
    /// separates by at most max_u u · (c_B − e) − r_B over the arc, c_B B's vertex mean and r_B
    /// the radius of the ball about it inside B): the same answer, fewer pairs tested (axesTested
    /// counts the pairs tested, nearlyParallelEdgePairs those met). false, or faceBiasRelative < 0:
    /// every crossing pair is tested (tests compare the walk's pairs with the traced query's;
    /// core/query/contact.cpp needs every nearly parallel pair counted).
    bool pruneEdgeArcs = true;
    /// Untraced query: skip the support descent of a face whose separation is bounded below its
    /// family's best so far (min_B n_f · x <= n_f · c_B − r_B, B's vertex mean and inradius about
    /// it), visiting the face of largest bound first: the same answer, fewer faces tested (and
    /// counted in axesTested). false: every face tested.
    bool pruneFaceAxes = true;
};

struct SatContactResult {
    SatContactStatus status = SatContactStatus::InvalidInput;
    std::string message;
    double separation = 0.0;      ///< max over all axes (world units): > 0 apart, <= 0 overlapping (= -SAT depth)
    double depth = 0.0;           ///< penetration along the chosen axis, >= 0 (>= -separation by at most the bias)
    Vec3 normal = Vec3::UnitX();  ///< unit, from A toward B (chosen axis)
    SatAxisKind axisKind = SatAxisKind::FaceA;
    FeatureRef featureA, featureB;       ///< face: reference / incident face; edge-edge: the two edges
    ContactManifold manifold;            ///< colliding: <= maxPoints points, deepest first
    double tolerance = 0.0;
    /// Axes whose separation was computed: every face normal of both bodies and every edge pair
    /// that forms a face of A − B (their Gauss arcs cross, edges not parallel). Without the pruning
    /// (pruneEdgeArcs, pruneFaceAxes) the untraced and the traced query test the same axes, found by
    /// walking the arcs or by testing all of them; with it, the untraced query tests fewer.
    int axesTested = 0;
    /// Edge pairs tested whose sine is below kPreciseEdgeSine (their axis computed in long double):
    /// their axis is only as good as the vertices, so a caller whose vertices were rounded (a
    /// translated frame) may want to run again on exact ones (core/query/contact.cpp does).
    int nearlyParallelEdgePairs = 0;
    /// The face clip kept no point (the manifold then holds the bodies' touching pair); with a face
    /// preference the query retries on the least-overlap axis first (contactPolyhedra).
    bool clipKeptNothing = false;
    bool colliding() const { return status == SatContactStatus::Touching || status == SatContactStatus::Penetrating; }
};

/// One axis tested.
struct SatAxisRecord {
    SatAxisKind kind = SatAxisKind::FaceA;
    int indexA = -1;           ///< face of A (FaceA) or edge of A (EdgeEdge)
    int indexB = -1;           ///< face of B (FaceB) or edge of B (EdgeEdge)
    Vec3 axis = Vec3::Zero();  ///< unit, world, oriented from A toward B
    double separation = 0.0;
};

/// One Sutherland–Hodgman step: the incident polygon clipped by one side plane of the reference face.
struct SatClipStep {
    int referenceEdge = -1;           ///< index of the reference face edge (in face order) whose side plane clips
    Vec3 planeNormal = Vec3::Zero();  ///< unit, world, pointing out of the reference face's prism
    double planeOffset = 0.0;         ///< world: planeNormal · x = planeOffset
    std::vector<Vec3> before, after;  ///< polygon before / after, world
};

struct SatContactTrace {
    std::vector<SatAxisRecord> axes;  ///< every face axis and every surviving edge pair, in test order
    int edgePairsTotal = 0;           ///< |E_A| x |E_B|
    int edgePairsPruned = 0;          ///< rejected by the Gauss-map arc test
    int edgePairsParallel = 0;        ///< skipped as parallel
    int bestFaceA = -1, bestFaceB = -1, bestEdgePair = -1;  ///< indices into axes
    int chosen = -1;                                        ///< index into axes
    bool referenceOnA = true;                               ///< face contact: which body holds the reference face
    int referenceFace = -1, incidentFace = -1;
    std::vector<Vec3> referencePolygon, incidentPolygon;  ///< world
    std::vector<SatClipStep> clipSteps;
    std::vector<ContactPoint> clipped;                          ///< points after clipping and the below-reference test
    std::vector<ManifoldReductionStep> reduction;               ///< indices into clipped
    Vec3 edgePointA = Vec3::Zero(), edgePointB = Vec3::Zero();  ///< edge contact: closest points
};

/// SAT contact of A (pose ta) and B (pose tb), world frame. See the file comment.
SatContactResult contactPolyhedra(const ConvexPolyhedron& a, const Transform& ta, const ConvexPolyhedron& b,
                                  const Transform& tb, const SatContactOptions& options = {},
                                  SatContactTrace* trace = nullptr);

}  // namespace cdlab
