// Bodies shared by drop and polyhedron_plane: any convex polytope the user gives (its hull,
// recentred at its centre of mass), the presets, and one-line errors for a flat polytope and for
// a pose written inside the body; a user's wedge dropped runs with the wedge's closed-form volume.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "core/geometry/mass_properties.h"
#include "app/catalog/catalog.h"
#include "app/scene/body_scene.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

ConvexPolyhedron body(const Json& j) {
    std::string name;
    return readConvexBody(JsonNode(j, "$.body", "test.json"), name);
}

std::string error(const Json& j) {
    try {
        body(j);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const Json kWedge = {{"polytope", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 0.6, 0}, {0, 0, 0.4}, {1, 0, 0.4}, {0, 0.6, 0.4}}}}}};

}  // namespace

TEST_CASE("body: a user's polytope is its hull, recentred at its centre of mass") {
    // An interior point is dropped by the hull.
    Json withInner = kWedge;
    withInner["polytope"]["vertices"].push_back({0.2, 0.1, 0.2});
    const ConvexPolyhedron w = body(withInner);
    CHECK(w.vertexCount() == 6);
    CHECK(w.faceCount() == 5);
    const MassProperties mp = computeMassProperties(w);
    REQUIRE(mp.ok());
    CHECK(mp.volume == doctest::Approx(0.5 * 1.0 * 0.6 * 0.4).epsilon(1e-12));  // triangle area x height
    CHECK(mp.centerOfMass.norm() < 1e-12);
    CHECK(body({{"prism", {{"sides", 6}, {"radius", 0.5}, {"half_height", 0.2}}}}).vertexCount() == 12);
    CHECK(body({{"box", {{"half_extents", {1, 2, 3}}}}}).vertexCount() == 8);
}

TEST_CASE("body: one vocabulary: radius or circumradius, sides or n, polytope or hull") {
    CHECK(body({{"icosahedron", {{"radius", 0.5}}}}).vertexCount() == 12);
    CHECK(body({{"icosahedron", {{"circumradius", 0.5}}}}).vertexCount() == 12);
    CHECK(body({{"dodecahedron", {{"radius", 0.5}}}}).vertexCount() == 20);
    CHECK(body({{"prism", {{"n", 5}, {"radius", 0.5}, {"half_height", 0.2}}}}).vertexCount() == 10);
    Json hull = kWedge;
    hull["hull"] = hull["polytope"];
    hull.erase("polytope");
    CHECK(body(hull).vertexCount() == 6);
    CHECK(error({{"tetrahedron", {{"radius", 0.5}, {"circumradius", 0.5}}}}).find("not both") != std::string::npos);
    CHECK(error({{"tetrahedron", Json::object()}}).find("missing \"circumradius\" (or its synonym \"radius\")") !=
          std::string::npos);
}

TEST_CASE("body: errors name the path and say where a pose belongs") {
    CHECK(error({{"polytope", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}}}}).find("span no volume") !=
          std::string::npos);
    Json posed = kWedge;
    posed["polytope"]["position"] = {0, 0, 1};
    const std::string e = error(posed);
    CHECK(e.find("$.body.polytope.position") != std::string::npos);
    CHECK(e.find("beside \"body\"") != std::string::npos);
    CHECK(error({{"cylinder", {{"radius", 1}}}}).find("expected box, tetrahedron, octahedron, icosahedron, dodecahedron, prism or polytope") !=
          std::string::npos);
}

TEST_CASE("body: a user's wedge dropped and a polytope against the plane run") {
    Json drop = {{"demo", "drop"}, {"title", "wedge"}, {"caption", "a wedge"}, {"body", kWedge},
                 {"position", {0, 0, 0.9}}, {"simulation", {{"duration", 0.5}}}};
    DemoOutput out = loadSceneText(drop.dump(), "wedge.json")->run(RunContext{});
    CHECK(out.trace["mass_properties"]["volume"].get<double>() == doctest::Approx(0.12).epsilon(1e-12));
    Json plane = {{"demo", "polyhedron_plane"}, {"title", "wedge"}, {"caption", "a wedge"}, {"body", kWedge},
                  {"poses", {{{"label", "resting"}, {"position", {0, 0, 0.1}}}}}};
    CHECK_NOTHROW(loadSceneText(plane.dump(), "wedge_plane.json")->run(RunContext{}));
}

TEST_CASE("body: rest_height rests a pose's lowest vertex that high above the plane, the recentring undone") {
    // The wedge's base is at z = 0 in its own file, but it is recentred at its centre of mass: at
    // position (0, 0, 0) it sinks. rest_height puts its lowest vertex at the height asked, on a
    // tilted plane too (along that plane's normal), whatever the pose's rotation.
    const Json tilted = {{"normal", {0, 0.6, 0.8}}, {"offset", 0.5}};
    for (const Json& plane : {Json(), tilted}) {
        Json scene = {{"demo", "polyhedron_plane"}, {"title", "wedge"}, {"body", kWedge},
                      {"poses", {{{"label", "at 0"}, {"position", {0, 0, 0}}},
                                 {{"label", "resting"}, {"position", {0, 0, 0}}, {"rest_height", 0}},
                                 {{"label", "sunk"}, {"position", {0.3, 0, 5}}, {"rest_height", -0.05}},
                                 {{"label", "above"}, {"rotation", {0.9, 0.3, 0.2, 0.1}}, {"rest_height", 0.25}}}}};
        if (!plane.is_null()) scene["plane"] = plane;
        const DemoOutput out = loadSceneText(scene.dump(), "wedge_rest.json")->run(RunContext{});
        const Json& poses = out.trace["frames"];
        REQUIRE(poses.size() == 4);
        const auto lowest = [&](int i) {
            const Json& d = poses[i]["vertex_signed_distances"];
            return *std::min_element(d.begin(), d.end());
        };
        if (plane.is_null()) CHECK(lowest(0).get<double>() < -0.1);  // recentred: sunk at position 0
        CHECK(lowest(1).get<double>() == doctest::Approx(0).epsilon(1e-12));
        CHECK(lowest(2).get<double>() == doctest::Approx(-0.05).epsilon(1e-12));
        CHECK(poses[2]["depth"].get<double>() == doctest::Approx(0.05).epsilon(1e-12));
        CHECK(lowest(3).get<double>() == doctest::Approx(0.25).epsilon(1e-12));
        CHECK(poses[3]["status"] == "Separated");
    }
}
