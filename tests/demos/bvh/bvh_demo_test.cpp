// The BVH demo draws its frames from the traces checked here: every committed scene of golden/bvh
// is run numerically (RunContext{} without GL) and its trace must back what the figures say.
//  - dual traversal: the step list is a consistent stack traversal (the pending pairs the frames
//    print never go negative and end at 0; the counted box tests, leaf pairs and triangle tests
//    equal core's counters), the hits of the traced triangle tests are exactly the reported pairs,
//    and those equal core's brute-force loop over all triangle pairs;
//  - hierarchy levels: the boxes of each drawn level cover every triangle exactly once;
//  - AABB vs OBB: both trees find the brute-force pairs, and the OBB tree needs fewer box and
//    triangle tests (the figure's claim), and has less volume at the deepest drawn level;
//  - refit: the refitted OBB tree is never tighter than the rebuilt one once the sheet is bent.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <utility>

#include "demos/catalog/catalog.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

Json runScene(const std::string& name) {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bvh/" + name + ".json";
    auto scene = loadScene(file);
    return scene->run(RunContext{}).trace;
}

}  // namespace

TEST_SUITE("bvh_demo") {
    TEST_CASE("dual traversal: the traced steps are a consistent traversal and find the brute-force pairs") {
        const Json t = runScene("dual_traversal");
        long long bv = 0, leaves = 0, tris = 0;
        int pending = 1;
        std::set<std::pair<int, int>> hits;
        for (const Json& s : t["steps"]) {
            const std::string action = s["action"];
            if (action == "triangle test") {
                ++tris;
                if (s["hit"].get<bool>()) hits.insert({s["triangle_a"].get<int>(), s["triangle_b"].get<int>()});
                continue;
            }
            ++bv;
            pending += (action == "descend A" || action == "descend B") ? 1 : -1;
            CHECK(s["pending"].get<int>() == pending);
            CHECK(pending >= 0);
            if (action == "leaf test") ++leaves;
            // Only overlapping boxes are descended or tested further.
            CHECK(s["overlap"].get<bool>() == (action != "prune"));
        }
        CHECK(pending == 0);
        CHECK(bv == t["stats"]["bv_tests"].get<long long>());
        CHECK(leaves == t["stats"]["leaf_pairs"].get<long long>());
        CHECK(tris == t["stats"]["triangle_tests"].get<long long>());
        std::set<std::pair<int, int>> pairs;
        for (const Json& p : t["pairs"]) pairs.insert({p[0].get<int>(), p[1].get<int>()});
        CHECK(pairs == hits);
        CHECK(pairs.size() == t["pairs"].size());  // no pair reported twice
        CHECK(!pairs.empty());                     // the scene shows intersecting triangles
        CHECK(t["brute_force"]["equal"].get<bool>());
        CHECK(tris < t["brute_force"]["triangle_tests"].get<long long>());
    }

    TEST_CASE("hierarchy levels: each drawn level covers every triangle once") {
        const Json t = runScene("hierarchy_levels");
        const int triangles = t["triangles"];
        int maxDepth = 0;
        for (const Json& s : t["build_steps"]) maxDepth = std::max(maxDepth, s["depth"].get<int>());
        REQUIRE(maxDepth >= 4);
        for (int level = 0; level <= maxDepth; ++level) {
            long long covered = 0;
            int nodes = 0;
            for (const Json& s : t["build_steps"]) {
                const int d = s["depth"];
                const bool leaf = s["split_axis"].get<int>() < 0;
                if (d == level || (leaf && d < level)) {
                    covered += s["count"].get<int>();
                    ++nodes;
                }
            }
            INFO("level " << level);
            CHECK(covered == triangles);
            CHECK(nodes == t["levels"][level]["nodes"].get<int>());
        }
    }

    TEST_CASE("AABB vs OBB on the torus: same pairs, the OBB tree does less work") {
        const Json t = runScene("torus_aabb_vs_obb");
        const Json& q = t["query"];
        REQUIRE(q["trees"].size() == 2);
        const Json& aabb = q["trees"][0];
        const Json& obb = q["trees"][1];
        CHECK(aabb["bv"] == "AABB");
        CHECK(obb["bv"] == "OBB");
        CHECK(aabb["equals_brute_force"].get<bool>());
        CHECK(obb["equals_brute_force"].get<bool>());
        CHECK(q["brute_force_pairs"].get<int>() > 0);
        CHECK(obb["bv_tests"].get<long long>() < aabb["bv_tests"].get<long long>());
        CHECK(obb["triangle_tests"].get<long long>() < aabb["triangle_tests"].get<long long>());
        const Json& la = t["trees"][0]["levels"];
        const Json& lo = t["trees"][1]["levels"];
        CHECK(lo.back()["volume"].get<double>() < la.back()["volume"].get<double>());
    }

    TEST_CASE("refit: the OBB tree refitted to the rolled sheet is looser than a rebuilt one") {
        const Json t = runScene("refit");
        REQUIRE(!t["frames"].empty());
        for (const Json& f : t["frames"]) {
            REQUIRE(f["trees"].size() == 2);
            const Json& obb = f["trees"][1];
            CHECK(obb["bv"] == "OBB");
            if (f["t"].get<double>() > 0)
                CHECK(obb["refit_total_volume"].get<double>() > obb["rebuilt_total_volume"].get<double>());
            for (const Json& k : f["trees"]) {
                CHECK(k["refit_total_volume"].get<double>() > 0);
                CHECK(k["rebuilt_total_volume"].get<double>() > 0);
            }
        }
    }

}  // TEST_SUITE
