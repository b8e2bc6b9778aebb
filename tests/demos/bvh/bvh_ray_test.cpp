// golden/bvh/ray_query run numerically: the walk checked without the tree's query code. Every box
// the walk pruned misses the ray and every box it entered meets it (a slab test written here on the
// node boxes of a tree built the same way); the hit triangles are exactly those a brute-force
// double-sided Möller–Trumbore test hits (none within 1e-9 of an edge in this scene), the first hit
// the smallest t; the counters are the walk's steps.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "app/scene/mesh_scene.h"
#include "core/bvh/bvh.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace bvh_ray_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

/// The ray o + t d, t >= 0, meets the closed box (slabs).
bool rayMeetsBox(const Vec3& o, const Vec3& d, const Obb& b) {
    double t0 = 0, t1 = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const Vec3 axis = b.axes.col(i);
        const double p = axis.dot(o - b.center), q = axis.dot(d);
        if (q == 0) {
            if (std::abs(p) > b.halfExtents[i]) return false;
            continue;
        }
        double a = (-b.halfExtents[i] - p) / q, c = (b.halfExtents[i] - p) / q;
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a), t1 = std::min(t1, c);
    }
    return t0 <= t1 * (1 + 1e-12) + 1e-12;
}

}  // namespace bvh_ray_test

TEST_CASE("BVH ray walk: pruned boxes miss, entered boxes meet, the hits are brute force's") {
    using namespace bvh_ray_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bvh/ray_query.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const Json torus = s["meshes"][0]["torus"];
    const JsonNode node(torus, "$.meshes[0].torus", file);
    ObjectReader r(node);
    TriangleMesh mesh;
    REQUIRE(readMeshGenerator("torus", node, r, MeshTessellation{24, 12, 16, 8}, mesh));
    const Vec3 o = vec(s["ray"]["origin"]), d = vec(s["ray"]["direction"]);
    BvhBuildOptions opt;
    opt.bvKind = BvKind::Aabb;
    opt.maxLeafTriangles = s["max_leaf_triangles"].get<int>();
    const Bvh tree = buildBvh(mesh, opt);
    REQUIRE(int(tree.nodes.size()) == t["tree"]["nodes"].get<int>());
    long long boxTests = 0, triangleTests = 0;
    for (const Json& st : t["steps"]) {
        const std::string action = st["action"].get<std::string>();
        if (action == "triangle test") {
            ++triangleTests;
            continue;
        }
        ++boxTests;
        CHECK(rayMeetsBox(o, d, tree.box(st["node"].get<int>())) == (action != "prune"));
    }
    CHECK(t["box_tests"].get<long long>() == boxTests);
    CHECK(t["triangle_tests"].get<long long>() == triangleTests);
    // Brute force, double-sided Möller–Trumbore.
    std::set<int> hits;
    double first = INFINITY;
    for (int i = 0; i < mesh.triangleCount(); ++i) {
        const Triangle tr = mesh.triangle(i);
        const Vec3 e1 = tr.b - tr.a, e2 = tr.c - tr.a, p = d.cross(e2);
        const double det = e1.dot(p);
        if (det == 0) continue;
        const Vec3 s0 = o - tr.a;
        const double u = s0.dot(p) / det;
        const Vec3 q = s0.cross(e1);
        const double v = d.dot(q) / det, tt = e2.dot(q) / det;
        const bool near = u >= -1e-9 && v >= -1e-9 && u + v <= 1 + 1e-9 && tt >= 0;
        if (near)  // the scene keeps away from edges, where two exact tests could disagree
            CHECK((std::abs(u) > 1e-9 && std::abs(v) > 1e-9 && std::abs(1 - u - v) > 1e-9));
        if (u >= 0 && v >= 0 && u + v <= 1 && tt >= 0) hits.insert(i), first = std::min(first, tt);
    }
    std::set<int> got;
    for (const Json& h : t["hits"]) got.insert(h.get<int>());
    CHECK(got == hits);
    CHECK(t["first_t"].get<double>() == doctest::Approx(first).epsilon(1e-12));
}
