// Closest point on a tetrahedron ("point vs 3D simplex"): against a long double brute force
// (min over the four faces + inside test), an exact BigInt region oracle near boundaries, all 24
// vertex orderings, ties, flat tetrahedra and non-finite input.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include "core/closest/closest_point.h"
#include "verification/closest_oracle.h"
#include "tests/core/closest/closest_test_support.h"

using namespace cdlab;
using T = TetrahedronRegion;

namespace {

using cdlab::test::N;

std::set<int> featureOf(T r) {
    static const std::set<int> kSets[15] = {{0},       {1},       {2},       {3},       {0, 1},
                                            {0, 2},    {0, 3},    {1, 2},    {1, 3},    {2, 3},
                                            {0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}, {0, 1, 2, 3}};
    return kSets[static_cast<int>(r)];
}

using cdlab::test::randomVec;

using cdlab::test::make;

}  // namespace

TEST_SUITE("closest_tetrahedron") {
    TEST_CASE("integer tetrahedron: every kind of region, known by construction") {
        const Tetrahedron t{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4)};
        struct Case {
            Vec3 p;
            T region;
            Vec3 point;
        };
        const Case cases[] = {
            {Vec3(-1, -1, -1), T::A, Vec3(0, 0, 0)}, {Vec3(5, -1, 0), T::B, Vec3(4, 0, 0)},
            {Vec3(-1, 6, -2), T::C, Vec3(0, 4, 0)},  {Vec3(0, -1, 7), T::D, Vec3(0, 0, 4)},
            {Vec3(2, -1, -1), T::AB, Vec3(2, 0, 0)}, {Vec3(-1, 3, -1), T::AC, Vec3(0, 3, 0)},
            {Vec3(-2, -2, 1), T::AD, Vec3(0, 0, 1)}, {Vec3(3, 3, -1), T::BC, Vec3(2, 2, 0)},
            {Vec3(3, -1, 3), T::BD, Vec3(2, 0, 2)},  {Vec3(-1, 3, 3), T::CD, Vec3(0, 2, 2)},
            {Vec3(1, 1, -2), T::ABC, Vec3(1, 1, 0)}, {Vec3(1, -3, 2), T::ABD, Vec3(1, 0, 2)},
            {Vec3(-5, 1, 1), T::ACD, Vec3(0, 1, 1)}, {Vec3(3, 3, 3), T::BCD, Vec3(5, 5, 5) / 3.0 - Vec3(1, 1, 1) / 3.0},
            {Vec3(1, 1, 1), T::ABCD, Vec3(1, 1, 1)},
        };
        for (const Case& c : cases) {
            TetrahedronTrace trace;
            const auto r = closestPointOnTetrahedron(c.p, t, &trace);
            CHECK(N(r.region) == N(c.region));
            CHECK((r.point - c.point).norm() < 1e-14);
            CHECK(r.distanceSquared == doctest::Approx((c.p - c.point).squaredNorm()).epsilon(1e-14));
            CHECK(r.status == SimplexStatus::Regular);
            // Weights vanish off the feature, sum to 1 and reproduce the point.
            const std::set<int> f = featureOf(r.region);
            Vec3 fromWeights = Vec3::Zero();
            const Vec3 v[4] = {t.a, t.b, t.c, t.d};
            for (int i = 0; i < 4; ++i) {
                CHECK(r.barycentric[i] >= 0.0);
                if (!f.count(i)) CHECK(r.barycentric[i] == 0.0);
                fromWeights += r.barycentric[i] * v[i];
            }
            CHECK(std::abs(r.barycentric.sum() - 1.0) < 1e-14);
            CHECK((fromWeights - r.point).norm() < 1e-13);
            // Trace: vertex, edge, face tests in order, only the last accepted.
            REQUIRE(!trace.tests.empty());
            CHECK(N(trace.tests.back().candidate) == N(c.region));
            CHECK(trace.tests.back().accepted);
            for (size_t k = 0; k + 1 < trace.tests.size(); ++k) {
                CHECK_FALSE(trace.tests[k].accepted);
                CHECK(static_cast<int>(trace.tests[k].candidate) == static_cast<int>(k));
            }
        }
    }

    TEST_CASE("ties: on a boundary the lower-dimensional feature wins") {
        const Tetrahedron t{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4)};
        CHECK(N(closestPointOnTetrahedron(Vec3(0, 0, 0), t).region) == "A");    // on a vertex
        CHECK(N(closestPointOnTetrahedron(Vec3(0, -1, -3), t).region) == "A");  // A | AB plane
        CHECK(N(closestPointOnTetrahedron(Vec3(2, 0, 0), t).region) == "AB");   // on an edge
        CHECK(N(closestPointOnTetrahedron(Vec3(2, -3, 0), t).region) == "AB");  // AB | ABD boundary... in z = 0
        CHECK(N(closestPointOnTetrahedron(Vec3(1, 1, 0), t).region) == "ABC");  // on a face: face beats inside
        CHECK(N(closestPointOnTetrahedron(Vec3(2, 2, -5), t).region) == "BC");  // BC | ABC boundary
        CHECK(closestPointOnTetrahedron(Vec3(1, 1, 0), t).distanceSquared == 0.0);
    }

    TEST_CASE("random queries vs long double brute force, all 24 orderings, offsets and scales") {
        std::mt19937_64 rng(11);
        std::array<int, 4> perm = {0, 1, 2, 3};
        std::vector<std::array<int, 4>> perms;
        do perms.push_back(perm);
        while (std::next_permutation(perm.begin(), perm.end()));
        const double offsets[] = {0.0, 1e4, 1e6};
        int inside = 0;
        for (double offset : offsets) {
            for (int i = 0; i < 250; ++i) {
                const double scale = std::pow(10.0, (i % 7) - 3);
                const Vec3 shift(offset, 0.5 * offset, -offset);
                const std::array<Vec3, 4> v = {scale * randomVec(rng, 1) + shift, scale * randomVec(rng, 1) + shift,
                                               scale * randomVec(rng, 1) + shift, scale * randomVec(rng, 1) + shift};
                Vec3 p = scale * randomVec(rng, 1.5) + shift;
                if (i % 9 == 4) p = v[i % 4];
                if (i % 3 == 0) {  // a random point of the solid (inside, or on its boundary)
                    std::uniform_real_distribution<double> w(0.0, 1.0);
                    Eigen::Vector4d wt(w(rng), w(rng), w(rng), w(rng));
                    wt /= wt.sum();
                    p = wt[0] * v[0] + wt[1] * v[1] + wt[2] * v[2] + wt[3] * v[3];
                }
                const long double truth = std::sqrt(oracle::tetrahedronDistance2(p, v));
                std::set<int> first;
                for (const auto& q : perms) {
                    const auto r = closestPointOnTetrahedron(p, make({v[q[0]], v[q[1]], v[q[2]], v[q[3]]}));
                    REQUIRE(r.status == SimplexStatus::Regular);
                    const long double d = std::sqrt(static_cast<long double>(r.distanceSquared));
                    CHECK(std::abs(d - truth) <= 1e-14L * (offset + 10 * scale) + 1e-12L * truth);
                    std::set<int> feature;
                    for (int local : featureOf(r.region)) feature.insert(q[local]);
                    if (&q == &perms.front()) {
                        first = feature;
                        inside += r.region == T::ABCD;
                    } else {
                        CHECK(feature == first);
                    }
                }
            }
        }
        CHECK(inside > 20);  // the inside region was exercised
    }

    TEST_CASE("near-boundary points: exact region vs BigInt oracle") {
        // Dyadic tetrahedra at offsets; p = an exact point on a feature, pushed along a face normal
        // or edge direction by dyadic amounts, then moved one ulp. Truth: closed-region tests by
        // increasing dimension in exact integer arithmetic (the oracle's own formulation).
        std::mt19937_64 rng(12);
        std::uniform_int_distribution<int> small(-6, 6);
        int total = 0, fallbacks = 0;
        std::set<int> regionsSeen;
        const double offsets[] = {1.0, 1e3, 1e5};
        for (double offset : offsets) {
            for (int i = 0; i < 500; ++i) {
                const Vec3 o(offset, -offset, 0.5 * offset);
                std::array<Vec3, 4> v;
                for (auto& x : v) x = o + Vec3(small(rng), small(rng), small(rng)) / 4.0;
                if ((v[1] - v[0]).cross(v[2] - v[0]).dot(v[3] - v[0]) == 0.0)
                    continue;  // exact for these small dyadics
                const int f = i % 4;
                const Vec3 x = v[f], y = v[(f + 1) % 4], z = v[(f + 2) % 4];
                const Vec3 n = (y - x).cross(z - x);
                Vec3 p = x + (y - x) * (small(rng) + 6) / 16.0 + (z - x) * (small(rng) + 6) / 32.0;
                p += n * (small(rng) / 8.0);
                if (i % 3 == 0) p += (y - x) * (small(rng) / 4.0);
                const int axis = i % 3;
                // (From 0 that is one subnormal ulp, 2^-1074: the predicates are exact there too.)
                const double toward = (i / 3) % 2 ? INFINITY : -INFINITY;
                p[axis] = std::nextafter(p[axis], toward);
                const T truth = oracle::exactTetrahedronRegion(p, v);
                TetrahedronTrace trace;
                const auto r = closestPointOnTetrahedron(p, make(v), &trace);
                CHECK(N(r.region) == N(truth));
                regionsSeen.insert(static_cast<int>(truth));
                ++total;
                for (const auto& test : trace.tests) {
                    for (int k = 0; k < test.termCount; ++k) fallbacks += test.terms[k].exactFallback;
                }
            }
        }
        MESSAGE("tetrahedron near-boundary queries: " << total << ", exact fallbacks: " << fallbacks
                                                      << ", distinct regions: " << regionsSeen.size());
        CHECK(fallbacks > 0);
        CHECK(regionsSeen.size() >= 10);
    }

    TEST_CASE("flat tetrahedra fall back to the faces, non-finite input") {
        // Coplanar: d inside triangle abc (all in z = 0).
        const Tetrahedron flat{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(1, 1, 0)};
        auto r = closestPointOnTetrahedron(Vec3(1, 2, 3), flat);
        CHECK(r.status == SimplexStatus::Degenerate);
        CHECK(r.point == Vec3(1, 2, 0));
        CHECK(r.distanceSquared == 9.0);
        r = closestPointOnTetrahedron(Vec3(-1, -1, 0), flat);
        CHECK(N(r.region) == "A");
        // Random flat tetrahedra (dyadic, exactly coplanar), including collinear and repeated points.
        std::mt19937_64 rng(13);
        std::uniform_int_distribution<int> k(-4, 4);
        for (int i = 0; i < 400; ++i) {
            const Vec3 base = (4 * randomVec(rng, 4)).array().round() / 4;
            const Vec3 u(k(rng), k(rng), k(rng)), w = (i % 5 == 0) ? u : Vec3(k(rng), k(rng), k(rng));
            std::array<Vec3, 4> v;
            for (auto& x : v) x = base + u * (k(rng) / 4.0) + w * (k(rng) / 4.0);
            const Vec3 p = randomVec(rng, 5);
            r = closestPointOnTetrahedron(p, make(v));
            REQUIRE(r.point.allFinite());
            CHECK(r.status == SimplexStatus::Degenerate);
            CHECK(std::abs(std::sqrt(r.distanceSquared) - std::sqrt(double(oracle::tetrahedronDistance2(p, v)))) <
                  1e-11);
        }
        r = closestPointOnTetrahedron(Vec3(NAN, 0, 0),
                                      Tetrahedron{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        CHECK(r.status == SimplexStatus::NonFinite);
        CHECK(std::isnan(r.distanceSquared));
    }

}  // TEST_SUITE
