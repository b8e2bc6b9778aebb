// The primitives demo's scene format and dispatch (docs/scenes.md, "primitives"). Shapes use the
// words of `cdlab query` (docs/query.md), with the scenes' coordinate limits.
//
// Scene keys (besides the common ones in scene.h):
//   "test": "raycast" | "sat" | "point_in_polygon" | "closest_features" | "sphere_overlap" | "moving_2d"
//   raycast:           "ray": {"origin": o, "direction": d} or "segment": [p, q]; "shape": S
//                      (sphere, aabb, obb / box, triangle)
//   sat:               "a": S, "b": S (box and box, segment and box, triangle and aabb; either order)
//   point_in_polygon:  "polygon": [[x, y], ...] (3 or more corners, any polygon), "queries": [[x, y], ...]
//   closest_features:  "a": S, "b": S (point, segment, triangle, tetrahedron)
//   sphere_overlap:    "a": {"sphere": ...}, "b": S (sphere, aabb, obb / box, triangle)
//   moving_2d:         "moving": S2, "still": S2, "velocity": [vx, vy] (S2: point, segment, rectangle,
//                      triangle, circle in the plane)
// Layers: "labels" (names and numbers on the picture), "numbers" (the block of numbers under it).
#include "demos/primitives/primitives_demo.h"

#include "demos/primitives/primitive_scenes.h"
#include "app/scene/body_scene.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace {

const std::vector<std::string> kLayers = {"labels", "numbers"};

/// The 8 corners of the box [-e, e] turned by R and moved to c.
std::vector<Vec3> boxCorners(const Vec3& c, const Vec3& e, const Mat3& R) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.push_back(c + R * Vec3(i & 1 ? e.x() : -e.x(), i & 2 ? e.y() : -e.y(), i & 4 ? e.z() : -e.z()));
    return corners;
}

PrimitiveShape readBody(const std::string& key, const JsonNode& body) {
    using K = PrimitiveShape::Kind;
    PrimitiveShape s;
    if (key == "point") {
        s.kind = K::Point;
        s.vertices = {sceneVec3(body)};
        return s;
    }
    if (key == "segment" || key == "triangle" || key == "tetrahedron") {
        const std::size_t n = key == "segment" ? 2 : key == "triangle" ? 3 : 4;
        if (!body.isArray() || body.size() != n)
            body.fail(std::string("expected ") + (n == 2 ? "[p, q]" : n == 3 ? "[a, b, c]" : "[a, b, c, d]") + ", got " +
                      JsonNode::describe(body.raw()));
        s.kind = n == 2 ? K::Segment : n == 3 ? K::Triangle : K::Tetrahedron;
        s.vertices = sceneVec3List(body, n, n);
        return s;
    }
    ObjectReader r(body);
    if (key == "sphere") {
        s.kind = K::Sphere;
        s.vertices = {sceneVec3(getEither(r, "center", "position"))};
        s.radius = sceneSize(r.get("radius"));
    } else if (key == "aabb") {
        s.kind = K::Aabb;
        const Vec3 lo = sceneVec3(r.get("min"));
        JsonNode maxNode = r.get("max");
        const Vec3 hi = sceneVec3(maxNode);
        if ((hi.array() < lo.array()).any()) maxNode.fail("aabb max is below min on some axis");
        s.box = Obb{0.5 * (lo + hi), 0.5 * (hi - lo), Mat3::Identity()};
        for (int i = 0; i < 8; ++i)  // exact corners: the triangle-AABB test reads min and max from them
            s.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    } else {  // "obb" or "box": the scenes' word, its position defaulting to the origin
        s.kind = K::Obb;
        const std::optional<JsonNode> cn = findEither(r, "center", "position");
        if (!cn && key == "obb") r.get("center");  // the obb's error: its center is required
        const Vec3 c = cn ? sceneVec3(*cn) : Vec3::Zero();
        const Vec3 e = sceneSizes(r.get("half_extents"));
        Quat q = Quat::Identity();
        if (auto rot = r.find("rotation")) q = rot->asQuat();
        s.box = Obb{c, e, q.toRotationMatrix()};
        s.vertices = boxCorners(c, e, s.box.axes);
    }
    r.finish();
    return s;
}

}  // namespace

const char* nameOf(PrimitiveShape::Kind kind) {
    switch (kind) {
        case PrimitiveShape::Kind::Sphere: return "sphere";
        case PrimitiveShape::Kind::Aabb: return "aabb";
        case PrimitiveShape::Kind::Obb: return "obb";
        case PrimitiveShape::Kind::Segment: return "segment";
        case PrimitiveShape::Kind::Triangle: return "triangle";
        case PrimitiveShape::Kind::Point: return "point";
        case PrimitiveShape::Kind::Tetrahedron: return "tetrahedron";
    }
    return "?";
}

PrimitiveShape readPrimitiveShape(const JsonNode& node, const std::vector<PrimitiveShape::Kind>& allowed,
                                  const std::string& what) {
    if (!node.isObject() || node.raw().size() != 1)
        node.fail("expected a shape: an object with exactly one key (" + what + "), got " + JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    static const std::vector<std::pair<std::string, PrimitiveShape::Kind>> kKeys = {
        {"sphere", PrimitiveShape::Kind::Sphere}, {"aabb", PrimitiveShape::Kind::Aabb},
        {"obb", PrimitiveShape::Kind::Obb},       {"box", PrimitiveShape::Kind::Obb},
        {"segment", PrimitiveShape::Kind::Segment}, {"triangle", PrimitiveShape::Kind::Triangle},
        {"point", PrimitiveShape::Kind::Point},     {"tetrahedron", PrimitiveShape::Kind::Tetrahedron}};
    bool ok = false;
    for (const auto& [k, kind] : kKeys)
        if (k == key)
            for (PrimitiveShape::Kind a : allowed) ok = ok || a == kind;
    if (!ok) node.fail("shape '" + key + "' is not drawn here (expected " + what + ")");
    return readBody(key, JsonNode(node.raw().begin().value(), node.path() + "." + key, node.source()));
}

namespace {

std::unique_ptr<PreparedScene> readRaycast(ObjectReader& r, SceneCommon common);
std::unique_ptr<PreparedScene> readSat(ObjectReader& r, SceneCommon common);
std::unique_ptr<PreparedScene> readPointInPolygon(ObjectReader& r, SceneCommon common);
std::unique_ptr<PreparedScene> readClosestFeatures(ObjectReader& r, SceneCommon common);
std::unique_ptr<PreparedScene> readSphereOverlap(ObjectReader& r, SceneCommon common);
std::unique_ptr<PreparedScene> readMoving2d(ObjectReader& r, SceneCommon common);

/// A prepared scene of any family: the input read, the family's run function.
template <class Input, DemoOutput (*Run)(const SceneCommon&, const Input&, const RunContext&)>
class FamilyScene final : public PreparedScene {
public:
    FamilyScene(SceneCommon common, Input input) : PreparedScene(std::move(common)), input_(std::move(input)) {}
    DemoOutput execute(const RunContext& ctx) const override { return Run(common_, input_, ctx); }

private:
    Input input_;
};

std::unique_ptr<PreparedScene> readRaycast(ObjectReader& r, SceneCommon common) {
    RaycastInput in;
    if (r.has("ray") == r.has("segment")) r.node().fail("expected exactly one of 'ray' or 'segment'");
    if (auto ray = r.find("ray")) {
        ObjectReader rr(*ray);
        in.origin = sceneVec3(rr.get("origin"));
        JsonNode d = rr.get("direction");
        in.direction = sceneVec3(d);
        rr.finish();
        if (in.direction.isZero(0.0)) d.fail("ray direction must be non-zero");
    } else {
        JsonNode s = r.get("segment");
        if (!s.isArray() || s.size() != 2) s.fail("expected [p, q], got " + JsonNode::describe(s.raw()));
        in.segment = true;
        in.origin = sceneVec3(s.at(0));
        in.direction = sceneVec3(s.at(1)) - in.origin;
    }
    using K = PrimitiveShape::Kind;
    in.shape = readPrimitiveShape(r.get("shape"), {K::Sphere, K::Aabb, K::Obb, K::Triangle}, "sphere, aabb, obb / box or triangle");
    r.finish();
    return std::make_unique<FamilyScene<RaycastInput, runRaycast>>(std::move(common), std::move(in));
}

std::unique_ptr<PreparedScene> readSat(ObjectReader& r, SceneCommon common) {
    using K = PrimitiveShape::Kind;
    const std::vector<K> kinds = {K::Aabb, K::Obb, K::Segment, K::Triangle};
    const char* what = "aabb, obb / box, segment or triangle";
    SatInput in;
    JsonNode an = r.get("a"), bn = r.get("b");
    in.a = readPrimitiveShape(an, kinds, what);
    in.b = readPrimitiveShape(bn, kinds, what);
    r.finish();
    const auto isBox = [](const PrimitiveShape& s) { return s.kind == K::Aabb || s.kind == K::Obb; };
    if (!isBox(in.a) && !isBox(in.b))
        bn.fail("one of the two shapes must be a box (the tests are box-box, segment-box and triangle-aabb)");
    const PrimitiveShape& other = isBox(in.a) ? in.b : in.a;
    const PrimitiveShape& box = isBox(in.a) ? in.a : in.b;
    if (other.kind == K::Triangle && box.kind != K::Aabb)
        (isBox(in.a) ? an : bn).fail("the triangle-box test takes an aabb (Akenine-Möller's 13 axes), got an obb");
    return std::make_unique<FamilyScene<SatInput, runSat>>(std::move(common), std::move(in));
}

std::unique_ptr<PreparedScene> readSphereOverlap(ObjectReader& r, SceneCommon common) {
    using K = PrimitiveShape::Kind;
    SphereOverlapInput in;
    in.sphere = readPrimitiveShape(r.get("a"), {K::Sphere}, "sphere");
    in.other = readPrimitiveShape(r.get("b"), {K::Sphere, K::Aabb, K::Obb, K::Triangle}, "sphere, aabb, obb / box or triangle");
    r.finish();
    return std::make_unique<FamilyScene<SphereOverlapInput, runSphereOverlap>>(std::move(common), std::move(in));
}

std::unique_ptr<PreparedScene> readMoving2d(ObjectReader& r, SceneCommon common) {
    Moving2dInput in;
    in.moving = readShape2d(r.get("moving"));
    in.still = readShape2d(r.get("still"));
    in.velocity = sceneVec2(r.get("velocity"));
    r.finish();
    return std::make_unique<FamilyScene<Moving2dInput, runMoving2d>>(std::move(common), std::move(in));
}

std::unique_ptr<PreparedScene> readClosestFeatures(ObjectReader& r, SceneCommon common) {
    using K = PrimitiveShape::Kind;
    const std::vector<K> kinds = {K::Point, K::Segment, K::Triangle, K::Tetrahedron};
    const char* what = "point, segment, triangle or tetrahedron";
    ClosestFeaturesInput in;
    in.a = readPrimitiveShape(r.get("a"), kinds, what);
    in.b = readPrimitiveShape(r.get("b"), kinds, what);
    r.finish();
    return std::make_unique<FamilyScene<ClosestFeaturesInput, runClosestFeatures>>(std::move(common), std::move(in));
}

std::unique_ptr<PreparedScene> readPointInPolygon(ObjectReader& r, SceneCommon common) {
    PointInPolygonInput in;
    JsonNode poly = r.get("polygon");
    if (!poly.isArray() || poly.size() < 3) poly.fail("expected at least 3 corners [[x, y], ...]");
    requireAtMost(poly, double(poly.size()), double(kMaxShapeVertices), "the number of corners", "the limit of a shape");
    for (const JsonNode& item : poly.items()) in.polygon.push_back(sceneVec2(item).head<2>());
    JsonNode queries = r.get("queries");
    if (!queries.isArray() || queries.size() < 1) queries.fail("expected at least one point [[x, y], ...]");
    requireAtMost(queries, double(queries.size()), double(kMaxQueryPoints), "the number of points",
                  "the limit of a scene list");
    for (const JsonNode& item : queries.items()) in.queries.push_back(sceneVec2(item).head<2>());
    r.finish();
    return std::make_unique<FamilyScene<PointInPolygonInput, runPointInPolygon>>(std::move(common), std::move(in));
}

class PrimitivesDemo final : public Demo {
public:
    std::string name() const override { return "primitives"; }
    std::string description() const override {
        return "primitive tests: ray/segment casts (sphere quadratic, AABB slabs, triangle barycentrics), "
               "separating axes (6, 13, 15), point in polygon three ways";
    }
    SceneFormat sceneFormat() const override {
        return {kLayers, ImageSettings{1280, 960, 1}, {960, 720, 0, 0}};
    }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        const std::string test =
            r.get("test").asEnum({"raycast", "sat", "point_in_polygon", "closest_features", "sphere_overlap", "moving_2d"});
        if (test == "moving_2d") return readMoving2d(r, std::move(common));
        if (test == "sphere_overlap") return readSphereOverlap(r, std::move(common));
        if (test == "raycast") return readRaycast(r, std::move(common));
        if (test == "sat") return readSat(r, std::move(common));
        if (test == "closest_features") return readClosestFeatures(r, std::move(common));
        return readPointInPolygon(r, std::move(common));
    }
};

}  // namespace

const Demo& primitivesDemo() {
    static const PrimitivesDemo demo;
    return demo;
}

}  // namespace cdlab::demos
