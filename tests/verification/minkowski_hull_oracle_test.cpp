// The oracles behind `cdlab bench`'s error columns (verification/minkowski_hull_oracle.h) against answers
// known in closed form: axis-aligned boxes (face / edge / vertex distance, overlap depth), the
// same configurations rigidly rotated and offset, and points vs triangle / tetrahedron.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "verification/minkowski_facet_oracle.h"
#include "verification/minkowski_hull_oracle.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

std::vector<Vec3> boxCorners(const Vec3& center, const Vec3& half, const Quat& q = Quat::Identity(),
                             const Vec3& offset = Vec3::Zero()) {
    std::vector<Vec3> c;
    for (int i = 0; i < 8; ++i)
        c.push_back(offset + q * (center + Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                                (i & 4) ? half.z() : -half.z())));
    return c;
}

struct BoxCase {
    Vec3 centerB;
    double distance;  // exact separation (0 when overlapping)
    double depth;     // exact overlap depth (0 when separated)
    Vec3 normal;      // outward normal of A - B's nearest face when overlapping (from A toward B)
};

}  // namespace

TEST_SUITE("bench oracle") {
    TEST_CASE("the two Minkowski oracles agree: hull of the differences vs facet enumeration by triples") {
        // Two independent ways to the same answer (the bench's builds core's hull of {a_i - b_j}; the
        // tests' enumerates facet planes by triples and uses no core algorithm): distance, inside
        // and depth agree on random 6-vertex pairs, separated and overlapping.
        std::mt19937_64 rng(7);
        int separated = 0, overlapping = 0;
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 offset = (trial % 2 ? 0.5 : 2.2) * cdlab::test::randomUnit(rng);
            const std::vector<Vec3> a = cdlab::test::randomPolytope(rng, 6, 1.0, Vec3::Zero());
            const std::vector<Vec3> b = cdlab::test::randomPolytope(rng, 6, 1.0, offset);
            const MinkowskiOracle hull = minkowskiOracle(a, b);
            const cdlab::test::HullOracle facets = cdlab::test::hullOracle(a, b);
            REQUIRE(hull.ok);
            REQUIRE(hull.inside == facets.inside);
            if (hull.inside) {
                ++overlapping;
                CHECK(hull.depth == doctest::Approx(double(facets.depth)).epsilon(1e-12));
            } else {
                ++separated;
                CHECK(hull.distance == doctest::Approx(double(facets.distance)).epsilon(1e-12));
            }
        }
        CHECK(separated > 30);
        CHECK(overlapping > 30);
    }

    TEST_CASE("boxes: face, edge, vertex distance and overlap depth, under rotations and offsets") {
        const Vec3 halfA(1.0, 2.0, 3.0);
        const Vec3 halfB(0.5, 0.5, 0.5);
        // Gaps per axis: |c| - (hA + hB) = (c - 1.5, c - 2.5, c - 3.5).
        const BoxCase cases[] = {
            {Vec3(4.0, 0.3, -0.2), 2.5, 0.0, Vec3::Zero()},                      // face x
            {Vec3(3.0, 4.0, 0.0), std::sqrt(2 * 1.5 * 1.5), 0.0, Vec3::Zero()},  // edge xy
            {Vec3(3.0, 4.0, 5.0), std::sqrt(3 * 1.5 * 1.5), 0.0, Vec3::Zero()},  // vertex
            {Vec3(1.2, 0.0, 0.0), 0.0, 0.3, Vec3(1, 0, 0)},                      // overlap 0.3 along x
            {Vec3(0.0, -2.25, 0.5), 0.0, 0.25, Vec3(0, -1, 0)},                  // overlap 0.25 along y
        };
        std::mt19937_64 rng(7);
        std::normal_distribution<double> g(0.0, 1.0);
        for (int trial = 0; trial < 4; ++trial) {
            Quat q = Quat::Identity();
            Vec3 offset = Vec3::Zero();
            if (trial > 0) {
                q = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
                offset = Vec3(g(rng), g(rng), g(rng)) * (trial == 3 ? 1e3 : 1.0);
            }
            for (const BoxCase& k : cases) {
                CAPTURE(trial);
                CAPTURE(k.centerB.transpose());
                const MinkowskiOracle o = minkowskiOracle(boxCorners(Vec3::Zero(), halfA, q, offset),
                                                          boxCorners(k.centerB, halfB, q, offset));
                REQUIRE(o.ok);
                const double tol = trial == 3 ? 1e-11 : 1e-13;  // 1e3 offset: corners rounded to ~1e-13
                CHECK(o.inside == (k.depth > 0));
                CHECK(std::abs(o.distance - k.distance) <= tol * (1 + k.distance));
                CHECK(std::abs(o.depth - k.depth) <= tol);
                if (k.depth > 0) {
                    // A - B spans x in [-c - 1.5, -c + 1.5]: for B at +x the nearest face is x = 1.5 - c,
                    // outward +x, i.e. pointing from A toward B.
                    CHECK((o.normal - q * k.normal).norm() <= 1e-12);
                }
            }
        }
    }

    TEST_CASE("touching boxes: distance 0, not inside") {
        const MinkowskiOracle o = minkowskiOracle(boxCorners(Vec3::Zero(), Vec3(1, 1, 1)),
                                                  boxCorners(Vec3(2.0, 0.25, 0.0), Vec3(1, 0.5, 0.5)));
        REQUIRE(o.ok);
        CHECK_FALSE(o.inside);
        CHECK(o.distance <= 1e-15);
    }

    TEST_CASE("sphere-like point clouds: distance between the analytic sphere bounds") {
        // Points on two unit spheres (in convex position): their hull lies inside the balls and
        // contains the inscribed polytope, so the distance is at least the ball distance and
        // approaches it as the sampling gets dense (here 400 points: within 2%).
        std::mt19937_64 rng(11);
        std::normal_distribution<double> g(0.0, 1.0);
        std::vector<Vec3> a, b;
        const Vec3 cb(3.0, 1.0, -0.5);
        for (int i = 0; i < 400; ++i) {
            a.push_back(Vec3(g(rng), g(rng), g(rng)).normalized());
            b.push_back(cb + Vec3(g(rng), g(rng), g(rng)).normalized());
        }
        // Make the closest points exact members of each cloud: the distance is then exactly analytic.
        a.push_back(cb.normalized());
        b.push_back(cb - cb.normalized());
        const MinkowskiOracle o = minkowskiOracle(a, b);
        REQUIRE(o.ok);
        CHECK_FALSE(o.inside);
        CHECK(std::abs(o.distance - (cb.norm() - 2.0)) <= 1e-12);
    }

    TEST_CASE("point vs triangle and tetrahedron: closed-form distances") {
        const Triangle t{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
        CHECK(oracleDistanceToTriangle(Vec3(0.5, 0.5, 3.0), t) == doctest::Approx(3.0).epsilon(1e-15));    // face
        CHECK(oracleDistanceToTriangle(Vec3(1.0, -2.0, 0.0), t) == doctest::Approx(2.0).epsilon(1e-15));   // edge
        CHECK(oracleDistanceToTriangle(Vec3(-3.0, -4.0, 0.0), t) == doctest::Approx(5.0).epsilon(1e-15));  // vertex
        CHECK(oracleDistanceToTriangle(Vec3(2.0, 2.0, 0.0), t) == doctest::Approx(std::sqrt(2.0)).epsilon(1e-15));
        const Tetrahedron k{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
        CHECK(oracleDistanceToTetrahedron(Vec3(0.1, 0.1, 0.1), k) == 0.0);                                   // inside
        CHECK(oracleDistanceToTetrahedron(Vec3(0.2, 0.2, -1.0), k) == doctest::Approx(1.0).epsilon(1e-15));  // face z=0
        CHECK(oracleDistanceToTetrahedron(Vec3(1, 1, 1), k) == doctest::Approx(2.0 / std::sqrt(3.0)).epsilon(1e-15));
        CHECK(oracleDistanceToTetrahedron(Vec3(-1, -1, -1), k) == doctest::Approx(std::sqrt(3.0)).epsilon(1e-15));
    }
}
