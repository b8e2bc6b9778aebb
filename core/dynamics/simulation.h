// A single rigid convex polyhedron falling onto a static ground plane: the driver that ties the
// mass properties (core/geometry/mass_properties.h), the integrator (core/dynamics/rigid_body.h), the polyhedron–plane
// contact manifold (core/contact/contact_plane.h) and the impulse solver (core/dynamics/impulse_solver.h) together,
// recording every step as plain data.
//
// One step of length dt (fixed), in this order:
//   1. v ← v + g dt, implicit gyroscopic ω update               (semi-implicit Euler, velocities first)
//   2. manifold at the current pose: contactPolyhedronPlane with tolerance = margin,
//        margin = slop + dt (|v| + |ω| ρ)    (ρ = farthest vertex from the centre of mass)
//      so every vertex that can reach the plane during the step is a (speculative) contact point;
//      separation s = n̂ · p − d̂ per point; at most maxContactPoints points (area-keeping reduction)
//   3. solveContacts: sequential impulses, restitution, friction (rules in core/dynamics/impulse_solver.h)
//   4. x ← x + v dt, q ← exp(ω dt/2) q
//   5. position correction (minimum translation): if the deepest vertex is below the plane by more
//      than slop, translate the body along n̂ so it is exactly slop deep. A plane's distance changes
//      by the same amount at every vertex under a translation along n̂, so after the step no vertex
//      is deeper than slop. Velocities are not touched (no energy from a Baumgarte bias); the lift
//      adds m |g·n̂| Δ of potential energy, recorded as `correction` in the step.
// Deterministic: fixed iteration counts, no threads, no unordered containers; with
// -ffp-contract=off two runs of the same input give bit-identical traces.
#pragma once

#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/contact/contact_plane.h"
#include "core/dynamics/impulse_solver.h"
#include "core/dynamics/rigid_body.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/polyhedron.h"

namespace cdlab {

struct DropInput {
    ConvexPolyhedron shape;                ///< any body frame; recentred at its centre of mass
    double density = 1.0;                  ///< mass per unit volume
    Transform pose;                        ///< of the shape's own frame (not the centre of mass)
    Vec3 linearVelocity = Vec3::Zero();    ///< of the centre of mass, world
    Vec3 angularVelocity = Vec3::Zero();   ///< world, rad/s
    Plane ground{Vec3::UnitZ(), 0.0};      ///< the solid half-space n · x <= d (n need not be unit)
    Vec3 gravity = Vec3(0.0, 0.0, -9.81);  ///< world units / s²
};

struct SimulationOptions {
    double timeStep = 1.0 / 240.0;  ///< s (the solver's timeStep is set from this)
    int steps = 960;                ///< steps to run (4 s at 240 Hz)
    ImpulseSolverOptions solver;    ///< restitution, friction, threshold, iterations
    /// Allowed penetration (world units): the position correction leaves bodies this deep, so a
    /// resting contact stays in the manifold from step to step. 1e-3 suits bodies of size ~1.
    double slop = 1e-3;
    int maxContactPoints = 4;  ///< manifold size (see PlaneContactOptions::maxPoints)
    /// "At rest": |v| and |ω| ρ both below this (world units / s). g dt = 0.04 at 240 Hz is the
    /// speed gravity adds per step; a resting body's solver removes it every step.
    double restSpeed = 0.02;
};

enum class SimulationStatus {
    Ok,              ///< every output meaningful
    InvalidShape,    ///< mass properties failed (see message: flat, NaN, non-planar face)
    InvalidBody,     ///< makeDynamicBody failed (zero mass, NaN pose / velocity)
    InvalidPlane,    ///< zero or non-finite ground normal / offset
    InvalidOptions,  ///< timeStep <= 0, steps < 0, negative slop / friction, restitution outside [0, 1]
};

/// Name of a status, e.g. "InvalidShape".
const char* nameOf(SimulationStatus status);

/// One step's record (state after the step; contacts as solved during it). World frame.
struct SimulationStep {
    int step = 0;                  ///< 0 = the initial state (no contacts), then 1..steps
    double time = 0.0;             ///< s, after the step
    Vec3 position = Vec3::Zero();  ///< centre of mass
    Quat orientation = Quat::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();  ///< unit ground normal n̂ (from the ground toward the body)
    PlaneContactStatus contactStatus = PlaneContactStatus::Separated;  ///< of the manifold query (2.)
    std::vector<ContactImpulse> contacts;  ///< the manifold points and their impulses (pose at step start)
    double kinetic = 0.0, potential = 0.0, energy = 0.0;  ///< J (potential −m g · x)
    double penetrationBeforeCorrection = 0.0;             ///< max(0, −s_min) after 4.
    double correction = 0.0;                              ///< translation along n̂ applied in 5. (world units, >= 0)
    double maxPenetration = 0.0;                          ///< max(0, −s_min) after the step (<= slop)
};

struct SimulationTrace {
    std::vector<SimulationStep> steps;  ///< steps[0] is the initial state
};

struct SimulationResult {
    SimulationStatus status = SimulationStatus::Ok;
    std::string message;          ///< one line; empty when Ok
    MassProperties mass;          ///< of the input shape (its frame)
    ConvexPolyhedron shape;       ///< the shape recentred: body frame origin = centre of mass
    RigidBody body;               ///< the final state
    double boundingRadius = 0.0;  ///< ρ: farthest vertex from the centre of mass
    int stepsRun = 0;
    double maxPenetration = 0.0;  ///< over all steps, after correction
    double maxPenetrationBeforeCorrection = 0.0;
    double maxEnergyIncrease = 0.0;  ///< max over steps of E_k − E_{k−1} (0 if energy never rises)
    double totalCorrection = 0.0;    ///< sum of the position corrections
    /// First time from which the body stays at rest to the end (restSpeed); −1 if it never settles.
    double restTime = -1.0;
    bool ok() const { return status == SimulationStatus::Ok; }
};

/// Runs the drop (see the file comment). trace (optional) receives every step. World frame, SI-like
/// units (length, s, mass = density * length³).
SimulationResult simulateDrop(const DropInput& input, const SimulationOptions& options = {},
                              SimulationTrace* trace = nullptr);

/// One step (1.–5. of the file comment) of `body` (whose body frame has its origin at the centre of
/// mass: `shape` as SimulationResult::shape) against the plane n̂ · x <= d̂ (n̂ unit). Returns the
/// step's record with step = 0 and time = 0 (the caller numbers them). radius = ρ.
SimulationStep stepBodyOnPlane(RigidBody& body, const ConvexPolyhedron& shape, double radius, const Vec3& unitNormal,
                               double unitOffset, const Vec3& gravity, const SimulationOptions& options);

}  // namespace cdlab
