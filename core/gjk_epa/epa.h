// EPA: penetration depth, contact normal and witness points of two intersecting convex shapes.
//
// Expanding Polytope Algorithm, van den Bergen, "Proximity Queries and Penetration Depth
// Computation on 3D Game Objects" (GDC 2001) and "Collision Detection in Interactive 3D
// Environments" §4.3.8. Outline:
//   P = a tetrahedron inside C = A - B that contains the origin (from GJK's terminal simplex;
//       point / segment / triangle simplices are blown up with support points)
//   loop: F = face of P nearest the origin (distance d_F = lower bound of the depth)
//         w = s_C(n_F), upper bound min(n_F · w)
//         stop when n_F · w - d_F <= eps_rel * n_F · w        (relative gap)
//         remove every face visible from w, walk the horizon (edge loop), fan it to w
// Conventions: the contact normal is a unit vector pointing from A toward B. Translating B by
// +depth * normal (or A by -depth * normal) brings the shapes to touching, and
// pointA - pointB = depth * normal (up to rounding): pointA is the deepest point of A inside B.
//
// Support points w = a - b are exact (Sterbenz) when the shapes are near each other, so the
// polytope lives around the origin at the shapes' scale no matter how far they are from the world
// origin; witness points are rebuilt relative to one vertex for the same reason.
// No heap allocation unless a trace is recorded (the polytope lives in fixed arrays on the stack).
//
// This header is the API: statuses, options, results, traces and the two entry points. The
// machinery (the fixed-capacity polytope, the expansion loop, the edge-pair refinements, trace
// recording) is core/gjk_epa/epa_impl.h, included at the end.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/base/support.h"
#include "core/base/types.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

/// Outcome of an EPA query.
enum class EpaStatus {
    Penetrating,   ///< depth > 0: depth, normal, pointA, pointB meaningful
    Touching,      ///< depth = 0 up to rounding; normal is a valid unit contact normal
    Separated,     ///< (penetration() only) GJK found the shapes apart: depth 0, see the GJK result
    InvalidInput,  ///< empty start simplex or NaN support points: outputs are zero
};

/// Why the EPA loop stopped.
enum class EpaTermination {
    Converged,         ///< relative gap between the depth bounds <= relativeTolerance
    DuplicateSupport,  ///< the new support point is already a polytope vertex: no progress left
    MaxIterations,     ///< iteration cap: depth is the lower bound, see lowerBound / upperBound
    CapacityExceeded,  ///< fixed vertex / face arrays full: as MaxIterations
    Degenerate,        ///< expansion would create a zero-area face: stopped with the current best
    Touching,          ///< during blow-up the origin was found on the boundary of A - B
    NotIntersecting,   ///< (penetration() only) GJK says separated
    InvalidInput,      ///< empty simplex / NaN
    /// (penetration(), penetrationWithMargins only) EPA did not run, iterations 0: GJK's answer
    /// decided the depth (a crossed edge pair, GjkTermination::EdgePairCrossed; with margins also
    /// cores apart within the radii, whose GJK iterations are reported)
    DecidedByGjk,
};

/// How a query runs: the stopping rule, the iteration cap, the GJK run of penetration(), and
/// whether an edge-edge answer is refined from the two lines.
struct EpaOptions {
    /// Stop when (upper - lower) <= relativeTolerance * upper on the depth. Polytopes converge
    /// exactly (gap at rounding level); smooth shapes need many vertices, see maxIterations.
    double relativeTolerance = 1e-13;
    /// Iteration cap (one vertex per iteration); the arrays hold 128 vertices and 256 faces.
    int maxIterations = 120;
    /// Options of the GJK run inside penetration().
    GjkOptions gjk{};
    /// When the final face spans an edge of A and an edge of B (edge-edge penetration), take
    /// depth, normal and witnesses from the two lines' common perpendicular in double-double
    /// (core/closest/edge_pair_distance.h): the face normal, a cross product of rounded differences,
    /// errs by ~u / angle on nearly parallel edges.
    bool refineEdgePairs = true;
};

/// The answer of epaPenetration / penetration: status, depth, normal and deepest points, why and
/// after how many iterations the loop stopped, the depth bounds and the polytope's final size.
struct EpaResult {
    EpaStatus status = EpaStatus::InvalidInput;
    double depth = 0.0;           ///< penetration depth, world units, >= 0
    Vec3 normal = Vec3::UnitX();  ///< unit, from A toward B (see file comment)
    Vec3 pointA = Vec3::Zero();   ///< deepest point of A in B, world frame
    Vec3 pointB = Vec3::Zero();   ///< deepest point of B in A, world frame
    int iterations = 0;
    EpaTermination termination = EpaTermination::InvalidInput;
    double lowerBound = 0.0;  ///< depth >= lowerBound (distance of nearest face)
    double upperBound = 0.0;  ///< depth <= upperBound (best support value)
    int vertexCount = 0;      ///< polytope size at the end
    int faceCount = 0;
    bool edgePairRefined = false;  ///< depth and normal from the edge pair (options)
};

/// One EPA iteration as plain data. Vertex ids index `vertices`; faces are CCW seen from outside.
struct EpaTraceStep {
    int iteration = 0;
    std::vector<Vec3> vertices;             ///< polytope vertices w = a - b (before expansion)
    std::vector<std::array<int, 3>> faces;  ///< live faces before expansion
    int closestFace = -1;                   ///< index into faces
    Vec3 closestNormal = Vec3::Zero();      ///< its outward unit normal
    double closestDistance = 0.0;           ///< its distance to the origin (lower bound)
    Vec3 closestPoint = Vec3::Zero();       ///< projection of the origin on it
    Vec3 direction = Vec3::Zero();          ///< support direction (= closestNormal)
    Vec3 support = Vec3::Zero();            ///< new point w and its shape points a, b
    Vec3 supportA = Vec3::Zero();
    Vec3 supportB = Vec3::Zero();
    std::vector<std::array<int, 3>> removedFaces;  ///< faces visible from w (vertex ids)
    std::vector<std::array<int, 2>> horizon;       ///< horizon edges (vertex ids), in loop order
    double lowerBound = 0.0;
    double upperBound = 0.0;
    bool terminated = false;  ///< loop stopped here (no expansion)
};

/// A face of the final polytope with the weights of the origin's projection p on its plane.
struct EpaWitnessFace {
    std::array<Vec3, 3> w{}, a{}, b{};  ///< its vertices w_i = a_i − b_i and their points of A and B
    std::array<double, 3> weights{};    ///< p = sum weights_i w_i; convex when all are >= 0
};

/// The barycentric witness step of a traced query: p = depth · n written in the nearest face's
/// vertices; pointA = sum l_i a_i, pointB = sum l_i b_i. When p lies outside that face (a negative
/// weight: a coplanar face of A − B holds it, as in golden/epa/box_box), the live face nearest p gives
/// the weights instead, clamped to a convex combination. Recorded from the face the loop ended on,
/// before any edge-pair refinement or fallback replaces the answer.
struct EpaWitnessStep {
    bool recorded = false;
    Vec3 projection = Vec3::Zero();
    EpaWitnessFace nearest;  ///< the face the loop ended on
    bool covered = false;    ///< nearest's weights are not convex: `used` is the face holding p
    EpaWitnessFace used;     ///< the weights that gave pointA and pointB
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
};

/// Every iteration of one traced query (pass an EpaTrace* to epaPenetration / penetration).
struct EpaTrace {
    std::string start;                   ///< how the first tetrahedron was made
    std::vector<Vec3> blowUpDirections;  ///< directions used to blow up a degenerate simplex
    std::vector<Vec3> blowUpPoints;      ///< the support points they gave
    std::vector<EpaTraceStep> steps;
    EpaWitnessStep witness;
    EpaTermination termination = EpaTermination::InvalidInput;
};

/// Display name of the enum values.
const char* nameOf(EpaStatus status);
const char* nameOf(EpaTermination termination);

/// Penetration depth of intersecting shapes A and B (world frame, world units) starting from
/// GJK's terminal simplex `start` (any size 1..4, containing the origin up to rounding). See the
/// file comment for the normal / witness convention. Never NaN for finite shapes.
template <SupportMapping A, SupportMapping B>
EpaResult epaPenetration(const A& shapeA, const B& shapeB, const GjkSimplex& start, const EpaOptions& options = {},
                         EpaTrace* trace = nullptr);

/// GJK followed by EPA when the shapes intersect. Separated shapes give status Separated
/// (depth 0, normal = GJK's separating axis, witness points = GJK's closest points). A shallow
/// crossing of nearly parallel edges that GJK decided (GjkTermination::EdgePairCrossed) is answered
/// from crossedEdgePenetration without EPA: termination DecidedByGjk, 0 iterations.
/// `gjkOut` optionally receives the GJK result (distance, simplex).
template <SupportMapping A, SupportMapping B>
EpaResult penetration(const A& shapeA, const B& shapeB, const EpaOptions& options = {}, EpaTrace* trace = nullptr,
                      GjkResult* gjkOut = nullptr);

}  // namespace cdlab

#include "core/gjk_epa/epa_impl.h"
