// golden/bounding_volumes/aabb_refit run numerically: per angle the turned points, their AABB and
// the AABB of the old box's four turned corners recomputed with cos / sin, and the areas.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("AABB refit figure: both boxes and their areas recomputed with cos and sin") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bounding_volumes/aabb_refit.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    std::vector<Eigen::Vector2d> p;
    for (const Json& q : s["points"]) p.emplace_back(q[0].get<double>(), q[1].get<double>());
    Eigen::Vector2d lo = p[0], hi = p[0];
    for (const auto& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    const Eigen::Vector2d c = 0.5 * (lo + hi);
    const auto bounds = [](const std::vector<Eigen::Vector2d>& pts, Eigen::Vector2d& a, Eigen::Vector2d& b) {
        a = b = pts[0];
        for (const auto& q : pts) a = a.cwiseMin(q), b = b.cwiseMax(q);
    };
    const Json& cases = t["cases"];
    REQUIRE(cases.size() == s["angles"].size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const double rad = s["angles"][k].get<double>() * M_PI / 180.0;
        const double co = std::cos(rad), si = std::sin(rad);
        const auto turn = [&](const Eigen::Vector2d& q) {
            const Eigen::Vector2d d = q - c;
            return Eigen::Vector2d(c.x() + co * d.x() - si * d.y(), c.y() + si * d.x() + co * d.y());
        };
        std::vector<Eigen::Vector2d> turned, corners;
        for (const auto& q : p) turned.push_back(turn(q));
        for (const Eigen::Vector2d& q : {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())})
            corners.push_back(turn(q));
        Eigen::Vector2d a1, b1, a2, b2;
        bounds(turned, a1, b1);
        bounds(corners, a2, b2);
        const Json& cs = cases[k];
        for (int i = 0; i < 2; ++i) {
            CHECK(cs["refit"]["min"][i].get<double>() == doctest::Approx(a1[i]).epsilon(1e-12));
            CHECK(cs["refit"]["max"][i].get<double>() == doctest::Approx(b1[i]).epsilon(1e-12));
            CHECK(cs["from_box"]["min"][i].get<double>() == doctest::Approx(a2[i]).epsilon(1e-12));
            CHECK(cs["from_box"]["max"][i].get<double>() == doctest::Approx(b2[i]).epsilon(1e-12));
        }
        const double area1 = (b1 - a1).prod(), area2 = (b2 - a2).prod();
        CHECK(cs["refit_area"].get<double>() == doctest::Approx(area1).epsilon(1e-12));
        CHECK(cs["from_box_area"].get<double>() == doctest::Approx(area2).epsilon(1e-12));
        CHECK(area1 <= area2 * (1 + 1e-12));  // the refit is never looser
    }
}
