#include "app/scene/pair_scene.h"

#include <cmath>

#include "core/geometry/convex_hull.h"
#include "app/scene/scene_limits.h"

namespace cdlab::demos {

Vec3 SceneShape::support(const Vec3& dWorld) const {
    Vec3 d = pose.rotateInverse(dWorld);
    if (planar) d.z() = 0.0;  // in-plane directions only (a rotation about z keeps z = 0 exactly)
    Vec3 s = Vec3::Zero();
    switch (kind) {
        case Kind::Box: s = BoxShape{halfExtents}.support(d); break;
        case Kind::Sphere: s = SphereShape{radius}.support(d); break;
        case Kind::Cylinder: s = CylinderShape{halfHeight, radius}.support(d); break;
        case Kind::Cone: s = ConeShape{halfHeight, radius}.support(d); break;
        case Kind::Polytope: s = polytope.support(d); break;
    }
    return pose.apply(s);
}

std::vector<Vec3> SceneShape::worldVertices() const {
    std::vector<Vec3> out;
    if (kind == Kind::Box) {
        const int corners = planar ? 4 : 8;
        for (int i = 0; i < corners; ++i)
            out.push_back(pose.apply(Vec3((i & 1 ? 1 : -1) * halfExtents.x(), (i & 2 ? 1 : -1) * halfExtents.y(),
                                          planar ? 0.0 : (i & 4 ? 1 : -1) * halfExtents.z())));
    } else if (kind == Kind::Polytope) {
        for (const Vec3& v : polytope.vertices()) out.push_back(pose.apply(v));
    }
    return out;
}

std::string SceneShape::kindName() const {
    switch (kind) {
        case Kind::Box: return planar ? "rectangle" : "box";
        case Kind::Sphere: return planar ? "circle" : "sphere";
        case Kind::Cylinder: return "cylinder";
        case Kind::Cone: return "cone";
        case Kind::Polytope: return planar ? "polygon" : "polytope";
    }
    return "?";
}

namespace {

Vec3 readVec2(const JsonNode& n) { return sceneVec2(n); }

// An explicit polygon / polytope: at most kMaxShapeVertices (the configuration-space view draws
// the hull of all n·m differences of the pair).
void requireShapeVertices(const JsonNode& vn) {
    requireAtMost(vn, double(vn.size()), double(kMaxShapeVertices), "the number of vertices",
                  "the Minkowski-difference view builds the hull of all n·m differences of the pair");
}

}  // namespace

SceneShape parseSceneShape(const JsonNode& node, bool planar) {
    const char* kinds3 = "box, sphere, cylinder, cone or polytope";
    const char* kinds2 = "polygon, box or circle";
    if (!node.isObject() || node.raw().size() != 1)
        node.fail(std::string("expected a shape: an object with exactly one key (") + (planar ? kinds2 : kinds3) +
                  "), got " + JsonNode::describe(node.raw()));
    const std::string key = node.raw().begin().key();
    const JsonNode body(node.raw().begin().value(), node.path() + "." + key, node.source());
    ObjectReader r(body);
    SceneShape s;
    s.planar = planar;
    if (planar) {
        if (key == "box") {
            s.kind = SceneShape::Kind::Box;
            JsonNode h = r.get("half_extents");
            if (!h.isArray() || h.size() != 2) h.fail("expected [x, y], got " + JsonNode::describe(h.raw()));
            s.halfExtents = Vec3(sceneSize(h.at(0)), sceneSize(h.at(1)), 0.0);
        } else if (key == "circle") {
            s.kind = SceneShape::Kind::Sphere;
            s.radius = sceneSize(r.get("radius"));
        } else if (key == "polygon") {
            s.kind = SceneShape::Kind::Polytope;
            JsonNode vn = r.get("vertices");
            requireShapeVertices(vn);
            std::vector<Vec3> v;
            for (const JsonNode& item : vn.items()) v.push_back(readVec2(item));
            if (v.size() < 3) vn.fail("a polygon needs at least 3 vertices, got " + std::to_string(v.size()));
            s.polytope = PolytopeShape(std::move(v));
        } else {
            node.fail("unknown 2D shape '" + key + "' (expected " + kinds2 + ")");
        }
        if (auto p = r.find("position")) s.pose.position = readVec2(*p);
        if (auto a = r.find("angle")) {
            if (s.kind == SceneShape::Kind::Sphere) a->fail("a circle has no angle");
            s.pose.rotation = Quat(Eigen::AngleAxisd(std::fmod(a->asNumber(), 360.0) * M_PI / 180.0, Vec3::UnitZ()));
        }
    } else {
        if (key == "box") {
            s.kind = SceneShape::Kind::Box;
            JsonNode h = r.get("half_extents");
            s.halfExtents = sceneSizes(h);
        } else if (key == "sphere") {
            s.kind = SceneShape::Kind::Sphere;
            s.radius = sceneSize(r.get("radius"));
        } else if (key == "cylinder" || key == "cone") {
            s.kind = key == "cylinder" ? SceneShape::Kind::Cylinder : SceneShape::Kind::Cone;
            s.radius = sceneSize(r.get("radius"));
            s.halfHeight = sceneSize(r.get("half_height"));
        } else if (key == "polytope" || key == "hull") {  // one vocabulary: the feature-walk scenes' "hull"
            s.kind = SceneShape::Kind::Polytope;
            JsonNode vn = r.get("vertices");
            requireShapeVertices(vn);
            std::vector<Vec3> v = sceneVec3List(vn, 0, kMaxShapeVertices);
            if (v.size() < 4) vn.fail("a polytope needs at least 4 vertices, got " + std::to_string(v.size()));
            if (!convexHull(v).ok()) vn.fail("the polytope's vertices span no volume");
            s.polytope = PolytopeShape(std::move(v));
        } else {
            node.fail("unknown shape '" + key + "' (expected " + kinds3 + ")");
        }
        if (auto p = r.find("position")) s.pose.position = sceneVec3(*p);
        if (auto q = r.find("rotation")) s.pose.rotation = q->asQuat();
    }
    r.finish();
    return s;
}

PairScene readPairScene(ObjectReader& r) {
    PairScene s;
    if (auto d = r.find("dimension")) {
        s.dimension = d->asInt(2, 3);
    }
    JsonNode shapes = r.get("shapes");
    if (!shapes.isArray() || shapes.size() != 2) shapes.fail("expected [shapeA, shapeB]");
    s.a = parseSceneShape(shapes.at(0), s.dimension == 2);
    s.b = parseSceneShape(shapes.at(1), s.dimension == 2);
    if (s.a.isPolytope() && s.b.isPolytope())
        requireAtMost(shapes, double(s.a.worldVertices().size()) * double(s.b.worldVertices().size()),
                      kMaxMinkowskiPoints, "vertices of A x vertices of B",
                      "the Minkowski-difference view builds the hull of every difference");
    if (auto v = r.find("view")) {
        if (s.dimension == 2) v->fail("'view' is for 3D scenes");
        s.view = sceneVec3(*v);
        if (s.view.squaredNorm() == 0) v->fail("view direction must be non-zero");
    }
    if (auto m = r.find("max_step_frames")) s.maxStepFrames = m->asInt(2, 60);
    s.gif = r.boolOr("gif", true);
    return s;
}

}  // namespace cdlab::demos
