// Polishing GJK's distance and EPA's depth where the shapes are curved.
//
// Both answers are one minimum over unit directions m of the support function of A − B,
//   g(m) = h_A(m) + h_B(−m) = max over A of m·x − min over B of m·x:
// separated shapes: distance = −min g, at m = the axis from A toward B; overlapping: depth = min g,
// at m = the normal along which b is pushed out (van den Bergen 2003, §4.3.8: the penetration
// depth is the distance from the origin to the boundary of A − B; Gilbert & Foo 1990 for the
// distance as the same minimum). On polytopes GJK and EPA land on a vertex of the Gauss map and
// are exact; on a cylinder, cone or sphere the minimum sits on a smooth patch where GJK's simplex
// shrinks to nearly coincident points and EPA needs ever more faces, and both stop ~1e-8 short.
//
// refineDirection takes such an answer's m and minimises g on the sphere in two stages.
//  1. A pattern search (Hooke & Jeeves 1961): steps of angle s along ± two tangents and their
//     diagonals, a step kept when it lowers g beyond rounding, s halved down to 1e-15 rad when no
//     step gains and doubled after two that do.
//     It needs no derivative, so it also walks along a ridge of g — a cylinder's side, where the
//     support point jumps between the two rims as m crosses the plane normal to the axis — and
//     pins the direction across the ridge to rounding; but on a smooth patch g is flat at the
//     minimum (an angle ε costs ~ε²), so values alone stop ~1e-8 from it there.
//  2. Newton's method in the tangent plane for the smooth directions: the gradient of g at m is
//     the tangential part of p = s_A(m) − s_B(−m) (the support point of A − B is the gradient of
//     its support function), the Hessian the tangential derivative of p (the radii of curvature
//     of A − B, by a finite difference of supports) minus g·I (the sphere's own curvature). The
//     gradient shrinks like ε where values cannot tell, so a step is kept when g does not rise
//     beyond rounding and the gradient shrinks. At a kink the gradient shrinks under no step.
// An answer that is exact already (a face, an edge: a kink of g in every direction) gains nothing
// beyond rounding from any step and is returned unchanged, steps = 0.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/base/tolerances.h"
#include "core/base/types.h"

namespace cdlab {

struct DirectionRefinement {
    Vec3 direction = Vec3::UnitX();  ///< unit m: the refined axis (from A toward B)
    double value = 0.0;              ///< g(m): −distance when separated, the depth when overlapping
    int steps = 0;                   ///< Newton steps kept (0: the input was already the minimum)
};

namespace detail {

/// The rounding floor of g(m) = m·(s_A(m) − s_B(−m)) and of its gradient, in ulps of the scale of
/// A − B: a step that gains less, or a gradient below it, is rounding, not progress.
inline constexpr double kRefinementFloorUlps = 8;

/// p = s_A(m) − s_B(−m), the support point of A − B along m.
template <class A, class B>
Vec3 differenceSupport(const A& a, const B& b, const Vec3& m) {
    return Vec3(a.support(m)) - Vec3(b.support(Vec3(-m)));
}

/// The tangent directions at m along which g is smooth: both (a smooth patch of A − B), one (a
/// ridge: one shape's support point jumps along a segment J — an edge of a polytope, the side of a
/// cylinder — as m crosses the great circle normal to J, so g is smooth along that circle and
/// kinked across it), or none (both shapes jump, or one jumps two ways: a face or a corner). A jump
/// is a support point moving by more than 100·delta·scale for a turn of ±delta.
/// The ridge's direction e must be normal to J to rounding, else the gradient along it mixes in
/// the kink (e·J). J is measured on the jumping shape alone, so the other shape's smooth motion
/// stays out of it, and again across J's own tangential direction: a cylinder's rim points then
/// keep their azimuth to second order, and two passes more leave rounding.
struct SmoothDirections {
    Vec3 e[2] = {Vec3::Zero(), Vec3::Zero()};
    int count = 0;
};

template <class A, class B>
SmoothDirections smoothDirections(const A& a, const B& b, const Vec3& m, double delta, double scale) {
    // Support motion of A (along m) or of B (along −m) for a turn of m by ±delta toward t.
    const auto jumpA = [&](const Vec3& t) {
        return Vec3(Vec3(a.support(Vec3((m + delta * t).normalized()))) -
                    Vec3(a.support(Vec3((m - delta * t).normalized()))));
    };
    const auto jumpB = [&](const Vec3& t) {
        return Vec3(Vec3(b.support(Vec3(-(m - delta * t).normalized()))) -
                    Vec3(b.support(Vec3(-(m + delta * t).normalized()))));
    };
    const double limit = 100 * delta * scale;
    const Vec3 t1 = m.unitOrthogonal(), t2 = m.cross(t1);
    const Vec3 a1 = jumpA(t1), a2 = jumpA(t2), b1 = jumpB(t1), b2 = jumpB(t2);
    const bool aJumps = std::max(a1.norm(), a2.norm()) > limit, bJumps = std::max(b1.norm(), b2.norm()) > limit;
    SmoothDirections s;
    if (!aJumps && !bJumps) {
        s.e[0] = t1, s.e[1] = t2, s.count = 2;
        return s;
    }
    if (aJumps && bJumps) return s;
    const auto jump = [&](const Vec3& t) { return aJumps ? jumpA(t) : jumpB(t); };
    Vec3 j = aJumps ? (a1.norm() >= a2.norm() ? a1 : a2) : (b1.norm() >= b2.norm() ? b1 : b2), across = Vec3::Zero();
    for (int pass = 0; pass < 3; ++pass) {
        const Vec3 tangential = j - m.dot(j) * m;
        if (!(tangential.norm() > limit)) return s;  // a jump along m itself: no ridge to follow
        across = tangential.normalized();
        j = jump(across);
    }
    s.e[0] = m.cross(across).normalized();
    // Along the ridge the other shape moves smoothly and this one stays or flips between J's ends.
    const Vec3 other = aJumps ? jumpB(s.e[0]) : jumpA(s.e[0]);
    if (other.norm() <= limit && jump(s.e[0]).cross(j).norm() <= limit * j.norm()) s.count = 1;
    return s;
}

}  // namespace detail

/// Minimises g from the unit direction m; `scale` is the size of A − B (the step of the finite
/// difference and the rounding floor of g are relative to it). `firstAngle`: the pattern search's
/// first step, about the error of m (a start far off costs a few doublings more).
template <class A, class B>
DirectionRefinement refineDirection(const A& a, const B& b, const Vec3& m, double scale, double firstAngle = 1e-3) {
    DirectionRefinement r;
    r.direction = m.normalized();
    r.value = r.direction.dot(detail::differenceSupport(a, b, r.direction));
    // A few ulps of g: a step that gains less is rounding, not progress.
    const double floor = ulps(detail::kRefinementFloorUlps, scale);
    // Finite-difference angle: ~cube root of the precision, a balance of truncation (~δ) and
    // rounding (~u/δ) in the curvature; the Newton step only needs it to a few digits.
    const double delta = 1e-6;
    const auto valueAt = [&](const Vec3& n) { return n.dot(detail::differenceSupport(a, b, n)); };
    // Stage 1: from firstAngle, halving when no move gains, doubling after two gains in a row (a
    // start far from the minimum walks there in a few doublings); a budget bounds the evaluations.
    double angle = std::clamp(firstAngle, 1e-14, 1e-2);
    int streak = 0;
    for (int budget = 4000; angle > 1e-15 && budget > 0; budget -= 8) {
        const Vec3 n = r.direction;
        const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
        bool kept = false;
        for (const Vec3& t : {t1, Vec3(-t1), t2, Vec3(-t2), Vec3(t1 + t2), Vec3(-t1 - t2), Vec3(t1 - t2), Vec3(t2 - t1)}) {
            const Vec3 trial = (n + angle * t).normalized();
            const double value = valueAt(trial);
            if (value < r.value - floor) {
                r.direction = trial;
                r.value = value;
                ++r.steps;
                kept = true;
                break;
            }
        }
        if (!kept) angle *= 0.5, streak = 0;
        else if (++streak >= 2) angle = std::min(2 * angle, 1e-2), streak = 0;
    }
    // Stage 2: Newton on the directions along which g is smooth at m (see SmoothDirections).
    for (int iteration = 0; iteration < 40; ++iteration) {
        const Vec3 n = r.direction;
        const detail::SmoothDirections here = detail::smoothDirections(a, b, n, delta, scale);
        if (here.count == 0) break;
        const Vec3 p = detail::differenceSupport(a, b, n);
        Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
        Eigen::Matrix2d hessian = Eigen::Matrix2d::Identity();
        for (int i = 0; i < here.count; ++i) gradient[i] = here.e[i].dot(p);
        if (gradient.norm() <= floor) break;
        for (int j = 0; j < here.count; ++j) {
            const Vec3 dp = (detail::differenceSupport(a, b, Vec3((n + delta * here.e[j]).normalized())) -
                             detail::differenceSupport(a, b, Vec3((n - delta * here.e[j]).normalized()))) /
                            (2 * delta);
            for (int i = 0; i < here.count; ++i) hessian(i, j) = here.e[i].dot(dp) - (i == j ? r.value : 0.0);
        }
        hessian = 0.5 * (hessian + hessian.transpose()).eval();
        // Newton where g curves upward; else a gradient step of the gradient's own length, which
        // the line search shortens as needed.
        Eigen::Vector2d step = -gradient;
        const Eigen::LLT<Eigen::Matrix2d> llt(hessian);
        if (llt.info() == Eigen::Success) step = llt.solve(-gradient);
        if (here.count == 1) step[1] = 0;
        bool kept = false;
        for (double alpha = 1.0; alpha > 1e-6 && !kept; alpha *= 0.5) {
            const Vec3 move = alpha * (step[0] * here.e[0] + step[1] * here.e[1]);
            Vec3 trial = (n + move).normalized();
            double value = valueAt(trial);
            if (here.count == 1) {
                // Back onto the ridge, which curves away from the great circle along e by ~|move|².
                const Vec3 across = trial.cross(here.e[0]).normalized();
                for (double angle = std::max(move.norm(), 1e-15); angle > 1e-17; angle *= 0.5)
                    for (const Vec3& t : {across, Vec3(-across)}) {
                        const Vec3 pinned = (trial + angle * t).normalized();
                        if (const double v = valueAt(pinned); v < value) value = v, trial = pinned;
                    }
            }
            const detail::SmoothDirections there = detail::smoothDirections(a, b, trial, delta, scale);
            const Vec3 q = detail::differenceSupport(a, b, trial);
            double trialGradient = 0;
            for (int i = 0; i < there.count; ++i) trialGradient += there.e[i].dot(q) * there.e[i].dot(q);
            if (there.count == here.count && value <= r.value + floor &&
                std::sqrt(trialGradient) < 0.9 * gradient.norm()) {
                r.direction = trial;
                r.value = value;
                ++r.steps;
                kept = true;
            }
        }
        if (!kept) break;
    }
    return r;
}

}  // namespace cdlab
