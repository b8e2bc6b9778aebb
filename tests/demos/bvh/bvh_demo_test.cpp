// The BVH demo draws its frames from the traces checked here: every committed scene of golden/bvh
// is run numerically (RunContext{} without GL) and its trace must back what the figures say.
//  - dual traversal: the step list is a consistent stack traversal (the pending pairs the frames
//    print never go negative and end at 0; the counted box tests, leaf pairs and triangle tests
//    equal core's counters), the hits of the traced triangle tests are exactly the reported pairs,
//    and those equal core's brute-force loop over all triangle pairs;
//  - hierarchy levels: the boxes of each drawn level cover every triangle exactly once;
//  - AABB vs OBB: both trees find the brute-force pairs, and the OBB tree needs fewer box and
//    triangle tests (the figure's claim), and has less volume at the deepest drawn level;
//  - refit: the refitted OBB tree is never tighter than the rebuilt one once the sheet is bent;
//  - dynamic tree: each insertion's SAH cost is the least over every node of the tree before it
//    (recomputed from the previous step's tree and the scene's boxes, not from core), every box is
//    in the tree once, a move re-inserts exactly when the box left its fat box.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "app/catalog/catalog.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

Json runScene(const std::string& name) {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bvh/" + name + ".json";
    auto scene = loadScene(file);
    return scene->run(RunContext{}).trace;
}

// A tree from the trace's nested text "((A,B),C)": leaves are box letters.
struct TextNode {
    int box = -1;
    std::unique_ptr<TextNode> left, right;
};
std::unique_ptr<TextNode> parseTree(const std::string& t, std::size_t& i) {
    auto n = std::make_unique<TextNode>();
    if (t[i] == '(') {
        ++i;
        n->left = parseTree(t, i);
        REQUIRE(t[i] == ',');
        ++i;
        n->right = parseTree(t, i);
        REQUIRE(t[i] == ')');
        ++i;
    } else {
        n->box = t[i++] - 'A';
    }
    return n;
}
std::unique_ptr<TextNode> without(std::unique_ptr<TextNode> n, int box) {  // the box's sibling takes their parent's place
    if (!n) return n;
    if (n->box >= 0) return n->box == box ? nullptr : std::move(n);
    n->left = without(std::move(n->left), box);
    n->right = without(std::move(n->right), box);
    if (!n->left) return std::move(n->right);
    if (!n->right) return std::move(n->left);
    return n;
}
using Box = std::pair<Vec3, Vec3>;
Box unite(const Box& a, const Box& b) { return {a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)}; }
double area(const Box& b) {
    const Vec3 d = b.second - b.first;
    return 2 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}
Box boxOf(const TextNode& n, const std::vector<Box>& fat) {
    return n.box >= 0 ? fat[n.box] : unite(boxOf(*n.left, fat), boxOf(*n.right, fat));
}
// The least SAH cost of pairing `leaf` with any node: its union's area plus each ancestor's growth.
double leastCost(const TextNode& n, const std::vector<Box>& fat, const Box& leaf, double inherited) {
    const Box b = boxOf(n, fat);
    double best = area(unite(b, leaf)) + inherited;
    if (n.box < 0) {
        const double below = inherited + area(unite(b, leaf)) - area(b);
        best = std::min({best, leastCost(*n.left, fat, leaf, below), leastCost(*n.right, fat, leaf, below)});
    }
    return best;
}
void leaves(const TextNode& n, std::vector<int>& out) {
    if (n.box >= 0) return out.push_back(n.box);
    leaves(*n.left, out);
    leaves(*n.right, out);
}

}  // namespace

TEST_SUITE("bvh_demo") {
    TEST_CASE("dynamic tree: each insertion pairs with the least-cost node, moves re-insert exactly when they leave") {
        const Json t = runScene("dynamic_tree");
        std::ifstream in(std::string(CDLAB_SOURCE_DIR) + "/golden/bvh/dynamic_tree.json");
        const Json scene = Json::parse(in);
        const double m = scene["margin"];
        std::vector<Box> boxes, fat;
        for (const Json& b : scene["boxes"]) {
            const Vec3 lo(b["min"][0], b["min"][1], b["min"][2]), hi(b["max"][0], b["max"][1], b["max"][2]);
            boxes.push_back({lo, hi});
        }
        std::string previous;
        std::size_t move = 0;
        int inserted = 0, reinserted = 0;
        for (const Json& s : t["steps"]) {
            const int box = s["box"].get<std::string>()[0] - 'A';
            CAPTURE(s.dump());
            if (s["kind"] == "move") {
                const Json& mv = scene["moves"][move++];
                REQUIRE(mv["box"] == box);
                const Vec3 by(mv["by"][0], mv["by"][1], mv["by"][2]);
                boxes[box] = {boxes[box].first + by, boxes[box].second + by};
                const bool left = !((fat[box].first.array() <= boxes[box].first.array()).all() &&
                                    (boxes[box].second.array() <= fat[box].second.array()).all());
                CHECK(s["left_fat_box"] == left);
                if (!left) continue;
                ++reinserted;
            } else {
                ++inserted;
                fat.resize(box + 1);
            }
            // The fat box the leaf goes in with (the figure grows boxes by the margin, no stretch).
            fat[box] = {boxes[box].first - Vec3::Constant(m), boxes[box].second + Vec3::Constant(m)};
            if (!previous.empty()) {
                std::size_t i = 0;
                std::unique_ptr<TextNode> before = parseTree(previous, i);
                if (s["kind"] == "move") before = without(std::move(before), box);
                CHECK(s["sah_cost"].get<double>() == doctest::Approx(leastCost(*before, fat, fat[box], 0.0)).epsilon(1e-12));
            }
            std::size_t i = 0;
            const std::string now = s["tree"];
            const std::unique_ptr<TextNode> after = parseTree(now, i);
            std::vector<int> ls;
            leaves(*after, ls);
            std::sort(ls.begin(), ls.end());
            CHECK(ls.size() == std::set<int>(ls.begin(), ls.end()).size());  // each box once
            CHECK(static_cast<int>(ls.size()) == inserted);
            previous = now;
        }
        CHECK(inserted == static_cast<int>(scene["boxes"].size()));
        CHECK(reinserted >= 1);
        CHECK(t["rotations"].get<int>() >= 1);  // the committed scene shows one
    }

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
