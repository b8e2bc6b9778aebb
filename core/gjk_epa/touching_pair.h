// The touching pair of two overlapping convex shapes along a given normal: the one construction
// behind EPA's fallback witnesses (epa_impl.h, epaFallbackWitness) and the contact manifold's point
// when the face clip keeps none (core/contact/contact_stages.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/base/types.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

/// `shape` moved by `shift`: a support mapping.
template <class S>
struct ShiftedShape {
    const S& shape;
    Vec3 shift;
    Vec3 support(const Vec3& d) const { return shape.support(d) + shift; }
};

/// A and B overlapping by `depth` >= 0 along the unit normal n (from A toward B): B pushed along n
/// by depth + δ, δ = max(depth, 2^-30 M) (M: the magnitude of the coordinates), lies about δ from
/// A when n is a least-overlap direction, so GJK's closest points of that pair — convex
/// combinations of support points — give pointA on A and pointB = (B's closest point) − push on B
/// to rounding, with pointA − pointB = depth · n as far as n is least overlap. False (outputs
/// untouched) when δ is not a positive finite push or GJK does not separate them.
/// Tests: tests/core/gjk_epa/epa_fallback_witness_test.cpp; cdlab stress "contact manifolds".
template <SupportMapping A, SupportMapping B>
bool touchingPairAlong(const A& shapeA, const B& shapeB, const Vec3& n, double depth, double M, Vec3& pointA,
                       Vec3& pointB) {
    const double delta = std::max(depth, std::ldexp(M, -30));
    if (!(delta > 0) || !std::isfinite(delta + depth)) return false;
    const Vec3 push = (depth + delta) * n;
    const GjkResult g = gjkDistance(shapeA, ShiftedShape<B>{shapeB, push});
    if (g.status != GjkStatus::Separated || !g.pointA.allFinite() || !g.pointB.allFinite()) return false;
    pointA = g.pointA;
    pointB = g.pointB - push;
    return true;
}

}  // namespace cdlab
