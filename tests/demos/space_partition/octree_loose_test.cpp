// golden/space_partition/octree_loose run numerically, against the boxes alone: both octrees find
// the brute-force pairs; in the tight one the boxes crossing the root's split lines stay at the root;
// in the loose one (k = 2) each box lies in the loose cell of the cell holding its centre at its
// depth, none at the root here; and the loose octree tests fewer pairs.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("loose octree figure: pairs by brute force, boxes on the root's split lines, depths in the loose tree") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/space_partition/octree_loose.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    const Json& boxes = t["box_list"];
    const int n = int(boxes.size());
    const auto b = [&](int i, int k) { return boxes[std::size_t(i)][std::size_t(k)].get<double>(); };
    int pairs = 0;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            pairs += b(i, 0) <= b(j, 2) && b(j, 0) <= b(i, 2) && b(i, 1) <= b(j, 3) && b(j, 1) <= b(i, 3);
    CHECK(t["tight"]["pairs"].get<int>() == pairs);
    CHECK(t["loose"]["pairs"].get<int>() == pairs);
    // Tight: a box crossing a split line of the root cannot go below it.
    const double S = t["root_side"].get<double>(), half = 0.5 * S;
    int crossing = 0;
    for (int i = 0; i < n; ++i) {
        const bool cross = (b(i, 0) < half && b(i, 2) > half) || (b(i, 1) < half && b(i, 3) > half);
        crossing += cross;
        if (cross) CHECK(t["box_depths"][std::size_t(i)][0].get<int>() == 0);
    }
    CHECK(crossing >= 1);
    CHECK(t["tight"]["objects_at_root"].get<int>() >= crossing);
    // Loose, k = 2: the box lies inside the loose cell (the cell grown by half its side on every
    // side) of the depth-d cell holding its centre, d its depth in the loose tree (the root's square
    // starts at the region's corner, here the origin); none needs the root.
    REQUIRE(t["looseness"].get<double>() == 2.0);
    for (int i = 0; i < n; ++i) {
        const int d = t["box_depths"][std::size_t(i)][1].get<int>();
        CHECK(d >= 1);
        const double side = S / std::pow(2.0, d);
        for (int k = 0; k < 2; ++k) {
            const double centre = 0.5 * (b(i, k) + b(i, k + 2));
            const double cellMin = std::floor(centre / side) * side;
            CHECK(b(i, k) >= cellMin - 0.5 * side - 1e-12);
            CHECK(b(i, k + 2) <= cellMin + 1.5 * side + 1e-12);
        }
    }
    CHECK(t["loose"]["objects_at_root"].get<int>() == 0);
    CHECK(t["loose"]["pair_tests"].get<long long>() < t["tight"]["pair_tests"].get<long long>());
}
