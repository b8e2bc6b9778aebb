#include "core/dynamics/impulse_solver.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

namespace {

// 1 / (1/m + d · ((I⁻¹ (r × d)) × r)): the inverse of the velocity change along d per unit impulse along d.
double effectiveMass(const RigidBody& body, const Mat3& invInertia, const Vec3& r, const Vec3& d) {
    const Vec3 rd = r.cross(d);
    const double w = body.inverseMass + rd.dot(invInertia * rd);  // = n·((I⁻¹(r×n))×r), same scalar
    return w > 0 ? 1.0 / w : 0.0;
}

// An orthonormal tangent pair for n (Frisvad-style choice by the smallest |component|: no branch
// near a pole that flips between steps for a fixed ground normal).
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
    Vec3 a = Vec3::UnitX();
    const Vec3 m = n.cwiseAbs();
    if (m.y() <= m.x() && m.y() <= m.z()) a = Vec3::UnitY();
    else if (m.z() <= m.x() && m.z() <= m.y()) a = Vec3::UnitZ();
    t1 = n.cross(a).normalized();
    t2 = n.cross(t1);
}

}  // namespace

double singleContactImpulse(const RigidBody& body, const Vec3& normal, const Vec3& point, double restitution) {
    const Vec3 r = point - body.position;
    const double vn = body.velocityAt(point).dot(normal);
    if (vn >= 0) return 0.0;
    return -(1.0 + restitution) * vn * effectiveMass(body, body.inverseInertiaWorld(), r, normal);
}

ImpulseSolverResult solveContacts(RigidBody& body, const Vec3& normal,
                                  const std::vector<ContactConstraintPoint>& points,
                                  const ImpulseSolverOptions& options) {
    ImpulseSolverResult result;
    if (body.isStatic() || points.empty()) return result;
    const Mat3 invI = body.inverseInertiaWorld();  // constant during the solve (positions do not move)
    Vec3 t1, t2;
    tangents(normal, t1, t2);
    const double dt = options.timeStep;
    const double e = options.restitution;
    const double mu = options.friction;

    struct Row {
        double kn = 0, kt1 = 0, kt2 = 0;
        double lambdaT1 = 0, lambdaT2 = 0;
    };
    std::vector<Row> rows(points.size());
    result.points.resize(points.size());
    // Prepare: effective masses and targets from the velocities before any impulse.
    for (std::size_t i = 0; i < points.size(); ++i) {
        ContactImpulse& c = result.points[i];
        c.point = points[i].point;
        c.separation = points[i].separation;
        c.r = c.point - body.position;
        c.normalMass = effectiveMass(body, invI, c.r, normal);
        rows[i].kn = c.normalMass;
        rows[i].kt1 = effectiveMass(body, invI, c.r, t1);
        rows[i].kt2 = effectiveMass(body, invI, c.r, t2);
        c.normalVelocityBefore = body.velocityAt(c.point).dot(normal);
        const double vn = c.normalVelocityBefore, s = c.separation;
        if (vn < -options.restitutionThreshold && s + vn * dt <= 0) {
            c.bounce = true;  // compression phase: stop the approach; restitution comes after the loop
            c.targetVelocity = 0.0;
        } else if (s > 0) {
            c.targetVelocity = -s / dt;
        } else {
            c.targetVelocity = 0.0;
        }
    }
    const auto record = [&](double change) {
        std::vector<double> lambdas;
        for (const ContactImpulse& c : result.points) lambdas.push_back(c.normalImpulse);
        result.history.push_back(std::move(lambdas));
        result.historyChange.push_back(change);
    };
    const auto apply = [&](const Vec3& impulse, const ContactImpulse& c) {
        body.linearVelocity += body.inverseMass * impulse;
        body.angularVelocity += invI * c.r.cross(impulse);
        result.linearImpulse += impulse;
    };
    for (int it = 0; it < options.iterations; ++it) {
        double change = 0.0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            ContactImpulse& c = result.points[i];
            Row& row = rows[i];
            // Normal: accumulated clamping λ >= 0.
            const double vn = (body.linearVelocity + body.angularVelocity.cross(c.r)).dot(normal);
            const double lambda = std::max(0.0, c.normalImpulse + row.kn * (c.targetVelocity - vn));
            const double d = lambda - c.normalImpulse;
            c.normalImpulse = lambda;
            apply(d * normal, c);
            change = std::max(change, std::abs(d));
            // Friction after the normal, against this iteration's λ_n, so the cone |λ_t| <= μ λ_n holds
            // exactly when the loop ends. Per-direction Δλ, then the accumulated 2D impulse clamped
            // to the disc μ λ_n.
            if (mu > 0) {
                const Vec3 v = body.linearVelocity + body.angularVelocity.cross(c.r);
                double n1 = row.lambdaT1 - row.kt1 * v.dot(t1);
                double n2 = row.lambdaT2 - row.kt2 * v.dot(t2);
                const double limit = mu * c.normalImpulse;
                const double len = std::hypot(n1, n2);
                if (len > limit) {
                    const double scale = len > 0 ? limit / len : 0.0;
                    n1 *= scale;
                    n2 *= scale;
                }
                const double d1 = n1 - row.lambdaT1, d2 = n2 - row.lambdaT2;
                row.lambdaT1 = n1;
                row.lambdaT2 = n2;
                apply(d1 * t1 + d2 * t2, c);
                change = std::max({change, std::abs(d1), std::abs(d2)});
            }
        }
        result.lastIterationChange = change;
        if (options.recordIterations) record(change);
    }
    // Restitution pass (Newton's law, normal impulses only, after compression and friction; after
    // Box2D v3's b2ApplyRestitution): bouncing points get v_target = −e v_n⁻, every other point keeps
    // its target, so a bounce cannot drive a neighbouring point into the ground. Sequential
    // impulses clamped on the total normal impulse, the same number of sweeps. The clamp is
    // λ_n >= |λ_t| / μ rather than >= 0, so the friction impulse of the compression phase stays
    // inside the cone |λ_t| <= μ λ_n (it is 0 without friction).
    bool anyBounce = false;
    for (const ContactImpulse& c : result.points) anyBounce = anyBounce || (c.bounce && c.normalImpulse > 0);
    if (e > 0 && anyBounce) {
        for (ContactImpulse& c : result.points)
            if (c.bounce && c.normalImpulse > 0) c.targetVelocity = -e * c.normalVelocityBefore;
        for (int it = 0; it < options.iterations; ++it) {
            double change = 0.0;
            for (std::size_t i = 0; i < points.size(); ++i) {
                ContactImpulse& c = result.points[i];
                const double floor = mu > 0 ? std::hypot(rows[i].lambdaT1, rows[i].lambdaT2) / mu : 0.0;
                const double vn = (body.linearVelocity + body.angularVelocity.cross(c.r)).dot(normal);
                const double lambda = std::max(floor, c.normalImpulse + c.normalMass * (c.targetVelocity - vn));
                const double d = lambda - c.normalImpulse;
                c.normalImpulse = lambda;
                c.restitutionImpulse += d;
                apply(d * normal, c);
                change = std::max(change, std::abs(d));
            }
            if (options.recordIterations) record(change), ++result.historyRestitution;
        }
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        ContactImpulse& c = result.points[i];
        c.normalVelocityAfter = body.velocityAt(c.point).dot(normal);
        c.tangentImpulse = rows[i].lambdaT1 * t1 + rows[i].lambdaT2 * t2;
    }
    return result;
}

}  // namespace cdlab
