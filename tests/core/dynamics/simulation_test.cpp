// The drop simulation. Oracles computed from the trace's states, not from the solver's own
// numbers: vertex heights from (position, orientation) and the shape, energies by hand, free fall
// in closed form before the first contact, v⁺ = −e v⁻ at the first bounce, determinism by
// comparing two runs field by field, and the status of every invalid input.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/dynamics/simulation.h"
#include "core/geometry/polyhedron_presets.h"

using namespace cdlab;

namespace {

DropInput dropOf(const std::string& which, double spin) {
    DropInput in;
    in.shape = which == "box"     ? presets::box(Vec3(0.5, 0.3, 0.2))
               : which == "cube"  ? presets::box(Vec3(0.3, 0.3, 0.3))
               : which == "tetra" ? presets::tetrahedron(0.5)
                                  : presets::icosahedron(0.5);
    in.pose.position = Vec3(0.1, -0.2, 1.5);
    in.pose.rotation = Quat(Eigen::AngleAxisd(0.6, Vec3(1, 1, 0).normalized()));
    in.linearVelocity = Vec3(0.5, 0, 0);
    in.angularVelocity = spin * Vec3(2, -3, 5);
    return in;
}

// Lowest vertex height above the ground from the recorded state (independent of the solver).
double lowestHeight(const SimulationResult& r, const SimulationStep& s, const Vec3& n, double d) {
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : r.shape.positions()) lo = std::min(lo, n.dot(s.orientation * v + s.position) - d);
    return lo;
}

}  // namespace

TEST_SUITE("simulation") {
    TEST_CASE(
        "box, cube, tetrahedron, icosahedron with spin: no vertex deeper than slop, energy never rises, comes to "
        "rest") {
        for (const std::string name : {"box", "cube", "tetra", "ico"})
            for (double e : {0.0, 0.5, 1.0})
                for (double mu : {0.0, 0.5}) {
                    DropInput in = dropOf(name, 1.0);
                    SimulationOptions o;
                    o.steps = 1440;  // 6 s
                    o.solver.restitution = e;
                    o.solver.friction = mu;
                    SimulationTrace tr;
                    const SimulationResult r = simulateDrop(in, o, &tr);
                    INFO(name << " e = " << e << " mu = " << mu << " " << r.message);
                    REQUIRE(r.ok());
                    REQUIRE(tr.steps.size() == 1441);
                    const double m = r.mass.mass, g = 9.81;
                    // Energy: E_k <= E_{k-1} + tol_k with
                    //   m |g| correction_k   the potential energy the position correction adds (recorded),
                    //   1e-9 E_0             rounding,
                    //   1e-4 m |g|² dt²      the PGS residual of resting contacts: 16 sweeps leave an upward
                    //                        normal velocity of up to ~1e-5 g dt (measured 4.6e-7 m/s on a face),
                    //                        lifting the body by that times dt,
                    //   3 m |g| dt |v_n⁻|    in a step with a bounce: first-order time stepping across an impact
                    //                        (the step's gravity increment g dt is reflected with the velocity and
                    //                        the position update uses the reflected velocity: 2 m |g| |v_n| dt for a
                    //                        point mass at e = 1; measured up to 1.98 m |g| dt |v_n|).
                    // Free rotation cannot add energy (implicit gyroscopic step), friction only removes it.
                    const double E0 = tr.steps[0].energy;
                    double worst = 0;
                    for (std::size_t k = 1; k < tr.steps.size(); ++k) {
                        const SimulationStep& s = tr.steps[k];
                        // Hand energy from the state.
                        const Mat3 R = s.orientation.toRotationMatrix();
                        const double ke =
                            0.5 * m * s.linearVelocity.squaredNorm() +
                            0.5 * s.angularVelocity.dot(R * r.mass.inertia * R.transpose() * s.angularVelocity);
                        CHECK(s.energy == doctest::Approx(ke + m * g * s.position.z()).epsilon(1e-12));
                        double impact = 0;
                        for (const ContactImpulse& c : s.contacts)
                            if (c.bounce) impact = std::max(impact, -c.normalVelocityBefore);
                        const double dt = o.timeStep;
                        const double rise = s.energy - tr.steps[k - 1].energy - m * g * s.correction - 1e-9 * E0 -
                                            1e-4 * m * g * g * dt * dt;
                        if (impact > 0) worst = std::max(worst, rise / (m * g * dt * impact));
                        CHECK(rise <= 3 * m * g * dt * impact);
                        CHECK(lowestHeight(r, s, Vec3::UnitZ(), 0.0) >= -o.slop * (1 + 1e-9));
                    }
                    MESSAGE(name << " e=" << e << " mu=" << mu << ": rest " << r.restTime << " s, max penetration "
                                 << r.maxPenetration << ", before correction " << r.maxPenetrationBeforeCorrection
                                 << ", worst rise / (m g dt |v_n|) " << worst);
                    if (mu > 0 && e < 1) {  // friction stops sliding and spinning about the normal
                        CHECK(r.restTime > 0.3);
                        CHECK(r.restTime < 5.0);
                        CHECK(r.body.kineticEnergy() < 1e-6 * E0);
                    }
                }
    }

    TEST_CASE(
        "free fall in closed form, then v⁺ = −e v⁻ at the first bounce (face-down cube, vertex-down tetrahedron)") {
        for (const std::string name : {"cube", "tetra"})
            for (double e : {0.0, 0.4, 0.9}) {
                DropInput in = dropOf(name, 0.0);
                in.linearVelocity = Vec3::Zero();
                // Cube face down; tetrahedron vertex (1,1,1)/√3 pointing straight down.
                in.pose.rotation = name == "cube" ? Quat::Identity()
                                                  : Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), -Vec3::UnitZ());
                SimulationOptions o;
                o.steps = 300;
                o.solver.restitution = e;
                SimulationTrace tr;
                const SimulationResult r = simulateDrop(in, o, &tr);
                REQUIRE(r.ok());
                const double dt = o.timeStep, g = 9.81;
                int first = -1;
                for (std::size_t k = 1; k < tr.steps.size() && first < 0; ++k)
                    if (!tr.steps[k].contacts.empty() && tr.steps[k].contacts[0].normalImpulse > 0)
                        first = static_cast<int>(k);
                INFO(name << " e = " << e);
                REQUIRE(first > 1);
                // Before: z_k = z_0 − g dt² k(k+1)/2 (semi-implicit recursion).
                const int k = first - 1;
                CHECK(tr.steps[k].position.z() ==
                      doctest::Approx(tr.steps[0].position.z() - g * dt * dt * k * (k + 1) / 2).epsilon(1e-12));
                const double vBefore = tr.steps[k].linearVelocity.z() - g * dt;  // after gravity, before impulses
                CHECK(tr.steps[first].linearVelocity.z() == doctest::Approx(-e * vBefore).epsilon(1e-6));
                // Symmetric landing: no spin, up to the 16-sweep PGS residual on the 4-point face (measured 4e-6).
                CHECK(tr.steps[first].angularVelocity.norm() < 2e-5);
            }
    }

    TEST_CASE("determinism: two runs give bit-identical traces") {
        for (const std::string name : {"box", "ico"}) {
            SimulationTrace a, b;
            simulateDrop(dropOf(name, 1.0), {}, &a);
            simulateDrop(dropOf(name, 1.0), {}, &b);
            REQUIRE(a.steps.size() == b.steps.size());
            for (std::size_t k = 0; k < a.steps.size(); ++k) {
                const SimulationStep &x = a.steps[k], &y = b.steps[k];
                CHECK(x.position == y.position);
                CHECK(x.orientation.coeffs() == y.orientation.coeffs());
                CHECK(x.linearVelocity == y.linearVelocity);
                CHECK(x.angularVelocity == y.angularVelocity);
                CHECK(x.energy == y.energy);
                REQUIRE(x.contacts.size() == y.contacts.size());
                for (std::size_t i = 0; i < x.contacts.size(); ++i) {
                    CHECK(x.contacts[i].point == y.contacts[i].point);
                    CHECK(x.contacts[i].normalImpulse == y.contacts[i].normalImpulse);
                }
            }
        }
    }

    TEST_CASE("a tilted ground far from the origin (offset 1e4): same guarantees") {
        DropInput in = dropOf("tetra", 1.0);
        const Vec3 n = Vec3(0.2, -0.1, 1.0).normalized();
        in.ground = Plane{3.0 * n, 3.0 * 1e4};  // n̂ · x = 1e4, normal not unit
        in.pose.position = 1e4 * n + Vec3(0.0, 0.0, 1.0);
        in.gravity = -9.81 * n;
        SimulationOptions o;
        o.steps = 1200;
        SimulationTrace tr;
        const SimulationResult r = simulateDrop(in, o, &tr);
        REQUIRE(r.ok());
        for (const SimulationStep& s : tr.steps) CHECK(lowestHeight(r, s, n, 1e4) >= -o.slop * (1 + 1e-6));
        CHECK(r.restTime > 0);
    }

    TEST_CASE("invalid inputs: empty shape, zero density, NaN pose, zero normal, bad options") {
        DropInput in = dropOf("cube", 0.0);
        DropInput e = in;
        e.shape = ConvexPolyhedron{};
        CHECK(simulateDrop(e).status == SimulationStatus::InvalidShape);
        DropInput z = in;
        z.density = 0.0;
        CHECK(simulateDrop(z).status == SimulationStatus::InvalidShape);
        DropInput nanPose = in;
        nanPose.pose.position.x() = std::numeric_limits<double>::quiet_NaN();
        CHECK(simulateDrop(nanPose).status == SimulationStatus::InvalidBody);
        DropInput nanV = in;
        nanV.angularVelocity.y() = std::numeric_limits<double>::quiet_NaN();
        CHECK(simulateDrop(nanV).status == SimulationStatus::InvalidBody);
        DropInput plane = in;
        plane.ground.normal = Vec3::Zero();
        CHECK(simulateDrop(plane).status == SimulationStatus::InvalidPlane);
        SimulationOptions o;
        o.solver.restitution = 1.5;
        CHECK(simulateDrop(in, o).status == SimulationStatus::InvalidOptions);
        o = {};
        o.timeStep = 0.0;
        CHECK(simulateDrop(in, o).status == SimulationStatus::InvalidOptions);
        o = {};
        o.solver.friction = -1;
        CHECK(simulateDrop(in, o).status == SimulationStatus::InvalidOptions);
        CHECK(!simulateDrop(plane).message.empty());
    }
}
