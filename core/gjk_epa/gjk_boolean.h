// The boolean GJK's fast path: does A − B contain the origin? Decided only with a margin, else left
// to the full GJK loop (core/gjk_epa/gjk.h), which gjkIntersect runs then.
//
// GJK for intersection alone (Gilbert, Johnson, Keerthi 1988; van den Bergen, "Collision
// Detection in Interactive 3D Environments", §4.3.6; Ericson, "Real-Time Collision Detection",
// §9.5): no closest point and no barycentric weights. Each step adds the support point w of A − B
// along the search direction d and keeps the feature of the simplex whose Voronoi region holds the
// origin, searching on perpendicular to it towards the origin. Two answers are proofs:
//   - separated: w · d < 0, so every point x of A − B has x · d <= w · d < 0 and the origin is not in it;
//   - intersecting: a tetrahedron of points of A − B (inside it, by convexity) holds the origin.
// Both are taken only when the origin clears the plane by more than kMargin of the largest support
// coordinate (rounding is ~1e-16 of it): touching within that band, a degenerate simplex or a stall
// is Undecided, and the full loop decides it (its touching rules, its exact flat-simplex test).
#pragma once

#include <algorithm>

#include "core/base/types.h"

namespace cdlab::detail {

enum class QuickBoolean { Separated, Intersecting, Undecided };

/// Keeps the feature of the simplex p[0..n) (p[n-1] the newest point a) nearest the origin and sets
/// d towards the origin, perpendicular to that feature; n == 4 on return: the origin is inside the
/// tetrahedron. False when the answer is within `margin` (world units) of a plane or the simplex
/// is degenerate.
inline bool gjkBooleanSimplexStep(Vec3 (&p)[4], int& n, Vec3& d, double margin);

namespace gjk_boolean {

// |v| > length, compared squared (no square root; an underflow or overflow of the squares, or a
// NaN, only makes the fast path give up, never decide).
inline bool longer(const Vec3& v, double length) { return v.squaredNorm() > length * length; }

// The sign of s where |s| clears a band (given squared, so no square root is taken): +1 or -1, and 0
// within the band or for NaN (an overflow near the double limit: give up, never decide).
inline int clearSign(double s, double bandSquared) {
    if (!(s * s > bandSquared)) return 0;
    return s > 0.0 ? 1 : -1;
}

// The origin's side of the plane through `a` with normal = e1 x e2 (the caller's cross product): +1
// in front by more than the band, -1 behind by more, 0 within it or NaN. The band is the margin plus
// the rounding of the cross product, ~u |e1| |e2| |a|, which dominates on a sliver face (e1, e2 nearly
// parallel: the computed normal's direction is off by ~u / sine). Both enter through a bound without
// square roots: (m |n| + c |e1| |e2| |a|)^2 <= 2 (m^2 + c^2 |a|^2) |e1|^2 |e2|^2, as |n| <= |e1| |e2|.
// The squared norms e1², e2² and the factor 2 (m² + c² |a|²) are given (shared between faces).
inline int sideOf(const Vec3& normal, double e1Squared, double e2Squared, const Vec3& a, double aFactor) {
    return clearSign(-normal.dot(a), aFactor * e1Squared * e2Squared);
}
inline double sideFactor(const Vec3& a, double margin) {
    constexpr double kRounding = 16.0 * 1.1102230246251565e-16;  // 16 u: the cross and dot products' error
    return 2.0 * (margin * margin + kRounding * kRounding * a.squaredNorm());
}
inline int sideOf(const Vec3& e1, const Vec3& e2, const Vec3& a, double margin) {
    return sideOf(e1.cross(e2), e1.squaredNorm(), e2.squaredNorm(), a, sideFactor(a, margin));
}

// Segment [b, a] (a newest): the segment's interior or a alone (the region beyond b is impossible:
// a was found beyond the origin along the previous direction).
inline bool line(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    const Vec3 a = p[1], ab = p[0] - a, ao = -a;
    if (ab.dot(ao) > 0.0) {
        d = ab.cross(ao).cross(ab);
        if (!longer(d, margin * ab.squaredNorm())) return false;  // origin on the line
        return true;
    }
    p[0] = a;
    n = 1;
    d = ao;
    return longer(ao, margin);
}

// Triangle (c, b, a), a newest: an edge through a, or the face (d along its normal on the
// origin's side, the vertices ordered so that d = (b − a) x (c − a)).
inline bool triangle(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    const Vec3 a = p[2], b = p[1], c = p[0];
    const Vec3 ab = b - a, ac = c - a, ao = -a, abc = ab.cross(ac);
    // Collinear within 1e-12 (the sine of the angle at a): no plane to decide by.
    const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
    if (!longer(abc, 1e-12 * std::max(ab2, ac2))) return false;
    if (abc.cross(ac).dot(ao) > 0.0) {  // beyond edge ac
        if (ac.dot(ao) > 0.0) {
            p[0] = c, p[1] = a, n = 2;
            d = ac.cross(ao).cross(ac);
            return longer(d, margin * ac2);
        }
        p[0] = b, p[1] = a, n = 2;
        return line(p, n, d, margin);
    }
    if (ab.cross(abc).dot(ao) > 0.0) {  // beyond edge ab
        p[0] = b, p[1] = a, n = 2;
        return line(p, n, d, margin);
    }
    const int s = sideOf(abc, ab2, ac2, a, sideFactor(a, margin));
    if (s == 0) return false;  // the origin on the triangle's plane (touching)
    if (s > 0) {
        d = abc;  // keep (c, b, a)
    } else {
        p[0] = b, p[1] = c;  // (b, c, a): its normal ab x ac flips towards the origin
        d = -abc;
    }
    return true;
}

// Tetrahedron (d0, c, b, a), a newest, built on the triangle (d0, c, b) whose normal points at the
// origin and at a: the origin is beyond one of the three new faces, or inside.
inline bool tetrahedron(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    const Vec3 a = p[3], b = p[2], c = p[1], d0 = p[0];
    const Vec3 ab = b - a, ac = c - a, ad = d0 - a;
    const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm(), ad2 = ad.squaredNorm(), f = sideFactor(a, margin);
    const int sAbc = sideOf(ab.cross(ac), ab2, ac2, a, f), sAcd = sideOf(ac.cross(ad), ac2, ad2, a, f),
              sAdb = sideOf(ad.cross(ab), ad2, ab2, a, f);
    if (sAbc > 0) {
        p[0] = c, p[1] = b, p[2] = a, n = 3;
        return triangle(p, n, d, margin);
    }
    if (sAcd > 0) {
        p[0] = d0, p[1] = c, p[2] = a, n = 3;
        return triangle(p, n, d, margin);
    }
    if (sAdb > 0) {
        p[0] = b, p[1] = d0, p[2] = a, n = 3;
        return triangle(p, n, d, margin);
    }
    return sAbc < 0 && sAcd < 0 && sAdb < 0;  // inside, clear of every new face; else on one
}

}  // namespace gjk_boolean

inline bool gjkBooleanSimplexStep(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    switch (n) {
        case 1: d = -p[0]; return gjk_boolean::longer(p[0], margin);
        case 2: return gjk_boolean::line(p, n, d, margin);
        case 3: return gjk_boolean::triangle(p, n, d, margin);
        default: return gjk_boolean::tetrahedron(p, n, d, margin);
    }
}

/// The fast path itself: support points of A − B from `support(d, w)` (w = s_A(d) − s_B(−d)),
/// starting along +x as the full loop does, or from `start` when given: any point of A − B (a
/// vertex of A minus one of B), the first simplex without a support call, searched from towards the
/// origin. iterations: support points taken.
template <class Support>
QuickBoolean gjkQuickBoolean(Support&& support, int& iterations, const Vec3* start = nullptr) {
    // 1e-12 of the coordinates: ~5000 ulps, above the rounding of every dot and cross product here.
    constexpr double kMargin = 1e-12;
    constexpr int kMaxIterations = 32;  // polytopes need a handful; smooth shapes go to the full loop
    Vec3 p[4];
    int n = 0;
    Vec3 d = Vec3::UnitX();
    double size = 0.0;
    iterations = 0;
    if (start) {
        if (!start->allFinite()) return QuickBoolean::Undecided;
        size = start->cwiseAbs().maxCoeff();
        p[n++] = *start;
        // The origin at the start point (within the margin): touching or deep, the loop decides.
        if (!gjkBooleanSimplexStep(p, n, d, kMargin * size)) return QuickBoolean::Undecided;
    }
    for (iterations = 1; iterations <= kMaxIterations; ++iterations) {
        Vec3 w;
        support(d, w);
        if (!w.allFinite()) return QuickBoolean::Undecided;
        size = std::max(size, w.cwiseAbs().maxCoeff());
        const double margin = kMargin * size;
        // w · d against margin |d|: within it, a support plane through the origin (or NaN).
        const int reach = gjk_boolean::clearSign(w.dot(d), margin * margin * d.squaredNorm());
        if (reach == 0) return QuickBoolean::Undecided;
        if (reach < 0) return QuickBoolean::Separated;
        p[n++] = w;
        if (!gjkBooleanSimplexStep(p, n, d, margin)) return QuickBoolean::Undecided;
        if (n == 4) return QuickBoolean::Intersecting;
    }
    return QuickBoolean::Undecided;
}

/// A point of the shape without a support call, where it has one to hand (a polytope's first
/// vertex): the boolean fast path starts from their difference.
template <class S>
bool anyPointOf(const S& shape, Vec3& point) {
    if constexpr (requires { shape.vertexCount(); shape.vertex(0); }) {
        if (shape.vertexCount() == 0) return false;
        point = shape.vertex(0);
        return true;
    } else {
        return false;
    }
}

}  // namespace cdlab::detail
