#include "core/dynamics/simulation.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

const char* nameOf(SimulationStatus status) {
    switch (status) {
        case SimulationStatus::Ok: return "Ok";
        case SimulationStatus::InvalidShape: return "InvalidShape";
        case SimulationStatus::InvalidBody: return "InvalidBody";
        case SimulationStatus::InvalidPlane: return "InvalidPlane";
        case SimulationStatus::InvalidOptions: return "InvalidOptions";
    }
    return "?";
}

namespace {

void recordState(SimulationStep& s, const RigidBody& body, const Vec3& gravity) {
    s.position = body.position;
    s.orientation = body.orientation;
    s.linearVelocity = body.linearVelocity;
    s.angularVelocity = body.angularVelocity;
    s.kinetic = body.kineticEnergy();
    s.potential = body.potentialEnergy(gravity);
    s.energy = s.kinetic + s.potential;
}

}  // namespace

SimulationStep stepBodyOnPlane(RigidBody& body, const ConvexPolyhedron& shape, double radius, const Vec3& unitNormal,
                               double unitOffset, const Vec3& gravity, const SimulationOptions& options) {
    SimulationStep out;
    out.normal = unitNormal;
    const double dt = options.timeStep;
    const Plane plane{unitNormal, unitOffset};

    // 1. Gravity.
    integrateVelocity(body, gravity, dt);

    // 2. Manifold, speculative: every vertex that can reach the plane in this step is a candidate.
    PlaneContactOptions contactOptions;
    contactOptions.tolerance = options.slop + dt * (body.linearVelocity.norm() + body.angularVelocity.norm() * radius);
    contactOptions.maxPoints = options.maxContactPoints;
    const PlaneContactResult contact = contactPolyhedronPlane(shape, body.transform(), plane, contactOptions);
    out.contactStatus = contact.status;
    std::vector<ContactConstraintPoint> points;
    if (contact.colliding())
        for (const ContactPoint& p : contact.manifold)
            points.push_back({p.pointA, unitNormal.dot(p.pointA) - unitOffset});

    // 3. Impulses.
    ImpulseSolverOptions solver = options.solver;
    solver.timeStep = dt;
    out.contacts = solveContacts(body, unitNormal, points, solver).points;

    // 4. Positions with the new velocities.
    integratePosition(body, dt);

    // 5. Minimum-translation correction down to the slop.
    const double s = signedDistancePolyhedronPlane(shape, body.transform(), plane);
    out.penetrationBeforeCorrection = std::max(0.0, -s);
    if (s < -options.slop) {
        out.correction = -options.slop - s;
        body.position += out.correction * unitNormal;
    }
    out.maxPenetration = std::max(0.0, -signedDistancePolyhedronPlane(shape, body.transform(), plane));
    recordState(out, body, gravity);
    return out;
}

SimulationResult simulateDrop(const DropInput& input, const SimulationOptions& options, SimulationTrace* trace) {
    SimulationResult res;
    const auto fail = [&](SimulationStatus s, const std::string& m) {
        res.status = s;
        res.message = m;
        return res;
    };
    const ImpulseSolverOptions& so = options.solver;
    if (!(options.timeStep > 0) || !std::isfinite(options.timeStep) || options.steps < 0 || !(options.slop >= 0) ||
        !std::isfinite(options.slop) || !(so.friction >= 0) || !std::isfinite(so.friction) || !(so.restitution >= 0) ||
        !(so.restitution <= 1) || !(so.restitutionThreshold >= 0) || so.iterations < 1 || !(options.restSpeed >= 0))
        return fail(
            SimulationStatus::InvalidOptions,
            "options: need timeStep > 0, steps >= 0, slop >= 0, friction >= 0, restitution in [0, 1], iterations >= 1");
    const double nn = input.ground.normal.norm();
    if (!(nn > 0) || !std::isfinite(nn) || !std::isfinite(input.ground.offset) || !input.gravity.allFinite())
        return fail(SimulationStatus::InvalidPlane,
                    "ground normal must be non-zero and finite, offset and gravity finite");
    const Vec3 n = input.ground.normal / nn;
    const double d = input.ground.offset / nn;

    res.mass = computeMassProperties(input.shape, {.density = input.density});
    if (!res.mass.ok())
        return fail(SimulationStatus::InvalidShape, std::string(nameOf(res.mass.status)) + ": " + res.mass.message);

    // Recentre: body frame origin at the centre of mass (the inertia about it is unchanged).
    PolyhedronBuild recentred = input.shape.translated(-res.mass.centerOfMass);
    if (!recentred.ok()) return fail(SimulationStatus::InvalidShape, recentred.check.message);
    res.shape = std::move(recentred.polyhedron);
    for (const Vec3& p : res.shape.positions()) res.boundingRadius = std::max(res.boundingRadius, p.norm());

    const Transform comPose{input.pose.apply(res.mass.centerOfMass), input.pose.rotation};
    RigidBodyBuild built =
        makeDynamicBody(res.mass.mass, res.mass.inertia, comPose, input.linearVelocity, input.angularVelocity);
    if (!built.ok())
        return fail(SimulationStatus::InvalidBody, std::string(nameOf(built.status)) + ": " + built.message);
    RigidBody body = built.body;

    SimulationStep initial;
    initial.normal = n;
    initial.contactStatus = contactPolyhedronPlane(res.shape, body.transform(), Plane{n, d}).status;
    initial.maxPenetration = std::max(0.0, -signedDistancePolyhedronPlane(res.shape, body.transform(), Plane{n, d}));
    recordState(initial, body, input.gravity);
    if (trace) {
        trace->steps.clear();
        trace->steps.reserve(options.steps + 1);
        trace->steps.push_back(initial);
    }
    double previousEnergy = initial.energy;
    double restSince = 0.0;
    bool resting = false;
    for (int k = 1; k <= options.steps; ++k) {
        SimulationStep s = stepBodyOnPlane(body, res.shape, res.boundingRadius, n, d, input.gravity, options);
        s.step = k;
        s.time = k * options.timeStep;
        res.maxPenetration = std::max(res.maxPenetration, s.maxPenetration);
        res.maxPenetrationBeforeCorrection =
            std::max(res.maxPenetrationBeforeCorrection, s.penetrationBeforeCorrection);
        res.maxEnergyIncrease = std::max(res.maxEnergyIncrease, s.energy - previousEnergy);
        res.totalCorrection += s.correction;
        previousEnergy = s.energy;
        const bool still = body.linearVelocity.norm() < options.restSpeed &&
                           body.angularVelocity.norm() * res.boundingRadius < options.restSpeed;
        if (still && !resting) restSince = s.time;
        resting = still;
        if (trace) trace->steps.push_back(std::move(s));
        res.stepsRun = k;
    }
    res.restTime = resting ? restSince : -1.0;
    res.body = body;
    return res;
}

}  // namespace cdlab
