// Uniform grid broad phase (core/broadphase/uniform_grid.h) against the O(n^2) testAabbAabb loop
// (verification/broad_phase_oracle.h): every overlapping pair exactly once, for cell sizes below,
// at and above the box size, on integer boxes whose faces lie on cell boundaries.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>
#include <limits>

#include "core/broadphase/uniform_grid.h"
#include "verification/broad_phase_oracle.h"

using namespace cdlab;
using broad_oracle::bruteForcePairs;
using broad_oracle::IdPair;
using broad_oracle::sortedPairs;

namespace {

void check(UniformGrid& grid, const std::vector<Aabb>& boxes, double h) {
    UniformGridOptions o;
    o.cellSize = h;
    const UniformGridResult r = grid.build(boxes, o);
    REQUIRE(r.status == GridStatus::Ok);
    const std::vector<IdPair> got = sortedPairs(grid.pairs());  // duplicates would survive the sort
    REQUIRE(got == bruteForcePairs(boxes));
    CHECK(r.pairs == static_cast<int>(got.size()));
    CHECK(r.pairTests >= r.pairs);
}

}  // namespace

TEST_SUITE("uniform_grid") {
    TEST_CASE("random coherent motion: each overlapping pair exactly once, for several cell sizes") {
        UniformGrid grid;  // reused across frames, as per-frame rebuilding does
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            std::mt19937_64 rng(seed);
            auto m = broad_oracle::Motion::random(rng, 30 + static_cast<int>(rng() % 60), 10.0, 0.2, 1.5, 0.2);
            for (int f = 0; f < 20; ++f) {
                m.step();
                for (double h : {0.37, 1.0, 2.5, 20.0}) check(grid, m.boxes(), h);
            }
        }
    }

    TEST_CASE("integer boxes on cell boundaries: ties, touching faces, zero-size and identical boxes") {
        UniformGrid grid;
        for (std::uint64_t seed = 1; seed <= 40; ++seed) {
            std::mt19937_64 rng(seed + 100);
            std::vector<Aabb> boxes;
            const int n = 10 + static_cast<int>(rng() % 40);
            for (int i = 0; i < n; ++i) boxes.push_back(broad_oracle::integerBox(rng, 6, seed % 3 == 0 ? 0 : 3));
            for (int i = 0; i < n / 4; ++i) boxes.push_back(boxes[rng() % boxes.size()]);
            for (double h : {0.5, 1.0, 2.0, 3.0}) check(grid, boxes, h);
            // Negative coordinates: floor, not truncation, decides the cell.
            for (Aabb& b : boxes) b.min -= Vec3(3, 3, 3), b.max -= Vec3(3, 3, 3);
            for (double h : {1.0, 2.0}) check(grid, boxes, h);
        }
        // Two boxes touching exactly on a cell boundary: one pair, reported once.
        check(grid, {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 1)}}, 1.0);
        check(grid, {{Vec3(0, 0, 0), Vec3(2, 2, 2)}, {Vec3(2, 2, 2), Vec3(2, 2, 2)}}, 1.0);
    }

    TEST_CASE("huge offsets (1e6) and tiny sizes (1e-6 .. 1e-3)") {
        UniformGrid grid;
        for (std::uint64_t seed = 1; seed <= 10; ++seed) {
            std::mt19937_64 rng(seed + 300);
            const double scale = seed % 2 ? 1e-3 : 1e-6;
            auto m = broad_oracle::Motion::random(rng, 60, 10 * scale, 0.2 * scale, 1.5 * scale, 0.2 * scale);
            const Vec3 offset(1e6, -1e6, 3e6);
            for (int f = 0; f < 10; ++f) {
                m.step();
                for (double h : {1.0 * scale, 3.0 * scale}) check(grid, m.boxes(offset), h);
            }
        }
    }

    TEST_CASE("bad input: NaN, inf, empty boxes, bad cell size, too many cells") {
        UniformGrid grid;
        UniformGridOptions o;
        const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        std::vector<Aabb> boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(0, 0, 0), Vec3(1, nan, 1)}};
        UniformGridResult r = grid.build(boxes, o);
        CHECK(r.status == GridStatus::NonFiniteBox);
        CHECK(r.object == 1);
        boxes[1] = {Vec3(0, 0, -inf), Vec3(1, 1, 1)};
        CHECK(grid.build(boxes, o).status == GridStatus::NonFiniteBox);
        boxes[1] = {Vec3(0, 2, 0), Vec3(1, 1, 1)};
        CHECK(grid.build(boxes, o).status == GridStatus::EmptyBox);
        boxes[1] = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
        for (double h : {0.0, -1.0, nan, inf}) {
            o.cellSize = h;
            CHECK(grid.build(boxes, o).status == GridStatus::BadCellSize);
        }
        o.cellSize = 1e-3;  // 1001^3 cells for a unit box
        r = grid.build(boxes, o);
        CHECK(r.status == GridStatus::TooManyCells);
        o.cellSize = 1e-300;  // cell indices beyond 2^53
        CHECK(grid.build({{Vec3(1, 1, 1), Vec3(1, 1, 1)}}, o).status == GridStatus::TooManyCells);
        o.cellSize = 1.0;
        check(grid, boxes, 1.0);
        CHECK(grid.pairs().size() == 1);
    }

}  // TEST_SUITE

TEST_CASE("uniform grid DDA: the cells along a segment are the cubes it crosses, in order of entry") {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-7.0, 7.0);
    for (int trial = 0; trial < 300; ++trial) {
        const Vec3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
        const double h = 0.5 + std::abs(u(rng)) / 3;
        const auto walk = UniformGrid::cellsAlongSegment(p, q, h, 100000);
        // Brute force: every cube of the segment's cell range it crosses with a positive length.
        std::vector<std::pair<double, std::array<std::int64_t, 3>>> expected;
        const auto lo = UniformGrid::cellOf(p.cwiseMin(q), h), hi = UniformGrid::cellOf(p.cwiseMax(q), h);
        for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
                    double t0 = 0, t1 = 1;
                    const std::int64_t c[3] = {i, j, k};
                    for (int a = 0; a < 3; ++a) {
                        const double d = q[a] - p[a];
                        double s0 = (double(c[a]) * h - p[a]) / d, s1 = (double(c[a] + 1) * h - p[a]) / d;
                        if (s0 > s1) std::swap(s0, s1);
                        t0 = std::max(t0, s0), t1 = std::min(t1, s1);
                    }
                    if (t1 - t0 > 1e-9) expected.push_back({t0, {i, j, k}});
                }
        std::sort(expected.begin(), expected.end());
        REQUIRE(walk.size() == expected.size());
        for (std::size_t n = 0; n < walk.size(); ++n) {
            CHECK(walk[n].cell == expected[n].second);
            CHECK(walk[n].tEnter == doctest::Approx(expected[n].first).epsilon(1e-9));
        }
    }
    CHECK(UniformGrid::cellsAlongSegment(Vec3::Zero(), Vec3::Ones(), 0.0, 10).empty());
    CHECK(UniformGrid::cellsAlongSegment(Vec3::Zero(), Vec3(1e9, 0, 0), 1.0, 50).size() == 50);  // capped
}
