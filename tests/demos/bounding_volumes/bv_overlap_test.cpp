// golden/bounding_volumes/bv_overlap run numerically: each test's numbers recomputed from the two
// polygons — the minimum circles by brute force over 2- and 3-point circles, the boxes and the
// in-plane slab intervals as the extremes of the projections (a diagonal slab may be wider by its
// rounding pad, at most 1e-12 here) — and each verdict from them.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace bv_overlap_test {

using V2 = Eigen::Vector2d;

std::vector<V2> points(const Json& j) {
    std::vector<V2> out;
    for (const Json& p : j) out.emplace_back(p[0].get<double>(), p[1].get<double>());
    return out;
}

/// Minimum enclosing circle by brute force: (centre, radius).
std::pair<V2, double> minCircle(const std::vector<V2>& p) {
    std::pair<V2, double> best{V2::Zero(), INFINITY};
    const auto consider = [&](const V2& c, double r) {
        for (const V2& q : p)
            if ((q - c).norm() > r * (1 + 1e-12)) return;
        if (r < best.second) best = {c, r};
    };
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            consider(0.5 * (p[i] + p[j]), 0.5 * (p[i] - p[j]).norm());
            for (std::size_t k = j + 1; k < p.size(); ++k) {
                const V2 a = p[j] - p[i], b = p[k] - p[i];
                const double det = 2 * (a.x() * b.y() - a.y() * b.x());
                if (det == 0) continue;
                const V2 u((b.y() * a.squaredNorm() - a.y() * b.squaredNorm()) / det, (a.x() * b.squaredNorm() - b.x() * a.squaredNorm()) / det);
                consider(p[i] + u, u.norm());
            }
        }
    return best;
}

}  // namespace bv_overlap_test

TEST_CASE("BV overlap figure: circles, boxes and slabs recomputed from the polygons, and each verdict") {
    using namespace bv_overlap_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bounding_volumes/bv_overlap.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const std::vector<V2> a = points(s["a"]), b = points(s["b"]);
    const auto [ca, ra] = minCircle(a);
    const auto [cb, rb] = minCircle(b);
    CHECK(t["spheres"][0]["radius"].get<double>() == doctest::Approx(ra).epsilon(1e-9));
    CHECK(t["spheres"][1]["radius"].get<double>() == doctest::Approx(rb).epsilon(1e-9));
    const double dist = (ca - cb).norm();
    CHECK(t["sphere_test"]["distance"].get<double>() == doctest::Approx(dist).epsilon(1e-9));
    CHECK(t["sphere_test"]["hit"].get<bool>() == (dist <= ra + rb));
    // Boxes and slabs: the extremes of each projection.
    const auto range = [](const std::vector<V2>& p, const V2& d) {
        double lo = INFINITY, hi = -INFINITY;
        for (const V2& q : p) lo = std::min(lo, d.dot(q)), hi = std::max(hi, d.dot(q));
        return std::pair{lo, hi};
    };
    bool boxesApart = false, slabsApart = false;
    for (int axis = 0; axis < 2; ++axis) {
        const auto [a0, a1] = range(a, V2::Unit(axis));
        const auto [b0, b1] = range(b, V2::Unit(axis));
        CHECK(t["boxes"][0]["min"][axis].get<double>() == a0);
        CHECK(t["boxes"][0]["max"][axis].get<double>() == a1);
        CHECK(t["boxes"][1]["min"][axis].get<double>() == b0);
        CHECK(t["boxes"][1]["max"][axis].get<double>() == b1);
        boxesApart |= a1 < b0 || b1 < a0;
    }
    CHECK(t["box_test"]["hit"].get<bool>() == !boxesApart);
    REQUIRE(t["kdop_slabs"].size() == 4);
    for (const Json& slab : t["kdop_slabs"]) {
        const std::string name = slab["name"].get<std::string>();
        const V2 d = name == "x" ? V2(1, 0) : name == "y" ? V2(0, 1) : name == "x + y" ? V2(1, 1) : V2(1, -1);
        const auto [a0, a1] = range(a, d);
        const auto [b0, b1] = range(b, d);
        CHECK(std::abs(slab["a"][0].get<double>() - a0) <= 1e-12);
        CHECK(std::abs(slab["a"][1].get<double>() - a1) <= 1e-12);
        CHECK(std::abs(slab["b"][0].get<double>() - b0) <= 1e-12);
        CHECK(std::abs(slab["b"][1].get<double>() - b1) <= 1e-12);
        slabsApart |= a1 < b0 || b1 < a0;
    }
    CHECK(t["kdop_test"]["hit"].get<bool>() == !slabsApart);
}
