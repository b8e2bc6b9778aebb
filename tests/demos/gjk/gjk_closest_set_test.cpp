// golden/gjk/box_box run numerically: its closest_set against the facing faces' overlap worked out
// from the scene's two axis-aligned boxes by interval arithmetic; GJK's own pair lies in it.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("GJK closest set: the overlap of box_box's facing faces, holding GJK's pair") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/gjk/box_box.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const auto vec = [](const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); };
    const Vec3 ha = vec(s["shapes"][0]["box"]["half_extents"]), hb = vec(s["shapes"][1]["box"]["half_extents"]);
    const Vec3 cb = vec(s["shapes"][1]["box"]["position"]);
    // B lies beyond A along +x: the faces x = ha.x and x = cb.x − hb.x face each other.
    const double gap = (cb.x() - hb.x()) - ha.x();
    REQUIRE(gap > 0);
    CHECK(t["distance"].get<double>() == doctest::Approx(gap).epsilon(1e-12));
    REQUIRE(t.contains("closest_set"));
    const Json& set = t["closest_set"];
    REQUIRE(set["on_a"].size() == 4);
    Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
    for (const Json& p : set["on_a"]) lo = lo.cwiseMin(vec(p)), hi = hi.cwiseMax(vec(p));
    CHECK(lo.x() == doctest::Approx(ha.x()).epsilon(1e-12));
    CHECK(hi.x() == doctest::Approx(ha.x()).epsilon(1e-12));
    for (int k = 1; k < 3; ++k) {
        CHECK(lo[k] == doctest::Approx(std::max(-ha[k], cb[k] - hb[k])).epsilon(1e-12));
        CHECK(hi[k] == doctest::Approx(std::min(ha[k], cb[k] + hb[k])).epsilon(1e-12));
    }
    CHECK((vec(set["offset"]) - Vec3(gap, 0, 0)).norm() <= 1e-12);
    const Vec3 pa = vec(t["point_a"]);
    for (int k = 0; k < 3; ++k) {
        CHECK(pa[k] >= lo[k] - 1e-12);
        CHECK(pa[k] <= hi[k] + 1e-12);
    }
}
