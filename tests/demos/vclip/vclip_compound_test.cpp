// golden/vclip/compound_exclusion run numerically: its compound exclusion recomputed from the
// scene's boxes. The region clipping the edge is the vertex region of B's vertex 0 (the corner at
// −h on every local axis: presets::box's numbering), bounded by one plane per incident edge,
// (x − V)·(N − V) <= 0 for its neighbour corner N. The edge e(λ) = tail + λ (head − tail) meets
// each plane at one λ; the largest lower bound is λmin, the smallest upper bound λmax. Compound:
// λmin > λmax although no single plane has both ends outside.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("V-Clip compound exclusion: the clip interval of the edge by the vertex region recomputed") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/vclip/compound_exclusion.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const auto vec = [](const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); };
    const Json& b = s["bodies"][1]["box"];
    const Vec3 h = vec(b["half_extents"]), c = vec(b["position"]);
    const Eigen::Quaterniond q(b["rotation"][0].get<double>(), b["rotation"][1].get<double>(), b["rotation"][2].get<double>(),
                               b["rotation"][3].get<double>());
    const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
    const Vec3 v0 = c + R * Vec3(-h.x(), -h.y(), -h.z());
    int found = 0;
    for (const Json& step : t["steps"])
        for (const Json& clip : step["clips"]) {
            if (!clip["compound_excluded"].get<bool>()) continue;
            REQUIRE(clip["region"] == "V0");
            REQUIRE(clip["edge_body"] == 0);
            const Vec3 tail = vec(clip["tail"]), head = vec(clip["head"]);
            double lo = 0, hi = 1;
            bool simple = false;
            for (int k = 0; k < 3; ++k) {
                Vec3 local(-h.x(), -h.y(), -h.z());
                local[k] = -local[k];
                const Vec3 u = c + R * local - v0;  // along the incident edge
                const double a = (tail - v0).dot(u), slope = (head - tail).dot(u);
                simple |= a > 0 && a + slope > 0;  // both ends outside this one plane
                if (slope > 0) hi = std::min(hi, -a / slope);
                else if (slope < 0) lo = std::max(lo, -a / slope);
            }
            CHECK_FALSE(simple);
            CHECK(lo > hi);
            CHECK(clip["lambda_min"].get<double>() == doctest::Approx(lo).epsilon(1e-9));
            CHECK(clip["lambda_max"].get<double>() == doctest::Approx(hi).epsilon(1e-9));
            ++found;
        }
    CHECK(found >= 1);
}
