// golden/bvh/sah_split run numerically: the root's SAH candidates recomputed from the mesh without
// the builder: centroids binned uniformly over their box on each axis, each bin plane's left and
// right triangle counts and the surface areas of their triangles' boxes, relative to the root box's,
// the cost (A_L N_L + A_R N_R) / A, the lowest chosen; the median split's cost from sorted
// centroids. Every traced node: counts add up to the node's and its cost is its candidates' minimum.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "app/scene/mesh_scene.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace bvh_sah_test {

double area(const Vec3& lo, const Vec3& hi) {
    const Vec3 d = hi - lo;
    return 2 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

}  // namespace bvh_sah_test

TEST_CASE("BVH SAH figure: the root's bin costs and the median split's recomputed from the mesh") {
    using namespace bvh_sah_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/bvh/sah_split.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const Json meshJson = s["meshes"][0]["blob"];
    const JsonNode node(meshJson, "$.meshes[0].blob", file);
    ObjectReader r(node);
    TriangleMesh mesh;
    REQUIRE(readMeshGenerator("blob", node, r, MeshTessellation{24, 12, 16, 8}, mesh));
    REQUIRE(mesh.triangleCount() == t["triangles"].get<int>());
    const int n = mesh.triangleCount(), bins = s["sah_bins"].get<int>();
    std::vector<Vec3> cen;
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY), clo = lo, chi = hi;
    for (int i = 0; i < n; ++i) {
        const Triangle tr = mesh.triangle(i);
        cen.push_back((tr.a + tr.b + tr.c) / 3.0);
        clo = clo.cwiseMin(cen.back()), chi = chi.cwiseMax(cen.back());
        for (const Vec3& v : {tr.a, tr.b, tr.c}) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    }
    const double rootArea = area(lo, hi);
    const Json& root = t["nodes"][0];
    REQUIRE(root["node"].get<int>() == 0);
    std::size_t k = 0;
    double best = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
        const double extent = chi[axis] - clo[axis];
        for (int split = 0; split + 1 < bins; ++split) {
            int nl = 0, nr = 0;
            Vec3 llo = Vec3::Constant(INFINITY), lhi = -llo, rlo = llo, rhi = -llo;
            for (int i = 0; i < n; ++i) {
                const int b = std::clamp(int((cen[i][axis] - clo[axis]) / extent * bins), 0, bins - 1);
                const Triangle tr = mesh.triangle(i);
                for (const Vec3& v : {tr.a, tr.b, tr.c})
                    if (b <= split) llo = llo.cwiseMin(v), lhi = lhi.cwiseMax(v);
                    else rlo = rlo.cwiseMin(v), rhi = rhi.cwiseMax(v);
                (b <= split ? nl : nr) += 1;
            }
            if (nl == 0 || nr == 0) continue;
            REQUIRE(k < root["candidates"].size());
            const Json& c = root["candidates"][k++];
            CAPTURE(axis);
            CAPTURE(split);
            CHECK(c["axis"].get<int>() == axis);
            CHECK(c["position"].get<double>() == doctest::Approx(clo[axis] + extent * (split + 1) / bins).epsilon(1e-12));
            CHECK(c["left_count"].get<int>() == nl);
            CHECK(c["right_count"].get<int>() == nr);
            const double al = area(llo, lhi) / rootArea, ar = area(rlo, rhi) / rootArea;
            CHECK(c["left_area"].get<double>() == doctest::Approx(al).epsilon(1e-12));
            CHECK(c["right_area"].get<double>() == doctest::Approx(ar).epsilon(1e-12));
            CHECK(c["cost"].get<double>() == doctest::Approx(al * nl + ar * nr).epsilon(1e-12));
            best = std::min(best, al * nl + ar * nr);
        }
    }
    CHECK(k == root["candidates"].size());
    CHECK(root["cost"].get<double>() == doctest::Approx(best).epsilon(1e-12));
    // The median split on the centroids' longest axis: sorted, the first n / 2 to the left.
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    CHECK(root["median_axis"].get<int>() == axis);
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return cen[a][axis] < cen[b][axis]; });
    Vec3 llo = Vec3::Constant(INFINITY), lhi = -llo, rlo = llo, rhi = -llo;
    for (int j = 0; j < n; ++j) {
        const Triangle tr = mesh.triangle(order[j]);
        for (const Vec3& v : {tr.a, tr.b, tr.c})
            if (j < n / 2) llo = llo.cwiseMin(v), lhi = lhi.cwiseMax(v);
            else rlo = rlo.cwiseMin(v), rhi = rhi.cwiseMax(v);
    }
    CHECK(root["median_cost"].get<double>() ==
          doctest::Approx((area(llo, lhi) * (n / 2) + area(rlo, rhi) * (n - n / 2)) / rootArea).epsilon(1e-9));
    for (const Json& nd : t["nodes"]) {
        double lowest = INFINITY;
        for (const Json& c : nd["candidates"]) {
            CHECK(c["left_count"].get<int>() + c["right_count"].get<int>() == nd["count"].get<int>());
            lowest = std::min(lowest, c["cost"].get<double>());
        }
        CHECK(nd["cost"].get<double>() == doctest::Approx(lowest).epsilon(1e-12));
    }
}
