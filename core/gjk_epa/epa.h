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
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/simplex_solver.h"
#include "core/base/support.h"

namespace cdlab {

enum class EpaStatus {
    Penetrating,   ///< depth > 0: depth, normal, pointA, pointB meaningful
    Touching,      ///< depth = 0 up to rounding; normal is a valid unit contact normal
    Separated,     ///< (penetration() only) GJK found the shapes apart: depth 0, see the GJK result
    InvalidInput,  ///< empty start simplex or NaN support points: outputs are zero
};

enum class EpaTermination {
    Converged,         ///< relative gap between the depth bounds <= relativeTolerance
    DuplicateSupport,  ///< the new support point is already a polytope vertex: no progress left
    MaxIterations,     ///< iteration cap: depth is the lower bound, see lowerBound / upperBound
    CapacityExceeded,  ///< fixed vertex / face arrays full: as MaxIterations
    Degenerate,        ///< expansion would create a zero-area face: stopped with the current best
    Touching,          ///< during blow-up the origin was found on the boundary of A - B
    NotIntersecting,   ///< (penetration() only) GJK says separated
    InvalidInput,      ///< empty simplex / NaN
};

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

struct EpaResult {
    EpaStatus status = EpaStatus::InvalidInput;
    double depth = 0.0;                      ///< penetration depth, world units, >= 0
    Vec3 normal = Vec3::UnitX();             ///< unit, from A toward B (see file comment)
    Vec3 pointA = Vec3::Zero();              ///< deepest point of A in B, world frame
    Vec3 pointB = Vec3::Zero();              ///< deepest point of B in A, world frame
    int iterations = 0;
    EpaTermination termination = EpaTermination::InvalidInput;
    double lowerBound = 0.0;                 ///< depth >= lowerBound (distance of nearest face)
    double upperBound = 0.0;                 ///< depth <= upperBound (best support value)
    int vertexCount = 0;                     ///< polytope size at the end
    int faceCount = 0;
    bool edgePairRefined = false;            ///< depth and normal from the edge pair (options)
};

/// One EPA iteration as plain data. Vertex ids index `vertices`; faces are CCW seen from outside.
struct EpaTraceStep {
    int iteration = 0;
    std::vector<Vec3> vertices;                    ///< polytope vertices w = a - b (before expansion)
    std::vector<std::array<int, 3>> faces;         ///< live faces before expansion
    int closestFace = -1;                          ///< index into faces
    Vec3 closestNormal = Vec3::Zero();             ///< its outward unit normal
    double closestDistance = 0.0;                  ///< its distance to the origin (lower bound)
    Vec3 closestPoint = Vec3::Zero();              ///< projection of the origin on it
    Vec3 direction = Vec3::Zero();                 ///< support direction (= closestNormal)
    Vec3 support = Vec3::Zero();                   ///< new point w and its shape points a, b
    Vec3 supportA = Vec3::Zero();
    Vec3 supportB = Vec3::Zero();
    std::vector<std::array<int, 3>> removedFaces;  ///< faces visible from w (vertex ids)
    std::vector<std::array<int, 2>> horizon;       ///< horizon edges (vertex ids), in loop order
    double lowerBound = 0.0;
    double upperBound = 0.0;
    bool terminated = false;                       ///< loop stopped here (no expansion)
};

struct EpaTrace {
    std::string start;                       ///< how the first tetrahedron was made
    std::vector<Vec3> blowUpDirections;      ///< directions used to blow up a degenerate simplex
    std::vector<Vec3> blowUpPoints;          ///< the support points they gave
    std::vector<EpaTraceStep> steps;
    EpaTermination termination = EpaTermination::InvalidInput;
};

const char* nameOf(EpaStatus status);
const char* nameOf(EpaTermination termination);

namespace detail {

struct EpaVertex {
    Vec3 w, a, b;
};

struct EpaFace {
    int v[3];        // vertex ids, CCW seen from outside; edge e runs v[e] -> v[(e+1)%3]
    int adj[3];      // face across edge e
    int adjEdge[3];  // index of that edge in the neighbour
    Vec3 normal;     // outward unit normal
    double distance; // normal · (any vertex): signed distance of the plane from the origin
    bool live;
};

enum class EpaExpand { Ok, Degenerate, Capacity };

/// Convex polytope with fixed capacity (no heap). Non-template part of EPA.
class EpaPolytope {
public:
    static constexpr int kMaxVertices = 128;
    static constexpr int kMaxFaces = 256;

    EpaVertex vertex[kMaxVertices];
    int vertexCount = 0;
    EpaFace face[kMaxFaces];
    int faceEnd = 0;   // slots [0, faceEnd) have been used; dead ones sit in the free list
    int liveCount = 0;
    double scale = 0.0;  // max |w| over the vertices: the length scale for absolute tolerances

    int addVertex(const EpaVertex& v);
    /// Tetrahedron on vertices 0..3, oriented outward. False if a face has zero area.
    bool buildTetrahedron();
    /// Live face with the smallest distance, -1 if none.
    int closestFace() const;
    /// True if w equals a vertex of the polytope exactly.
    bool hasVertex(const Vec3& w) const;
    /// Remove all faces visible from vertex vi (flood fill from `seed`, which must be visible)
    /// and fan the horizon to vi. On failure the polytope is left unchanged.
    EpaExpand expand(int seed, int vi, double visibleTolerance, EpaTraceStep* trace);
    /// Witness points of the origin's projection on face f: depth * normal = sum l_i w_i.
    void witness(int f, double depth, Vec3& pointA, Vec3& pointB) const;
    /// Record vertices and live faces into a trace step; returns the index of face f in it.
    int snapshot(EpaTraceStep& step, int f) const;

private:
    int freeList[kMaxFaces];
    int freeCount = 0;
    int horizonFace[kMaxFaces];
    int horizonEdge[kMaxFaces];
    int horizonCount = 0;
    int removed[kMaxFaces];
    int removedCount = 0;
    bool overflow = false;

    bool plane(int i0, int i1, int i2, Vec3& normal, double& distance) const;
    void silhouette(int f, int edge, const Vec3& w, double tol);
};

/// Contact point of GJK's terminal simplex (for touching contacts).
void epaSimplexWitness(const EpaVertex* v, const SimplexClosest& c, Vec3& pointA, Vec3& pointB);

/// Final face f spanning exactly two points of A and two of B: depth, normal and witnesses from
/// the lines' common perpendicular (EpaOptions::refineEdgePairs). Refused (false, r unchanged)
/// when the feet leave the edges or the depth moves by more than EPA's rounding could explain;
/// the caller still certifies the plane with the supports.
bool epaRefineEdgePair(const EpaPolytope& poly, int f, EpaResult& r);

}  // namespace detail

/// Penetration depth of intersecting shapes A and B (world frame, world units) starting from
/// GJK's terminal simplex `start` (any size 1..4, containing the origin up to rounding). See the
/// file comment for the normal / witness convention. Never NaN for finite shapes.
template <SupportMapping A, SupportMapping B>
EpaResult epaPenetration(const A& shapeA, const B& shapeB, const GjkSimplex& start,
                         const EpaOptions& options = {}, EpaTrace* trace = nullptr)
{
    // Absolute tolerances relative to the polytope's scale max|w|: a support value, face distance
    // or plane test carries a rounding error of a few ulps of |w| (Sterbenz keeps w itself exact).
    constexpr double kTouch = 1e-14;    // origin within 1e-14 |w| of the boundary: touching
    constexpr double kVisible = 1e-14;  // w above a face plane by less than this: not visible
    constexpr double kAbsGap = 4.0 * 2.220446049250313e-16;  // gap noise floor (4 ulps of |w|)

    EpaResult r;
    detail::EpaPolytope poly;
    // Plain (cold) supports: successive EPA directions are face normals far apart, so starting a
    // hill climb at the previous answer costs more than the shape's own seeds (measured).
    auto support = [&](const Vec3& d, detail::EpaVertex& out) {
        out.a = shapeA.support(d);
        out.b = shapeB.support(-d);
        out.w = out.a - out.b;
    };
    auto stop = [&](EpaTermination why) {
        r.termination = why;
        if (trace) trace->termination = why;
        r.vertexCount = poly.vertexCount;
        r.faceCount = poly.liveCount;
        return r;
    };

    // 1. Seed: the distinct finite vertices of GJK's simplex, reduced to the smallest
    //    sub-simplex that holds the origin (a flat tetrahedron becomes a triangle, etc.).
    detail::EpaVertex seed[4];
    int n = 0;
    for (int i = 0; i < start.count && i < 4; ++i) {
        const GjkVertex& g = start.vertex[i];
        if (!g.w.allFinite() || !g.a.allFinite() || !g.b.allFinite()) return stop(EpaTermination::InvalidInput);
        bool dup = false;
        for (int j = 0; j < n; ++j) dup = dup || seed[j].w == g.w;
        if (!dup) seed[n++] = {g.w, g.a, g.b};
    }
    if (n == 0) return stop(EpaTermination::InvalidInput);
    {
        Vec3 wv[4];
        for (int i = 0; i < n; ++i) wv[i] = seed[i].w;
        const SimplexClosest c = closestSignedVolumes(wv, n);
        detail::EpaVertex kept[4];
        for (int k = 0; k < c.count; ++k) kept[k] = seed[c.index[k]];
        // Contact point for a touching answer: the point of the simplex nearest the origin.
        detail::epaSimplexWitness(seed, c, r.pointA, r.pointB);
        n = c.count;
        for (int k = 0; k < n; ++k) seed[k] = kept[k];
    }
    double scale = 0.0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, seed[i].w.norm());
    static const char* kStartName[5] = {"", "point", "segment", "triangle", "tetrahedron"};
    if (trace) trace->start = std::string(kStartName[n]) + (n < 4 ? " blown up" : " from GJK");

    // 2. Blow up a point / segment / triangle to a tetrahedron: add the support point along a
    //    direction orthogonal to its affine hull. If that support value is ~0, the whole of A - B
    //    lies behind the plane through the origin orthogonal to d: the origin is on the boundary,
    //    the shapes touch with normal d (depth <= h(d) ~ 0).
    while (n < 4) {
        Vec3 d;
        if (n == 1) {
            d = Vec3::UnitX();
        } else if (n == 2) {
            // Perpendicular to the segment via the axis it is least aligned with.
            const Vec3 u = seed[1].w - seed[0].w;
            int k = 0;
            if (std::abs(u[1]) < std::abs(u[k])) k = 1;
            if (std::abs(u[2]) < std::abs(u[k])) k = 2;
            d = u.cross(Vec3::Unit(k)).normalized();
        } else {
            d = (seed[1].w - seed[0].w).cross(seed[2].w - seed[0].w).normalized();
        }
        support(d, seed[n]);
        if (!seed[n].w.allFinite()) return stop(EpaTermination::InvalidInput);
        const double h = d.dot(seed[n].w);
        if (trace) {
            trace->blowUpDirections.push_back(d);
            trace->blowUpPoints.push_back(seed[n].w);
        }
        scale = std::max(scale, seed[n].w.norm());
        if (!(h > kTouch * scale)) {
            r.status = EpaStatus::Touching;
            r.depth = 0.0;
            r.normal = d;
            r.lowerBound = 0.0;
            r.upperBound = std::max(h, 0.0);
            return stop(EpaTermination::Touching);
        }
        ++n;
    }
    for (int i = 0; i < 4; ++i) poly.addVertex(seed[i]);
    if (!poly.buildTetrahedron()) {
        // Zero-volume start although every blow-up step gained height: only possible with
        // values at the rounding floor. Report touching along the first face's normal.
        r.status = EpaStatus::Touching;
        r.normal = (seed[1].w - seed[0].w).cross(seed[2].w - seed[0].w).normalized();
        if (!r.normal.allFinite()) r.normal = Vec3::UnitX();
        return stop(EpaTermination::Degenerate);
    }

    // 3. Expand.
    double upper = INFINITY;
    int f = -1;
    EpaTermination why = EpaTermination::MaxIterations;
    for (int iter = 1; iter <= options.maxIterations; ++iter) {
        r.iterations = iter;
        f = poly.closestFace();
        if (f < 0) {
            why = EpaTermination::Degenerate;
            break;
        }
        const detail::EpaFace& F = poly.face[f];
        const double lower = F.distance;
        detail::EpaVertex s;
        support(F.normal, s);
        if (!s.w.allFinite()) return stop(EpaTermination::InvalidInput);
        const double h = F.normal.dot(s.w);
        upper = std::min(upper, h);
        r.lowerBound = lower;
        r.upperBound = upper;
        EpaTraceStep* step = nullptr;
        if (trace) {
            trace->steps.emplace_back();
            step = &trace->steps.back();
            step->iteration = iter;
            step->closestFace = poly.snapshot(*step, f);
            step->closestNormal = F.normal;
            step->closestDistance = lower;
            step->closestPoint = lower * F.normal;
            step->direction = F.normal;
            step->support = s.w;
            step->supportA = s.a;
            step->supportB = s.b;
            step->lowerBound = lower;
            step->upperBound = upper;
        }
        scale = std::max({scale, poly.scale, s.w.norm()});
        // Relative gap: h(n_F) - d_F bounds both the depth error and |h(n) - depth| of the
        // reported normal. The absolute floor stops at the rounding level of near-zero depths.
        if (h - lower <= std::max(options.relativeTolerance * std::abs(h), kAbsGap * scale)) {
            why = EpaTermination::Converged;
            if (step) step->terminated = true;
            break;
        }
        // Support point already on the polytope: the polytope cannot grow, exit to avoid cycling.
        if (poly.hasVertex(s.w)) {
            why = EpaTermination::DuplicateSupport;
            if (step) step->terminated = true;
            break;
        }
        const int vi = poly.addVertex(s);
        if (vi < 0) {
            why = EpaTermination::CapacityExceeded;
            if (step) step->terminated = true;
            break;
        }
        const detail::EpaExpand e = poly.expand(f, vi, kVisible * scale, step);
        if (e != detail::EpaExpand::Ok) {
            --poly.vertexCount;  // expansion rolled back: drop the unused vertex
            why = e == detail::EpaExpand::Capacity ? EpaTermination::CapacityExceeded
                                                   : EpaTermination::Degenerate;
            if (step) step->terminated = true;
            break;
        }
        f = -1;
    }
    if (f < 0) f = poly.closestFace();
    if (f < 0) {
        r.status = EpaStatus::Touching;
        return stop(EpaTermination::Degenerate);
    }
    const detail::EpaFace& F = poly.face[f];
    // The origin may sit a rounding error outside the polytope (touching): clamp to 0.
    r.depth = std::max(F.distance, 0.0);
    r.normal = F.normal;
    r.lowerBound = F.distance;
    r.upperBound = upper;
    poly.witness(f, r.depth, r.pointA, r.pointB);
    if (options.refineEdgePairs) {
        // Certify the edge pair's plane with the supports: h_C(n) = n.(s_A(n) - s_B(-n)) bounds
        // the depth from above; equal to the refined depth up to rounding, the plane is a face
        // of A - B and the depth is exact.
        EpaResult refined = r;
        if (detail::epaRefineEdgePair(poly, f, refined)) {
            const Vec3& n = refined.normal;
            const Vec3 sa = shapeA.support(n), sb = shapeB.support(Vec3(-n));
            const double h = n.dot(sa) - n.dot(sb);
            const double m = std::max(sa.cwiseAbs().maxCoeff(), sb.cwiseAbs().maxCoeff());
            if (h <= refined.depth + 64.0 * 0x1p-53 * m) r = refined;
        }
    }
    r.status = r.depth <= kTouch * scale ? EpaStatus::Touching : EpaStatus::Penetrating;
    return stop(why);
}

/// GJK followed by EPA when the shapes intersect. Separated shapes give status Separated
/// (depth 0, normal = GJK's separating axis, witness points = GJK's closest points).
/// `gjkOut` optionally receives the GJK result (distance, simplex).
template <SupportMapping A, SupportMapping B>
EpaResult penetration(const A& shapeA, const B& shapeB, const EpaOptions& options = {},
                      EpaTrace* trace = nullptr, GjkResult* gjkOut = nullptr)
{
    const GjkResult g = gjkDistance(shapeA, shapeB, options.gjk);
    if (gjkOut) *gjkOut = g;
    if (g.status == GjkStatus::InvalidInput) {
        EpaResult r;
        if (trace) trace->termination = EpaTermination::InvalidInput;
        return r;
    }
    if (!g.intersect) {
        EpaResult r;
        r.status = EpaStatus::Separated;
        r.termination = EpaTermination::NotIntersecting;
        r.normal = g.separatingAxis;
        r.pointA = g.pointA;
        r.pointB = g.pointB;
        if (trace) trace->termination = r.termination;
        return r;
    }
    return epaPenetration(shapeA, shapeB, g.simplex, options, trace);
}

}  // namespace cdlab
