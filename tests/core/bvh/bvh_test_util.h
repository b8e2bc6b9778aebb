// Shared helpers of the BVH and mesh-collision tests: brute-force oracles over the world
// triangles (every pair / every triangle, no hierarchy), random poses, every build combination.
#pragma once

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "core/bvh/bvh.h"
#include "core/geometry/triangle_mesh.h"
#include "core/overlap/intersect_ray.h"
#include "core/overlap/triangle_triangle.h"

namespace bvhtest {

using namespace cdlab;

using PairList = std::vector<std::pair<int, int>>;

/// Every pair of world triangles, tested exactly (the O(n m) oracle).
inline PairList brutePairs(const TriangleMesh& a, const Transform& pa, const TriangleMesh& b, const Transform& pb) {
    PairList out;
    std::vector<Triangle> wb;
    for (int j = 0; j < b.triangleCount(); ++j) wb.push_back(b.triangle(j, pb));
    for (int i = 0; i < a.triangleCount(); ++i) {
        const Triangle wa = a.triangle(i, pa);
        for (int j = 0; j < b.triangleCount(); ++j)
            if (intersectTriangleTriangle(wa, wb[j]).hit) out.emplace_back(i, j);
    }
    return out;
}

inline std::vector<int> sorted(std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
}

struct Combo {
    BvhBuildMethod method;
    BvKind kind;
    const char* name;
};

inline std::vector<Combo> allCombos() {
    return {{BvhBuildMethod::TopDownMedian, BvKind::Aabb, "median/AABB"},
            {BvhBuildMethod::TopDownMedian, BvKind::Obb, "median/OBB"},
            {BvhBuildMethod::TopDownSah, BvKind::Aabb, "SAH/AABB"},
            {BvhBuildMethod::TopDownSah, BvKind::Obb, "SAH/OBB"},
            {BvhBuildMethod::BottomUp, BvKind::Aabb, "bottom-up/AABB"},
            {BvhBuildMethod::BottomUp, BvKind::Obb, "bottom-up/OBB"}};
}

inline Bvh build(const TriangleMesh& mesh, const Combo& c, int leaf = 1) {
    BvhBuildOptions o;
    o.method = c.method;
    o.bvKind = c.kind;
    o.maxLeafTriangles = leaf;
    return buildBvh(mesh, o);
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

inline Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    Vec3 v(g(rng), g(rng), g(rng));
    return v.normalized();
}

inline Quat randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    Quat q(g(rng), g(rng), g(rng), g(rng));
    q.normalize();
    return q;
}

/// Scales every vertex by s and adds offset (body frame).
inline TriangleMesh transformed(TriangleMesh m, double s, const Vec3& offset) {
    for (Vec3& v : m.vertices) v = s * v + offset;
    return m;
}

}  // namespace bvhtest
