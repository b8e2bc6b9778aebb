// The V-Clip demo draws its frames from the traces checked here: every committed scene of
// golden/vclip is run numerically (RunContext{} without GL) and its trace must tell a correct walk
// (Mirtich 1998, Thm. 2/3): the inter-feature distance never increases, an update that lowers a
// feature's dimension keeps it equal, no feature pair repeats, a separated result satisfies the
// Theorem-1 check the result frame draws and its distance equals GJK's (an independent algorithm),
// a penetration verdict agrees with GJK; the motion scene stays coherent (about one update per call).
// The scene set covers every figure the V-Clip lecture needs: the five states, clipping, local minima, coherence.
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "app/catalog/catalog.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

std::vector<std::string> vclipScenes() {
    std::vector<std::string> out;
    for (const auto& f : findSceneFiles(std::string(CDLAB_SOURCE_DIR) + "/golden"))
        if (f.find("/golden/vclip/") != std::string::npos) out.push_back(f);
    return out;
}

// "V3" -> 0, "E12" -> 1, "F0" -> 2.
int dimensionOf(const std::string& feature) {
    REQUIRE(!feature.empty());
    return feature[0] == 'V' ? 0 : feature[0] == 'E' ? 1 : feature[0] == 'F' ? 2 : -1;
}

// Checks one call's result against GJK and the Theorem-1 margins.
void checkResult(const Json& r, const std::string& where) {
    INFO(where);
    const std::string status = r["status"];
    REQUIRE((status == "Separated" || status == "Penetrating"));
    const double d = r["distance"], g = r["gjk_distance"];
    if (status == "Separated") {
        CHECK_FALSE(r["gjk_intersect"].get<bool>());
        CHECK(std::abs(d - g) <= 1e-9 * std::max(1.0, g));
        // Theorem 1: each closest point inside the other feature's Voronoi region (signed
        // distances positive inside); 1e-12 absorbs rounding on unit-sized bodies.
        CHECK(r["theorem1_a_in_region_b"].get<double>() >= -1e-12);
        CHECK(r["theorem1_b_in_region_a"].get<double>() >= -1e-12);
    } else {
        CHECK(r["gjk_intersect"].get<bool>());
        CHECK(d == 0.0);
    }
}

}  // namespace

TEST_SUITE("vclip_demo") {
    TEST_CASE("every scene's walk is monotone, repeat-free and ends at GJK's answer") {
        const auto scenes = vclipScenes();
        REQUIRE(scenes.size() >= 5);
        for (const auto& file : scenes) {
            const DemoOutput out = loadScene(file)->run(RunContext{});
            CHECK(out.frames.empty());
            const Json& t = out.trace;
            if (t.contains("calls")) continue;  // the motion scene, below
            INFO(file);
            checkResult(t["result"], file);
            std::set<std::pair<std::string, std::string>> seen;
            const Json& steps = t["steps"];
            REQUIRE(!steps.empty());
            for (std::size_t i = 0; i < steps.size(); ++i) {
                const Json& s = steps[i];
                INFO("step " << i);
                const bool fresh =
                    seen.insert({s["feature_a"].get<std::string>(), s["feature_b"].get<std::string>()}).second;
                CHECK(fresh);
                const double before = s["distance_before"], after = s["distance_after"];
                // 1e-12 relative: the distance of a pair recomputed after the update (rounding only).
                const double tol = 1e-12 * std::max(1.0, before);
                CHECK(after <= before + tol);
                if (s["kind"] == "Update") {
                    const int from = dimensionOf(s["from"]), to = dimensionOf(s["to"]);
                    if (to < from) CHECK(std::abs(after - before) <= tol);
                    // The next step starts from the updated pair.
                    if (i + 1 < steps.size()) {
                        const std::string changed = s["updated_body"] == 0 ? "feature_a" : "feature_b";
                        CHECK(steps[i + 1][changed] == s["to"]);
                        CHECK(std::abs(steps[i + 1]["distance_before"].get<double>() - after) <= tol);
                    }
                } else {
                    CHECK(i + 1 == steps.size());  // Done / Penetration ends the walk
                }
            }
            CHECK(steps.size() == t["result"]["steps"].get<std::size_t>() + 1);
        }
    }

    TEST_CASE("the scene set covers the paper's figures") {
        bool localMin = false, edgeEdge = false, disk = false, penetration = false, motion = false;
        for (const auto& file : vclipScenes()) {
            const Json t = loadScene(file)->run(RunContext{}).trace;
            if (t.contains("calls")) {
                motion = true;
                continue;
            }
            for (const Json& s : t["steps"]) localMin = localMin || s["local_minimum"].get<bool>();
            const Json& r = t["result"];
            edgeEdge = edgeEdge || (dimensionOf(r["feature_a"]) == 1 && dimensionOf(r["feature_b"]) == 1 &&
                                    r["status"] == "Separated");
            penetration = penetration || r["status"] == "Penetrating";
            for (const Json& b : t["bodies"]) disk = disk || (b["kind"] == "disk" && b["faces"] == 62);
        }
        CHECK(localMin);
        CHECK(edgeEdge);
        CHECK(disk);
        CHECK(penetration);
        CHECK(motion);
    }

    TEST_CASE("the coherent motion takes about one update per call and matches GJK every call") {
        for (const auto& file : vclipScenes()) {
            const Json t = loadScene(file)->run(RunContext{}).trace;
            if (!t.contains("calls")) continue;
            const Json& calls = t["calls"];
            REQUIRE(calls.size() >= 10);
            double updates = 0;
            for (std::size_t k = 0; k < calls.size(); ++k) {
                checkResult(calls[k], file + " call " + std::to_string(k));
                updates += calls[k]["steps"].get<double>();
                // Warm start: each call begins at the previous call's final pair.
                if (k > 0) {
                    CHECK(calls[k]["seed"][0] == calls[k - 1]["feature_a"]);
                    CHECK(calls[k]["seed"][1] == calls[k - 1]["feature_b"]);
                }
            }
            // The first call is cold; the rest should need about one update each (7.5° per call).
            CHECK((updates - calls[0]["steps"].get<double>()) / double(calls.size() - 1) <= 1.5);
        }
    }

    TEST_CASE("scene errors name the key") {
        const auto bad = [](const std::string& text) {
            const Json j = parseJson(text, "inline");
            CHECK_THROWS_AS(findDemo("vclip")->prepare(j, "inline.json"), InputError);
        };
        bad(R"({"demo": "vclip", "bodies": [{"box": {"half_extents": [1, 1, 1]}}]})");                       // one body
        bad(R"({"demo": "vclip", "bodies": [{"box": {"half_extents": [1, 0, 1]}}, {"icosahedron": {}}]})");  // flat box
        bad(R"({"demo": "vclip", "bodies": [{"sphere": {"radius": 1}}, {"icosahedron": {}}]})");  // not a polyhedron
        bad(R"({"demo": "vclip", "bodies": [{"icosahedron": {}}, {"icosahedron": {}}], "seed": ["V12", "V0"]})");  // out
                                                                                                                   // of
                                                                                                                   // range
        bad(R"({"demo": "vclip", "bodies": [{"icosahedron": {}}, {"icosahedron": {}}], "seed": ["X1", "V0"]})");  // not
                                                                                                                  // a
                                                                                                                  // feature
        bad(R"({"demo": "vclip", "bodies": [{"icosahedron": {}}, {"icosahedron": {}}], "motion": {"orbit_axis": [0, 0, 0]}})");
        bad(R"({"demo": "vclip", "bodies": [{"icosahedron": {}}, {"icosahedron": {}}], "colour": 1})");  // unknown key
    }

}  // TEST_SUITE
