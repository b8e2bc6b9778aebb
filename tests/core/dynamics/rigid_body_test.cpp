// Rigid-body state and the semi-implicit Euler integrator. Oracles: closed-form sums of the
// discrete free-fall recursion, rotation by a constant angular velocity (axis-angle by hand),
// conservation of world angular momentum, impulse responses with a diagonal inertia by hand, and
// the input errors (zero mass, NaN, non-physical inertia).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/dynamics/rigid_body.h"

using namespace cdlab;

namespace {

RigidBody boxBody(const Transform& pose = {}) {
    // Box 1 x 2 x 3, mass 6: I = diag(m(b²+c²), m(a²+c²), m(a²+b²)) / 12 = diag(6.5, 5, 2.5).
    RigidBodyBuild b = makeDynamicBody(6.0, Vec3(6.5, 5.0, 2.5).asDiagonal(), pose);
    REQUIRE(b.ok());
    return b.body;
}

}  // namespace

TEST_SUITE("rigid_body") {
    TEST_CASE("errors: zero / negative / NaN mass, NaN pose and velocity, bad inertia") {
        const Mat3 I = Mat3::Identity();
        CHECK(makeDynamicBody(0.0, I, {}).status == RigidBodyStatus::ZeroMass);
        CHECK(makeDynamicBody(-1.0, I, {}).status == RigidBodyStatus::ZeroMass);
        CHECK(makeDynamicBody(kNaN, I, {}).status == RigidBodyStatus::NonFinite);
        CHECK(makeDynamicBody(std::numeric_limits<double>::infinity(), I, {}).status == RigidBodyStatus::NonFinite);
        Transform bad;
        bad.position.x() = kNaN;
        CHECK(makeDynamicBody(1.0, I, bad).status == RigidBodyStatus::NonFinite);
        CHECK(makeDynamicBody(1.0, I, {}, Vec3(kNaN, 0, 0)).status == RigidBodyStatus::NonFinite);
        CHECK(makeDynamicBody(1.0, I, {}, Vec3::Zero(), Vec3(0, kNaN, 0)).status == RigidBodyStatus::NonFinite);
        Transform zeroQ;
        zeroQ.rotation = Quat(0, 0, 0, 0);
        CHECK(makeDynamicBody(1.0, I, zeroQ).status == RigidBodyStatus::NonFinite);
        Mat3 nanI = I;
        nanI(1, 2) = kNaN;
        CHECK(makeDynamicBody(1.0, nanI, {}).status == RigidBodyStatus::NonFinite);
        CHECK(makeDynamicBody(1.0, Vec3(1, 1, 0).asDiagonal(), {}).status == RigidBodyStatus::BadInertia);  // singular
        CHECK(makeDynamicBody(1.0, Vec3(1, -1, 1).asDiagonal(), {}).status ==
              RigidBodyStatus::BadInertia);  // indefinite
        CHECK(makeDynamicBody(1.0, Vec3(1, 1, 3).asDiagonal(), {}).status == RigidBodyStatus::BadInertia);  // 1 + 1 < 3
        Mat3 asym = I;
        asym(0, 1) = 0.1;
        CHECK(makeDynamicBody(1.0, asym, {}).status == RigidBodyStatus::BadInertia);
        CHECK(makeDynamicBody(1.0, Vec3(1, 1, 2).asDiagonal(), {}).ok());  // a thin plate: I1 + I2 = I3 exactly
        CHECK(!makeDynamicBody(0.0, I, {}).message.empty());
    }

    TEST_CASE("static body: infinite mass, impulses and the integrator leave it alone") {
        RigidBody s = makeStaticBody(Transform{Vec3(1, 2, 3), Quat::Identity()});
        CHECK(s.isStatic());
        CHECK(std::isinf(s.mass()));
        s.applyImpulse(Vec3(5, 5, 5), Vec3(0, 0, 0));
        integrateVelocity(s, Vec3(0, 0, -9.81), 0.1);
        integratePosition(s, 0.1);
        CHECK(s.position == Vec3(1, 2, 3));
        CHECK(s.linearVelocity == Vec3::Zero());
        CHECK(s.angularVelocity == Vec3::Zero());
        CHECK(s.kineticEnergy() == 0.0);
        CHECK(s.potentialEnergy(Vec3(0, 0, -9.81)) == 0.0);
    }

    TEST_CASE("free fall: the semi-implicit recursion in closed form") {
        // v_k = v0 + k g dt, x_N = x0 + N dt v0 + g dt² N(N+1)/2 (positions use the new velocity).
        RigidBody b = boxBody(Transform{Vec3(1e4, -2, 5), Quat::Identity()});
        const Vec3 v0(0.3, -0.2, 1.0), g(0, 0, -9.81);
        b.linearVelocity = v0;
        const double dt = 1.0 / 240.0;
        const int N = 480;
        for (int k = 0; k < N; ++k) {
            integrateVelocity(b, g, dt);
            integratePosition(b, dt);
        }
        CHECK((b.linearVelocity - (v0 + N * dt * g)).norm() < 1e-12);
        const Vec3 x = Vec3(1e4, -2, 5) + N * dt * v0 + g * (dt * dt * N * (N + 1) / 2.0);
        CHECK((b.position - x).norm() < 1e-9);
        // Energy of the discrete orbit drops by ½ m |g|² dt² per step (first-order method): the
        // expected total after N steps, checked to 1e-6 relative.
        RigidBody start = boxBody(Transform{Vec3(1e4, -2, 5), Quat::Identity()});
        start.linearVelocity = v0;
        const double E0 = start.kineticEnergy() + start.potentialEnergy(g);
        const double E = b.kineticEnergy() + b.potentialEnergy(g);
        CHECK(E - E0 == doctest::Approx(-0.5 * 6.0 * g.squaredNorm() * dt * dt * N).epsilon(1e-6));
    }

    TEST_CASE("spherical top: constant ω rotates by N |ω| dt about ω, ω unchanged") {
        RigidBodyBuild b = makeDynamicBody(2.0, 0.4 * Mat3::Identity(), {});
        REQUIRE(b.ok());
        const Vec3 w = Vec3(1, -2, 0.5);
        b.body.angularVelocity = w;
        const double dt = 0.01;
        for (int k = 0; k < 300; ++k) integratePosition(b.body, dt);
        const Quat expected(Eigen::AngleAxisd(300 * dt * w.norm(), w.normalized()));
        CHECK(b.body.orientation.angularDistance(expected) < 1e-12);
        CHECK((b.body.angularVelocity - w).norm() < 1e-12);
    }

    TEST_CASE(
        "asymmetric top: rotational energy never rises, |L| drifts only at first order, principal-axis spin is "
        "steady") {
        RigidBody b = boxBody(Transform{Vec3::Zero(), Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 1).normalized()))});
        b.angularVelocity = Vec3(0.5, 3.0, -1.0);
        const Vec3 L0 = b.inertiaWorld() * b.angularVelocity;
        double previous = b.kineticEnergy();
        const double E0 = previous;
        for (int k = 0; k < 1000; ++k) {
            integrateVelocity(b, Vec3::Zero(), 1.0 / 240.0);
            integratePosition(b, 1.0 / 240.0);
            const double E = b.kineticEnergy();
            CHECK(E <= previous * (1 + 1e-12));  // implicit Euler gyroscopic step: dissipative
            previous = E;
        }
        // First-order method over ~4 s: world angular momentum and energy within a few percent.
        const Vec3 L = b.inertiaWorld() * b.angularVelocity;
        MESSAGE("asymmetric top after 1000 steps: |ΔL|/|L| " << (L - L0).norm() / L0.norm() << ", ΔE/E "
                                                             << (previous - E0) / E0);
        CHECK((L - L0).norm() < 0.02 * L0.norm());  // measured 0.6 %
        CHECK(previous > 0.97 * E0);                // measured −1.3 %
        CHECK(std::abs(b.orientation.norm() - 1.0) < 1e-15 * 10);

        RigidBody p = boxBody();
        p.angularVelocity = Vec3(0, 0, 2.0);  // about a principal axis: ω stays put exactly
        for (int k = 0; k < 1000; ++k) {
            integrateVelocity(p, Vec3::Zero(), 1.0 / 240.0);
            integratePosition(p, 1.0 / 240.0);
        }
        CHECK((p.angularVelocity - Vec3(0, 0, 2.0)).norm() < 1e-12);
        // The hand check of one gyroscopic step: ω' solves I (ω' − ω) + dt ω' × I ω' ≈ 0 (to O(dt²) after one Newton
        // step).
        RigidBody q = boxBody();
        q.angularVelocity = Vec3(1.0, 2.0, 0.5);
        const Vec3 w = q.angularVelocity;
        const Mat3 I = q.inertiaBody;
        const double dt = 0.01;
        integrateVelocity(q, Vec3::Zero(), dt);
        const Vec3 w1 = q.angularVelocity;
        const Vec3 residual = I * (w1 - w) + dt * w1.cross(I * w1);
        CHECK(residual.norm() < 1e-3 * (dt * w.cross(I * w)).norm());
    }

    TEST_CASE("impulse at a point, kinetic energy and point velocity by hand") {
        RigidBody b = boxBody(Transform{Vec3(1, 1, 1), Quat::Identity()});
        const Vec3 J(0, 0, 3), p(1.5, 1, 1);  // r = (0.5, 0, 0), r × J = (0, −1.5, 0)
        b.applyImpulse(J, p);
        CHECK((b.linearVelocity - Vec3(0, 0, 0.5)).norm() < 1e-15);
        CHECK((b.angularVelocity - Vec3(0, -1.5 / 5.0, 0)).norm() < 1e-15);
        // Velocity of p: v + ω × r = (0, 0, 0.5) + (0, −0.3, 0) × (0.5, 0, 0) = (0, 0, 0.5 + 0.15).
        CHECK((b.velocityAt(p) - Vec3(0, 0, 0.65)).norm() < 1e-15);
        CHECK(b.kineticEnergy() == doctest::Approx(0.5 * 6 * 0.25 + 0.5 * 5 * 0.09));
        CHECK(b.potentialEnergy(Vec3(0, 0, -10)) == doctest::Approx(60.0));
        // Rotated body: the world tensor is R I Rᵀ; 90° about z swaps the x and y moments.
        RigidBody r = boxBody(Transform{Vec3::Zero(), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))});
        const Mat3 Iw = r.inertiaWorld();
        CHECK(Iw(0, 0) == doctest::Approx(5.0));
        CHECK(Iw(1, 1) == doctest::Approx(6.5));
        CHECK((r.inverseInertiaWorld() * Iw - Mat3::Identity()).norm() < 1e-14);
    }
}
