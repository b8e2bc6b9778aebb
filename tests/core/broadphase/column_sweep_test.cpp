// Sort and sweep in columns (core/broadphase/column_sweep.h) against the O(n^2) testAabbAabb loop
// (verification/broad_phase_oracle.h): every overlapping pair exactly once, on random motion, on
// integer boxes whose faces meet exactly (ties on the sweep axis and on column boundaries), with mixed sizes,
// far from the origin, and for bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/broadphase/column_sweep.h"
#include "verification/broad_phase_oracle.h"

using namespace cdlab;
using broad_oracle::bruteForcePairs;
using broad_oracle::IdPair;
using broad_oracle::sortedPairs;

namespace {

ColumnSweepResult check(ColumnSweep& sweep, const std::vector<Aabb>& boxes) {
    const ColumnSweepResult r = sweep.run(boxes);
    REQUIRE(r.status == BoxStatus::Ok);
    const std::vector<IdPair> got = sortedPairs(sweep.pairs());  // duplicates would survive the sort
    REQUIRE(got == bruteForcePairs(boxes));
    CHECK(r.pairs == static_cast<int>(got.size()));
    CHECK(r.candidates >= r.pairs);
    CHECK(r.entries >= static_cast<std::int64_t>(boxes.size()));
    return r;
}

}  // namespace

TEST_SUITE("column_sweep") {
    TEST_CASE("random coherent motion: each overlapping pair exactly once, the buffers reused") {
        ColumnSweep sweep;
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            std::mt19937_64 rng(seed);
            auto m = broad_oracle::Motion::random(rng, 30 + static_cast<int>(rng() % 300), 10.0, 0.2, 1.5, 0.2);
            for (int f = 0; f < 10; ++f) {
                m.step();
                check(sweep, m.boxes());
            }
        }
    }

    TEST_CASE("integer boxes: ties on every axis, touching faces on column boundaries, zero-size and identical boxes") {
        ColumnSweep sweep;
        int severalColumns = 0;
        for (std::uint64_t seed = 1; seed <= 60; ++seed) {
            std::mt19937_64 rng(seed + 100);
            std::vector<Aabb> boxes;
            const int n = 10 + static_cast<int>(rng() % 200);
            for (int i = 0; i < n; ++i) boxes.push_back(broad_oracle::integerBox(rng, 12, seed % 3 == 0 ? 0 : 3));
            for (int i = 0; i < n / 4; ++i) boxes.push_back(boxes[rng() % boxes.size()]);
            severalColumns += check(sweep, boxes).columns > 1;
            for (Aabb& b : boxes) b.min -= Vec3(7, 7, 7), b.max -= Vec3(7, 7, 7);  // negative: floor decides
            check(sweep, boxes);
        }
        CHECK(severalColumns >= 40);  // all but the zero-size seeds (every third: one column, no extent)
        check(sweep, {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 1)}});
        check(sweep, {{Vec3(0, 0, 0), Vec3(2, 2, 2)}, {Vec3(2, 2, 2), Vec3(2, 2, 2)}});
        check(sweep, {{Vec3(0, 0, 0), Vec3(0, 0, 0)}});
        check(sweep, {});
    }

    TEST_CASE("mixed sizes (100x), flat boxes, a million from the origin") {
        ColumnSweep sweep;
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int trial = 0; trial < 12; ++trial) {
            const Vec3 offset = trial % 2 ? Vec3(1e6, -3e6, 2e6) : Vec3::Zero();
            std::vector<Aabb> boxes;
            for (int i = 0; i < 400; ++i) {
                const Vec3 c(30 * u(rng), 30 * u(rng), 30 * u(rng));
                Vec3 h(std::pow(10.0, -1.5 + 2 * u(rng)), std::pow(10.0, -1.5 + 2 * u(rng)), std::pow(10.0, -1.5 + 2 * u(rng)));
                if (trial % 3 == 0) h[i % 3] = 0.0;  // flat along one axis
                boxes.push_back({offset + c - h, offset + c + h});
            }
            check(sweep, boxes);
        }
        // 2% of the boxes 300 times the others' size: the columns coarsen, the entries stay O(n).
        std::vector<Aabb> mix;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 c(100 * u(rng), 100 * u(rng), 100 * u(rng));
            const double h = i % 50 == 0 ? 150.0 : 0.5;
            mix.push_back({c - Vec3(h, h, h), c + Vec3(h, h, h)});
        }
        const ColumnSweepResult r = check(sweep, mix);
        CHECK(r.entries <= 8 * 2000 + 64);
        CHECK(r.columns > 1);
        // Every box flat along one axis, a diagonal row: columns along the other.
        std::vector<Aabb> flat;
        for (int i = 0; i < 50; ++i) flat.push_back({Vec3(i * 0.5, 0, i * 0.25), Vec3(i * 0.5 + 1, 0, i * 0.25 + 1)});
        check(sweep, flat);
    }

    TEST_CASE("bad input: a NaN or an empty box is refused, nothing reported") {
        ColumnSweep sweep;
        std::vector<Aabb> boxes{{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)}};
        check(sweep, boxes);
        boxes.push_back({Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0), Vec3(1, 1, 1)});
        ColumnSweepResult r = sweep.run(boxes);
        CHECK(r.status == BoxStatus::NonFinite);
        CHECK(r.object == 2);
        CHECK(sweep.pairs().empty());
        boxes.back() = {Vec3(1, 0, 0), Vec3(0, 1, 1)};
        r = sweep.run(boxes);
        CHECK(r.status == BoxStatus::Empty);
        CHECK(r.object == 2);
    }
}
