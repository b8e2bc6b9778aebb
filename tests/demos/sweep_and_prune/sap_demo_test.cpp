// golden/sweep_and_prune run numerically (RunContext{} without GL); their numbers recomputed from
// the scene's boxes without core's SweepAndPrune: the sweep along x by sorting the endpoints and
// keeping the active set by hand, the pairs by testing every pair of boxes, the swaps of an update
// as the inversions between the last frame's order and the new values (counted by merge sort).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"
#include "demos/sweep_and_prune/sap_coherence.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace sap_demo_test {

Json sceneJson(const std::string& name) {
    return readJsonFile(std::string(CDLAB_SOURCE_DIR) + "/golden/sweep_and_prune/" + name + ".json");
}
Json runScene(const std::string& name) {
    return loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/sweep_and_prune/" + name + ".json")
        ->run(RunContext{})
        .trace;
}

bool overlap(const Aabb& a, const Aabb& b, int k) { return a.min[k] <= b.max[k] && b.min[k] <= a.max[k]; }
bool overlap3(const Aabb& a, const Aabb& b) { return overlap(a, b, 0) && overlap(a, b, 1) && overlap(a, b, 2); }

std::string name(int id) { return std::string(1, static_cast<char>('A' + id)); }

/// Pairs (i, j), i < j, with v[j] < v[i]: merge sort.
long long inversions(std::vector<double>& v, std::size_t lo, std::size_t hi, std::vector<double>& tmp) {
    if (hi - lo < 2) return 0;
    const std::size_t mid = (lo + hi) / 2;
    long long count = inversions(v, lo, mid, tmp) + inversions(v, mid, hi, tmp);
    std::size_t i = lo, j = mid, o = lo;
    while (i < mid || j < hi) {
        if (j == hi || (i < mid && v[i] <= v[j])) tmp[o++] = v[i++];
        else count += static_cast<long long>(mid - i), tmp[o++] = v[j++];
    }
    std::copy(tmp.begin() + lo, tmp.begin() + hi, v.begin() + lo);
    return count;
}

}  // namespace sap_demo_test

TEST_CASE("sweep and prune: frame 0's sweep along x, its active list and its pairs recomputed by hand") {
    using namespace sap_demo_test;
    for (const char* scene : {"initial_sweep", "moving_boxes", "touching"}) {
        CAPTURE(scene);
        const Json s = sceneJson(scene), t = runScene(scene);
        std::vector<Aabb> boxes;
        for (const Json& b : s["boxes"]) {
            Aabb a;
            for (int k = 0; k < 3; ++k) a.min[k] = b["min"][k].get<double>(), a.max[k] = b["max"][k].get<double>();
            boxes.push_back(a);
        }
        const int n = static_cast<int>(boxes.size());
        // x endpoints in order: by value, a min before a max at equal values (closed boxes).
        struct End {
            double x;
            int isMax, id;
        };
        std::vector<End> ends;
        for (int i = 0; i < n; ++i) ends.push_back({boxes[i].min.x(), 0, i}), ends.push_back({boxes[i].max.x(), 1, i});
        std::sort(ends.begin(), ends.end(), [](const End& a, const End& b) {
            return a.x != b.x ? a.x < b.x : a.isMax != b.isMax ? a.isMax < b.isMax : a.id < b.id;
        });
        const Json& sweep = t["frames"][0]["sweep"];
        REQUIRE(sweep.size() == ends.size());
        std::set<int> active;
        std::set<std::pair<int, int>> pairs;
        for (std::size_t i = 0; i < ends.size(); ++i) {
            const End& e = ends[i];
            const Json& step = sweep[i];
            CHECK(step["endpoint"] == (e.isMax ? name(e.id) + "]" : "[" + name(e.id)));
            CHECK(step["value"].get<double>() == e.x);
            std::set<int> met;
            for (const Json& m : step["meets"]) {
                const int other = m["box"].get<std::string>()[0] - 'A';
                met.insert(other);
                CHECK(m["y"].get<bool>() == overlap(boxes[e.id], boxes[other], 1));
                CHECK(m["z"].get<bool>() == overlap(boxes[e.id], boxes[other], 2));
                if (overlap3(boxes[e.id], boxes[other])) pairs.insert({std::min(e.id, other), std::max(e.id, other)});
            }
            CHECK(met == (e.isMax ? std::set<int>{} : active));
            if (e.isMax) active.erase(e.id);
            else active.insert(e.id);
            std::set<int> listed;
            for (const Json& a : step["active"]) listed.insert(a.get<std::string>()[0] - 'A');
            CHECK(listed == active);
        }
        // Every overlapping pair is met by the sweep, and the sweep's pairs are the frame's pairs.
        std::set<std::pair<int, int>> brute;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (overlap3(boxes[i], boxes[j])) brute.insert({i, j});
        CHECK(pairs == brute);
        std::set<std::pair<int, int>> reported;
        for (const Json& p : t["frames"][0]["pairs"])
            reported.insert({p.get<std::string>()[0] - 'A', p.get<std::string>()[1] - 'A'});
        CHECK(reported == brute);
    }
}

TEST_CASE("sweep and prune coherence: each update's swaps are the inversions of the last order, pairs by brute force") {
    using namespace sap_demo_test;
    const Json s = sceneJson("coherence"), t = runScene("coherence");
    const Json& runs = t["runs"];
    REQUIRE(runs.size() == s["counts"].size() * s["speeds"].size());
    const int updates = s["updates"].get<int>();
    std::map<double, std::map<int, double>> perBox;  // speed -> n -> swaps per box
    for (const Json& r : runs) {
        const int n = r["n"].get<int>();
        const double speed = r["speed"].get<double>();
        CAPTURE(n);
        CAPTURE(speed);
        const CoherenceBoxes b = coherenceBoxes(n, speed, s["density"].get<double>(), s["seed"].get<unsigned>());
        REQUIRE(static_cast<int>(b.centres.size()) == n);
        auto at = [&](int f) { return b.at(f); };
        double total = 0;
        for (int f = 0; f <= updates; ++f) {
            const std::vector<Aabb> now = at(f);
            int brute = 0;
            for (int i = 0; i < n; ++i)
                for (int j = i + 1; j < n; ++j) brute += overlap3(now[i], now[j]);
            CHECK(r["pairs"][f].get<int>() == brute);
            if (f == 0) continue;
            const std::vector<Aabb> before = at(f - 1);
            long long swaps = 0;
            for (int k = 0; k < 3; ++k) {
                // Endpoints in last frame's order (random coordinates: no ties), this frame's values.
                std::vector<std::pair<double, double>> ends;  // (old, new)
                for (int i = 0; i < n; ++i) {
                    ends.push_back({before[i].min[k], now[i].min[k]});
                    ends.push_back({before[i].max[k], now[i].max[k]});
                }
                std::sort(ends.begin(), ends.end());
                std::vector<double> v, tmp(ends.size());
                for (const auto& e : ends) v.push_back(e.second);
                const long long inv = inversions(v, 0, v.size(), tmp);
                CHECK(r["swaps_per_axis"][3 * (f - 1) + k].get<long long>() == inv);
                swaps += inv;
            }
            CHECK(r["swaps"][f - 1].get<long long>() == swaps);
            total += static_cast<double>(swaps);
        }
        CHECK(r["swaps_per_box"].get<double>() == doctest::Approx(total / updates / n).epsilon(1e-12));
        perBox[speed][n] = total / updates / n;
    }
    // The legend's slope: log-log, smallest to largest n, to two decimals.
    for (const Json& r : runs) {
        const auto& byN = perBox[r["speed"].get<double>()];
        const auto& [n0, y0] = *byN.begin();
        const auto& [n1, y1] = *byN.rbegin();
        CHECK(r["slope"].get<double>() == std::round(100 * std::log(y1 / y0) / std::log(double(n1) / n0)) / 100);
    }
}

TEST_CASE("sweep and prune coherence: a scene past a limit is one error naming its key") {
    const std::string base = R"({"demo": "sweep_and_prune", "figure": "coherence", "title": "t", )";
    const std::pair<const char*, const char*> bad[] = {
        {R"("counts": [16, 5000]})", "counts[1]"}, {R"("counts": [16]})", "counts"},
        {R"("speeds": [0.1, 5]})", "speeds[1]"},   {R"("speeds": [0.1, 0.2, 0.4, 0.8, 1.6]})", "speeds"},
        {R"("updates": 11})", "updates"},          {R"("density": 2})", "density"},
        {R"("speeds": [0]})", "speeds[0]"},        {R"("counts": [1, 16]})", "counts[0]"},
        {R"("counts": [64, 64]})", "counts[1]"},   {R"("density": 1})", "density"},
        {R"("counts": [2, 4096], "speeds": [4], "updates": 10, "density": 0.5})", "estimated insertion-sort swaps"}};
    for (const auto& [keys, path] : bad) {
        CAPTURE(keys);
        const std::string error = test::sceneTextError(base + keys);
        CHECK(error.find(path) != std::string::npos);
    }
    CHECK(test::sceneTextError(base + R"("counts": [2, 2048], "speeds": [4], "updates": 10, "density": 0.5})") == "");
}
