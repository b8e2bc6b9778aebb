// Impulse-based collision response of one dynamic body against a static surface (the ground):
// sequential impulses with accumulated clamping over the contact manifold, restitution, Coulomb
// friction and speculative contacts.
//
// Single contact (Baraff, "Rigid Body Simulation", SIGGRAPH 2001 course notes, §8 "Colliding
// contact"; Hecker, "Physics, Part 3: Collision Response", Game Developer, Mar. 1997): at a point p
// with r = p − x and unit normal n (from the static surface toward the body), the relative normal
// velocity is v_n = (v + ω × r) · n and an impulse j n changes it by j / k with the effective mass
//     1 / k = 1/m + n · ((I_world⁻¹ (r × n)) × r).
// A collision (v_n⁻ < 0) wants v_n⁺ = −e v_n⁻, hence j = −(1 + e) v_n⁻ k.
//
// Several contacts (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005; Box2D's
// b2SolveContact): each point keeps its accumulated impulse λ; one iteration visits the points in
// order, first the normal, then friction (so the friction cone holds exactly at the end):
//     Δλ = k (v_target − v_n),  λ_new = max(0, λ + Δλ),  apply (λ_new − λ) n at p.
// Clamping the ACCUMULATED impulse (not Δλ) lets an iteration take back impulse an earlier one put
// in too much, so the iteration converges to the projected Gauss-Seidel solution of the contact
// LCP. Target velocity per point, from v_n⁻ (before any impulse) and the separation s (> 0: gap):
//     bounce       v_n⁻ < −restitutionThreshold and s + v_n⁻ dt <= 0 (reaches the surface this step):
//                  v_target = 0 during the iterations (compression), then the restitution pass
//     speculative  s > 0: v_target = −s / dt (may approach, but only to touching; no bounce)
//     resting      s <= 0: v_target = 0 (penetration is removed by the position correction of
//                  core/dynamics/simulation.h, not by a velocity bias: no energy is added)
// Restitution (a second pass after the compression iterations, normal impulses only, after Box2D
// v3's b2ApplyRestitution): Newton's law v_target = −e v_n⁻ at the bouncing points while every other
// point keeps its target, sequential impulses clamped on the total λ_n (>= |λ_t| / μ, so friction
// stays inside the cone), the same number of sweeps. At one frictionless contact this is exactly
// v_n⁺ = −e v_n⁻, j = (1 + e) λ_c. Measured alternatives: −e v_n⁻ inside the friction iterations let
// friction inflate the normal impulse (energy gains up to 0.8 J per bounce at e = 1); Poisson's
// e λ_c after the loop was worse; a pass over the bouncing points alone drove neighbouring points
// 2 mm into the ground (a tetrahedron tipping onto a face).
// Friction (Coulomb, coefficient μ): tangent impulses along two directions t1, t2 ⟂ n, each with
// its own effective mass, the 2D accumulated tangent impulse clamped to the disc |λ_t| <= μ λ_n
// during the compression iterations; the restitution pass adds normal impulse only (so the cone
// |λ_t| <= μ λ_n still holds, with λ_n the total).
#pragma once

#include <vector>

#include "core/base/types.h"
#include "core/dynamics/rigid_body.h"

namespace cdlab {

struct ImpulseSolverOptions {
    double restitution = 0.5;  ///< e in [0, 1]
    double friction = 0.5;     ///< Coulomb μ >= 0 (0: frictionless)
    /// Approach speeds below this (world units / s) do not bounce: resting and slow contacts are
    /// perfectly inelastic, so a body can come to rest (a bounce of v_n ~ |g| dt every step is jitter).
    double restitutionThreshold = 0.25;
    int iterations = 16;            ///< fixed count: deterministic, same work every step
    double timeStep = 1.0 / 240.0;  ///< s, for the speculative target −s / dt
    /// Record λ_n of every point after each sweep (ImpulseSolverResult::history); for figures.
    bool recordIterations = false;
};

/// One contact point of the manifold (input).
struct ContactConstraintPoint {
    Vec3 point = Vec3::Zero();  ///< world point of the body
    double separation = 0.0;    ///< signed distance to the surface along n (< 0: penetrating)
};

/// What the solver did at one point (all world frame).
struct ContactImpulse {
    Vec3 point = Vec3::Zero();
    double separation = 0.0;
    Vec3 r = Vec3::Zero();            ///< point − centre of mass
    double normalMass = 0.0;          ///< k = 1 / (1/m + n·((I⁻¹(r×n))×r))
    double targetVelocity = 0.0;      ///< v_target of the iterations (see file comment)
    bool bounce = false;              ///< the restitution rule applied
    double restitutionImpulse = 0.0;  ///< net change of λ_n in the restitution pass (part of normalImpulse; may be < 0)
    double normalVelocityBefore = 0.0;   ///< v_n⁻
    double normalVelocityAfter = 0.0;    ///< v_n⁺ after the last iteration
    double normalImpulse = 0.0;          ///< λ_n >= 0 (N·s), compression + restitution
    Vec3 tangentImpulse = Vec3::Zero();  ///< λ_t1 t1 + λ_t2 t2, |·| <= μ λ_n
};

struct ImpulseSolverResult {
    std::vector<ContactImpulse> points;  ///< in input order
    Vec3 linearImpulse = Vec3::Zero();   ///< sum of all impulses applied (N·s)
    double lastIterationChange = 0.0;    ///< max |Δλ| of the final iteration (convergence indicator)
    /// With options.recordIterations: λ_n per point after each compression sweep, then after each
    /// restitution sweep (historyRestitution of them, at the end), and each sweep's max |Δλ|.
    std::vector<std::vector<double>> history;
    std::vector<double> historyChange;
    int historyRestitution = 0;
};

/// Solves the contacts of `body` against a static surface with unit normal `normal` (from the
/// surface toward the body) and applies the impulses to body's velocities. Static bodies and an
/// empty point list are left untouched.
ImpulseSolverResult solveContacts(RigidBody& body, const Vec3& normal,
                                  const std::vector<ContactConstraintPoint>& points,
                                  const ImpulseSolverOptions& options = {});

/// Closed-form single-contact collision impulse magnitude j = −(1 + e) v_n k (0 if v_n >= 0),
/// frictionless; Baraff §8 eq. (8-18). For checks and figures; normal unit, from surface to body.
double singleContactImpulse(const RigidBody& body, const Vec3& normal, const Vec3& point, double restitution);

}  // namespace cdlab
