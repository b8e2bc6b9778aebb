#include "core/dynamics/rigid_body.h"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace cdlab {

const char* nameOf(RigidBodyStatus status) {
    switch (status) {
        case RigidBodyStatus::Ok: return "Ok";
        case RigidBodyStatus::ZeroMass: return "ZeroMass";
        case RigidBodyStatus::NonFinite: return "NonFinite";
        case RigidBodyStatus::BadInertia: return "BadInertia";
    }
    return "?";
}

double RigidBody::mass() const { return inverseMass > 0 ? 1.0 / inverseMass : std::numeric_limits<double>::infinity(); }

Mat3 RigidBody::inverseInertiaWorld() const {
    const Mat3 R = orientation.toRotationMatrix();
    return R * inverseInertiaBody * R.transpose();
}

Mat3 RigidBody::inertiaWorld() const {
    const Mat3 R = orientation.toRotationMatrix();
    return R * inertiaBody * R.transpose();
}

Vec3 RigidBody::velocityAt(const Vec3& worldPoint) const {
    return linearVelocity + angularVelocity.cross(worldPoint - position);
}

void RigidBody::applyImpulse(const Vec3& impulse, const Vec3& worldPoint) {
    if (isStatic()) return;
    linearVelocity += inverseMass * impulse;
    angularVelocity += inverseInertiaWorld() * (worldPoint - position).cross(impulse);
}

double RigidBody::kineticEnergy() const {
    if (isStatic()) return 0.0;
    return 0.5 * mass() * linearVelocity.squaredNorm() + 0.5 * angularVelocity.dot(inertiaWorld() * angularVelocity);
}

double RigidBody::potentialEnergy(const Vec3& gravity) const {
    if (isStatic()) return 0.0;
    return -mass() * gravity.dot(position);
}

RigidBodyBuild makeDynamicBody(double mass, const Mat3& inertiaBody, const Transform& pose, const Vec3& linearVelocity,
                               const Vec3& angularVelocity) {
    RigidBodyBuild b;
    const auto fail = [&](RigidBodyStatus s, const std::string& m) {
        b.status = s;
        b.message = m;
        return b;
    };
    if (!std::isfinite(mass) || !inertiaBody.allFinite() || !pose.position.allFinite() ||
        !pose.rotation.coeffs().allFinite() || !linearVelocity.allFinite() || !angularVelocity.allFinite())
        return fail(RigidBodyStatus::NonFinite, "mass, inertia, pose or velocity is not finite");
    if (!(mass > 0))
        return fail(RigidBodyStatus::ZeroMass, "a dynamic body needs mass > 0 (got " + std::to_string(mass) + ")");
    // Symmetric within rounding: 1e-12 of the tensor's size (mass-property sums are symmetric to ~1e-16).
    const double scale = inertiaBody.cwiseAbs().maxCoeff();
    if (!((inertiaBody - inertiaBody.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale))
        return fail(RigidBodyStatus::BadInertia, "inertia tensor is not symmetric");
    const Mat3 sym = 0.5 * (inertiaBody + inertiaBody.transpose());
    Eigen::SelfAdjointEigenSolver<Mat3> eig(sym, Eigen::EigenvaluesOnly);
    const Vec3 p = eig.eigenvalues();  // ascending
    // Positive definite, and the triangle inequality every real mass distribution satisfies
    // (I1 + I2 >= I3); 1e-12 relative slack for rounding (a thin rod/plate sits on the boundary).
    if (!(p[0] > 1e-12 * p[2])) return fail(RigidBodyStatus::BadInertia, "inertia tensor is not positive definite");
    if (!(p[0] + p[1] >= p[2] * (1 - 1e-12)))
        return fail(RigidBodyStatus::BadInertia, "principal moments violate I1 + I2 >= I3");
    const double qn = pose.rotation.norm();
    if (!(qn > 0)) return fail(RigidBodyStatus::NonFinite, "orientation quaternion is zero");
    RigidBody& body = b.body;
    body.position = pose.position;
    body.orientation = pose.rotation.normalized();
    body.linearVelocity = linearVelocity;
    body.angularVelocity = angularVelocity;
    body.inverseMass = 1.0 / mass;
    body.inertiaBody = sym;
    body.inverseInertiaBody = sym.inverse();
    return b;
}

RigidBody makeStaticBody(const Transform& pose) {
    RigidBody body;
    body.position = pose.position;
    body.orientation = pose.rotation.normalized();
    return body;
}

namespace {

Mat3 skew(const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

}  // namespace

void integrateVelocity(RigidBody& body, const Vec3& gravity, double dt) {
    if (body.isStatic()) return;
    body.linearVelocity += gravity * dt;
    // Gyroscopic term, implicit Euler in body axes with one Newton step (Catto, "Numerical Methods",
    // GDC 2015): solve f(ω') = I (ω' − ω) + dt ω' × I ω' = 0 from ω' = ω:
    //   f = dt ω × I ω,  J = I + dt (skew(ω) I − skew(I ω)),  ω' = ω − J⁻¹ f.
    // Exact (f = 0) for spin about a principal axis and for spherical tops; otherwise slightly
    // dissipative (implicit Euler), so free rotation never gains energy.
    const Vec3 w = body.orientation.conjugate() * body.angularVelocity;
    const Vec3 Iw = body.inertiaBody * w;
    const Vec3 f = dt * w.cross(Iw);
    if (f.squaredNorm() == 0.0) return;
    const Mat3 J = body.inertiaBody + dt * (skew(w) * body.inertiaBody - skew(Iw));
    body.angularVelocity = body.orientation * (w - J.partialPivLu().solve(f));
}

void integratePosition(RigidBody& body, double dt) {
    if (body.isStatic()) return;
    body.position += body.linearVelocity * dt;
    const double angle = body.angularVelocity.norm() * dt;
    if (angle > 0) {
        const Quat dq(Eigen::AngleAxisd(angle, body.angularVelocity.normalized()));
        body.orientation = (dq * body.orientation).normalized();  // renormalise: rounding only
    }
}

}  // namespace cdlab
