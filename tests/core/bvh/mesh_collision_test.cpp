// Mesh-mesh collision through BVHs (core/bvh/mesh_collision.h). Oracle: every pair of world
// triangles tested with intersectTriangleTriangle (bvh_test_util.h brutePairs, its own loop);
// the pair SETS must be equal exactly, for every build method x BV type (and mixed trees), over
// random poses from deep to just separated (bisection on the contact distance), exactly
// touching copies, interlocked tori, offsets 1e4..1e6 and scales 1e-3..1e3.
#include <doctest/doctest.h>

#include <cmath>

#include "core/bvh/mesh_collision.h"
#include "tests/core/bvh/bvh_test_util.h"

using namespace cdlab;
using namespace bvhtest;

namespace {

PairList pairsOf(const MeshCollisionResult& r) {
    PairList out;
    for (const TrianglePair& p : r.pairs) out.emplace_back(p.a, p.b);
    std::sort(out.begin(), out.end());
    return out;
}

/// Trees for both meshes under every combination (same kind on both sides, plus two mixed).
struct TreeSet {
    std::vector<std::string> names;
    std::vector<Bvh> a, b;
};

TreeSet treesFor(const TriangleMesh& ma, const TriangleMesh& mb, int leaf = 1) {
    TreeSet s;
    const std::vector<Combo> combos = allCombos();
    for (const Combo& c : combos) {
        s.names.push_back(c.name);
        s.a.push_back(build(ma, c, leaf));
        s.b.push_back(build(mb, c, leaf));
    }
    s.names.push_back("median/AABB vs SAH/OBB");
    s.a.push_back(build(ma, combos[0], leaf));
    s.b.push_back(build(mb, combos[3], leaf));
    s.names.push_back("bottom-up/OBB vs median/AABB (leaf 4)");
    s.a.push_back(build(ma, combos[5], 4));
    s.b.push_back(build(mb, combos[0], 4));
    return s;
}

/// Checks every tree combination against the brute-force pairs; returns the pair count.
size_t checkPose(const TriangleMesh& ma, const TriangleMesh& mb, const TreeSet& trees, const Transform& pa,
                 const Transform& pb) {
    const PairList expect = brutePairs(ma, pa, mb, pb);
    for (size_t k = 0; k < trees.a.size(); ++k) {
        INFO(trees.names[k], " expected pairs ", expect.size());
        const MeshCollisionResult r = collideMeshes(ma, trees.a[k], pa, mb, trees.b[k], pb);
        REQUIRE(r.status == MeshCollisionStatus::Ok);
        REQUIRE(pairsOf(r) == expect);
        CHECK(r.hit == !expect.empty());
        MeshCollisionOptions first;
        first.firstHitOnly = true;
        const MeshCollisionResult f = collideMeshes(ma, trees.a[k], pa, mb, trees.b[k], pb, first);
        REQUIRE(f.hit == !expect.empty());
        REQUIRE(f.pairs.size() == (expect.empty() ? 0u : 1u));
        if (!f.pairs.empty())
            CHECK(std::binary_search(expect.begin(), expect.end(), std::make_pair(f.pairs[0].a, f.pairs[0].b)));
    }
    return expect.size();
}

/// Largest s in [0, hi] at which B (moved by s * dir from pb) still hits A, by bisection on the
/// brute-force answer (lo hits, hi does not), to a relative 1e-15.
double contactDistance(const TriangleMesh& ma, const Transform& pa, const TriangleMesh& mb, Transform pb,
                       const Vec3& dir, double hi) {
    double lo = 0.0;
    const Vec3 p0 = pb.position;
    for (int it = 0; it < 60 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        pb.position = p0 + mid * dir;
        if (brutePairs(ma, pa, mb, pb).empty()) hi = mid;
        else lo = mid;
    }
    return lo;
}

}  // namespace

TEST_SUITE("mesh_collision") {
    TEST_CASE("random poses: deep, near, just touching and just separated, every combination") {
        std::mt19937_64 rng(9001);
        const TriangleMesh torus = torusMesh(1.0, 0.3, 16, 8);
        const TriangleMesh blob = noisyBlobMesh(0.8, 0.35, 12, 8, 21);
        const TreeSet trees = treesFor(torus, blob);
        size_t hits = 0, misses = 0;
        for (int p = 0; p < 30; ++p) {
            Transform pa, pb;
            pa.rotation = randomRotation(rng);
            pb.rotation = randomRotation(rng);
            pa.position = Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
            pb.position = pa.position + uniform(rng, 0.0, 2.5) * randomUnit(rng);
            (checkPose(torus, blob, trees, pa, pb) ? hits : misses)++;
        }
        // Just touching / just separated: bisection on the distance along a random direction.
        for (int p = 0; p < 6; ++p) {
            Transform pa, pb;
            pa.rotation = randomRotation(rng);
            pb.rotation = randomRotation(rng);
            const Vec3 dir = randomUnit(rng);
            const double s = contactDistance(torus, pa, blob, pb, dir, 4.0);
            for (double f : {1.0 - 1e-12, 1.0, 1.0 + 1e-15, 1.0 + 1e-12, 1.0 + 1e-9}) {
                pb.position = f * s * dir;
                checkPose(torus, blob, trees, pa, pb);
            }
        }
        CHECK(hits > 5);
        CHECK(misses > 5);
    }

    TEST_CASE("exactly touching: identical copies, coplanar soups, tori side by side") {
        std::mt19937_64 rng(77);
        const TriangleMesh torus = torusMesh(1.0, 0.3, 16, 8);
        {
            // The same mesh at the same pose: every triangle meets itself and its neighbours.
            const TreeSet trees = treesFor(torus, torus);
            Transform pose;
            pose.rotation = randomRotation(rng);
            pose.position = Vec3(3, -2, 1);
            CHECK(checkPose(torus, torus, trees, pose, pose) >= 10u * torus.triangles.size());
            // Side by side: outermost vertices (1.3, 0, 0) and (-1.3, ~1e-16, 0) + 2.6 meet up to rounding.
            Transform pb;
            pb.position = Vec3(2.6, 0, 0);
            checkPose(torus, torus, trees, Transform{}, pb);
            pb.position = Vec3(2.6 * (1 + 1e-16), 0, 0);
            checkPose(torus, torus, trees, Transform{}, pb);
        }
        {
            // Two random soups in the plane z = 0 (exactly coplanar overlaps), B shifted in the plane.
            TriangleMesh a = randomSoupMesh(120, 1.0, 0.4, 5), b = randomSoupMesh(120, 1.0, 0.4, 6);
            for (Vec3& v : a.vertices) v.z() = 0;
            for (Vec3& v : b.vertices) v.z() = 0;
            const TreeSet trees = treesFor(a, b);
            Transform pb;
            pb.position = Vec3(0.25, -0.125, 0);
            CHECK(checkPose(a, b, trees, Transform{}, pb) > 0u);
            pb.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
            checkPose(a, b, trees, Transform{}, pb);
            pb.position.z() = 1e-300;  // parallel planes, no contact
            checkPose(a, b, trees, Transform{}, pb);
        }
    }

    TEST_CASE("interlocked tori: linked rings perturbed into and out of contact") {
        std::mt19937_64 rng(4242);
        const TriangleMesh a = torusMesh(1.0, 0.25, 20, 8);
        const TriangleMesh b = torusMesh(1.0, 0.25, 18, 7);
        const TreeSet trees = treesFor(a, b);
        size_t hits = 0, misses = 0;
        for (int p = 0; p < 25; ++p) {
            Transform pb;
            // B in the xz plane through A's hole: linked, core circles 1 apart everywhere at rest.
            pb.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())) *
                          Quat(Eigen::AngleAxisd(uniform(rng, -0.6, 0.6), randomUnit(rng)));
            pb.position = Vec3(1.0, 0, 0) + uniform(rng, 0.0, 0.7) * randomUnit(rng);
            (checkPose(a, b, trees, Transform{}, pb) ? hits : misses)++;
        }
        CHECK(hits > 2);
        CHECK(misses > 2);
    }

    TEST_CASE("large offsets (1e4..1e6) and scales (1e-3..1e3)") {
        std::mt19937_64 rng(555);
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e4, 1e6}) {
                INFO("scale ", scale, " offset ", offset);
                // Offset in the body frame (vertices far from the origin) for A, in the pose for B.
                const Vec3 bodyOffset = offset * Vec3(1, -0.5, 0.25);
                const TriangleMesh a = transformed(torusMesh(1.0, 0.3, 12, 6), scale, bodyOffset);
                const TriangleMesh b = transformed(noisyBlobMesh(0.8, 0.3, 10, 6, 3), scale, Vec3::Zero());
                const TreeSet trees = treesFor(a, b);
                for (int p = 0; p < 6; ++p) {
                    Transform pa, pb;
                    pa.rotation = randomRotation(rng);
                    pa.position = offset * Vec3(-0.5, 0.25, 1);
                    pb.rotation = randomRotation(rng);
                    pb.position = pa.apply(bodyOffset) + scale * uniform(rng, 0.0, 2.2) * randomUnit(rng);
                    checkPose(a, b, trees, pa, pb);
                }
                // Just touching at this scale and offset.
                Transform pa, pb;
                pa.position = offset * Vec3(-0.5, 0.25, 1);
                pb.rotation = randomRotation(rng);
                pb.position = pa.apply(bodyOffset);
                const Vec3 dir = randomUnit(rng);
                const double s = contactDistance(a, pa, b, pb, dir, 3.0 * scale);
                const Vec3 p0 = pb.position;
                for (double f : {1.0, 1.0 + 1e-14, 1.0 + 1e-10}) {
                    pb.position = p0 + f * s * dir;
                    checkPose(a, b, trees, pa, pb);
                }
            }
    }

    TEST_CASE("refit after deformation gives the brute-force pairs of the deformed mesh") {
        std::mt19937_64 rng(31337);
        const TriangleMesh torus = torusMesh(1.0, 0.3, 16, 8);
        const TriangleMesh blob = noisyBlobMesh(0.7, 0.3, 10, 7, 8);
        TreeSet trees = treesFor(torus, blob);
        for (int frame = 1; frame <= 4; ++frame) {
            // Waves travelling over the torus (large: up to 0.5, i.e. beyond the tube radius).
            TriangleMesh bent = torus;
            for (Vec3& v : bent.vertices)
                v += 0.12 * frame * Vec3(std::sin(2 * v.y() + frame), std::cos(3 * v.x()), std::sin(4 * v.x() + v.y()));
            for (size_t k = 0; k < trees.a.size(); ++k) REQUIRE(refitBvh(trees.a[k], bent) == BvhStatus::Ok);
            for (int p = 0; p < 6; ++p) {
                Transform pb;
                pb.rotation = randomRotation(rng);
                pb.position = uniform(rng, 0.5, 1.8) * randomUnit(rng);
                checkPose(bent, blob, trees, Transform{}, pb);
            }
        }
    }

    TEST_CASE("degenerate meshes never crash: empty, zero-area, duplicated, invalid trees") {
        TriangleMesh empty;
        TriangleMesh one;
        one.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        one.triangles = {{0, 1, 2}};
        TriangleMesh degenerate;
        degenerate.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.5, 0, 0)};
        degenerate.triangles = {{0, 0, 0}, {0, 1, 3}, {0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {1, 1, 1}};
        const TriangleMesh torus = torusMesh(0.5, 0.2, 8, 6);
        std::vector<const TriangleMesh*> meshes{&empty, &one, &degenerate, &torus};
        for (const TriangleMesh* ma : meshes)
            for (const TriangleMesh* mb : meshes) {
                const TreeSet trees = treesFor(*ma, *mb);
                Transform pb;
                pb.rotation = Quat(Eigen::AngleAxisd(0.5, Vec3(1, 1, 0).normalized()));
                pb.position = Vec3(0.2, 0.1, 0.0);
                checkPose(*ma, *mb, trees, Transform{}, pb);
                checkPose(*ma, *mb, trees, Transform{}, Transform{});
            }
        // Invalid tree and a tree of another mesh: clear statuses.
        TriangleMesh nan = one;
        nan.vertices[1].x() = std::nan("");
        const Bvh bad = buildBvh(nan);
        const Bvh good = buildBvh(one);
        const Bvh torusTree = buildBvh(torus);
        CHECK(collideMeshes(nan, bad, Transform{}, one, good, Transform{}).status == MeshCollisionStatus::InvalidTree);
        CHECK(collideMeshes(one, torusTree, Transform{}, one, good, Transform{}).status ==
              MeshCollisionStatus::TreeMeshMismatch);
    }

    TEST_CASE("traces and counters: steps match the stats, OBB trees test fewer boxes on a torus") {
        const TriangleMesh a = torusMesh(1.0, 0.3, 32, 12);
        Transform pb;
        pb.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
        pb.position = Vec3(1.0, 0.0, 0.05);
        long long bvTests[2] = {0, 0};
        for (BvKind kind : {BvKind::Aabb, BvKind::Obb}) {
            BvhBuildOptions o;
            o.bvKind = kind;
            const Bvh t = buildBvh(a, o);
            BvhTraversalTrace trace;
            const MeshCollisionResult r = collideMeshes(a, t, Transform{}, a, t, pb, {}, &trace);
            long long bv = 0, leaves = 0, tris = 0, hitSteps = 0;
            for (const BvhTraversalStep& s : trace.steps) {
                if (s.action == BvhTraversalAction::TriangleTest) {
                    ++tris;
                    hitSteps += s.triangleHit;
                } else {
                    ++bv;
                }
                leaves += s.action == BvhTraversalAction::LeafTest;
                if (s.action == BvhTraversalAction::DescendA) CHECK(!t.nodes[s.nodeA].isLeaf());
                if (s.action == BvhTraversalAction::DescendB) CHECK(!t.nodes[s.nodeB].isLeaf());
            }
            CHECK(bv == r.stats.bvTests);
            CHECK(leaves == r.stats.leafVisits);
            CHECK(tris == r.stats.triangleTests);
            CHECK(hitSteps == static_cast<long long>(r.pairs.size()));
            bvTests[kind == BvKind::Obb] = r.stats.bvTests;
            CHECK(pairsOf(r) == brutePairs(a, Transform{}, a, pb));
        }
        // Gottschalk et al. 1996: on a curved surface OBBs fit much tighter than AABBs.
        CHECK(bvTests[1] < bvTests[0]);
    }

}  // TEST_SUITE
