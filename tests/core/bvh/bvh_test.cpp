// Bounding-volume hierarchies (core/bvh/bvh.h) and triangle meshes (core/geometry/triangle_mesh.h).
// Oracles: the tree structure checked node by node (ranges partition, every vertex inside its
// nodes' boxes, in long double for OBBs); basic queries (ray, triangle, box) against a loop over
// every world triangle; degenerate meshes for statuses and termination.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <set>

#include "core/overlap/sat_tests.h"
#include "tests/core/bvh/bvh_test_util.h"

using namespace cdlab;
using namespace bvhtest;

namespace {

using LD = long double;

/// Every vertex of the node's triangles inside the node's box: exactly for AABBs, in long
/// double for OBBs (|axes^T (v - c)| <= h with the stored double axes).
bool boxContains(const Bvh& bvh, int node, const Vec3& v) {
    if (bvh.kind == BvKind::Aabb) {
        const Aabb& b = bvh.aabbs[node];
        return (v.array() >= b.min.array()).all() && (v.array() <= b.max.array()).all();
    }
    const Obb& o = bvh.obbs[node];
    for (int k = 0; k < 3; ++k) {
        LD s = 0;
        for (int r = 0; r < 3; ++r) s += (LD(v[r]) - LD(o.center[r])) * LD(o.axes(r, k));
        if (std::abs(s) > LD(o.halfExtents[k])) return false;
    }
    return true;
}

/// Structure of a built tree: ranges, links, depths, leaf sizes, containment.
void checkStructure(const Bvh& bvh, const TriangleMesh& mesh, int maxLeaf) {
    REQUIRE(bvh.status == BvhStatus::Ok);
    const int n = mesh.triangleCount();
    REQUIRE(bvh.triangleCount() == n);
    std::vector<int> order = sorted(bvh.triangleOrder);
    for (int i = 0; i < n; ++i) REQUIRE(order[i] == i);  // a permutation
    REQUIRE(!bvh.nodes.empty());
    REQUIRE(bvh.nodes[0].first == 0);
    REQUIRE(bvh.nodes[0].count == n);
    REQUIRE(bvh.nodes[0].parent == -1);
    REQUIRE(bvh.nodes[0].depth == 0);
    const size_t boxes = bvh.kind == BvKind::Aabb ? bvh.aabbs.size() : bvh.obbs.size();
    REQUIRE(boxes == bvh.nodes.size());
    for (int i = 0; i < static_cast<int>(bvh.nodes.size()); ++i) {
        const BvhNode& nd = bvh.nodes[i];
        REQUIRE(nd.count >= 1);
        if (nd.isLeaf()) {
            REQUIRE(nd.count <= maxLeaf);
            REQUIRE(nd.right == -1);
        } else {
            REQUIRE(nd.right == nd.left + 1);
            REQUIRE(nd.left > i);
            const BvhNode& l = bvh.nodes[nd.left];
            const BvhNode& r = bvh.nodes[nd.right];
            REQUIRE(l.parent == i);
            REQUIRE(r.parent == i);
            REQUIRE(l.depth == nd.depth + 1);
            REQUIRE(l.first == nd.first);
            REQUIRE(r.first == l.first + l.count);
            REQUIRE(l.count + r.count == nd.count);
        }
        for (int k = nd.first; k < nd.first + nd.count; ++k) {
            const Triangle t = mesh.triangle(bvh.triangleOrder[k]);
            INFO("node ", i, " triangle ", bvh.triangleOrder[k]);
            REQUIRE(boxContains(bvh, i, t.a));
            REQUIRE(boxContains(bvh, i, t.b));
            REQUIRE(boxContains(bvh, i, t.c));
        }
    }
}

std::vector<TriangleMesh> testMeshes() {
    std::vector<TriangleMesh> meshes;
    meshes.push_back(torusMesh(1.0, 0.3, 24, 10));
    meshes.push_back(noisyBlobMesh(1.0, 0.3, 14, 9, 7));
    meshes.push_back(randomSoupMesh(200, 1.0, 0.4, 11));
    TriangleMesh flat = randomSoupMesh(150, 1.0, 0.5, 12);  // all in the plane z = 0.25
    for (Vec3& v : flat.vertices) v.z() = 0.25;
    meshes.push_back(flat);
    meshes.push_back(transformed(torusMesh(1.0, 0.3, 16, 8), 1e-3, Vec3(1e4, -2e4, 3e4)));
    meshes.push_back(transformed(noisyBlobMesh(1.0, 0.4, 12, 8, 3), 1e3, Vec3(-1e6, 1e6, 5e5)));
    return meshes;
}

/// Rays for a mesh whose vertices lie within radius R of c (world frame): random, axis
/// parallel (zero direction components) and aimed exactly at vertices.
std::vector<Ray> testRays(std::mt19937_64& rng, const TriangleMesh& mesh, const Transform& pose, int count) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : mesh.vertices) c += pose.apply(v);
    c /= static_cast<double>(mesh.vertices.size());
    double R = 0;
    for (const Vec3& v : mesh.vertices) R = std::max(R, (pose.apply(v) - c).norm());
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const Vec3 o = c + 2.0 * R * randomUnit(rng);
        Vec3 target = c + 0.6 * R * randomUnit(rng);
        if (i % 4 == 1) target = pose.apply(mesh.vertices[rng() % mesh.vertices.size()]);  // through a vertex
        Vec3 d = target - o;
        if (i % 4 == 2) d = Vec3::Unit(static_cast<int>(rng() % 3)) * (rng() % 2 ? 1.0 : -1.0) * R;  // axis parallel
        rays.push_back(Ray{o, d});
    }
    rays.push_back(Ray{c, Vec3(1, 0, 0)});  // from inside
    return rays;
}

}  // namespace

TEST_SUITE("bvh") {
    TEST_CASE("generators: counts, closedness of the torus, orientation, validity") {
        const TriangleMesh torus = torusMesh(2.0, 0.5, 12, 6);
        CHECK(torus.triangleCount() == 2 * 12 * 6);
        CHECK(torus.vertices.size() == 12u * 6u);
        const TriangleMesh ell = ellipsoidMesh(Vec3(1, 2, 3), 10, 5);
        CHECK(ell.triangleCount() == 2 * 10 * 4);
        const TriangleMesh blob = noisyBlobMesh(1.0, 0.3, 10, 6, 5);
        const TriangleMesh blob2 = noisyBlobMesh(1.0, 0.3, 10, 6, 5);
        CHECK(blob.vertices == blob2.vertices);  // deterministic
        for (const TriangleMesh* m : {&torus, &ell, &blob}) {
            CHECK(validateMesh(*m).status == MeshStatus::Valid);
            // Closed and outward: every directed edge appears once and its reverse once; the
            // divergence theorem gives a positive volume.
            std::set<std::pair<int, int>> edges;
            long double volume = 0;
            for (const auto& t : m->triangles) {
                for (int k = 0; k < 3; ++k) CHECK(edges.insert({t[k], t[(k + 1) % 3]}).second);
                const Triangle tri = m->triangle(static_cast<int>(&t - m->triangles.data()));
                volume += tri.a.dot(tri.b.cross(tri.c)) / 6.0;
            }
            for (const auto& e : edges) CHECK(edges.count({e.second, e.first}) == 1);
            CHECK(volume > 0);
        }
        // Torus volume 2 pi² R r² (polygonal: a bit less).
        long double v = 0;
        const TriangleMesh fine = torusMesh(2.0, 0.5, 200, 100);
        for (int i = 0; i < fine.triangleCount(); ++i) {
            const Triangle t = fine.triangle(i);
            v += t.a.dot(t.b.cross(t.c)) / 6.0;
        }
        CHECK(double(v) == doctest::Approx(2 * M_PI * M_PI * 2.0 * 0.25).epsilon(2e-3));
        const TriangleMesh soup = randomSoupMesh(50, 1.0, 0.2, 9);
        CHECK(soup.triangleCount() == 50);
        for (const Vec3& p : soup.vertices) CHECK(p.cwiseAbs().maxCoeff() <= 1.2);
    }

    TEST_CASE("validation: out-of-range index and NaN vertex give clear statuses") {
        TriangleMesh m = torusMesh(1.0, 0.3, 6, 4);
        CHECK(validateMesh(m).status == MeshStatus::Valid);
        TriangleMesh bad = m;
        bad.triangles[5][1] = static_cast<int>(bad.vertices.size());
        MeshValidation v = validateMesh(bad);
        CHECK(v.status == MeshStatus::IndexOutOfRange);
        CHECK(v.triangle == 5);
        bad = m;
        bad.triangles[3][2] = -1;
        CHECK(validateMesh(bad).status == MeshStatus::IndexOutOfRange);
        bad = m;
        bad.vertices[bad.triangles[7][0]].y() = std::numeric_limits<double>::quiet_NaN();
        v = validateMesh(bad);
        CHECK(v.status == MeshStatus::NonFiniteVertex);
        CHECK(v.vertex == bad.triangles[7][0]);
        CHECK(std::string(nameOf(v.status)) == "non-finite vertex");
        for (const Combo& c : allCombos()) {
            const Bvh t = build(bad, c);
            CHECK(t.status == BvhStatus::InvalidMesh);
            CHECK(t.empty());
            CHECK(queryBvhRay(t, bad, Transform{}, Ray{Vec3::Zero(), Vec3(1, 0, 0)}).hits.empty());
        }
        bad = m;
        bad.vertices.push_back(Vec3::Constant(std::numeric_limits<double>::infinity()));  // unused: fine
        CHECK(validateMesh(bad).status == MeshStatus::Valid);
        TriangleMesh zero = m;
        zero.triangles.push_back({0, 0, 1});
        CHECK(validateMesh(zero).zeroAreaTriangles == 1);
    }

    TEST_CASE("structure and containment: every build x BV type x mesh, leaf sizes 1 and 3") {
        for (const TriangleMesh& mesh : testMeshes())
            for (const Combo& c : allCombos())
                for (int leaf : {1, 3}) {
                    INFO(c.name, " leaf ", leaf, " triangles ", mesh.triangleCount());
                    BvhBuildTrace trace;
                    BvhBuildOptions o;
                    o.method = c.method;
                    o.bvKind = c.kind;
                    o.maxLeafTriangles = leaf;
                    const Bvh bvh = buildBvh(mesh, o, &trace);
                    checkStructure(bvh, mesh, leaf);
                    // The trace has each node once, with its box and range.
                    REQUIRE(trace.steps.size() == bvh.nodes.size());
                    std::vector<int> seen(bvh.nodes.size(), 0);
                    for (const BvhBuildStep& s : trace.steps) {
                        ++seen[s.node];
                        CHECK(s.first == bvh.nodes[s.node].first);
                        CHECK(s.count == bvh.nodes[s.node].count);
                        CHECK(s.depth == bvh.nodes[s.node].depth);
                        CHECK(s.box.center == bvh.box(s.node).center);
                        if (c.method != BvhBuildMethod::BottomUp)
                            CHECK((s.splitAxis >= 0) == !bvh.nodes[s.node].isLeaf());
                    }
                    for (int x : seen) CHECK(x == 1);
                    // A balanced-enough tree: median splits give height ceil(log2(n / leaf)) or so.
                    if (c.method == BvhBuildMethod::TopDownMedian)
                        CHECK(bvh.height() <= static_cast<int>(std::ceil(std::log2(mesh.triangleCount()))) + 1);
                }
    }

    TEST_CASE("coordinates near the top of double range: every build method gives a valid tree") {
        // Regression (found by the scene fuzzer): a bvh scene torus of major radius 1.1e308 crashed the
        // bottom-up build. Box surface areas overflowed to inf (and 0 x inf extents to NaN), so no
        // cluster had a nearest neighbour (index -1); the binned SAH likewise found no finite split.
        for (double R : {1e154, 1e200, 1.1e308}) {
            for (double r : {0.35, 1e-300, 0.35 * R}) {
                const TriangleMesh mesh = torusMesh(R, r, 12, 6);
                REQUIRE(validateMesh(mesh).status == MeshStatus::Valid);
                for (const Combo& c : allCombos()) {
                    INFO(c.name, " R ", R, " r ", r);
                    BvhBuildOptions o;
                    o.method = c.method;
                    o.bvKind = c.kind;
                    o.maxLeafTriangles = 2;
                    const Bvh bvh = buildBvh(mesh, o);
                    REQUIRE(bvh.status == BvhStatus::Ok);
                    checkStructure(bvh, mesh, 2);
                }
            }
        }
    }

    TEST_CASE("ray queries equal a loop over every world triangle (hits and first t)") {
        std::mt19937_64 rng(101);
        for (const TriangleMesh& mesh : testMeshes()) {
            std::vector<Bvh> trees;
            for (const Combo& c : allCombos()) trees.push_back(build(mesh, c, 2));
            for (int p = 0; p < 3; ++p) {
                Transform pose;
                pose.rotation = randomRotation(rng);
                pose.position = p == 0 ? Vec3::Zero() : Vec3(uniform(rng, -1e4, 1e4), uniform(rng, -1e4, 1e4), 3e3);
                if (p == 0) pose.rotation = Quat::Identity();
                for (const Ray& ray : testRays(rng, mesh, pose, 40)) {
                    std::vector<int> expect;
                    double firstT = std::numeric_limits<double>::infinity();
                    for (int i = 0; i < mesh.triangleCount(); ++i) {
                        const RayTriangleHit h = intersectRayTriangle(ray, mesh.triangle(i, pose));
                        if (!h.hit) continue;
                        expect.push_back(i);
                        firstT = std::min(firstT, h.t);
                    }
                    for (size_t k = 0; k < trees.size(); ++k) {
                        INFO(allCombos()[k].name);
                        const BvhQueryResult r = queryBvhRay(trees[k], mesh, pose, ray);
                        REQUIRE(sorted(r.hits) == expect);
                        if (!expect.empty()) CHECK(r.firstT == firstT);
                        CHECK((r.firstTriangle >= 0) == !expect.empty());
                        CHECK(r.stats.triangleTests == static_cast<long long>(r.candidates.size()));
                    }
                }
            }
        }
    }

    TEST_CASE("triangle and box queries equal a loop over every world triangle") {
        std::mt19937_64 rng(202);
        for (const TriangleMesh& mesh : testMeshes()) {
            std::vector<Bvh> trees;
            for (const Combo& c : allCombos()) trees.push_back(build(mesh, c));
            Transform pose;
            pose.rotation = randomRotation(rng);
            pose.position = Vec3(uniform(rng, -10, 10), 5, -3);
            const double size = (mesh.vertices[0] - mesh.vertices[mesh.vertices.size() / 2]).norm() + 1e-300;
            for (int q = 0; q < 30; ++q) {
                // The mesh's own triangles touch their neighbours exactly; random ones cut through.
                Triangle tri;
                if (q % 2 == 0) {
                    tri = mesh.triangle(static_cast<int>(rng() % mesh.triangles.size()), pose);
                } else {
                    const Vec3 c = pose.apply(mesh.vertices[rng() % mesh.vertices.size()]);
                    tri = Triangle{c + 0.3 * size * randomUnit(rng), c + 0.3 * size * randomUnit(rng),
                                   c + 0.3 * size * randomUnit(rng)};
                }
                std::vector<int> expect;
                for (int i = 0; i < mesh.triangleCount(); ++i)
                    if (intersectTriangleTriangle(mesh.triangle(i, pose), tri).hit) expect.push_back(i);
                if (q % 2 == 0) CHECK(expect.size() >= 1);
                const Obb box = Obb::fromRotation(pose.apply(mesh.vertices[rng() % mesh.vertices.size()]),
                                                  Vec3(0.2, 0.1, 0.05) * size, randomRotation(rng));
                std::vector<int> expectBox;
                for (int i = 0; i < mesh.triangleCount(); ++i)
                    if (testTriangleObb(mesh.triangle(i, pose), box)) expectBox.push_back(i);
                for (size_t k = 0; k < trees.size(); ++k) {
                    INFO(allCombos()[k].name, " query ", q);
                    REQUIRE(sorted(queryBvhTriangle(trees[k], mesh, pose, tri).hits) == expect);
                    const BvhQueryResult rb = queryBvhBox(trees[k], mesh, pose, box);
                    REQUIRE(sorted(rb.hits) == expectBox);
                }
            }
        }
    }

    TEST_CASE("testTriangleObb agrees with testTriangleAabb for axis-aligned boxes") {
        std::mt19937_64 rng(5);
        for (int i = 0; i < 2000; ++i) {
            const Triangle t{Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2)),
                             Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2)),
                             Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2))};
            // Dyadic box: centre and extents exact, identity axes: the same test after a shift.
            const Obb box{Vec3(0.5, -0.25, 0.125), Vec3(0.5, 0.75, 1.0), Mat3::Identity()};
            const Aabb aabb{box.center - box.halfExtents, box.center + box.halfExtents};
            CHECK(testTriangleObb(t, box) == testTriangleAabb(t, aabb).hit);
        }
    }

    TEST_CASE("traversal traces: one step per BV test plus one per triangle test") {
        const TriangleMesh mesh = torusMesh(1.0, 0.3, 20, 10);
        for (const Combo& c : allCombos()) {
            const Bvh bvh = build(mesh, c);
            BvhTraversalTrace trace;
            const BvhQueryResult r =
                queryBvhRay(bvh, mesh, Transform{}, Ray{Vec3(-3, 0.1, 0.05), Vec3(1, 0, 0)}, &trace);
            long long bv = 0, tri = 0;
            for (const BvhTraversalStep& s : trace.steps) {
                if (s.action == BvhTraversalAction::TriangleTest) ++tri;
                else ++bv;
                if (s.action == BvhTraversalAction::Prune) CHECK(!s.overlap);
                if (s.action == BvhTraversalAction::DescendA || s.action == BvhTraversalAction::LeafTest)
                    CHECK(s.overlap);
            }
            CHECK(bv == r.stats.bvTests);
            CHECK(tri == r.stats.triangleTests);
            CHECK(r.hits.size() == 4u);  // the ray crosses the tube twice on each side
            CHECK(trace.steps.front().nodeA == 0);
        }
    }

    TEST_CASE("refit after deformation: containment holds, queries equal brute force") {
        const TriangleMesh mesh = torusMesh(1.0, 0.3, 24, 10);
        TriangleMesh bent = mesh;
        for (Vec3& v : bent.vertices) v += Vec3(0.1 * std::sin(3 * v.y()), 0.0, 0.4 * std::sin(2 * v.x()));
        std::mt19937_64 rng(303);
        for (const Combo& c : allCombos()) {
            INFO(c.name);
            Bvh bvh = build(mesh, c);
            REQUIRE(refitBvh(bvh, bent) == BvhStatus::Ok);
            checkStructure(bvh, bent, 1);
            for (const Ray& ray : testRays(rng, bent, Transform{}, 30)) {
                std::vector<int> expect;
                for (int i = 0; i < bent.triangleCount(); ++i)
                    if (intersectRayTriangle(ray, bent.triangle(i, Transform{})).hit) expect.push_back(i);
                REQUIRE(sorted(queryBvhRay(bvh, bent, Transform{}, ray).hits) == expect);
            }
            // Refit back to the original: the boxes contain the original triangles again.
            REQUIRE(refitBvh(bvh, mesh) == BvhStatus::Ok);
            checkStructure(bvh, mesh, 1);
            // Wrong topology / invalid mesh: status, tree unchanged.
            TriangleMesh smaller = mesh;
            smaller.triangles.pop_back();
            CHECK(refitBvh(bvh, smaller) == BvhStatus::TopologyMismatch);
            TriangleMesh nan = mesh;
            nan.vertices[0].x() = std::numeric_limits<double>::quiet_NaN();
            CHECK(refitBvh(bvh, nan) == BvhStatus::InvalidMesh);
            checkStructure(bvh, mesh, 1);
        }
    }

    TEST_CASE("degenerate meshes: empty, one triangle, zero area, duplicates, coplanar, bottom-up limit") {
        TriangleMesh empty;
        for (const Combo& c : allCombos()) {
            const Bvh t = build(empty, c);
            CHECK(t.status == BvhStatus::Ok);
            CHECK(t.empty());
            CHECK(t.height() == -1);
            CHECK(queryBvhRay(t, empty, Transform{}, Ray{Vec3::Zero(), Vec3(1, 0, 0)}).candidates.empty());
        }
        TriangleMesh one;
        one.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        one.triangles = {{0, 1, 2}};
        // Zero area (a point and a segment), duplicated triangles, all coplanar and identical centroids.
        TriangleMesh degenerate;
        degenerate.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
        degenerate.triangles = {{0, 0, 0}, {0, 1, 3}, {0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {1, 1, 1}, {0, 1, 2}};
        TriangleMesh same;  // 64 copies of one triangle: every centroid equal, every split a tie
        same.vertices = one.vertices;
        for (int i = 0; i < 64; ++i) same.triangles.push_back({0, 1, 2});
        TriangleMesh points;  // 40 zero-area triangles at one point: boxes of zero size
        points.vertices = {Vec3(3, 3, 3)};
        for (int i = 0; i < 40; ++i) points.triangles.push_back({0, 0, 0});
        for (const TriangleMesh* m : {&one, &degenerate, &same, &points})
            for (const Combo& c : allCombos())
                for (int leaf : {1, 2}) {
                    INFO(c.name, " triangles ", m->triangleCount());
                    const Bvh t = build(*m, c, leaf);
                    checkStructure(t, *m, leaf);
                    const Ray ray{Vec3(0.25, 0.25, 1), Vec3(0, 0, -1)};
                    std::vector<int> expect;
                    for (int i = 0; i < m->triangleCount(); ++i)
                        if (intersectRayTriangle(ray, m->triangle(i)).hit) expect.push_back(i);
                    CHECK(sorted(queryBvhRay(t, *m, Transform{}, ray).hits) == expect);
                }
        // Bottom-up refuses meshes above its limit with a status, at once.
        BvhBuildOptions o;
        o.method = BvhBuildMethod::BottomUp;
        o.bottomUpMaxTriangles = 100;
        const Bvh big = buildBvh(randomSoupMesh(101, 1, 0.1, 1), o);
        CHECK(big.status == BvhStatus::TooManyTrianglesForBottomUp);
        CHECK(big.empty());
        CHECK(std::string(nameOf(big.status)) == "too many triangles for bottom-up");
    }

}  // TEST_SUITE
