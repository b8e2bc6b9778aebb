// Rigid-body state and the fixed-step semi-implicit (symplectic) Euler integrator.
//
// State (Baraff, "Rigid Body Simulation", SIGGRAPH 2001 course notes "Physically Based Modeling",
// §2-3): position x of the centre of mass, orientation q (unit quaternion, body -> world), linear
// velocity v and angular velocity ω (both world frame), mass m and the inertia tensor I_body about
// the centre of mass in body axes. World inverse inertia: I_world⁻¹ = R I_body⁻¹ Rᵀ, R = R(q).
// A static body (the ground) has inverse mass 0 and inverse inertia 0: impulses do not move it.
//
// Integrator, one step of length dt (semi-implicit Euler: velocities first, then positions with
// the NEW velocities; Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005):
//   v ← v + g dt                                  (integrateVelocity; contact impulses come after)
//   ω ← ω − dt I⁻¹ (ω × I ω), implicit            (gyroscopic term, body axes, one Newton step:
//                                                  Catto, "Numerical Methods", GDC 2015; zero for
//                                                  spherical tops and principal-axis spin; dissipative
//                                                  otherwise, so free rotation never gains energy)
//   x ← x + v dt
//   q ← exp(ω dt / 2) q                           (rotation by |ω| dt about ω: unit by construction)
#pragma once

#include <string>

#include "core/base/types.h"

namespace cdlab {

enum class RigidBodyStatus {
    Ok,          ///< body meaningful
    ZeroMass,    ///< a dynamic body needs mass > 0 (use makeStaticBody for infinite mass)
    NonFinite,   ///< NaN / Inf in mass, inertia, pose or velocities
    BadInertia,  ///< inertia not symmetric positive definite or principal moments violate I1 + I2 >= I3
};

/// Name of a status, e.g. "ZeroMass".
const char* nameOf(RigidBodyStatus status);

struct RigidBody {
    Vec3 position = Vec3::Zero();            ///< centre of mass, world frame
    Quat orientation = Quat::Identity();     ///< body -> world, unit
    Vec3 linearVelocity = Vec3::Zero();      ///< of the centre of mass, world frame
    Vec3 angularVelocity = Vec3::Zero();     ///< world frame, rad/s
    double inverseMass = 0.0;                ///< 1 / m; 0: static (infinite mass)
    Mat3 inertiaBody = Mat3::Zero();         ///< about the centre of mass, body axes (0 for static)
    Mat3 inverseInertiaBody = Mat3::Zero();  ///< its inverse (0 for static)

    bool isStatic() const { return inverseMass == 0.0; }
    /// Mass (+infinity for a static body).
    double mass() const;
    /// Body frame (origin at the centre of mass) to world.
    Transform transform() const { return Transform{position, orientation}; }
    /// R I_body⁻¹ Rᵀ, world axes (0 for static).
    Mat3 inverseInertiaWorld() const;
    /// R I_body Rᵀ, world axes.
    Mat3 inertiaWorld() const;
    /// Velocity of the body point currently at `worldPoint`: v + ω × (p − x).
    Vec3 velocityAt(const Vec3& worldPoint) const;
    /// Applies `impulse` (world, N·s) at `worldPoint`: v += J / m, ω += I_world⁻¹ ((p − x) × J).
    void applyImpulse(const Vec3& impulse, const Vec3& worldPoint);
    /// ½ m |v|² + ½ ω · I_world ω (J). 0 for static.
    double kineticEnergy() const;
    /// −m g · x (J), zero at the world origin. 0 for static.
    double potentialEnergy(const Vec3& gravity) const;
};

struct RigidBodyBuild {
    RigidBody body;
    RigidBodyStatus status = RigidBodyStatus::Ok;
    std::string message;  ///< one line; empty when Ok
    bool ok() const { return status == RigidBodyStatus::Ok; }
};

/// A dynamic body: mass > 0, inertiaBody about the centre of mass in body axes (symmetric positive
/// definite, e.g. MassProperties::inertia of the recentred shape), pose of the centre of mass.
RigidBodyBuild makeDynamicBody(double mass, const Mat3& inertiaBody, const Transform& pose,
                               const Vec3& linearVelocity = Vec3::Zero(), const Vec3& angularVelocity = Vec3::Zero());

/// A static (infinite mass) body at `pose`: never moved by impulses or the integrator.
RigidBody makeStaticBody(const Transform& pose = {});

/// v ← v + g dt and the implicit gyroscopic update of ω (no-op for static bodies). gravity in
/// world units / s², dt in s.
void integrateVelocity(RigidBody& body, const Vec3& gravity, double dt);

/// x ← x + v dt, q ← exp(ω dt/2) q (see the file comment). No-op for static.
void integratePosition(RigidBody& body, double dt);

}  // namespace cdlab
