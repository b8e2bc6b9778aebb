// Octree pairs and box queries against the brute-force oracle: testAabbAabb (core/overlap/sat_tests.h)
// over all n(n-1)/2 pairs / all n boxes.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/broadphase/octree.h"
#include "core/overlap/sat_tests.h"

using namespace cdlab;

namespace {

using IndexPairs = std::vector<std::pair<int, int>>;

IndexPairs allOverlappingPairs(const std::vector<Aabb>& boxes) {
    IndexPairs out;
    for (int i = 0; i < int(boxes.size()); ++i)
        for (int j = i + 1; j < int(boxes.size()); ++j)
            if (testAabbAabb(boxes[std::size_t(i)], boxes[std::size_t(j)]).hit) out.emplace_back(i, j);
    return out;
}

std::vector<int> bruteForceQuery(const std::vector<Aabb>& boxes, const Aabb& q) {
    std::vector<int> out;
    for (int i = 0; i < int(boxes.size()); ++i)
        if (testAabbAabb(boxes[std::size_t(i)], q).hit) out.push_back(i);
    return out;
}

std::vector<Aabb> randomBoxes(std::mt19937& rng, int n, double world, double maxSize, const Vec3& offset,
                              bool integer) {
    std::uniform_real_distribution<double> pos(0.0, world), size(0.0, maxSize);
    std::vector<Aabb> boxes;
    for (int i = 0; i < n; ++i) {
        Vec3 lo(pos(rng), pos(rng), pos(rng)), ext(size(rng), size(rng), size(rng));
        if (integer) {
            lo = lo.array().floor();
            ext = ext.array().floor();
        }
        boxes.push_back({lo + offset, lo + ext + offset});
    }
    return boxes;
}

// Builds with the options and checks pairs and a few queries against brute force.
void checkAgainstBruteForce(const std::vector<Aabb>& boxes, const OctreeOptions& options, std::mt19937& rng) {
    Octree tree;
    tree.build(boxes, options);
    std::int64_t tests = 0;
    const IndexPairs pairs = tree.overlappingPairs(&tests);
    CHECK(pairs == allOverlappingPairs(boxes));
    // Every valid box is stored in exactly one node, inside that node's (loose) cell unless it is the root.
    std::vector<int> seen(boxes.size(), 0);
    for (std::size_t n = 0; n < tree.nodes().size(); ++n)
        for (int i : tree.nodes()[n].objects) {
            ++seen[std::size_t(i)];
            CHECK(tree.nodeOf(i) == int(n));
            if (n > 0) {
                const Aabb& c = tree.nodes()[n].looseCell;
                CHECK((c.min.array() <= boxes[std::size_t(i)].min.array()).all());
                CHECK((boxes[std::size_t(i)].max.array() <= c.max.array()).all());
            }
        }
    for (std::size_t i = 0; i < boxes.size(); ++i) CHECK(seen[i] == (isValidBox(boxes[i]) ? 1 : 0));
    // Box queries: some input boxes themselves (ties) and random ones.
    for (int k = 0; k < 10 && !boxes.empty(); ++k) {
        Aabb q = boxes[std::size_t(rng() % boxes.size())];
        if (k % 2 == 1 && isValidBox(q)) {
            const Vec3 d = (q.max - q.min) * 1.5 + Vec3::Constant(0.5);
            q = {q.min - d, q.max + d};
        }
        CHECK(tree.query(q) == bruteForceQuery(boxes, q));
    }
}

}  // namespace

TEST_SUITE("octree") {
    TEST_CASE("random boxes: pairs and queries equal brute force, classic and loose") {
        std::mt19937 rng(7);
        for (double looseness : {1.0, 2.0, 1.5})
            for (int leaf : {1, 4}) {
                OctreeOptions o;
                o.looseness = looseness;
                o.maxObjectsPerLeaf = leaf;
                checkAgainstBruteForce(randomBoxes(rng, 300, 100.0, 8.0, Vec3::Zero(), false), o, rng);
            }
    }

    TEST_CASE("integer coordinates: touching boxes and boxes on split planes are pairs") {
        // Integer boxes in [0, 16]^3: the root midpoint and the cell midpoints are integers, so
        // many boxes touch each other exactly and end exactly on split planes.
        std::mt19937 rng(11);
        for (double looseness : {1.0, 2.0}) {
            OctreeOptions o;
            o.looseness = looseness;
            o.maxObjectsPerLeaf = 2;
            o.useRootBounds = true;
            o.rootBounds = {Vec3::Zero(), Vec3::Constant(16.0)};
            checkAgainstBruteForce(randomBoxes(rng, 250, 16.0, 3.0, Vec3::Zero(), true), o, rng);
        }
        // A hand-made case: two unit boxes touching on the root's split plane x = 8.
        const std::vector<Aabb> two = {{Vec3(7, 1, 1), Vec3(8, 2, 2)},
                                       {Vec3(8, 1, 1), Vec3(9, 2, 2)},
                                       {Vec3(1, 1, 1), Vec3(2, 2, 2)},
                                       {Vec3(14, 14, 14), Vec3(15, 15, 15)}};
        OctreeOptions o;
        o.maxObjectsPerLeaf = 0;
        o.useRootBounds = true;
        o.rootBounds = {Vec3::Zero(), Vec3::Constant(16.0)};
        Octree tree;
        tree.build(two, o);
        CHECK(tree.overlappingPairs() == IndexPairs{{0, 1}});
        CHECK(tree.nodeOf(0) == 0);  // touches x = 8: stays in the root
        CHECK(tree.nodes()[std::size_t(tree.nodeOf(2))].depth ==
              2);  // [1, 2] touches the plane x = 2 of the cell [0, 4]
    }

    TEST_CASE("zero-size boxes, duplicates and all objects on one point terminate") {
        std::mt19937 rng(3);
        std::vector<Aabb> boxes = randomBoxes(rng, 100, 10.0, 0.0, Vec3::Zero(), false);  // points
        for (int i = 0; i < 20; ++i) boxes.push_back(boxes[std::size_t(i)]);              // duplicates
        checkAgainstBruteForce(boxes, {}, rng);
        // 50 copies of one point: every pair overlaps, the depth limit stops the splitting.
        std::vector<Aabb> same(50, Aabb{Vec3(1, 2, 3), Vec3(1, 2, 3)});
        Octree tree;
        OctreeOptions o;
        o.maxDepth = 30;
        tree.build(same, o);
        CHECK(tree.overlappingPairs().size() == 50u * 49u / 2u);
        CHECK(tree.stats().nodeCount <= 31);
    }

    TEST_CASE("large offsets and scales") {
        std::mt19937 rng(5);
        for (double offset : {1e4, 1e6})
            for (double scale : {1e-3, 1.0, 1e3}) {
                OctreeOptions o;
                o.maxObjectsPerLeaf = 3;
                checkAgainstBruteForce(
                    randomBoxes(rng, 150, 10.0 * scale, scale, Vec3(offset, -offset, 0.5 * offset), false), o, rng);
                o.looseness = 2.0;
                checkAgainstBruteForce(randomBoxes(rng, 150, 10.0 * scale, scale, Vec3(-offset, offset, offset), false),
                                       o, rng);
            }
    }

    TEST_CASE("boxes larger than or outside a given root stay in the root, pairs stay exact") {
        std::mt19937 rng(9);
        std::vector<Aabb> boxes = randomBoxes(rng, 120, 10.0, 2.0, Vec3::Zero(), false);
        boxes.push_back({Vec3::Constant(-50), Vec3::Constant(50)});  // contains the root
        boxes.push_back({Vec3(20, 20, 20), Vec3(21, 21, 21)});       // outside the root
        boxes.push_back({Vec3(9, 9, 9), Vec3(30, 9.5, 9.5)});        // sticks out of the root
        for (double looseness : {1.0, 2.0}) {
            OctreeOptions o;
            o.looseness = looseness;
            o.maxObjectsPerLeaf = 2;
            o.useRootBounds = true;
            o.rootBounds = {Vec3::Zero(), Vec3::Constant(10.0)};
            checkAgainstBruteForce(boxes, o, rng);
            Octree tree;
            tree.build(boxes, o);
            CHECK(tree.nodeOf(120) == 0);
            CHECK(tree.nodeOf(121) == 0);
            CHECK(tree.nodeOf(122) == 0);
        }
    }

    TEST_CASE("invalid boxes are rejected with a status, never paired") {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        std::vector<Aabb> boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)},
                                   {Vec3(nan, 0, 0), Vec3(1, 1, 1)},
                                   {Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)},
                                   {Vec3(1, 1, 1), Vec3(0, 0, 0)},  // min > max: empty
                                   {Vec3(0, 0, 0), Vec3(INFINITY, 1, 1)}};
        Octree tree;
        tree.build(boxes);
        CHECK(tree.status() == OctreeStatus::SomeRejected);
        CHECK(tree.rejected() == std::vector<int>{1, 3, 4});
        CHECK(tree.overlappingPairs() == IndexPairs{{0, 2}});
        CHECK(tree.query({Vec3::Constant(nan), Vec3::Constant(1)}).empty());
        Octree empty;
        empty.build({});
        CHECK(empty.status() == OctreeStatus::Empty);
        CHECK(empty.overlappingPairs().empty());
        CHECK(empty.query({Vec3::Zero(), Vec3::Ones()}).empty());
    }

    TEST_CASE("the pair query does fewer tests than brute force on spread-out boxes, trace matches nodes") {
        std::mt19937 rng(13);
        const std::vector<Aabb> boxes = randomBoxes(rng, 1000, 100.0, 1.0, Vec3::Zero(), false);
        for (double looseness : {1.0, 2.0}) {
            Octree tree;
            OctreeTrace trace;
            OctreeOptions o;
            o.looseness = looseness;
            tree.build(boxes, o, &trace);
            std::int64_t tests = 0;
            CHECK(tree.overlappingPairs(&tests) == allOverlappingPairs(boxes));
            CHECK(tests < 1000 * 999 / 2 / 10);
            CHECK(trace.steps.size() == tree.nodes().size());
            const OctreeStats s = tree.stats();
            int total = 0;
            for (int c : s.objectsPerDepth) total += c;
            CHECK(total == 1000);
        }
    }

}  // TEST_SUITE
