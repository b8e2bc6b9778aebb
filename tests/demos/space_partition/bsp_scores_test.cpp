// golden/space_partition/bsp_scores run numerically: the root's candidate scores recomputed from the
// polygon with exact orientation tests (core/base/orient.h), without the BSP: each edge against each
// candidate edge's line (front = outside, to the right of a counter-clockwise edge; both ends on the
// line = on it, counted in front), score K * cut + (1 - K) * |front - back|; the first lowest wins.
// Every other split: its counts add up to the node's pieces and its choice is the first lowest.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "core/base/orient.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("BSP splitter scores: the root's recomputed with exact orientations, every choice the first lowest") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/space_partition/bsp_scores.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    std::vector<Vec2> v;
    for (const Json& p : s["polygon"]) v.emplace_back(p[0].get<double>(), p[1].get<double>());
    const int n = static_cast<int>(v.size());
    const double K = s["bsp"]["split_weight"].get<double>();
    const Json& steps = t["steps"];
    REQUIRE(steps.size() >= 1);
    const Json& root = steps[0];
    REQUIRE(root["candidates"].size() == static_cast<std::size_t>(n));
    for (int c = 0; c < n; ++c) {
        CAPTURE(c);
        const Vec2 a = v[c], b = v[(c + 1) % n];
        int front = 0, back = 0, cut = 0;
        for (int j = 0; j < n; ++j) {
            if (j == c) {
                ++front;  // the candidate itself lies on its line
                continue;
            }
            // orient2d > 0: left of a -> b, inside the counter-clockwise polygon: back.
            const int s0 = -orient2d(a, b, v[j]), s1 = -orient2d(a, b, v[(j + 1) % n]);
            if (s0 >= 0 && s1 >= 0) ++front;  // includes both on the line
            else if (s0 <= 0 && s1 <= 0) ++back;
            else ++cut;
        }
        const Json& got = root["candidates"][c];
        CHECK(got["edge"].get<int>() == c);
        CHECK(got["front"].get<int>() == front);
        CHECK(got["back"].get<int>() == back);
        CHECK(got["straddling"].get<int>() == cut);
        CHECK(got["score"].get<double>() == doctest::Approx(K * cut + (1 - K) * std::abs(front - back)).epsilon(1e-15));
    }
    for (const Json& step : steps) {
        CAPTURE(step["node"].get<int>());
        double lowest = INFINITY;
        int first = -1;
        for (const Json& c : step["candidates"]) {
            CHECK(c["front"].get<int>() + c["back"].get<int>() + c["straddling"].get<int>() == step["polygons"].get<int>());
            CHECK(c["score"].get<double>() ==
                  doctest::Approx(K * c["straddling"].get<int>() +
                                  (1 - K) * std::abs(c["front"].get<int>() - c["back"].get<int>()))
                      .epsilon(1e-15));
            if (c["score"].get<double>() < lowest) lowest = c["score"].get<double>(), first = c["edge"].get<int>();
        }
        CHECK(step["splitter"].get<int>() == first);
        CHECK(step["score"].get<double>() == lowest);
    }
}
