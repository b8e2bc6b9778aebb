// Dynamic AABB tree (core/broadphase/dynamic_tree.h) and its fat-box broad phase
// (core/broadphase/tree_broad_phase.h): the tree's invariants after every insert, move and remove;
// queries against a loop over every box; the broad phase's pairs against the O(n^2) testAabbAabb
// loop (verification/broad_phase_oracle.h) after every frame of coherent motion, teleports,
// growing and shrinking object counts, exact ties; rotations against the same insertions without
// them; the pair set against std::set.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "core/broadphase/pair_set.h"
#include "core/broadphase/tree_broad_phase.h"
#include "verification/broad_phase_oracle.h"

using namespace cdlab;
using broad_oracle::bruteForcePairs;
using broad_oracle::sortedPairs;

namespace {

Aabb randomBox(std::mt19937_64& rng, double extent, double minHalf, double maxHalf) {
    const Vec3 c(broad_oracle::uniform(rng, 0, extent), broad_oracle::uniform(rng, 0, extent),
                 broad_oracle::uniform(rng, 0, extent));
    const Vec3 h(broad_oracle::uniform(rng, minHalf, maxHalf), broad_oracle::uniform(rng, minHalf, maxHalf),
                 broad_oracle::uniform(rng, minHalf, maxHalf));
    return Aabb{c - h, c + h};
}

// Every leaf whose box overlaps q, by a query and by a loop over the leaves.
void checkQuery(const DynamicAabbTree& tree, const std::vector<int>& leafOf, const std::vector<Aabb>& boxes,
                const std::vector<char>& alive, const Aabb& q) {
    std::vector<int> found;
    tree.query(q, [&](int id, int leaf) {
        CHECK(leafOf[id] == leaf);
        found.push_back(id);
    });
    std::sort(found.begin(), found.end());
    std::vector<int> truth;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
        if (alive[i] && testAabbAabb(boxes[i], q).hit) truth.push_back(i);
    CHECK(found == truth);
}

}  // namespace

TEST_SUITE("dynamic_tree") {
    TEST_CASE("inserts, moves and removes keep every invariant, queries find exactly the overlapping leaves") {
        std::mt19937_64 rng(5);
        DynamicAabbTree tree;
        std::vector<Aabb> boxes;
        std::vector<int> leafOf;
        std::vector<char> alive;
        for (int step = 0; step < 3000; ++step) {
            const int op = static_cast<int>(rng() % 10);
            if (op < 5 || boxes.size() < 4) {  // insert
                boxes.push_back(randomBox(rng, 20, 0.1, 2));
                leafOf.push_back(tree.insert(boxes.back(), static_cast<int>(boxes.size()) - 1));
                alive.push_back(1);
            } else {
                const int id = static_cast<int>(rng() % boxes.size());
                if (!alive[id]) continue;
                if (op < 8) {  // move, sometimes far
                    boxes[id] = op == 7 ? randomBox(rng, 20, 0.1, 2)
                                        : Aabb{boxes[id].min + Vec3::Constant(0.1), boxes[id].max + Vec3::Constant(0.1)};
                    tree.move(leafOf[id], boxes[id]);
                } else {
                    tree.remove(leafOf[id]);
                    alive[id] = 0;
                }
            }
            if (step % 50 == 0) {
                CAPTURE(step);
                REQUIRE(tree.validate() == "");
                checkQuery(tree, leafOf, boxes, alive, randomBox(rng, 20, 0.5, 4));
            }
        }
        REQUIRE(tree.validate() == "");
        int live = 0;
        for (char a : alive) live += a;
        CHECK(tree.leafCount() == live);
        // Removing everything empties it; the freed nodes are reused.
        const int capacity = tree.nodeCapacity();
        for (int i = 0; i < static_cast<int>(alive.size()); ++i)
            if (alive[i]) tree.remove(leafOf[i]);
        CHECK(tree.root() == DynamicAabbTree::kNull);
        CHECK(tree.validate() == "");
        for (int i = 0; i < 100; ++i) tree.insert(randomBox(rng, 20, 0.1, 2), i);
        CHECK(tree.nodeCapacity() == capacity);
    }

    TEST_CASE("rotations repair a tree grown along a line: lower area and height than plain SAH insertion") {
        // 1024 unit boxes inserted in order along x: without rotations each new box pairs with the
        // previous one's subtree; with them the tree stays balanced.
        DynamicTreeOptions plain;
        plain.rotate = false;
        DynamicAabbTree rotated, unrotated(plain);
        for (int i = 0; i < 1024; ++i) {
            const Aabb b{Vec3(2.0 * i, 0, 0), Vec3(2.0 * i + 1, 1, 1)};
            rotated.insert(b, i);
            unrotated.insert(b, i);
        }
        REQUIRE(rotated.validate() == "");
        REQUIRE(unrotated.validate() == "");
        MESSAGE("height ", rotated.height(), " vs ", unrotated.height(), "; internal area ", rotated.internalArea(), " vs ",
                unrotated.internalArea(), "; rotations ", rotated.counters().rotations);
        CHECK(rotated.counters().rotations > 0);
        CHECK(rotated.height() <= 2 * 10 + 2);  // within about twice a balanced tree's 10
        CHECK(rotated.height() < unrotated.height());
        CHECK(rotated.internalArea() < unrotated.internalArea());
    }

    TEST_CASE("insertion trace: the branch and bound's sibling costs no more than any other node") {
        std::mt19937_64 rng(9);
        DynamicTreeOptions plain;
        plain.rotate = false;  // the trace's sibling is then still where it was costed
        DynamicAabbTree tree(plain);
        for (int i = 0; i < 200; ++i) tree.insert(randomBox(rng, 10, 0.1, 1), i);
        for (int trial = 0; trial < 50; ++trial) {
            const Aabb box = randomBox(rng, 10, 0.1, 1);
            // The SAH cost of pairing with every node, by walking up from it.
            double best = INFINITY;
            for (int i = 0; i < tree.nodeCapacity(); ++i) {
                if (tree.node(i).height < 0) continue;
                double cost = surfaceArea(unionOf(tree.node(i).box, box));
                for (int p = tree.node(i).parent; p != DynamicAabbTree::kNull; p = tree.node(p).parent)
                    cost += surfaceArea(unionOf(tree.node(p).box, box)) - surfaceArea(tree.node(p).box);
                best = std::min(best, cost);
            }
            DynamicTreeInsertTrace trace;
            tree.insert(box, 200 + trial, &trace);
            CHECK(trace.cost == doctest::Approx(best).epsilon(1e-12));
            CHECK(trace.costed.size() >= 1u);
        }
    }

    TEST_CASE("broad phase: the pairs of the O(n^2) loop after every frame (motion, teleports, n changing)") {
        std::mt19937_64 rng(3);
        for (double margin : {0.0, 0.05, 0.4}) {
            CAPTURE(margin);
            broad_oracle::Motion motion = broad_oracle::Motion::random(rng, 300, 12, 0.2, 0.8, 0.06);
            TreeBroadPhaseOptions options;
            options.margin = margin;
            if (margin == 0.0) options.predictFrames = 0.0;  // a fat box that is the box itself
            TreeBroadPhase bp(options);
            int movedTotal = 0;
            for (int frame = 0; frame < 60; ++frame) {
                motion.step();
                if (frame % 10 == 5) motion.center[rng() % motion.center.size()] = Vec3(6, 6, 6);  // teleport
                std::vector<Aabb> boxes = motion.boxes();
                if (frame >= 40) boxes.resize(boxes.size() - static_cast<std::size_t>(frame - 39) * 3);  // shrink
                const TreeBroadPhaseResult r = bp.update(boxes);
                CAPTURE(frame);
                REQUIRE(r.status == BoxStatus::Ok);
                REQUIRE(sortedPairs(bp.pairs()) == bruteForcePairs(boxes));
                CHECK(r.pairs == static_cast<int>(bp.pairs().size()));
                CHECK(r.fatPairs >= r.pairs);
                if (frame > 0) movedTotal += r.moved;
                REQUIRE(bp.tree().validate() == "");
                for (int i = 0; i < static_cast<int>(boxes.size()); ++i) CHECK(contains(bp.fatBox(i), boxes[i]));
            }
            // A margin moves fewer leaves: with none (and no prediction) every moving box is
            // re-inserted every frame.
            MESSAGE("margin ", margin, ": ", movedTotal, " re-insertions over 59 frames of 300 boxes");
            if (margin == 0.0) CHECK(movedTotal >= 59 * 250);
            if (margin == 0.4) CHECK(movedTotal < 59 * 300 / 3);
            // Growing again inserts new objects.
            std::vector<Aabb> boxes = motion.boxes();
            REQUIRE(bp.update(boxes).status == BoxStatus::Ok);
            CHECK(sortedPairs(bp.pairs()) == bruteForcePairs(boxes));
        }
    }

    TEST_CASE("broad phase: fat boxes stretched along the motion re-insert less, a stopped box's fat box shrinks") {
        std::mt19937_64 rng(6);
        const broad_oracle::Motion start = broad_oracle::Motion::random(rng, 400, 14, 0.2, 0.8, 0.05);
        int moved[2] = {0, 0};
        for (int predict : {0, 1}) {
            broad_oracle::Motion motion = start;
            TreeBroadPhaseOptions options;
            options.margin = 0.1;
            options.predictFrames = predict ? 4.0 : 0.0;
            TreeBroadPhase bp(options);
            for (int frame = 0; frame < 80; ++frame) {
                motion.step();
                const std::vector<Aabb> boxes = motion.boxes();
                const TreeBroadPhaseResult r = bp.update(boxes);
                REQUIRE(sortedPairs(bp.pairs()) == bruteForcePairs(boxes));
                if (frame >= 20) moved[predict] += r.moved;
            }
        }
        MESSAGE("re-insertions over 60 frames of 400 boxes: ", moved[0], " without prediction, ", moved[1], " with");
        CHECK(moved[1] < moved[0] * 3 / 4);
        // One box moving along x, then stopping: its stretched fat box is replaced by a tight one.
        TreeBroadPhaseOptions small;
        small.margin = 0.01;
        TreeBroadPhase bp(small);
        std::vector<Aabb> boxes = {Aabb{Vec3::Zero(), Vec3::Ones()}, Aabb{Vec3(5, 5, 5), Vec3(6, 6, 6)}};
        bp.update(boxes);
        for (int frame = 0; frame < 3; ++frame) {
            boxes[0].min.x() += 0.1;
            boxes[0].max.x() += 0.1;
            bp.update(boxes);
        }
        CHECK(bp.fatBox(0).max.x() > boxes[0].max.x() + 0.1);  // stretched 0.4 ahead when made, 2 frames ago
        bp.update(boxes);                                     // stopped: zero displacement
        CHECK(bp.fatBox(0).max.x() == doctest::Approx(boxes[0].max.x() + 0.01));
        // A teleport is not extrapolated past 4 margins plus the box's size.
        boxes[0].min.x() += 100;
        boxes[0].max.x() += 100;
        bp.update(boxes);
        CHECK(bp.fatBox(0).max.x() <= boxes[0].max.x() + 0.01 + 0.04 + 1.0 + 1e-12);
        CHECK(sortedPairs(bp.pairs()) == bruteForcePairs(boxes));
        // A NaN margin counts as 0: the pairs are still found.
        TreeBroadPhaseOptions nan;
        nan.margin = std::numeric_limits<double>::quiet_NaN();
        nan.predictFrames = -1;
        TreeBroadPhase plain(nan);
        std::vector<Aabb> two = {Aabb{Vec3::Zero(), Vec3::Ones()}, Aabb{Vec3::Constant(0.5), Vec3::Constant(2)}};
        plain.update(two);
        CHECK(plain.pairs().size() == 1);
    }

    TEST_CASE("broad phase: exact ties (integer boxes touching), flat boxes, bad boxes refused, nothing changed") {
        std::mt19937_64 rng(4);
        TreeBroadPhase bp;
        for (int frame = 0; frame < 30; ++frame) {
            std::vector<Aabb> boxes;
            for (int i = 0; i < 200; ++i) boxes.push_back(broad_oracle::integerBox(rng, 12, 3));
            REQUIRE(bp.update(boxes).status == BoxStatus::Ok);
            REQUIRE(sortedPairs(bp.pairs()) == bruteForcePairs(boxes));
        }
        std::vector<Aabb> boxes(3, Aabb{Vec3::Zero(), Vec3::Ones()});
        REQUIRE(bp.update(boxes).status == BoxStatus::Ok);
        const auto before = sortedPairs(bp.pairs());
        boxes[1].max.x() = std::numeric_limits<double>::quiet_NaN();
        TreeBroadPhaseResult r = bp.update(boxes);
        CHECK(r.status == BoxStatus::NonFinite);
        CHECK(r.object == 1);
        boxes[1] = Aabb{Vec3::Ones(), Vec3::Zero()};
        r = bp.update(boxes);
        CHECK(r.status == BoxStatus::Empty);
        CHECK(sortedPairs(bp.pairs()) == before);
        CHECK(bp.tree().leafCount() == 3);
    }

    TEST_CASE("pair set: inserts and erases against std::set, through growth and backward shifts") {
        std::mt19937_64 rng(8);
        PairSet set;
        std::set<std::uint64_t> truth;
        for (int step = 0; step < 200000; ++step) {
            const BoxPair p = BoxPair::make(static_cast<int>(rng() % 300), static_cast<int>(rng() % 300) + 300);
            if (rng() % 3 == 0) CHECK(set.erase(p) == (truth.erase(p.key()) == 1));
            else CHECK(set.insert(p) == truth.insert(p.key()).second);
            if (step % 1000 == 0) {
                CHECK(set.size() == truth.size());
                for (int k = 0; k < 20; ++k) {
                    const BoxPair q = BoxPair::make(static_cast<int>(rng() % 300), static_cast<int>(rng() % 300) + 300);
                    CHECK(set.contains(q) == (truth.count(q.key()) == 1));
                }
            }
        }
    }
}
