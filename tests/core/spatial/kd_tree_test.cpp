// k-d tree range and nearest-neighbour queries against brute force over all points.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/spatial/kd_tree.h"

using namespace cdlab;

namespace {

std::vector<int> bruteRange(const std::vector<Vec3>& pts, const Aabb& box) {
    std::vector<int> out;
    for (int i = 0; i < int(pts.size()); ++i) {
        const Vec3& p = pts[std::size_t(i)];
        if (!p.allFinite()) continue;
        bool in = true;
        for (int a = 0; a < 3; ++a) in = in && box.min[a] <= p[a] && p[a] <= box.max[a];
        if (in) out.push_back(i);
    }
    return out;
}

// Nearest by brute force: smallest squared distance (computed the same way for every point),
// smallest index among ties.
KdNearestResult bruteNearest(const std::vector<Vec3>& pts, const Vec3& q) {
    KdNearestResult best;
    for (int i = 0; i < int(pts.size()); ++i) {
        if (!pts[std::size_t(i)].allFinite()) continue;
        const double d2 = (pts[std::size_t(i)] - q).squaredNorm();
        if (d2 < best.distanceSquared) {
            best.distanceSquared = d2;
            best.index = i;
        }
    }
    return best;
}

void checkTree(const std::vector<Vec3>& pts, const KdTreeOptions& options, std::mt19937& rng, double spread,
               const Vec3& offset, bool integerQueries) {
    KdTree tree;
    tree.build(pts, options);
    std::uniform_real_distribution<double> u(-0.2 * spread, 1.2 * spread), ext(0.0, 0.4 * spread);
    for (int k = 0; k < 60; ++k) {
        Vec3 q(u(rng), u(rng), u(rng));
        Vec3 e(ext(rng), ext(rng), ext(rng));
        if (integerQueries) {
            q = q.array().round();
            e = e.array().round();
        }
        q += offset;
        const KdNearestResult want = bruteNearest(pts, q);
        const KdNearestResult got = tree.nearest(q);
        CHECK(got.distanceSquared == want.distanceSquared);
        CHECK(got.index == want.index);
        const Aabb box{q - e, q + e};
        CHECK(tree.rangeQuery(box) == bruteRange(pts, box));
    }
    // Queries exactly at data points (distance 0, ties among duplicates).
    for (int k = 0; k < 20 && !pts.empty(); ++k) {
        const Vec3 q = pts[std::size_t(rng() % pts.size())];
        if (!q.allFinite()) continue;
        CHECK(tree.nearest(q).index == bruteNearest(pts, q).index);
        CHECK(tree.rangeQuery({q, q}) == bruteRange(pts, {q, q}));
    }
}

}  // namespace

TEST_SUITE("kd_tree") {
    TEST_CASE("random points: nearest and range equal brute force (both split rules, leaf sizes)") {
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(0.0, 10.0);
        std::vector<Vec3> pts;
        for (int i = 0; i < 2000; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
        for (KdSplitRule rule : {KdSplitRule::Cycle, KdSplitRule::WidestAxis})
            for (int leaf : {1, 8}) checkTree(pts, {rule, leaf}, rng, 10.0, Vec3::Zero(), false);
    }

    TEST_CASE("integer grid points: many equal distances and points on split planes") {
        std::mt19937 rng(2);
        std::vector<Vec3> pts;
        for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 8; ++y)
                for (int z = 0; z < 4; ++z) pts.emplace_back(x, y, z);
        std::shuffle(pts.begin(), pts.end(), rng);
        for (KdSplitRule rule : {KdSplitRule::Cycle, KdSplitRule::WidestAxis})
            for (int leaf : {1, 3}) checkTree(pts, {rule, leaf}, rng, 8.0, Vec3::Zero(), true);
        // Half-integer queries are equidistant from up to 8 grid points: the smallest index wins.
        KdTree tree;
        tree.build(pts);
        const KdNearestResult r = tree.nearest(Vec3(2.5, 3.5, 1.5));
        CHECK(r.distanceSquared == 0.75);
        CHECK(r.index == bruteNearest(pts, Vec3(2.5, 3.5, 1.5)).index);
    }

    TEST_CASE("duplicates, collinear and coplanar clouds, large offsets and scales") {
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e4, 1e6}) {
                const Vec3 o(offset, -offset, 0.5 * offset);
                std::vector<Vec3> pts;
                for (int i = 0; i < 300; ++i) pts.push_back(o + scale * Vec3(u(rng), u(rng), u(rng)));
                for (int i = 0; i < 50; ++i) pts.push_back(pts[std::size_t(i)]);                     // duplicates
                for (int i = 0; i < 50; ++i) pts.push_back(o + scale * Vec3(u(rng), 0.5, 0.5));      // collinear
                for (int i = 0; i < 50; ++i) pts.push_back(o + scale * Vec3(u(rng), u(rng), 0.25));  // coplanar
                checkTree(pts, {KdSplitRule::Cycle, 2}, rng, scale, o, false);
                checkTree(pts, {KdSplitRule::WidestAxis, 1}, rng, scale, o, false);
            }
        // All points equal: one leaf, no endless splitting.
        std::vector<Vec3> same(100, Vec3(1, 2, 3));
        KdTree tree;
        tree.build(same);
        CHECK(tree.nodes().size() == 1u);
        CHECK(tree.nearest(Vec3(0, 0, 0)).index == 0);
        CHECK(tree.rangeQuery({Vec3(1, 2, 3), Vec3(1, 2, 3)}).size() == 100u);
    }

    TEST_CASE("NaN points are rejected with a status, NaN queries give nothing, empty tree") {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const std::vector<Vec3> pts = {Vec3(0, 0, 0), Vec3(nan, 1, 1), Vec3(1, 1, 1), Vec3(INFINITY, 0, 0)};
        KdTree tree;
        tree.build(pts);
        CHECK(tree.status() == KdTreeStatus::SomeRejected);
        CHECK(tree.rejected() == std::vector<int>{1, 3});
        CHECK(tree.nearest(Vec3(0.9, 0.9, 0.9)).index == 2);
        CHECK(tree.nearest(Vec3(nan, 0, 0)).index == -1);
        CHECK(tree.rangeQuery({Vec3::Constant(-10), Vec3::Constant(10)}) == std::vector<int>{0, 2});
        CHECK(tree.rangeQuery({Vec3::Constant(nan), Vec3::Constant(10)}).empty());
        KdTree empty;
        empty.build({});
        CHECK(empty.status() == KdTreeStatus::Empty);
        CHECK(empty.nearest(Vec3::Zero()).index == -1);
        CHECK(empty.rangeQuery({Vec3::Zero(), Vec3::Ones()}).empty());
    }

    TEST_CASE("structure: median splits give depth ~log2 n, cells nest, the nearest query prunes") {
        std::mt19937 rng(4);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<Vec3> pts;
        for (int i = 0; i < 4096; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
        KdTree tree;
        tree.build(pts, {KdSplitRule::Cycle, 1});
        CHECK(tree.depth() == 12);
        CHECK(tree.leafCount() == 4096);
        for (const KdNode& n : tree.nodes()) {
            if (n.isLeaf()) continue;
            CHECK(n.axis == n.depth % 3);
            for (int k = n.begin; k < n.end; ++k) {
                const Vec3& p = pts[std::size_t(tree.order()[std::size_t(k)])];
                CHECK((n.cell.min.array() <= p.array()).all());
                CHECK((p.array() <= n.cell.max.array()).all());
            }
        }
        KdQueryTrace trace;
        tree.nearest(Vec3(0.5, 0.5, 0.5), &trace);
        CHECK(trace.distanceTests < 100);
        CHECK(!trace.pruned.empty());
    }

}  // TEST_SUITE
