// translationalTimeOfImpact against independent oracles: Cyrus–Beck of the relative motion against
// the brute-force facets of the Minkowski difference, the closed form of two moving spheres
// (Ericson §5.5.8), the first root of the capsule-capsule distance; and the degenerate motions
// (none, parallel to a face, touching at t = 0, grazing).
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/cast/time_of_impact.h"
#include "verification/cast_oracle.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/random_vectors.h"

using namespace cdlab;
namespace co = cdlab::demos::cast_oracle;

namespace {

using cdlab::test::randomVec;

double support(const std::vector<Vec3>& p, const Vec3& d, const Vec3& shift) {
    double best = -INFINITY;
    for (const Vec3& v : p) best = std::max(best, d.dot(v + shift));
    return best;
}

std::vector<Vec3> unitBox(const Vec3& lo) {
    std::vector<Vec3> out;
    for (int i = 0; i < 8; ++i) out.push_back(lo + Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    return out;
}

}  // namespace

TEST_CASE("time of impact: random polytopes agree with Cyrus-Beck on the Minkowski difference's facets") {
    std::mt19937_64 rng(11);
    int hits = 0, misses = 0, overlaps = 0;
    for (int trial = 0; trial < 600; ++trial) {
        const std::vector<Vec3> a = test::randomPolytope(rng, 4 + trial % 5, 1.0, randomVec(rng, 1.0));
        const std::vector<Vec3> b = test::randomPolytope(rng, 4 + trial % 4, 1.0, randomVec(rng, trial % 8 ? 4.0 : 1.0));
        // b heads roughly for a (or a for b): hits, misses and a few overlaps at t = 0.
        const Vec3 toward = (a[0] - b[0]) * (trial % 3 == 0 ? 0.5 : 1.5);
        const Vec3 ma = trial % 2 ? Vec3(-toward + randomVec(rng, 1.5)) : randomVec(rng, 0.5);
        const Vec3 mb = trial % 2 ? randomVec(rng, 0.5) : Vec3(toward + randomVec(rng, 1.5));
        std::vector<Vec3> difference;
        for (const Vec3& x : a)
            for (const Vec3& y : b) difference.push_back(y - x);
        const co::PolytopeCast want = co::castRayPolytope(Vec3::Zero(), Vec3(ma - mb), difference);
        const TimeOfImpactResult got = translationalTimeOfImpact(a, 0.0, ma, b, 0.0, mb);
        CAPTURE(trial);
        if (want.inside) {
            CHECK(got.initiallyOverlapping);
            ++overlaps;
        } else if (want.hit && want.tEnter <= 1 - 1e-9 && want.margin > 1e-9) {
            REQUIRE(got.hit);
            CHECK_FALSE(got.initiallyOverlapping);
            CHECK(std::abs(got.t - double(want.tEnter)) <= 1e-9 * got.t + 1e-12);
            // The touching points: on A(t) and B(t), at the extremes of the normal's supporting planes.
            CHECK(std::abs(got.normal.norm() - 1) < 1e-12);
            CHECK((got.pointA - got.pointB).norm() < 1e-9);
            CHECK(got.normal.dot(got.pointA) >= support(a, got.normal, got.t * ma) - 1e-9);
            CHECK(-got.normal.dot(got.pointB) >= support(b, Vec3(-got.normal), got.t * mb) - 1e-9);
            CHECK(got.normal.dot(mb - ma) <= 1e-12);  // the shapes were closing along it
            ++hits;
        } else if ((!want.hit && want.margin < -1e-9) || (want.hit && want.tEnter > 1 + 1e-9)) {
            CHECK_FALSE(got.hit);
            ++misses;
        }
    }
    CHECK(hits > 100);
    CHECK(misses > 100);
    CHECK(overlaps > 5);
}

TEST_CASE("time of impact: moving spheres in closed form, capsules by the first root of their distance") {
    std::mt19937_64 rng(5);
    int hits = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const Vec3 ca = randomVec(rng, 2.0), cb = randomVec(rng, 2.0), ma = randomVec(rng, 0.5);
        const Vec3 mb = (ca - cb) * 1.5 + randomVec(rng, 1.0);  // b heads roughly for a
        std::uniform_real_distribution<double> radius(0.05, 0.6);
        const double ra = radius(rng), rb = radius(rng);
        CAPTURE(trial);
        if (trial % 2 == 0) {
            // |s + t v| = r, s = cb − ca, v = mb − ma (Ericson §5.5.8), in long double.
            const co::LVec s = co::toL(cb) - co::toL(ca), v = co::toL(mb) - co::toL(ma);
            const long double r = (long double)ra + rb, c = s.squaredNorm() - r * r;
            const long double A = v.squaredNorm(), B = s.dot(v), disc = B * B - A * c;
            const TimeOfImpactResult got =
                translationalTimeOfImpact(std::vector<Vec3>{ca}, ra, ma, std::vector<Vec3>{cb}, rb, mb);
            if (c < -1e-9) CHECK(got.initiallyOverlapping);
            else if (c > 1e-9 && B < 0 && disc > 1e-9) {
                const long double t = (-B - std::sqrt(disc)) / A;
                if (t < 1 - 1e-9) {
                    REQUIRE(got.hit);
                    CHECK(std::abs(got.t - double(t)) < 1e-9);
                    ++hits;
                } else if (t > 1 + 1e-9) CHECK_FALSE(got.hit);
            } else if (c > 1e-9 && (B >= 0 || disc < -1e-9)) CHECK_FALSE(got.hit);
        } else {
            const Vec3 ea = randomVec(rng, 1.0), eb = randomVec(rng, 1.0);
            const auto gap = [&](long double t) {
                const co::LVec sa = co::toL(ca) + t * co::toL(ma), sb = co::toL(cb) + t * co::toL(mb);
                return co::segmentSegmentDistance(sa, sa + co::toL(ea), sb, sb + co::toL(eb)) - ra - rb;
            };
            const TimeOfImpactResult got = translationalTimeOfImpact(std::vector<Vec3>{ca, ca + ea}, ra, ma,
                                                                     std::vector<Vec3>{cb, cb + eb}, rb, mb);
            if (gap(0) < -1e-9) CHECK(got.initiallyOverlapping);
            else if (gap(0) > 1e-9) {
                const co::ConvexMinimum m = co::minimumOfConvex(gap, 1.0L);
                if (m.value < -1e-6) {
                    REQUIRE(got.hit);
                    CHECK(std::abs(got.t - double(co::firstRootOfConvex(gap, 1.0L))) < 1e-8);
                    CHECK((got.pointA - got.pointB).norm() < 1e-9);
                    ++hits;
                } else if (m.value > 1e-9) CHECK_FALSE(got.hit);
            }
        }
    }
    CHECK(hits > 80);
}

TEST_CASE("time of impact: no motion, parallel motion, touching at t = 0, grazing") {
    const std::vector<Vec3> a = unitBox(Vec3::Zero());
    SUBCASE("no relative motion") {
        CHECK_FALSE(translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(3, 0, 0)), 0, Vec3::Zero()).hit);
        CHECK_FALSE(translationalTimeOfImpact(a, 0, Vec3(1, 2, 3), unitBox(Vec3(3, 0, 0)), 0, Vec3(1, 2, 3)).hit);
        CHECK(translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(1, 0, 0)), 0, Vec3::Zero()).initiallyOverlapping);
    }
    SUBCASE("touching at t = 0, moving apart: touching counts (closed shapes)") {
        const TimeOfImpactResult r = translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(1, 0, 0)), 0, Vec3(1, 0, 0));
        CHECK(r.hit);
        CHECK(r.initiallyOverlapping);
        CHECK(r.t == 0);
    }
    SUBCASE("sliding along a face into a face") {
        // b lies on a's top face plane, one unit to the side, and slides back along it.
        const TimeOfImpactResult r = translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(2, 0, 1)), 0, Vec3(-2, 0, 0));
        REQUIRE(r.hit);
        CHECK_FALSE(r.initiallyOverlapping);
        CHECK(r.t == doctest::Approx(0.5).epsilon(1e-12));
        CHECK(r.normal.isApprox(Vec3(1, 0, 0), 1e-12));  // the face it runs into
        CHECK((r.pointA - r.pointB).norm() < 1e-12);
        CHECK(r.pointA.x() == doctest::Approx(1.0));
        CHECK(r.pointA.z() == doctest::Approx(1.0));
    }
    SUBCASE("parallel to a face above a gap: no contact") {
        CHECK_FALSE(translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(2, 0, 1 + 1e-9)), 0, Vec3(-4, 0, 0)).hit);
    }
    SUBCASE("an edge sliding along an edge until the corners meet") {
        // b's edge x = 1, z = 1 runs along the line of a's edge x = 1, z = 1 (their faces coplanar
        // on two sides): the two touch first when b's near corner reaches y = 1.
        const TimeOfImpactResult r =
            translationalTimeOfImpact(a, 0, Vec3::Zero(), unitBox(Vec3(1, 2, 1)), 0, Vec3(0, -4, 0));
        REQUIRE(r.hit);
        CHECK(r.t == doctest::Approx(0.25).epsilon(1e-12));
        CHECK(r.normal.isApprox(Vec3(0, 1, 0), 1e-12));
        CHECK(r.pointA.isApprox(Vec3(1, 1, 1), 1e-12));
    }
}
