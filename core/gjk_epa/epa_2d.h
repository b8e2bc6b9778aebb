// EPA in the plane (the "expanding polygon"): penetration depth of two convex shapes lying in the
// z = 0 plane. core's 3D EPA (core/gjk_epa/epa.h) cannot take flat input: it blows GJK's triangle up to a
// tetrahedron along the plane normal, where the support value of planar shapes is 0, and reports
// Touching. This is the same algorithm one dimension down (van den Bergen, "Proximity Queries and
// Penetration Depth Computation on 3D Game Objects", GDC 2001; the 2D form as in the textbook
// figures): polygon P inside C = A − B containing the origin;
//   loop: e = edge of P nearest the origin (distance d_e: lower bound), w = s_C(n_e),
//         upper bound min(n_e · w); stop when n_e · w − d_e <= eps_rel n_e · w;
//         remove the edges visible from w (a contiguous chain), connect its two ends to w.
// Same conventions as core/gjk_epa/epa.h: normal from A toward B, pointA − pointB = depth · normal.
// Its results and trace use core's types and status enums; tests/core/gjk_epa/epa_2d_test.cpp checks it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/base/tolerances.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

/// One iteration: the polygon before expansion (CCW, z = 0) and what the iteration did.
struct Epa2dStep {
    int iteration = 0;
    std::vector<Vec3> vertices;  ///< polygon, counter-clockwise; edge i runs i -> i+1
    int closestEdge = -1;
    Vec3 closestNormal = Vec3::Zero();  ///< outward unit normal of the closest edge
    double closestDistance = 0.0;       ///< its distance from the origin (lower bound)
    Vec3 closestPoint = Vec3::Zero();
    Vec3 support = Vec3::Zero(), supportA = Vec3::Zero(), supportB = Vec3::Zero();
    std::vector<int> removedEdges;         ///< edges visible from the support point (replaced)
    std::array<int, 2> horizon{{-1, -1}};  ///< the two kept vertices that get connected to w
    double lowerBound = 0.0, upperBound = 0.0;
    bool terminated = false;
};

struct Epa2dTrace {
    std::string start;
    std::vector<Epa2dStep> steps;
    EpaTermination termination = EpaTermination::InvalidInput;
};

struct Epa2dResult {
    EpaStatus status = EpaStatus::InvalidInput;
    double depth = 0.0;
    Vec3 normal = Vec3::UnitX();
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    int iterations = 0;
    EpaTermination termination = EpaTermination::InvalidInput;
    double lowerBound = 0.0, upperBound = 0.0;
};

namespace detail {

/// A vertex of the expanding polygon: w = a − b with its two support points.
struct Epa2dVertex {
    Vec3 w, a, b;
};

/// Outward normal direction of a counter-clockwise edge e.
inline Vec3 epa2dPerp(const Vec3& e) { return Vec3(e.y(), -e.x(), 0.0); }

/// The state of one epaPenetration2d call, split into its steps: seed (GJK's simplex), blowUp (to a
/// counter-clockwise triangle), iterate (one expansion), finish (witness on the closest edge).
template <class A, class B>
struct Epa2dSolver {
    // Tolerances relative to the polygon's scale max|w|, as in core/gjk_epa/epa.h: support values and edge
    // distances carry a few ulps of |w| of rounding.
    static constexpr double kTouch = 1e-14;
    static constexpr double kAbsGap = ulps(4, 1.0);
    static constexpr int kMaxVertices = 256;

    const A& shapeA;
    const B& shapeB;
    const EpaOptions& options;
    Epa2dTrace* trace;
    Epa2dResult r;
    std::vector<Epa2dVertex> p;
    double scale = 0.0;
    double upper = INFINITY;
    int best = -1;
    Vec3 bestN = Vec3::UnitX();
    double bestD = 0.0;
    EpaTermination why = EpaTermination::MaxIterations;

    Epa2dSolver(const A& a, const B& b, const EpaOptions& o, Epa2dTrace* t)
        : shapeA(a), shapeB(b), options(o), trace(t) {}

    Epa2dVertex support(const Vec3& d) const {
        Epa2dVertex v{Vec3::Zero(), shapeA.support(d), shapeB.support(-d)};
        v.w = v.a - v.b;
        return v;
    }

    Epa2dResult stop(EpaTermination reason) {
        r.termination = reason;
        if (trace) trace->termination = reason;
        return r;
    }

    /// The distinct vertices of GJK's simplex; nullopt when usable, else the InvalidInput result.
    std::optional<Epa2dResult> seed(const GjkSimplex& start) {
        for (int i = 0; i < start.count && i < 3; ++i) {
            const GjkVertex& g = start.vertex[i];
            if (!g.w.allFinite()) return stop(EpaTermination::InvalidInput);
            bool dup = false;
            for (const Epa2dVertex& q : p) dup = dup || q.w == g.w;
            if (!dup) p.push_back({g.w, g.a, g.b});
        }
        if (p.empty()) return stop(EpaTermination::InvalidInput);
        for (const Epa2dVertex& q : p) scale = std::max(scale, q.w.norm());
        if (trace)
            trace->start = p.size() == 3 ? "triangle from GJK" : p.size() == 2 ? "segment blown up" : "point blown up";
        r.pointA = p[0].a;
        r.pointB = p[0].b;
        return std::nullopt;
    }

    /// Blow-up: a point gets the support along +x, a segment the support along its normal; a
    /// support value ~0 means the origin is on the boundary of C (touching). Leaves P a
    /// counter-clockwise triangle; nullopt unless touching.
    std::optional<Epa2dResult> blowUp() {
        while (p.size() < 3) {
            Vec3 d = p.size() == 1 ? Vec3::UnitX() : Vec3(epa2dPerp(p[1].w - p[0].w).normalized());
            Epa2dVertex s = support(d);
            scale = std::max(scale, s.w.norm());
            if (!(d.dot(s.w) > kTouch * scale)) {
                s = support(-d);
                if (!(-d.dot(s.w) > kTouch * scale)) {
                    r.status = EpaStatus::Touching;
                    r.normal = d;
                    return stop(EpaTermination::Touching);
                }
            }
            p.push_back(s);
        }
        // Counter-clockwise.
        if ((p[1].w - p[0].w).x() * (p[2].w - p[0].w).y() - (p[1].w - p[0].w).y() * (p[2].w - p[0].w).x() < 0)
            std::swap(p[1], p[2]);
        return std::nullopt;
    }

    /// One expansion of P; false when the loop ends (`why` then says why).
    bool iterate(int iter) {
        r.iterations = iter;
        const int n = int(p.size());
        std::vector<Vec3> normal(n);
        std::vector<double> dist(n);
        best = -1;
        for (int i = 0; i < n; ++i) {
            const Vec3 e = p[(i + 1) % n].w - p[i].w;
            const double len = e.norm();
            if (!(len > 0)) continue;
            normal[i] = epa2dPerp(e) / len;
            dist[i] = normal[i].dot(p[i].w);
            if (best < 0 || dist[i] < dist[best]) best = i;
        }
        if (best < 0) {
            why = EpaTermination::Degenerate;
            return false;
        }
        bestN = normal[best];
        bestD = dist[best];
        const Epa2dVertex s = support(bestN);
        const double h = bestN.dot(s.w);
        upper = std::min(upper, h);
        scale = std::max(scale, s.w.norm());
        Epa2dStep* step = nullptr;
        if (trace) {
            trace->steps.emplace_back();
            step = &trace->steps.back();
            step->iteration = iter;
            for (const Epa2dVertex& q : p) step->vertices.push_back(q.w);
            step->closestEdge = best;
            step->closestNormal = bestN;
            step->closestDistance = bestD;
            step->closestPoint = bestD * bestN;
            step->support = s.w;
            step->supportA = s.a;
            step->supportB = s.b;
            step->lowerBound = bestD;
            step->upperBound = upper;
        }
        r.lowerBound = bestD;
        r.upperBound = upper;
        if (h - bestD <= std::max(options.relativeTolerance * std::abs(h), kAbsGap * scale)) {
            why = EpaTermination::Converged;
            if (step) step->terminated = true;
            return false;
        }
        bool dup = false;
        for (const Epa2dVertex& q : p) dup = dup || q.w == s.w;
        if (dup || n >= kMaxVertices) {
            why = dup ? EpaTermination::DuplicateSupport : EpaTermination::CapacityExceeded;
            if (step) step->terminated = true;
            return false;
        }
        // Edges visible from w form a chain around `best` (P is convex): grow it both ways.
        const double tol = kTouch * scale;  // w above an edge line by less than this: not visible
        auto visible = [&](int i) { return normal[i].dot(s.w - p[i].w) > tol; };
        int first = best, last = best, count = 1;
        while (count < n && visible((first + n - 1) % n)) first = (first + n - 1) % n, ++count;
        while (count < n && visible((last + 1) % n)) last = (last + 1) % n, ++count;
        if (count >= n) {  // cannot happen for an origin inside P; stop rather than loop
            why = EpaTermination::Degenerate;
            if (step) step->terminated = true;
            return false;
        }
        if (step) {
            for (int k = 0, i = first; k < count; ++k, i = (i + 1) % n) step->removedEdges.push_back(i);
            step->horizon = {first, (last + 1) % n};
        }
        // New polygon: from vertex last+1 around to vertex first, then w.
        std::vector<Epa2dVertex> next;
        for (int i = (last + 1) % n;; i = (i + 1) % n) {
            next.push_back(p[i]);
            if (i == first) break;
        }
        next.push_back(s);
        p = std::move(next);
        return true;
    }

    /// The result after the loop: the witness is the origin's projection on the closest edge, in
    /// barycentric form on its two vertices.
    Epa2dResult finish() {
        if (best < 0) {
            r.status = EpaStatus::Touching;
            return stop(EpaTermination::Degenerate);
        }
        const int n = int(p.size());
        int e = 0;
        double ed = INFINITY;
        for (int i = 0; i < n; ++i) {
            const Vec3 d = p[(i + 1) % n].w - p[i].w;
            if (!(d.norm() > 0)) continue;
            const double di = (epa2dPerp(d) / d.norm()).dot(p[i].w);
            if (di < ed) ed = di, e = i, bestN = epa2dPerp(d) / d.norm();
        }
        const Epa2dVertex& v0 = p[e];
        const Epa2dVertex& v1 = p[(e + 1) % n];
        const Vec3 seg = v1.w - v0.w;
        const double t = std::clamp((ed * bestN - v0.w).dot(seg) / seg.squaredNorm(), 0.0, 1.0);
        r.depth = std::max(ed, 0.0);
        r.normal = bestN;
        r.pointA = v0.a + t * (v1.a - v0.a);
        r.pointB = v0.b + t * (v1.b - v0.b);
        r.lowerBound = ed;
        r.upperBound = upper;
        r.status = r.depth <= kTouch * scale ? EpaStatus::Touching : EpaStatus::Penetrating;
        return stop(why);
    }
};

}  // namespace detail

/// Penetration of planar shapes A, B (z = 0, world frame) from GJK's terminal simplex.
template <class A, class B>
Epa2dResult epaPenetration2d(const A& shapeA, const B& shapeB, const GjkSimplex& start, const EpaOptions& options,
                             Epa2dTrace* trace = nullptr) {
    detail::Epa2dSolver<A, B> solver(shapeA, shapeB, options, trace);
    if (auto early = solver.seed(start)) return *early;
    if (auto early = solver.blowUp()) return *early;
    for (int iter = 1; iter <= options.maxIterations; ++iter)
        if (!solver.iterate(iter)) break;
    return solver.finish();
}

}  // namespace cdlab
