// Closest features of two simplices (core/closest/simplex_pair.h), against long-double brute force
// that shares nothing with it (verification/minkowski_hull_oracle.h: the least distance over every
// vertex triple of each set, and point-segment / point-triangle distances): the distance, the closest
// points lying on the features named, the least total dimension among equally near pairs, and the
// intersection of nested tetrahedra that no boundary pair sees. The demo's committed scenes: GJK
// agrees with the pair found.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "core/closest/simplex_pair.h"
#include "app/catalog/catalog.h"
#include "verification/minkowski_hull_oracle.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

// Distance from p to the feature of s (its vertices by index), long double brute force.
double distanceToFeature(const Vec3& p, const std::vector<Vec3>& s, const SimplexFeature& f) {
    const auto& v = f.vertices;
    if (v.size() == 1) return (p - s[std::size_t(v[0])]).norm();
    if (v.size() == 2) return oracleSegmentDistance(p, p, s[std::size_t(v[0])], s[std::size_t(v[1])]);
    if (v.size() == 3) return oracleDistanceToTriangle(p, {s[std::size_t(v[0])], s[std::size_t(v[1])], s[std::size_t(v[2])]});
    return oracleDistanceToTetrahedron(p, {s[0], s[1], s[2], s[3]});
}

}  // namespace

TEST_CASE("simplex pairs: the distance is the brute-force least, the points lie on the named features") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    int byDimension[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int round = 0; round < 600; ++round) {
        const int na = 1 + round % 4, nb = 1 + (round / 4) % 4;
        std::vector<Vec3> a, b;
        const Vec3 offset(2.2 + u(rng), u(rng), u(rng));
        for (int i = 0; i < na; ++i) a.emplace_back(u(rng), u(rng), u(rng));
        for (int i = 0; i < nb; ++i) b.push_back(offset + Vec3(u(rng), u(rng), u(rng)));
        const SimplexPairResult r = closestFeaturesOfSimplices(a, b);
        REQUIRE(r.valid);
        const double oracle = oracleDistanceBruteForce(a, b);
        if (oracle < 1e-3) continue;  // overlapping or nearly: the brute force is meaningful only apart
        CHECK_FALSE(r.intersect);
        CHECK(r.distance == doctest::Approx(oracle).epsilon(1e-9));
        CHECK((r.pointA - r.pointB).norm() == doctest::Approx(r.distance).epsilon(1e-12));
        CHECK(distanceToFeature(r.pointA, a, r.featureA) <= 1e-9);
        CHECK(distanceToFeature(r.pointB, b, r.featureB) <= 1e-9);
        ++byDimension[r.featureA.dimension() + r.featureB.dimension()];
    }
    CHECK(byDimension[0] > 5);  // vertex–vertex
    CHECK(byDimension[1] > 20);  // vertex–edge
    CHECK(byDimension[2] > 20);  // edge–edge or vertex–face
}

TEST_CASE("simplex pairs: least dimension among ties, containment, touching, bad input") {
    // A point straight above a triangle's vertex: vertex–vertex (not vertex–edge or vertex–face,
    // which are as near).
    const std::vector<Vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    SimplexPairResult r = closestFeaturesOfSimplices(std::vector<Vec3>{{0, 0, 2}}, tri);
    CHECK(r.featureB.vertices == std::vector<int>{0});
    CHECK(r.distance == 2);
    // A small tetrahedron inside a large one: no boundary pair meets, yet they intersect.
    const std::vector<Vec3> big = {{-5, -5, -5}, {5, -5, -5}, {0, 5, -5}, {0, 0, 5}};
    const std::vector<Vec3> small = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
    r = closestFeaturesOfSimplices(big, small);
    CHECK(r.intersect);
    CHECK(r.distance == 0);
    CHECK(r.featureA.dimension() == 3);
    // Touching segments: distance 0, intersecting.
    r = closestFeaturesOfSimplices(std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}}, std::vector<Vec3>{{1, -1, 0}, {1, 1, 0}});
    CHECK(r.intersect);
    CHECK(r.featureA.dimension() + r.featureB.dimension() == 2);  // edge–edge
    // Segments crossing where no double lies: within rounding of touching, reported as meeting.
    r = closestFeaturesOfSimplices(std::vector<Vec3>{{0, 0, 0}, {1, 1, 0}}, std::vector<Vec3>{{0, 0.3, 0}, {0.7, 0, 0}});
    CHECK(r.intersect);
    CHECK(r.distance == 0);
    CHECK_FALSE(closestFeaturesOfSimplices(std::vector<Vec3>{}, tri).valid);
    CHECK_FALSE(closestFeaturesOfSimplices(std::vector<Vec3>{{NAN, 0, 0}}, tri).valid);
}

TEST_CASE("closest_features scenes: GJK agrees with the pair found") {
    for (const char* name : {"closest_segment_triangle", "closest_tetrahedra", "closest_triangles_crossing"}) {
        const Json t = loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/primitives/" + name + ".json")->run(RunContext{}).trace;
        CHECK(t["gjk"]["intersect"] == t["intersect"]);
        CHECK(t["gjk"]["difference"].get<double>() <= 1e-12 * (1 + t["distance"].get<double>()));
    }
}
