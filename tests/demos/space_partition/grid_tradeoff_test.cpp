// golden/space_partition/grid_tradeoff run numerically: per cell size h the grid's entries recounted
// from the trace's boxes by hand (a flat box enters (floor(x1/h) − floor(x0/h) + 1) × (floor(y1/h) −
// floor(y0/h) + 1) cells), its pairs against brute force over those boxes (closed overlap), and its
// tests between the pairs and brute force's n(n − 1)/2, which one cell holding every box reaches.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("grid trade-off: entries counted by hand, pairs by brute force, tests between them") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/space_partition/grid_tradeoff.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    const Json& boxes = t["box_list"];
    const int n = t["boxes"].get<int>();
    REQUIRE(int(boxes.size()) == n);
    const auto b = [&](int i, int k) { return boxes[std::size_t(i)][std::size_t(k)].get<double>(); };
    int brutePairs = 0;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            brutePairs += b(i, 0) <= b(j, 2) && b(j, 0) <= b(i, 2) && b(i, 1) <= b(j, 3) && b(j, 1) <= b(i, 3);
    const double brute = double(n) * (n - 1) / 2;
    CHECK(t["brute_force_tests"].get<double>() == brute);
    for (const Json& r : t["rows"]) {
        const double h = r["cell_size"].get<double>();
        CAPTURE(h);
        REQUIRE(r["status"] == "ok");
        long long entries = 0;
        for (int i = 0; i < n; ++i)
            entries += (long long)(std::floor(b(i, 2) / h) - std::floor(b(i, 0) / h) + 1) *
                       (long long)(std::floor(b(i, 3) / h) - std::floor(b(i, 1) / h) + 1);
        CHECK(r["entries"].get<long long>() == entries);
        CHECK(r["pairs"].get<int>() == brutePairs);
        CHECK(r["pair_tests"].get<long long>() >= brutePairs);
        CHECK(double(r["pair_tests"].get<long long>()) <= brute);
    }
    // The largest cell holds every box: every pair tested once, each box entered once.
    CHECK(double(t["rows"].back()["pair_tests"].get<long long>()) == brute);
}
