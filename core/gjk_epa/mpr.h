// Minkowski Portal Refinement: does A − B contain the origin? (the lectures' "finding a common
// point"). Snethen, "XenoCollide: Complex Collision Made Simple", Game Programming Gems 7 (2008),
// §2.5; the same algorithm as libccd's ccdMPRIntersect.
//
// A point v0 inside A − B (an interior point of A minus one of B) and the ray from it towards the
// origin. Phase 1 finds a portal: a triangle (v1, v2, v3) of support points that the ray passes
// through. Phase 2 pushes the portal outwards along its normal until either the origin lies on v0's
// side of it (inside the tetrahedron v0 v1 v2 v3 of points of A − B: intersecting) or a support plane
// has the origin beyond it (separated).
//
// Decided only with a margin, as the boolean GJK fast path (core/gjk_epa/gjk_boolean.h): a support
// plane beyond the origin by more than 1e-12 of the coordinates, or the origin inside the
// tetrahedron clear of all four faces by that much. Touching within the margin, a degenerate
// portal, a portal that stops on the boundary with the origin within its tolerance, or too many
// steps give Undecided, and mprIntersect runs gjkIntersect's full loop (its touching rules, its
// exact flat-simplex test): the answer is always the loop's where the loop is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/base/support.h"
#include "core/base/types.h"
#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/gjk_boolean.h"

namespace cdlab {

enum class MprOutcome { Separated, Intersecting, Undecided };

struct MprResult {
    MprOutcome outcome = MprOutcome::Undecided;
    int supports = 0;  // support points of A − B taken (one per support call on each shape)
};

namespace detail {

// w = s_A(d) − s_B(−d), a point of A − B extreme along d. No climbing hints: MPR's directions
// jump between unrelated sides, where a hint from the last call only lengthens the climb.
template <class A, class B>
Vec3 mprSupport(const A& shapeA, const B& shapeB, const Vec3& d, int& count) {
    ++count;
    return shapeA.support(d) - shapeB.support(Vec3(-d));
}

}  // namespace detail

/// The MPR decision alone: Undecided where it cannot prove an answer (see the file comment).
/// `interiorA` must be a point of A and `interiorB` one of B (a vertex centroid, a centre); strictly
/// inside is best: on the boundary the portal may be degenerate and the answer Undecided.
template <SupportMapping A, SupportMapping B>
MprResult mprDecide(const A& shapeA, const Vec3& interiorA, const B& shapeB, const Vec3& interiorB) {
    constexpr double kMargin = 1e-12;   // of the coordinates, as the boolean GJK (gjk_boolean.h)
    constexpr int kMaxSteps = 64;       // polytopes need a handful; curved sets converge slowly: Undecided
    MprResult r;
    const auto support = [&](const Vec3& d) { return detail::mprSupport(shapeA, shapeB, d, r.supports); };
    const Vec3 v0 = interiorA - interiorB;
    if (!v0.allFinite()) return r;
    double size = v0.cwiseAbs().maxCoeff();
    const auto margin = [&](const Vec3& w) {
        size = std::max(size, w.cwiseAbs().maxCoeff());
        return kMargin * size;
    };
    // s against the band margin(w) |n| (gjk_boolean.h: clearSign): +1, -1, or 0 within it or NaN.
    const auto beyondBand = [&](double s, const Vec3& n, const Vec3& w) {
        const double m = margin(w);
        return detail::gjk_boolean::clearSign(s, m * m * n.squaredNorm());
    };
    // The support point w along n: with the origin beyond its plane, a proof of separation (the
    // outcome set); through the origin within the band, touching (Undecided). True: stop there.
    const auto stopsAt = [&](const Vec3& n, const Vec3& w) {
        const int s = beyondBand(w.dot(n), n, w);
        if (s < 0) r.outcome = MprOutcome::Separated;
        return s <= 0;
    };

    // Phase 1: a portal the ray from v0 towards the origin passes through.
    if (!(v0.squaredNorm() > margin(v0) * margin(v0))) return r;  // the origin at the interior point: let the loop decide
    Vec3 n = -v0;
    Vec3 v1 = support(n);
    if (!v1.allFinite()) return r;
    if (stopsAt(n, v1)) return r;
    n = v1.cross(v0);
    if (!(n.squaredNorm() > margin(v1) * margin(v1) * v1.squaredNorm())) return r;  // the origin on the line v0 v1
    Vec3 v2 = support(n);
    if (stopsAt(n, v2)) return r;
    n = (v1 - v0).cross(v2 - v0);
    if (n.dot(v0) > 0.0) {  // orient (v1, v2) so that n points from v0's plane towards the origin
        std::swap(v1, v2);
        n = -n;
    }
    Vec3 v3;
    for (int step = 0;; ++step) {
        if (step == kMaxSteps || !(n.squaredNorm() > 0.0)) return r;
        v3 = support(n);
        if (stopsAt(n, v3)) return r;
        if (v1.cross(v3).dot(v0) < 0.0) {  // the origin outside the plane (v0, v1, v3): drop v2
            v2 = v3;
            n = (v1 - v0).cross(v3 - v0);
            continue;
        }
        if (v3.cross(v2).dot(v0) < 0.0) {  // outside (v0, v3, v2): drop v1
            v1 = v3;
            n = (v3 - v0).cross(v2 - v0);
            continue;
        }
        break;
    }

    // Phase 2: refine the portal (v1, v2, v3); its normal points away from v0.
    for (int step = 0; step < kMaxSteps; ++step) {
        n = (v2 - v1).cross(v3 - v1);
        if (!(n.squaredNorm() > 0.0)) return r;  // a degenerate portal
        const double band = margin(v1);
        // Face sides clear of the margin and of the cross products' rounding, which on a sliver
        // portal (nearly collinear points) turns the computed normal (gjk_boolean.h: sideOf).
        const int portal = detail::gjk_boolean::sideOf(n, (v2 - v1).squaredNorm(), (v3 - v1).squaredNorm(), v1,
                                                       detail::gjk_boolean::sideFactor(v1, band));  // +1: beyond
        if (portal < 0) {
            // On v0's side of the portal: inside the tetrahedron v0 v1 v2 v3 (positively oriented:
            // each face normal below points towards the fourth vertex) if clear of its three other
            // faces too.
            const bool clear = (v1 - v0).cross(v2 - v0).dot(v3 - v0) > 0.0 &&
                               detail::gjk_boolean::sideOf(Vec3(v1 - v0), Vec3(v2 - v0), v0, band) > 0 &&
                               detail::gjk_boolean::sideOf(Vec3(v2 - v0), Vec3(v3 - v0), v0, band) > 0 &&
                               detail::gjk_boolean::sideOf(Vec3(v3 - v0), Vec3(v1 - v0), v0, band) > 0;
            if (clear) r.outcome = MprOutcome::Intersecting;
            return r;
        }
        if (portal == 0) return r;  // the origin on the portal's plane
        const Vec3 v4 = support(n);
        if (stopsAt(n, v4)) return r;
        // No progress: the portal lies on the boundary of A − B and the origin is beyond the portal
        // by less than the support plane's lead, within rounding of the boundary: leave it.
        if (beyondBand((v4 - v3).dot(n), n, v4) <= 0) return r;
        // The new portal: the one of the three triangles around v4 that the ray still crosses.
        const Vec3 t = v4.cross(v0);
        if (v1.dot(t) > 0.0) {
            if (v2.dot(t) > 0.0) v1 = v4;
            else v3 = v4;
        } else {
            if (v3.dot(t) > 0.0) v2 = v4;
            else v1 = v4;
        }
    }
    return r;
}

/// Boolean intersection by MPR: the MPR decision where it proves one, else gjkIntersect's full loop.
/// Same answer as gjkIntersect for every input where either is exact (see the file comment);
/// `interiorA` / `interiorB` as for mprDecide.
template <SupportMapping A, SupportMapping B>
bool mprIntersect(const A& shapeA, const Vec3& interiorA, const B& shapeB, const Vec3& interiorB,
                  MprResult* result = nullptr) {
    MprResult r = mprDecide(shapeA, interiorA, shapeB, interiorB);
    if (result) *result = r;
    if (r.outcome != MprOutcome::Undecided) return r.outcome == MprOutcome::Intersecting;
    GjkResult g;
    const bool hit = gjkIntersect(shapeA, shapeB, {}, nullptr, &g);
    if (result) result->supports += g.iterations;
    return hit;
}

}  // namespace cdlab
