// Bounding volumes side by side: each BV type fitted to the same shape, one panel each, with its
// tightness = BV volume / volume of the shape's convex hull (1 would be a perfect fit).
// Every fit, volume and construction detail comes from core (bounding_volume_fit.h: fitAabb,
// fitObbTriangles / fitObbCovariance; bounding_sphere.h: fitSphereRitter, fitSphereWelzl with
// their traces; kdop.h: fitKdop, kdopPolytope; swept_sphere.h: fitLss, fitRss; convex_hull.h
// for the hull volume). This file only builds drawing geometry (box corners, the swept shapes'
// outer hulls from sphere samples) and lays the panels out.
//
// Sources: Ericson, "Real-Time Collision Detection" (2005) ch. 4 (§4.2 AABB, §4.3 spheres,
// §4.4 OBB, §4.5 sphere-swept volumes, §4.6 k-DOPs); Gottschalk, Lin, Manocha, "OBBTree",
// SIGGRAPH 1996; Larsen et al., "Fast Distance Queries with Rectangular Swept Sphere Volumes",
// ICRA 2000.
//
// Scene keys (docs/scenes.md, "bounding_volumes"): "shape", "position", "rotation", "volumes",
// "columns", "view". Layers: "shape", "volumes", "cores", "labels".
#include "demos/bounding_volumes/bounding_volumes_demo.h"

#include "demos/bounding_volumes/aabb_refit_figure.h"
#include "demos/bounding_volumes/bv_overlap_figure.h"
#include "demos/bounding_volumes/sphere_steps_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/bounding/bounding_sphere.h"
#include "core/bounding/bounding_volume_fit.h"
#include "core/bounding/kdop.h"
#include "core/bounding/swept_sphere.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/triangle_mesh.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "app/scene/mesh_scene.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"shape", "volumes", "cores", "labels"};
const std::vector<std::string> kAllVolumes = {"ritter", "welzl",  "aabb",   "obb", "kdop6",
                                              "kdop14", "kdop18", "kdop26", "lss", "rss"};
const std::vector<std::string> kDefaultVolumes = {"ritter", "welzl", "aabb", "obb", "kdop14", "kdop26", "lss", "rss"};

// Deterministic uniform numbers on every platform (splitmix64; no std distributions).
struct SplitMix {
    std::uint64_t state;
    double uniform() {  // [0, 1)
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        z ^= z >> 31;
        return double(z >> 11) * 0x1.0p-53;
    }
};

// ---- the shape

struct ShapeSpec {
    std::string kind;         // "torus", "ellipsoid", "blob", "cloud"
    TriangleMesh mesh;        // meshes (body frame)
    std::vector<Vec3> cloud;  // cloud: points (body frame)
    Transform pose;
    bool isCloud() const { return kind == "cloud"; }
};

ShapeSpec parseShape(const JsonNode& node) {
    if (!node.isObject() || node.raw().size() != 1)
        node.fail("expected an object with one key: torus, ellipsoid, blob or cloud");
    ShapeSpec s;
    s.kind = node.raw().begin().key();
    JsonNode body(node.raw().begin().value(), node.path() + "." + s.kind, node.source());
    ObjectReader r(body);
    if (readMeshGenerator(s.kind, body, r, MeshTessellation{32, 12, 24, 12}, s.mesh)) {
        // torus, ellipsoid or blob
    } else if (s.kind == "cloud") {
        int count = 60, seed = 1;
        Vec3 stretch(1, 1, 1);
        if (auto n = r.find("count")) count = n->asInt(4, 5000);
        if (auto n = r.find("seed")) seed = n->asInt(0, 1 << 30);
        if (auto v = r.find("stretch")) stretch = sceneSizes(*v);
        // Uniform in the unit ball (rejection from the cube), then stretched.
        SplitMix rng{std::uint64_t(seed)};
        while (int(s.cloud.size()) < count) {
            const Vec3 p(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
            if (p.squaredNorm() <= 1.0) s.cloud.push_back(p.cwiseProduct(stretch));
        }
    } else {
        node.fail("unknown shape '" + s.kind + "' (torus, ellipsoid, blob, cloud)");
    }
    r.finish();
    return s;
}

// The shape's points in the world frame (its pose applied).
std::vector<Vec3> worldPoints(const ShapeSpec& shape) {
    std::vector<Vec3> pts;
    for (const Vec3& p : shape.isCloud() ? shape.cloud : shape.mesh.vertices) pts.push_back(shape.pose.apply(p));
    return pts;
}

// ---- drawing geometry

// Faces of a convex polyhedron as a drawable: fan triangles per face, hull edges when asked.
ConvexDrawable polyDrawable(const ConvexPolyhedron& p, bool withEdges) {
    ConvexDrawable d;
    if (p.empty()) return d;
    d.vertices = p.positions();
    for (int f = 0; f < p.faceCount(); ++f) {
        const std::vector<int> fv = p.faceVertices(f);
        for (std::size_t k = 1; k + 1 < fv.size(); ++k) d.triangles.emplace_back(fv[0], fv[k], fv[k + 1]);
    }
    if (withEdges)
        for (int e = 0; e < p.edgeCount(); ++e) d.edges.push_back(p.edgeVertices(e));
    boundingSphere(d.vertices, d.center, d.radius);
    d.valid = true;
    return d;
}

ConvexDrawable hullDrawable(const std::vector<Vec3>& points, bool withEdges) {
    const HullResult h = convexHull(points);
    if (h.status != HullStatus::Ok) return {};
    return polyDrawable(h.polyhedron, withEdges);
}

// A core (its corner points) swept by a sphere of radius r, drawn as the hull of spheres of
// 16 x 9 samples around each corner (inscribed in the true shape, within 2 % of r).
ConvexDrawable sweptDrawable(const std::vector<Vec3>& corners, double r) {
    std::vector<Vec3> pts;
    const int slices = 16, stacks = 9;
    for (const Vec3& c : corners) {
        pts.push_back(c + Vec3(0, 0, r));
        pts.push_back(c - Vec3(0, 0, r));
        for (int i = 1; i < stacks; ++i) {
            const double th = M_PI * i / stacks;
            for (int j = 0; j < slices; ++j) {
                const double ph = 2 * M_PI * j / slices;
                pts.push_back(c + r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
            }
        }
    }
    return hullDrawable(pts, false);
}

std::array<Vec3, 8> boxCorners(const Obb& b) {
    std::array<Vec3, 8> c;
    for (int k = 0; k < 8; ++k) {
        Vec3 u;
        for (int i = 0; i < 3; ++i) u[i] = (k >> i & 1 ? 1.0 : -1.0) * b.halfExtents[i];
        c[k] = b.center + b.axes * u;
    }
    return c;
}

std::array<Vec3, 4> rssCorners(const Rss& r) {
    const Vec3 u = r.axes.col(0) * r.halfLengths.x(), v = r.axes.col(1) * r.halfLengths.y();
    return {r.center - u - v, r.center + u - v, r.center + u + v, r.center - u + v};
}

Json vecListJson(std::span<const double> v) {
    Json a = Json::array();
    for (double x : v) a.push_back(x);
    return a;
}

Json axesJson(const Mat3& m) {
    Json a = Json::array();
    for (int i = 0; i < 3; ++i) a.push_back(vec3Json(m.col(i)));
    return a;
}

std::string sig3(double x) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

std::string fixed(double x, int digits) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", digits, x);
    return buf;
}

// One fitted bounding volume: what the trace records and what its panel draws.
struct FittedBv {
    std::string key;      // scene name: "welzl"
    std::string heading;  // "Welzl sphere (minimum)"
    double volume = 0.0;
    Json json;
    ConvexDrawable body;                      // the BV's surface (fill; edges for polytopes)
    std::vector<std::pair<Vec3, Vec3>> core;  // LSS segment / RSS rectangle / Ritter diameter
    std::vector<Vec3> marks;                  // Welzl support points, Ritter initial pair
    std::string detail;                       // footer line
};

template <int K>
FittedBv fitKdopBv(const std::vector<Vec3>& pts) {
    FittedBv f;
    f.key = "kdop" + std::to_string(K);
    f.heading = std::to_string(K) + "-DOP (" + std::to_string(K / 2) + " slabs)";
    const Kdop<K> dop = fitKdop<K>(std::span<const Vec3>(pts));
    f.volume = volume(dop);
    f.json = {{"min", vecListJson(dop.min)}, {"max", vecListJson(dop.max)}};
    const ConvexPolyhedron poly = kdopPolytope(dop);
    f.body = polyDrawable(poly, true);
    f.detail = std::to_string(poly.faceCount()) + " faces, " + std::to_string(poly.vertexCount()) + " corners";
    return f;
}

FittedBv fitOne(const std::string& key, const std::vector<Vec3>& pts, const std::vector<Triangle>& tris) {
    FittedBv f;
    f.key = key;
    const std::span<const Vec3> ps(pts);
    if (key == "ritter") {
        RitterTrace t;
        const Sphere s = fitSphereRitter(ps, &t);
        f.heading = "Ritter sphere";
        f.volume = volume(s);
        f.json = {{"center", vec3Json(s.center)},
                  {"radius", s.radius},
                  {"initial_pair", {t.initialPair[0], t.initialPair[1]}},
                  {"initial_radius", t.initial.radius},
                  {"grow_steps", t.steps.size()}};
        f.body = sweptDrawable({s.center}, s.radius);
        f.marks = {pts[t.initialPair[0]], pts[t.initialPair[1]]};
        f.core.emplace_back(pts[t.initialPair[0]], pts[t.initialPair[1]]);
        f.detail = "r " + formatNumber(s.radius) + ", " + std::to_string(t.steps.size()) + " grow steps; dashed: start";
    } else if (key == "welzl") {
        WelzlTrace t;
        const Sphere s = fitSphereWelzl(ps, &t);
        f.heading = "Welzl sphere (minimum)";
        f.volume = volume(s);
        f.json = {{"center", vec3Json(s.center)},
                  {"radius", s.radius},
                  {"support", t.finalSupport},
                  {"status", nameOf(t.status)},
                  {"steps", t.steps.size()}};
        f.body = sweptDrawable({s.center}, s.radius);
        for (int i : t.finalSupport) f.marks.push_back(pts[i]);
        f.detail =
            "r " + formatNumber(s.radius) + "; dots: " + std::to_string(t.finalSupport.size()) + " support points";
    } else if (key == "aabb") {
        const Aabb b = fitAabb(ps);
        f.heading = "AABB";
        f.volume = volume(b);
        f.json = {{"min", vec3Json(b.min)}, {"max", vec3Json(b.max)}};
        const std::array<Vec3, 8> c = boxCorners(Obb{0.5 * (b.min + b.max), 0.5 * (b.max - b.min), Mat3::Identity()});
        f.body = hullDrawable(std::vector<Vec3>(c.begin(), c.end()), true);
        f.detail = "world axes";
    } else if (key == "obb") {
        ObbFitTrace t;
        const Obb b = tris.empty() ? fitObbCovariance(ps, &t) : fitObbTriangles(std::span<const Triangle>(tris), &t);
        f.heading = tris.empty() ? "OBB (point covariance)" : "OBB (area covariance)";
        f.volume = volume(b);
        f.json = {{"center", vec3Json(b.center)},
                  {"half_extents", vec3Json(b.halfExtents)},
                  {"axes", axesJson(b.axes)},
                  {"method", nameOf(t.method)},
                  {"eigenvalues", vec3Json(t.eigenvalues)}};
        const std::array<Vec3, 8> c = boxCorners(b);
        f.body = hullDrawable(std::vector<Vec3>(c.begin(), c.end()), true);
        f.detail =
            "eigenvalues " + sig3(t.eigenvalues[0]) + ", " + sig3(t.eigenvalues[1]) + ", " + sig3(t.eigenvalues[2]);
    } else if (key == "kdop6") {
        f = fitKdopBv<6>(pts);
    } else if (key == "kdop14") {
        f = fitKdopBv<14>(pts);
    } else if (key == "kdop18") {
        f = fitKdopBv<18>(pts);
    } else if (key == "kdop26") {
        f = fitKdopBv<26>(pts);
    } else if (key == "lss") {
        SweptSphereFitTrace t;
        const Capsule c = fitLss(ps, &t);
        f.heading = "LSS (capsule)";
        f.volume = volume(c);
        f.json = {{"a", vec3Json(c.a)}, {"b", vec3Json(c.b)}, {"radius", c.radius}};
        f.body = sweptDrawable({c.a, c.b}, c.radius);
        f.core.emplace_back(c.a, c.b);
        f.detail = "r " + formatNumber(c.radius) + ", segment " + formatNumber((c.b - c.a).norm());
    } else if (key == "rss") {
        SweptSphereFitTrace t;
        const Rss r = fitRss(ps, &t);
        f.heading = "RSS (swept rectangle)";
        f.volume = volume(r);
        f.json = {{"center", vec3Json(r.center)},
                  {"axes", axesJson(r.axes)},
                  {"half_lengths", {r.halfLengths.x(), r.halfLengths.y()}},
                  {"radius", r.radius},
                  {"corner_fixes", t.cornerFixes}};
        const std::array<Vec3, 4> q = rssCorners(r);
        f.body = sweptDrawable(std::vector<Vec3>(q.begin(), q.end()), r.radius);
        for (int i = 0; i < 4; ++i) f.core.emplace_back(q[i], q[(i + 1) % 4]);
        f.detail = "r " + formatNumber(r.radius) + ", rectangle " + formatNumber(2 * r.halfLengths.x()) + " × " +
                   formatNumber(2 * r.halfLengths.y());
    }
    return f;
}

// ---- the scene

class BoundingVolumesScene final : public PreparedScene {
public:
    BoundingVolumesScene(SceneCommon common, ShapeSpec shape, std::vector<std::string> volumes, int columns, Vec3 view)
        : PreparedScene(std::move(common)),
          shape_(std::move(shape)),
          volumes_(std::move(volumes)),
          columns_(columns),
          view_(view) {}

    DemoOutput execute(const RunContext& ctx) const override {
        DemoOutput out;
        // World-frame points (and triangles for meshes): the pose applied once, here.
        const std::vector<Vec3> pts = worldPoints(shape_);
        std::vector<Triangle> tris;
        if (!shape_.isCloud())
            for (int i = 0; i < shape_.mesh.triangleCount(); ++i) tris.push_back(shape_.mesh.triangle(i, shape_.pose));
        const HullResult hull = convexHull(pts);  // checked in prepare
        if (hull.status != HullStatus::Ok)
            throw InputError(common_.file + ": the shape's convex hull failed: " + hull.message);
        const double hullVolume = hull.polyhedron.volume();

        std::vector<FittedBv> fitted;
        for (const std::string& key : volumes_) fitted.push_back(fitOne(key, pts, tris));

        Json t;
        t["shape"] = shape_.kind;
        t["points"] = pts.size();
        t["triangles"] = tris.size();
        t["hull_volume"] = hullVolume;
        Json vs = Json::array();
        for (const FittedBv& f : fitted) {
            Json j = f.json;
            j["bv"] = f.key;
            j["volume"] = f.volume;
            j["tightness"] = f.volume / hullVolume;
            vs.push_back(j);
        }
        t["volumes"] = vs;
        out.trace = t;
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(drawFrame(*ctx.gl, ctx, pts, hull.polyhedron, fitted, hullVolume));
        return out;
    }

private:
    ShapeSpec shape_;
    std::vector<std::string> volumes_;
    int columns_ = 4;
    Vec3 view_;

    Frame drawFrame(GlContext& gl, const RunContext& ctx, const std::vector<Vec3>& pts, const ConvexPolyhedron& hull,
                    const std::vector<FittedBv>& fitted, double hullVolume) const {
        const int ss = figureScale(common_, ctx);
        const int W = common_.image.width, H = common_.image.height;
        const int n = int(fitted.size());
        const int cols = std::min(columns_, n), rows = (n + cols - 1) / cols;
        const int titleBand = 44, captionBand = 62;
        const int pw = W / cols, ph = (H - titleBand - captionBand) / rows;

        // One camera for every panel (sizes compare across panels): frame every BV's surface.
        std::vector<Vec3> all = pts;
        for (const FittedBv& f : fitted)
            if (f.body.valid) all.insert(all.end(), f.body.vertices.begin(), f.body.vertices.end());
        Vec3 center;
        double radius;
        boundingSphere(all, center, radius);
        // The camera fits the sphere vertically; a panel narrower than tall needs more room.
        const double fit = radius * std::max(1.0, double(ph) / pw) * 1.02;
        const Camera cam = common_.camera ? *common_.camera : framingCamera(center, fit, view_, Vec3::UnitZ());

        // The shape itself: the mesh (opaque), or the cloud's points over its translucent hull.
        std::vector<Vec3> meshVerts;
        std::vector<Eigen::Vector3i> meshTris;
        for (const Vec3& p : shape_.mesh.vertices) meshVerts.push_back(shape_.pose.apply(p));
        for (const auto& tr : shape_.mesh.triangles) meshTris.emplace_back(tr[0], tr[1], tr[2]);
        const ConvexDrawable hullBody = polyDrawable(hull, false);

        const Color bvColor = roleColor(Role::Highlight);
        std::vector<Image> panels;
        for (const FittedBv& f : fitted) {
            Canvas c(gl, canvasOptions(pw, ph, ss), cam);
            if (common_.hasLayer("shape")) {
                if (shape_.isCloud()) {
                    drawBody(c, hullBody, roleColor(Role::ShapeA), 0.35f, roleColor(Role::ShapeA), 0.0f);
                    for (const Vec3& p : pts) c.drawPoint(p, 2.5f, roleColor(Role::ShapeA).scaled(0.7f), false, 0.0f);
                } else {
                    c.drawMesh(meshVerts, meshTris, roleColor(Role::ShapeA), true);
                }
            }
            if (common_.hasLayer("volumes") && f.body.valid)
                drawBody(c, f.body, bvColor, 0.16f, bvColor.scaled(0.75f), 1.6f);
            if (common_.hasLayer("cores")) {
                for (const auto& [a, b] : f.core) c.drawLine(a, b, lineStyle(Role::Ink, 2.5f, f.key == "ritter", true));
                for (const Vec3& m : f.marks)
                    c.drawPoint(m, 5.0f, roleColor(Role::Support), true, 1.2f, roleColor(Role::Ink));
            }
            const double tight = f.volume / hullVolume;
            drawPanelHeading(c, f.heading, "tightness " + fixed(tight, 2) + " × hull");
            if (common_.hasLayer("labels")) {
                TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::BottomLeft, true, false};
                c.drawTextPx(14, ph - 30, "volume " + formatNumber(f.volume), ts);
                c.drawTextPx(14, ph - 10, f.detail, ts);
            }
            panels.push_back(c.readPixels());
        }

        Canvas frame(gl, canvasOptions(W, H, ss), Camera::twoD(0, 0, 1));
        frame.drawTextPx(18, 10, common_.title, TextStyle{24.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
        std::vector<std::string> lines;
        if (!common_.caption.empty()) lines.push_back(common_.caption);
        lines.push_back(shapeWords(int(pts.size())) + "; convex hull volume " + formatNumber(hullVolume) +
                        ". Tightness = BV volume / hull volume (1 = perfect).");
        double y = H - captionBand + 8;
        for (const std::string& line : lines) {
            frame.drawTextPx(18, y, line, TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
            y += 24;
        }
        Image image = frame.readPixels();
        for (int i = 0; i < n; ++i) blit(image, panels[i], (i % cols) * pw, titleBand + (i / cols) * ph);
        // 1-pixel rules between panels.
        const Color m = roleColor(Role::Muted);
        for (int cI = 1; cI < cols; ++cI) paintRect(image, cI * pw, titleBand, 1, rows * ph, m);
        for (int rI = 1; rI < rows; ++rI) paintRect(image, 0, titleBand + rI * ph, cols * pw, 1, m);
        const std::string caption =
            std::to_string(n) + " bounding volumes of the " + shape_.kind + " with their tightness";
        return Frame{"volumes", caption, std::move(image)};
    }

    std::string shapeWords(int points) const {
        if (shape_.isCloud()) return std::to_string(points) + " random points";
        return shape_.kind + " mesh, " + std::to_string(shape_.mesh.triangleCount()) + " triangles, " +
               std::to_string(points) + " vertices";
    }
};

class BoundingVolumesDemo final : public Demo {
public:
    std::string name() const override { return "bounding_volumes"; }
    std::string description() const override {
        return "bounding volumes fitted to one shape: Ritter / Welzl spheres, AABB, covariance OBB, k-DOPs, LSS, RSS, "
               "with tightness";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {320, 240}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        if (auto f = r.find("figure")) {
            const std::string figure = f->asEnum({"volumes", "sphere_steps", "aabb_refit", "bv_overlap"});
            if (figure == "bv_overlap") return readBvOverlapScene(r, std::move(common));
            if (figure == "sphere_steps") return readSphereStepsScene(r, std::move(common));
            if (figure == "aabb_refit") return readAabbRefitScene(r, std::move(common));
        }
        const JsonNode shapeNode = r.get("shape");
        ShapeSpec shape = parseShape(shapeNode);
        if (auto p = r.find("position")) shape.pose.position = sceneVec3(*p);
        if (auto q = r.find("rotation")) shape.pose.rotation = q->asQuat();
        // Every figure compares with the hull's volume: a shape without one is refused here, with
        // its path, not after earlier scenes were written.
        if (const HullResult hull = convexHull(worldPoints(shape)); hull.status != HullStatus::Ok)
            shapeNode.fail("the shape has no convex hull with a volume: " + hull.message);
        std::vector<std::string> volumes = kDefaultVolumes;
        if (auto v = r.find("volumes")) {
            volumes.clear();
            for (const JsonNode& item : v->items()) volumes.push_back(item.asEnum(kAllVolumes));
            if (volumes.empty() || volumes.size() > 12) v->fail("expected 1..12 bounding volume names");
        }
        int columns = 4;
        if (auto c = r.find("columns")) columns = c->asInt(1, 6);
        Vec3 view(1.0, -1.4, 0.9);
        if (auto v = r.find("view")) view = sceneVec3(*v);
        if (!(view.norm() > 0)) r.node().fail("view must be a non-zero direction");
        r.finish();
        return std::make_unique<BoundingVolumesScene>(std::move(common), std::move(shape), std::move(volumes), columns,
                                                      view);
    }
};

}  // namespace

const Demo& boundingVolumesDemo() {
    static const BoundingVolumesDemo demo;
    return demo;
}

}  // namespace cdlab::demos
