#include "app/scene/body_scene.h"

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/polyhedron_presets.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace {

constexpr const char* kBodies =
    "{\"box\": {...}}, {\"tetrahedron\": {...}}, {\"icosahedron\": {...}}, {\"prism\": {...}} or {\"polytope\": "
    "{\"vertices\": [...]}}";

// The convex hull of the user's points, moved so that its centre of mass is the origin.
ConvexPolyhedron userPolytope(const JsonNode& vn) {
    requireAtMost(vn, double(vn.size()), double(kMaxShapeVertices), "the number of vertices",
                  "a body is drawn and simulated vertex by vertex");
    std::vector<Vec3> v = sceneVec3List(vn, 0, kMaxShapeVertices);
    if (v.size() < 4) vn.fail("a polytope needs at least 4 vertices, got " + std::to_string(v.size()));
    HullResult hull = convexHull(v);
    if (!hull.ok()) vn.fail("the polytope's vertices span no volume (" + hull.message + ")");
    const MassProperties mp = computeMassProperties(hull.polyhedron);
    if (!mp.ok()) vn.fail("the polytope has no usable mass properties: " + mp.message);
    for (Vec3& p : v) p -= mp.centerOfMass;
    hull = convexHull(v);
    if (!hull.ok()) vn.fail("the polytope's vertices span no volume (" + hull.message + ")");
    return hull.polyhedron;
}

}  // namespace

std::optional<JsonNode> findEither(ObjectReader& r, const char* key, const char* synonym) {
    std::optional<JsonNode> a = r.find(key), b = r.find(synonym);
    if (a && b) b->fail(std::string("give either \"") + key + "\" or \"" + synonym + "\" (the same), not both");
    return a ? a : b;
}

JsonNode getEither(ObjectReader& r, const char* key, const char* synonym) {
    if (std::optional<JsonNode> n = findEither(r, key, synonym)) return *n;
    r.node().fail(std::string("missing \"") + key + "\" (or its synonym \"" + synonym + "\")");
}

ConvexPolyhedron readConvexBody(const JsonNode& b, std::string& name) {
    if (!b.isObject() || b.raw().size() != 1) b.fail(std::string("expected ") + kBodies);
    name = b.raw().begin().key();
    const JsonNode body(b.raw().begin().value(), b.path() + "." + name, b.source());
    if (body.isObject())
        for (const char* pose : {"position", "rotation"})
            if (body.raw().contains(pose))
                JsonNode(body.raw()[pose], body.path() + "." + pose, b.source())
                    .fail("a body's pose goes beside \"body\" in the scene, not inside it");
    ObjectReader r(body);
    ConvexPolyhedron m;
    if (name == "box") {
        m = presets::box(sceneSizes(r.get("half_extents")));
    } else if (name == "tetrahedron" || name == "octahedron" || name == "icosahedron" || name == "dodecahedron") {
        const double rad = sceneSize(getEither(r, "circumradius", "radius"));
        m = name == "tetrahedron"   ? presets::tetrahedron(rad)
            : name == "octahedron"  ? presets::octahedron(rad)
            : name == "icosahedron" ? presets::icosahedron(rad)
                                    : presets::dodecahedron(rad);
    } else if (name == "prism") {
        const int n = getEither(r, "sides", "n").asInt(3, 64);
        const double rad = sceneSize(r.get("radius")), hh = sceneSize(r.get("half_height"));
        m = presets::prism(n, rad, hh);
    } else if (name == "polytope" || name == "hull") {
        m = userPolytope(r.get("vertices"));
    } else {
        b.fail("unknown body '" + name +
               "' (expected box, tetrahedron, octahedron, icosahedron, dodecahedron, prism or polytope)");
    }
    r.finish();
    return m;
}

}  // namespace cdlab::demos
