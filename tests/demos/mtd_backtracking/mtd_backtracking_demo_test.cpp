// The mtd_backtracking demo draws its frames from the traces checked here: every committed scene is
// run numerically (RunContext{} without GL) and each correction is checked against the polygons
// themselves (verification/polygon_oracle.h: distance and 2D-SAT depth in long double, no GJK/EPA):
// the MTD is the least overlap and leaves the bodies touching; the backtracked pose touches and an
// instant earlier is apart; conservative advancement ends within its tolerance, never inside A, each
// step's distance is the polygons' distance at its t and the steps only move forward.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/cast/conservative_advancement.h"
#include "app/catalog/catalog.h"
#include "verification/polygon_oracle.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

Json sceneJson(const std::string& name) {
    return readJsonFile(std::string(CDLAB_SOURCE_DIR) + "/golden/mtd_backtracking/" + name + ".json");
}

Json runScene(const std::string& name) {
    return loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/mtd_backtracking/" + name + ".json")->run(RunContext{}).trace;
}

Transform poseOf(const Json& pose) {
    Transform t;
    t.position = Vec3(pose["position"][0].get<double>(), pose["position"][1].get<double>(), 0);
    t.rotation = Quat(Eigen::AngleAxisd(pose.value("angle", pose.value("angle_degrees", 0.0)) * M_PI / 180.0, Vec3::UnitZ()));
    return t;
}

std::vector<oracle::P2> polygonAt(const Json& points, const Transform& pose) {
    std::vector<Vec3> out;
    for (const Json& p : points) out.push_back(pose.apply(Vec3(p[0].get<double>(), p[1].get<double>(), 0)));
    return oracle::polygon2(out);
}

}  // namespace

TEST_SUITE("mtd_backtracking_demo") {
    TEST_CASE("every scene: each correction checked against the polygons themselves") {
        for (const char* name : {"sliding_bar", "spinning_bar"}) {
            CAPTURE(name);
            const Json s = sceneJson(name), t = runScene(name);
            const auto A = polygonAt(s["a"], Transform{});
            const auto B = [&](const Transform& pose) { return polygonAt(s["b"], pose); };
            RigidMotion motion;
            motion.linear = Vec3(s["motion"]["linear"][0].get<double>(), s["motion"]["linear"][1].get<double>(), 0);
            motion.angular = Vec3(0, 0, s["motion"].value("angular", 0.0) * M_PI / 180.0);
            const Transform start = poseOf(s["start"]);
            const Transform end = poseAt(start, motion, 1.0);

            // 1. The MTD: EPA's depth is the least overlap; B moved by depth·n touches A.
            const Json& mtd = t["mtd"];
            REQUIRE(mtd["penetrating"].get<bool>());
            const double depth = mtd["depth"];
            CHECK(depth == doctest::Approx(double(oracle::polygonDepth(A, B(end)))).epsilon(1e-9));
            const Transform moved = poseOf(mtd["pose"]);
            CHECK(std::abs(double(oracle::polygonDepth(A, B(moved)))) <= 1e-9);
            const Vec3 n(mtd["normal"][0].get<double>(), mtd["normal"][1].get<double>(), 0);
            Transform further = moved;
            further.position += 1e-6 * n;
            CHECK(oracle::polygonDistance(A, B(further)) > 0);

            // 2. Backtracking: touching at t, apart an instant before (unless overlapping from the start).
            const Json& back = t["backtrack"];
            if (!back["initially_overlapping"].get<bool>()) {
                REQUIRE(back["hit"].get<bool>());
                Transform turned = end;
                const double tb = back["t"];
                turned.position = start.position + tb * motion.linear;
                CHECK(double(oracle::polygonDistance(A, B(turned))) <= 1e-9);
                CHECK(std::abs(double(oracle::polygonDepth(A, B(turned)))) <= 1e-9);
                turned.position -= 1e-6 * motion.linear;
                CHECK(oracle::polygonDistance(A, B(turned)) > 0);
            } else {
                Transform turned = end;
                turned.position = start.position;
                CHECK(oracle::polygonDepth(A, B(turned)) > 0);  // the figure's claim: overlapping already at t = 0
            }

            // 3. Conservative advancement: forward steps, each distance the polygons' distance, the end
            // within the tolerance and never inside A.
            const Json& adv = t["advance"];
            CHECK(adv["outcome"] == "contact");
            double previous = -1;
            for (const Json& step : adv["steps"]) {
                const double ts = step["t"];
                CHECK(ts > previous);
                previous = ts;
                CHECK(step["distance"].get<double>() ==
                      doctest::Approx(double(oracle::polygonDistance(A, B(poseAt(start, motion, ts))))).epsilon(1e-9));
            }
            const Transform last = poseAt(start, motion, adv["t"].get<double>());
            CHECK(double(oracle::polygonDistance(A, B(last))) <= 1e-6 + 1e-12);
            CHECK(double(oracle::polygonDepth(A, B(last))) <= 1e-12);
        }
    }

    TEST_CASE("bad scenes: one error naming the JSON path") {
        const auto errorOf = [](const std::string& text) { return test::sceneTextError(text); };
        const std::string body = R"("b": [[-1,-0.2],[1,-0.2],[1,0.2],[-1,0.2]], "start": {"position": [0, 2]}, )";
        CHECK(errorOf(R"({"demo": "mtd_backtracking", "a": [[0,0],[1,0],[2,0]], )" + body + R"("motion": {"linear": [0,-1]}})")
                  .find("$.a") != std::string::npos);
        CHECK(errorOf(R"({"demo": "mtd_backtracking", "a": [[0,0],[1,0],[0,1]], )" + body +
                      R"("motion": {"linear": [0,-1], "spin": 3}})")
                  .find("spin") != std::string::npos);
        CHECK(errorOf(R"({"demo": "mtd_backtracking", "a": [[0,0],[1,0],[0,1]], )" + body +
                      R"("motion": {"angular": 1e9}})")
                  .find("$.motion.angular") != std::string::npos);
        CHECK(errorOf(R"({"demo": "mtd_backtracking", "a": [[0,0],[1,0],[0,1]], )" + body +
                      R"("motion": {}, "tolerance": 0})")
                  .find("$.tolerance") != std::string::npos);
    }
}
