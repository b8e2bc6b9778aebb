// The nonconvex demo's traces checked against the bodies themselves: the verdict against sampling —
// a point inside both meshes by their generalized winding numbers (core/geometry/solid_mesh.h, no
// pieces, no GJK) — and the hierarchy's skipping against its own rules: a culled pair's boxes are
// apart (it cannot touch), a pruned pair's box distance is no less than the answer, the deepest pair
// is the largest tested depth. Reader errors name the JSON path.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/geometry/solid_mesh.h"
#include "core/geometry/triangle_mesh.h"
#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

Json runScene(const std::string& name) {
    return loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/nonconvex/" + name + ".json")->run(RunContext{}).trace;
}

/// The scene's body as a world mesh (the prism outline extruded, then posed).
TriangleMesh bodyMesh(const Json& body) {
    std::vector<Vec2> outline;
    for (const Json& p : body["prism"]["outline"]) outline.emplace_back(p[0].get<double>(), p[1].get<double>());
    TriangleMesh m = prismMesh(outline, body["prism"]["height"].get<double>());
    Transform pose;
    if (body.contains("position")) pose.position = Vec3(body["position"][0], body["position"][1], body["position"][2]);
    if (body.contains("rotation"))
        pose.rotation = Quat(body["rotation"][0], body["rotation"][1], body["rotation"][2], body["rotation"][3]).normalized();
    for (Vec3& v : m.vertices) v = pose.apply(v);
    return m;
}

/// Some grid point lies inside both meshes (winding number ~1 in each).
bool commonPoint(const TriangleMesh& a, const TriangleMesh& b) {
    Eigen::AlignedBox3d box;
    for (const Vec3& v : a.vertices) box.extend(v);
    const int n = 24;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            for (int k = 0; k <= n; ++k) {
                const Vec3 p = box.min() + box.sizes().cwiseProduct(Vec3(i, j, k) / double(n));
                if (windingNumber(a, p) > 0.5 && windingNumber(b, p) > 0.5) return true;
            }
    return false;
}

Json sceneJson(const std::string& name) {
    return readJsonFile(std::string(CDLAB_SOURCE_DIR) + "/golden/nonconvex/" + name + ".json");
}

std::string errorOf(const std::string& text) { return test::sceneTextError(text); }

}  // namespace

TEST_SUITE("nonconvex_demo") {
    TEST_CASE("the pairs: every tested answer, and nothing skipped that would change the result") {
        const Json u = runScene("u_and_l");
        CHECK(u["intersect"].get<bool>());
        CHECK(commonPoint(bodyMesh(sceneJson("u_and_l")["a"]), bodyMesh(sceneJson("u_and_l")["b"])));
        REQUIRE(u.contains("deepest"));
        // Culled pairs have boxes apart (so cannot touch); the deepest is the largest tested depth.
        double deepest = 0;
        for (const Json& p : u["pairs"]) {
            if (p["action"] == "tested" && p["intersect"].get<bool>()) deepest = std::max(deepest, p["depth"].get<double>());
            if (p["action"] != "tested") CHECK(p["box_distance"].get<double>() > 0);
        }
        CHECK(u["deepest"]["depth"].get<double>() == deepest);

        const Json apart = runScene("apart");
        CHECK_FALSE(apart["intersect"].get<bool>());
        CHECK_FALSE(commonPoint(bodyMesh(sceneJson("apart")["a"]), bodyMesh(sceneJson("apart")["b"])));
        REQUIRE(apart.contains("closest"));
        // Branch and bound: every pruned pair's box distance is at least the answer.
        const double best = apart["closest"]["distance"];
        int pruned = 0;
        for (const Json& p : apart["pairs"]) {
            if (p["action"] == "tested") CHECK(p["distance"].get<double>() >= best - 1e-12);
            else {
                ++pruned;
                CHECK(p["box_distance"].get<double>() >= best);
            }
        }
        CHECK(apart["tested"].get<int>() >= 1);
        CHECK(pruned + apart["tested"].get<int>() == int(apart["pairs"].size()));
    }

    TEST_CASE("bad bodies: one error naming the JSON path") {
        CHECK(errorOf(R"({"demo": "nonconvex", "a": {"prism": {"outline": [[0,0],[2,2],[2,0],[0,2]], "height": 1}},
                        "b": {"prism": {"outline": [[0,0],[1,0],[0,1]], "height": 1}}})")
                  .find("$.a.prism.outline") != std::string::npos);
        CHECK(errorOf(R"({"demo": "nonconvex", "a": {"mesh": {"vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
                        "triangles": [[0,1,2],[0,1,3],[0,2,3]]}}, "b": {"prism": {"outline": [[0,0],[1,0],[0,1]], "height": 1}}})")
                  .find("$.a.mesh.triangles") != std::string::npos);
        CHECK(errorOf(R"({"demo": "nonconvex", "a": {"prism": {"outline": [[0,0],[1,0],[0,1]], "height": 1}, "mesh": {}},
                        "b": {"prism": {"outline": [[0,0],[1,0],[0,1]], "height": 1}}})")
                  .find("exactly one of 'prism' or 'mesh'") != std::string::npos);
    }
}
