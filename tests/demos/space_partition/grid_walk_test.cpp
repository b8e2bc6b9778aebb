// golden/space_partition/grid_walk run numerically: the cells the DDA visits recomputed by clipping
// the segment to every grid square of its bounding range (slab test: the squares it passes through
// with a positive length), ordered by the t where it enters them; the candidates as the boxes whose
// cell range holds a visited cell; the hits by a slab test of the segment against each box.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace grid_walk_test {

/// The parameter interval [t0, t1] of p + t d, t in [0, 1], inside the closed rectangle, or t0 > t1.
std::pair<double, double> clip(const Eigen::Vector2d& p, const Eigen::Vector2d& d, const Eigen::Vector2d& lo,
                               const Eigen::Vector2d& hi) {
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0) {
            if (p[k] < lo[k] || p[k] > hi[k]) return {1, 0};
            continue;
        }
        double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    return {t0, t1};
}

}  // namespace grid_walk_test

TEST_CASE("grid walk: the DDA cells are the squares the segment crosses in order, candidates and hits recomputed") {
    using namespace grid_walk_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/space_partition/grid_walk.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    const double h = t["cell_size"].get<double>();
    const Eigen::Vector2d p(t["segment"][0][0].get<double>(), t["segment"][0][1].get<double>());
    const Eigen::Vector2d q(t["segment"][1][0].get<double>(), t["segment"][1][1].get<double>());
    const Eigen::Vector2d d = q - p;
    std::vector<std::pair<double, std::pair<long, long>>> expected;
    for (long i = long(std::floor(std::min(p.x(), q.x()) / h)) - 1; i <= long(std::floor(std::max(p.x(), q.x()) / h)) + 1; ++i)
        for (long j = long(std::floor(std::min(p.y(), q.y()) / h)) - 1; j <= long(std::floor(std::max(p.y(), q.y()) / h)) + 1; ++j) {
            const auto [t0, t1] = clip(p, d, Eigen::Vector2d(i * h, j * h), Eigen::Vector2d((i + 1) * h, (j + 1) * h));
            if (t1 - t0 > 1e-12) expected.push_back({t0, {i, j}});
        }
    std::sort(expected.begin(), expected.end());
    const Json& cells = t["cells"];
    REQUIRE(cells.size() == expected.size());
    for (std::size_t k = 0; k < cells.size(); ++k) {
        CHECK(cells[k]["cell"][0].get<long>() == expected[k].second.first);
        CHECK(cells[k]["cell"][1].get<long>() == expected[k].second.second);
        CHECK(cells[k]["t_enter"].get<double>() == doctest::Approx(expected[k].first).epsilon(1e-12));
    }
    std::vector<int> candidates, hits;
    const Json& boxes = t["box_list"];
    for (std::size_t b = 0; b < boxes.size(); ++b) {
        const Eigen::Vector2d lo(boxes[b][0].get<double>(), boxes[b][1].get<double>());
        const Eigen::Vector2d hi(boxes[b][2].get<double>(), boxes[b][3].get<double>());
        bool entered = false;
        for (const auto& [t0, c] : expected)
            entered |= c.first >= std::floor(lo.x() / h) && c.first <= std::floor(hi.x() / h) &&
                       c.second >= std::floor(lo.y() / h) && c.second <= std::floor(hi.y() / h);
        if (!entered) continue;
        candidates.push_back(int(b));
        const auto [t0, t1] = clip(p, d, lo, hi);
        if (t0 <= t1) hits.push_back(int(b));
    }
    CHECK(t["candidates"].get<std::vector<int>>() == candidates);
    CHECK(t["hits"].get<std::vector<int>>() == hits);
}
