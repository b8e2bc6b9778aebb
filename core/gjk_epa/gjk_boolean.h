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

// The origin's side of a plane through `a` with normal `normal`: +1 in front by more than margin,
// -1 behind by more than margin, 0 within it.
inline int side(const Vec3& normal, const Vec3& a, double margin) {
    const double s = -normal.dot(a), band = margin * normal.norm();
    return s > band ? 1 : s < -band ? -1 : 0;
}

// Segment [b, a] (a newest): the segment's interior or a alone (the region beyond b is impossible:
// a was found beyond the origin along the previous direction).
inline bool line(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    const Vec3 a = p[1], ab = p[0] - a, ao = -a;
    if (ab.dot(ao) > 0.0) {
        d = ab.cross(ao).cross(ab);
        if (!(d.norm() > margin * ab.norm() * ab.norm())) return false;  // origin on the line
        return true;
    }
    p[0] = a;
    n = 1;
    d = ao;
    return ao.norm() > margin;
}

// Triangle (c, b, a), a newest: an edge through a, or the face (d along its normal on the
// origin's side, the vertices ordered so that d = (b − a) x (c − a)).
inline bool triangle(Vec3 (&p)[4], int& n, Vec3& d, double margin) {
    const Vec3 a = p[2], b = p[1], c = p[0];
    const Vec3 ab = b - a, ac = c - a, ao = -a, abc = ab.cross(ac);
    // Collinear within 1e-12 (the sine of the angle at a): no plane to decide by.
    if (!(abc.norm() > 1e-12 * std::max(ab.squaredNorm(), ac.squaredNorm()))) return false;
    if (abc.cross(ac).dot(ao) > 0.0) {  // beyond edge ac
        if (ac.dot(ao) > 0.0) {
            p[0] = c, p[1] = a, n = 2;
            d = ac.cross(ao).cross(ac);
            return d.norm() > margin * ac.squaredNorm();
        }
        p[0] = b, p[1] = a, n = 2;
        return line(p, n, d, margin);
    }
    if (ab.cross(abc).dot(ao) > 0.0) {  // beyond edge ab
        p[0] = b, p[1] = a, n = 2;
        return line(p, n, d, margin);
    }
    const int s = side(abc, a, margin);
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
    const Vec3 abc = ab.cross(ac), acd = ac.cross(ad), adb = ad.cross(ab);
    const int sAbc = side(abc, a, margin), sAcd = side(acd, a, margin), sAdb = side(adb, a, margin);
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
        case 1: d = -p[0]; return p[0].norm() > margin;
        case 2: return gjk_boolean::line(p, n, d, margin);
        case 3: return gjk_boolean::triangle(p, n, d, margin);
        default: return gjk_boolean::tetrahedron(p, n, d, margin);
    }
}

/// The fast path itself: support points of A − B from `support(d, w)` (w = s_A(d) − s_B(−d)),
/// starting along +x as the full loop does. iterations: support points taken.
template <class Support>
QuickBoolean gjkQuickBoolean(Support&& support, int& iterations) {
    // 1e-12 of the coordinates: ~5000 ulps, above the rounding of every dot and cross product here.
    constexpr double kMargin = 1e-12;
    constexpr int kMaxIterations = 32;  // polytopes need a handful; smooth shapes go to the full loop
    Vec3 p[4];
    int n = 0;
    Vec3 d = Vec3::UnitX();
    double size = 0.0;
    for (iterations = 1; iterations <= kMaxIterations; ++iterations) {
        Vec3 w;
        support(d, w);
        if (!w.allFinite()) return QuickBoolean::Undecided;
        size = std::max(size, w.cwiseAbs().maxCoeff());
        const double margin = kMargin * size;
        const double reach = w.dot(d), band = margin * d.norm();
        if (reach < -band) return QuickBoolean::Separated;
        if (!(reach > band)) return QuickBoolean::Undecided;  // a support plane through the origin
        p[n++] = w;
        if (!gjkBooleanSimplexStep(p, n, d, margin)) return QuickBoolean::Undecided;
        if (n == 4) return QuickBoolean::Intersecting;
    }
    return QuickBoolean::Undecided;
}

}  // namespace cdlab::detail
