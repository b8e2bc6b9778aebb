// Every golden gjk scene with a "regions" frame: the reduction it draws recomputed in 3D without
// GJK's sub-simplex solver. The closest point of the step's simplex (segment or triangle) to the
// origin by brute force over its vertices, edges and face; the vertices whose weight in it is
// above zero must be the kept ones. Each drawn test value recomputed from the 3D points: (O − wi)·
// (wj − wi) and n·(O − wi) with n = (wj − wi) × N̂ turned away from the third vertex; each has the
// sign the figure prints.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace gjk_regions_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

/// Weights of the point of the simplex nearest the origin, by brute force over its features.
std::vector<double> nearestWeights(const std::vector<Vec3>& w) {
    const int n = int(w.size());
    std::vector<double> best(n, 0.0);
    double bestD = INFINITY;
    const auto offer = [&](const std::vector<double>& l) {
        Vec3 p = Vec3::Zero();
        for (int i = 0; i < n; ++i) p += l[i] * w[i];
        if (p.norm() < bestD - 1e-15) bestD = p.norm(), best = l;
    };
    for (int i = 0; i < n; ++i) {
        std::vector<double> l(n, 0.0);
        l[i] = 1;
        offer(l);
    }
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            const Vec3 e = w[j] - w[i];
            const double t = std::clamp(-w[i].dot(e) / e.squaredNorm(), 0.0, 1.0);
            std::vector<double> l(n, 0.0);
            l[i] = 1 - t, l[j] = t;
            offer(l);
        }
    if (n == 3) {  // the face: the origin's projection, when inside
        const Vec3 e1 = w[1] - w[0], e2 = w[2] - w[0];
        Eigen::Matrix2d g;
        g << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
        const Eigen::Vector2d rhs(-w[0].dot(e1), -w[0].dot(e2));
        const Eigen::Vector2d s = g.ldlt().solve(rhs);
        if (s.x() >= 0 && s.y() >= 0 && s.x() + s.y() <= 1) offer({1 - s.x() - s.y(), s.x(), s.y()});
    }
    return best;
}

}  // namespace gjk_regions_test

TEST_CASE("GJK regions frame: the kept vertices are brute force's, every drawn test recomputed in 3D") {
    using namespace gjk_regions_test;
    int checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(CDLAB_SOURCE_DIR) + "/golden/gjk")) {
        if (entry.path().extension() != ".json") continue;
        const Json t = loadScene(entry.path().string())->run(RunContext{}).trace;
        if (!t.contains("regions")) continue;
        CAPTURE(entry.path().filename().string());
        const Json& rg = t["regions"];
        const Json* step = nullptr;
        for (const Json& s : t["steps"])
            if (s["iteration"] == rg["iteration"]) step = &s;
        REQUIRE(step != nullptr);
        std::vector<Vec3> w;
        for (const Json& v : (*step)["simplex"]) w.push_back(vec(v["w"]));
        const std::vector<double> l = nearestWeights(w);
        std::string kept;
        for (std::size_t i = 0; i < w.size(); ++i)
            if (l[i] > 1e-12) kept += "w" + std::to_string(i);
        CHECK(rg["kept"].get<std::string>() == kept);
        Vec3 N = w.size() == 3 ? Vec3((w[1] - w[0]).cross(w[2] - w[0]).normalized()) : Vec3::Zero();
        for (const Json& test : rg["tests"]) {
            const std::string name = test["test"].get<std::string>();
            double value = 0;
            int i = -1, j = -1;
            if (std::sscanf(name.c_str(), "(O − w%d)·(w%d", &i, &j) == 2) {
                value = (-w[std::size_t(i)]).dot(w[std::size_t(j)] - w[std::size_t(i)]);
            } else {
                REQUIRE(std::sscanf(name.c_str(), "nw%dw%d", &i, &j) == 2);
                const int k = 3 - i - j;
                Vec3 n = (w[std::size_t(j)] - w[std::size_t(i)]).cross(N);
                if (n.dot(w[std::size_t(k)] - w[std::size_t(i)]) > 0) n = -n;
                value = n.dot(-w[std::size_t(i)]);
            }
            const double scale = 1e-9 * (1 + w[0].squaredNorm() + w[1].squaredNorm());
            CHECK(test["value"].get<double>() == doctest::Approx(value).epsilon(1e-9).scale(1.0));
            if (test["sign"] == ">= 0") CHECK(value >= -scale);
            else CHECK(value <= scale);
        }
        ++checked;
    }
    CHECK(checked >= 3);
}
