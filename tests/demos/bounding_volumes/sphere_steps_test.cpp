// golden/bounding_volumes/sphere_steps run numerically: Ritter's pass replayed from the points alone
// (the farthest pair among the axis-extreme points, then each point outside grows the circle to the
// old circle's far side and the point); Welzl's answer against the minimum enclosing circle by brute
// force (every circle through two points as a diameter or through three, the smallest holding all);
// each Welzl event's support points on its circle.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("sphere steps: Ritter's pass replayed, Welzl's circle the brute-force minimum") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bounding_volumes/sphere_steps.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    std::vector<Eigen::Vector2d> p;
    for (const Json& q : s["points"]) p.emplace_back(q[0].get<double>(), q[1].get<double>());
    const int n = static_cast<int>(p.size());
    const auto c2 = [](const Json& c) { return Eigen::Vector2d(c["center"][0].get<double>(), c["center"][1].get<double>()); };
    // Ritter: extreme points along x and y (z is 0 throughout), the farthest pair of them.
    std::vector<int> extreme;
    for (int k = 0; k < 2; ++k) {
        int lo = 0, hi = 0;
        for (int i = 1; i < n; ++i) {
            if (p[i][k] < p[lo][k]) lo = i;
            if (p[i][k] > p[hi][k]) hi = i;
        }
        extreme.push_back(lo), extreme.push_back(hi);
    }
    double best = -1;
    for (int i : extreme)
        for (int j : extreme) best = std::max(best, (p[i] - p[j]).norm());
    const Json& r = t["ritter"];
    const int i0 = r["initial_pair"][0].get<int>(), i1 = r["initial_pair"][1].get<int>();
    CHECK((p[i0] - p[i1]).norm() == best);
    Eigen::Vector2d c = 0.5 * (p[i0] + p[i1]);
    double rad = 0.5 * best;
    CHECK((c2(r["initial"]) - c).norm() <= 1e-12);
    std::size_t step = 0;
    for (int i = 0; i < n; ++i) {
        const double d = (p[i] - c).norm();
        if (d <= rad) continue;
        REQUIRE(step < r["steps"].size());
        const Json& st = r["steps"][step++];
        CHECK(st["point"].get<int>() == i);
        const double grown = 0.5 * (rad + d);
        c += (grown - rad) / d * (p[i] - c);
        rad = grown;
        CHECK(st["after"]["radius"].get<double>() == doctest::Approx(rad).epsilon(1e-12));
        CHECK((c2(st["after"]) - c).norm() <= 1e-9);
    }
    CHECK(step == r["steps"].size());
    for (const Eigen::Vector2d& q : p) CHECK((q - c2(r["sphere"])).norm() <= r["sphere"]["radius"].get<double>() * (1 + 1e-12));
    // Welzl: the smallest circle holding every point, over all 2- and 3-point circles.
    double minR = INFINITY;
    const auto consider = [&](const Eigen::Vector2d& centre, double radius) {
        for (const Eigen::Vector2d& q : p)
            if ((q - centre).norm() > radius * (1 + 1e-12)) return;
        minR = std::min(minR, radius);
    };
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            consider(0.5 * (p[i] + p[j]), 0.5 * (p[i] - p[j]).norm());
            for (int k = j + 1; k < n; ++k) {
                const Eigen::Vector2d a = p[j] - p[i], b = p[k] - p[i];
                const double det = 2 * (a.x() * b.y() - a.y() * b.x());
                if (det == 0) continue;
                const Eigen::Vector2d u((b.y() * a.squaredNorm() - a.y() * b.squaredNorm()) / det,
                                        (a.x() * b.squaredNorm() - b.x() * a.squaredNorm()) / det);
                consider(p[i] + u, u.norm());
            }
        }
    const Json& w = t["welzl"];
    CHECK(w["sphere"]["radius"].get<double>() == doctest::Approx(minR).epsilon(1e-12));
    CHECK(w["status"] == "Exact");
    for (const Json& e : w["steps"]) {
        if (!e["accepted"].get<bool>()) continue;
        for (const Json& i : e["support"])
            CHECK((p[i.get<int>()] - c2(e["ball"])).norm() ==
                  doctest::Approx(e["ball"]["radius"].get<double>()).epsilon(1e-9).scale(1.0));
    }
    for (const Json& i : w["final_support"])
        CHECK((p[i.get<int>()] - c2(w["sphere"])).norm() == doctest::Approx(minR).epsilon(1e-12));
}

TEST_CASE("bounding volume figures: degenerate point sets are one error naming the points") {
    const std::string steps = R"({"demo": "bounding_volumes", "figure": "sphere_steps", "title": "t", "points": [[1, 1], [1, 1]]})";
    CHECK(test::sceneTextError(steps).find("$.points") != std::string::npos);
    const std::string refit =
        R"({"demo": "bounding_volumes", "figure": "aabb_refit", "title": "t", "points": [[0, 0], [1, 0], [2, 0]], "angles": [0, 90]})";
    CHECK(test::sceneTextError(refit).find("$.points") != std::string::npos);
}
