// GJK: distance, witness points and intersection of two convex sets given by support mappings.
//
// Gilbert, Johnson, Keerthi 1988, in the formulation of van den Bergen, "Collision Detection in
// Interactive 3D Environments" §4.3 (see also Ericson, Real-Time Collision Detection §9.5).
// Iterates on the Minkowski difference C = A - B with support s_C(d) = s_A(d) - s_B(-d):
//   v = some point of C; W = {v}
//   loop: w = s_C(-v)                          // support point opposite the current estimate
//         lower bound on the distance: v·w / |v|, upper bound: |v|
//         stop when |v|² - v·w <= eps_rel |v|²   // relative gap (upper - lower) <= eps_rel upper
//         W = closest sub-simplex of W + {w} to the origin, v = its closest point
// Every simplex vertex keeps the two shape points a_i, b_i (w_i = a_i - b_i), so the witness
// points are pointA = sum lambda_i a_i and pointB = sum lambda_i b_i with the simplex weights.
//
// Shapes are given in one common (world) frame. No heap allocation unless a trace is recorded.
//
// This header is the API: statuses, options, results, traces and the two entry points. The
// machinery (the loop, the edge-pair refinements, trace recording) is core/gjk_epa/gjk_impl.h,
// included at the end.
#pragma once

#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/support.h"
#include "core/base/types.h"
#include "core/gjk_epa/simplex_solver.h"

namespace cdlab {

/// Outcome of a GJK query.
enum class GjkStatus {
    Separated,     ///< distance > 0: distance, pointA, pointB, separatingAxis are meaningful
    Intersecting,  ///< the shapes overlap or touch: distance = 0; gjkDistance's simplex contains the
                   ///< origin unless termination is EdgePairCrossed (see GjkTermination)
    InvalidInput,  ///< a support point was NaN or infinite: outputs are zero, nothing meaningful
};

/// Why the GJK loop stopped.
enum class GjkTermination {
    Converged,         ///< |v|² - v·w <= relativeTolerance |v|²: distance within the tolerance
    DuplicateSupport,  ///< the new support point is already in the simplex: no progress possible
    NoProgress,        ///< |v| did not decrease (rounding floor reached): previous simplex kept
    OriginInSimplex,   ///< v = 0 up to rounding, or a full tetrahedron enclosing the origin
    SeparatingAxis,    ///< gjkIntersect early-out: v·w > 0, so -v separates the shapes
    MaxIterations,     ///< iteration cap reached: bounds in the result say how far off it is
    InvalidInput,      ///< NaN / infinite support point
    /// The loop stopped "apart" on a doubtful sliver simplex (duplicate support, no progress or the
    /// cap), but an edge pair of it crosses: the shapes intersect (gjk_impl.h's
    /// gjkDecideCrossedEdges). The simplex does not contain the origin; crossedEdgePenetration
    /// gives the crossing's depth, normal and deepest points (EPA need not run).
    EdgePairCrossed,
};

/// One simplex vertex: the support points of both shapes and the direction that produced them.
struct GjkVertex {
    Vec3 w = Vec3::Zero();          ///< w = a - b, a point of the Minkowski difference A - B
    Vec3 a = Vec3::Zero();          ///< a = s_A(direction)
    Vec3 b = Vec3::Zero();          ///< b = s_B(-direction)
    Vec3 direction = Vec3::Zero();  ///< search direction (not normalized), kept for warm starts
};

/// GJK simplex: 0..4 vertices with their barycentric weights for the closest point v.
struct GjkSimplex {
    GjkVertex vertex[4];
    double lambda[4] = {};
    int count = 0;
};

/// How a query runs: the simplex solver, the stopping rule, an optional warm start, and whether a
/// doubtful answer is checked against the terminal simplex's feature pairs.
struct GjkOptions {
    SimplexSolver solver = SimplexSolver::SignedVolumes;
    /// Stop when (upper - lower) <= relativeTolerance * upper on the distance. 1e-13 keeps the
    /// distance within 1e-13 relative; rounding noise of v·w is ~1e-16 |w|, far below.
    double relativeTolerance = 1e-13;
    /// Safety cap; polytopes converge in a few iterations, smooth shapes in tens.
    int maxIterations = 128;
    /// Optional simplex of a previous query (e.g. last frame): its vertices are re-evaluated as
    /// support points of the current shapes along their stored directions.
    const GjkSimplex* warmStart = nullptr;
    /// When a separated answer is doubtful (a sliver terminal triangle, or an uncertified stop),
    /// recompute it from the edge pairs of the terminal simplex in double-double arithmetic,
    /// certified by the supports (core/closest/edge_pair_distance.h, gjk_impl.h's gjkRefineEdgePairs): exact
    /// to a few ulps even for nearly parallel edges, where |v| errs by ~u L / angle.
    bool refineEdgePairs = true;
};

/// The answer of gjkDistance (and of gjkIntersect's full loop): status, distance, witnesses and
/// axis, the terminal simplex, why and after how many iterations the loop stopped, and the bounds.
struct GjkResult {
    GjkStatus status = GjkStatus::InvalidInput;
    double distance = 0.0;               ///< Euclidean distance (0 when intersecting), world units
    Vec3 pointA = Vec3::Zero();          ///< closest point on A (when intersecting: a common point
    Vec3 pointB = Vec3::Zero();          ///<   of the simplex, pointA ~ pointB; EdgePairCrossed:
                                         ///<   the crossing's deepest points), world frame
    Vec3 separatingAxis = Vec3::Zero();  ///< unit, from A toward B: (pointB - pointA) / distance;
                                         ///< zero when intersecting
    GjkSimplex simplex;                  ///< terminal simplex (a warm start; EPA's start when it
                                         ///< contains the origin: intersecting, not EdgePairCrossed)
    int iterations = 0;
    GjkTermination termination = GjkTermination::InvalidInput;
    double lowerBound = 0.0;       ///< max over iterations of v·w / |v| (distance >= this)
    double upperBound = 0.0;       ///< |v| (distance <= this)
    bool edgePairRefined = false;  ///< distance and witnesses from the edge pair (see options)

    /// The verdict: status == Intersecting (overlapping or touching).
    bool intersect() const { return status == GjkStatus::Intersecting; }
};

/// The penetration of a crossed edge pair (GjkTermination::EdgePairCrossed): the face of A − B the
/// pair spans, with the origin behind it, is the nearest one.
struct EdgePairCrossing {
    double depth = 0.0;           ///< > 0, world units
    Vec3 normal = Vec3::UnitX();  ///< unit, from A toward B (out of A − B through the face)
    Vec3 pointA = Vec3::Zero();   ///< deepest points of the pair's features, world frame:
    Vec3 pointB = Vec3::Zero();   ///<   pointA − pointB = depth · normal (up to rounding)
};

/// One GJK iteration as plain data (for demos / debugging). The simplex slots are w0..w3
/// (simplex[i] is wi); a region string names kept slots by the letters A..D = w0..w3, not the bodies.
struct GjkTraceStep {
    int iteration = 0;
    GjkVertex simplex[4];  ///< simplex after adding the new support point, before reduction
    int simplexCount = 0;
    Vec3 direction = Vec3::Zero();  ///< search direction d = -v
    GjkVertex support;              ///< new support point (w, a, b)
    std::uint8_t keptSlots = 0;     ///< sub-simplex kept: bit i set = slot i of simplex[] kept
    double lambda[4] = {};          ///< barycentric weights of the kept vertices (ascending slots)
    Vec3 v = Vec3::Zero();          ///< closest point of the kept sub-simplex to the origin
    Vec3 pointA = Vec3::Zero();     ///< witness points for this v
    Vec3 pointB = Vec3::Zero();
    double lowerBound = 0.0;  ///< distance lower bound so far
    double upperBound = 0.0;  ///< |v| before this step's reduction
    double gapTest = 0.0;     ///< |v|² - v·w, compared with relativeTolerance * |v|²
    bool terminated = false;  ///< this step ended the loop; a stop before the reduction (Converged,
                              ///< DuplicateSupport, SeparatingAxis) keeps all of W in keptSlots

    int keptCount() const { return std::popcount(keptSlots); }
};

/// The slots of a kept sub-simplex by letter, ascending: 0b0101 -> "AC" (w0 and w2 kept; the trace
/// JSON's "region").
std::string slotLetters(std::uint8_t slots);

/// Every iteration of one traced query (pass a GjkTrace* to gjkDistance / gjkIntersect).
struct GjkTrace {
    std::vector<GjkTraceStep> steps;
    GjkTermination termination = GjkTermination::InvalidInput;  ///< the result's (EdgePairCrossed
                                                                ///< after a loop that stopped apart)
};

/// Display name of the enum values.
const char* nameOf(GjkStatus status);
const char* nameOf(GjkTermination termination);

/// Distance between convex shapes A and B (world frame, world units) with witness points and a
/// separating axis. Intersecting (or touching up to rounding) shapes give status Intersecting,
/// distance 0 and, unless termination is EdgePairCrossed, a terminal simplex that contains the
/// origin (feed it to epaPenetration; penetration() does both and handles the crossed pair).
template <SupportMapping A, SupportMapping B>
GjkResult gjkDistance(const A& shapeA, const B& shapeB, const GjkOptions& options = {}, GjkTrace* trace = nullptr);

/// The crossing of a result g of gjkDistance / gjkIntersect on the same shapes with termination
/// EdgePairCrossed, recomputed from its terminal simplex by the same decision GJK took
/// (gjk_impl.h's gjkCrossedAmong: the same operations, the same bits); nullopt for any other
/// termination. The penetration: EPA need not run (penetration(), marginPairOnCores).
template <SupportMapping A, SupportMapping B>
std::optional<EdgePairCrossing> crossedEdgePenetration(const A& shapeA, const B& shapeB, const GjkResult& g);

/// Boolean intersection test of A and B (world frame): stops as soon as a separating axis is
/// found. Untraced and without a warm start, the answer comes from the boolean fast path
/// (core/gjk_epa/gjk_boolean.h; for polytopes it starts from their first vertices' difference, one
/// support call fewer than along +x) when it decides with its margin; `result` then holds only status,
/// termination (SeparatingAxis or OriginInSimplex) and iterations. Otherwise, and for
/// touching within the margin, the full loop runs: optional `result` receives its (partial) GJK
/// result, for separated shapes a distance that is only an upper bound unless the loop converged.
template <SupportMapping A, SupportMapping B>
bool gjkIntersect(const A& shapeA, const B& shapeB, const GjkOptions& options = {}, GjkTrace* trace = nullptr,
                  GjkResult* result = nullptr);

}  // namespace cdlab

#include "core/gjk_epa/gjk_impl.h"
