// Many bodies: reads a world scene, runs core/world/world.h once and keeps the steps the frames
// show (demos/world/world_record.h); demos/world/world_frames.cpp draws them. Every number on a
// frame comes from the world's step stats and manifolds.
//
// Scene keys (besides the common ones; docs/scenes.md, "world"):
//   "ground": true (the plane z = 0, default) or false;
//   "bin": {"half_extents": [hx, hy], "height": h, "thickness": t} — four static walls around
//          [-hx, hx] × [-hy, hy] standing on z = 0;
//   "bodies": [{"box": {"half_extents": [..]}} | {"sphere": {"radius": r}} |
//              {"capsule": {"half_height": h, "radius": r}} (its segment along the body's y) |
//              {"hull": {"points": [[x, y, z], ...]}}, with "position", "rotation" [w, x, y, z],
//              "velocity", "angular_velocity", "static", "density", "friction", "restitution"];
//   "lattice": {"count": n, "columns": k, "spacing": s, "origin": [x, y, z], "shapes": ["box", ...],
//               "size": [lo, hi], "seed": s, "friction", "restitution"} — n bodies of the given kinds
//              in turn on a k × k grid, layer over layer from origin (the first layer's centre), sizes
//              uniform in [lo, hi] (a box's half extents, a sphere's radius, a capsule's radius with a
//              segment 1.6 r, a hull of 12 points on a sphere of that radius), random orientations;
//              the largest body of each kind must fit in half the spacing (none starts overlapping);
//   "simulation": {"time_step", "duration", "velocity_iterations", "position_iterations",
//                  "substeps", "slop", "broad_phase" ("sap" | "tree" | "grid"), "warm_start",
//                  "restitution_threshold", "gravity" (m/s² down z)};
//   "frame_every" (steps between frames, at most 12 frames), "pipeline_step" (the step drawn as
//   the pipeline; 0 or absent: none).
// Layers: "ground", "contacts", "impulses", "labels", "plot", "pipeline".
// Limits: docs/scenes.md, "world" (bodies, steps, body-steps at the default sweeps, sizes, the
// solver's regime checked before any work; pairs a step checked while it runs).
#include "demos/world/world_demo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "app/scene/scene_limits.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/world/world_record.h"

namespace cdlab::demos {

namespace {

const std::vector<std::string> kWorldLayers = {"ground", "contacts", "impulses", "labels", "plot", "pipeline"};
constexpr int kMaxWorldBodies = 2000;
// The work a scene may ask for, in body-steps at the default 8 + 6 sweeps (each substep and sweep
// past them counts in proportion): the golden 1000-body pile is 2.4e5; 1005 bodies for 1194 steps
// (1.2e6) took 18 s with the machine's other core busy; 2000 bodies for 300 steps (6e5) render in 12 s.
constexpr double kMaxBodySteps = 6e5;
constexpr int kMaxWorldFrames = 12;
// Pairs a step may test, per body: a settled pile has ~2.5; 2000 spheres heaped on one point made
// 2e6 and one step took 41 s and 1.7 GB (the hostile review).
constexpr std::int64_t kPairsPerBody = 20;

WorldShapeBuild readShape(ObjectReader& r) {
    const char* kinds[] = {"box", "sphere", "capsule", "hull"};
    int found = 0;
    for (const char* k : kinds) found += r.has(k);
    if (found != 1) r.node().fail("a body needs exactly one of box, sphere, capsule, hull");
    WorldShapeBuild b;
    JsonNode at = r.node();
    if (auto n = r.find("box")) {
        ObjectReader s(*n);
        at = s.get("half_extents");
        const Vec3 h = sceneVec3(at);
        s.finish();
        b = worldBox(h);
    } else if (auto n = r.find("sphere")) {
        ObjectReader s(*n);
        at = s.get("radius");
        b = worldSphere(at.asPositive());
        s.finish();
    } else if (auto n = r.find("capsule")) {
        ObjectReader s(*n);
        at = s.get("radius");
        const double radius = at.asPositive();
        b = worldCapsule(s.get("half_height").asNonNegative(), radius);
        s.finish();
    } else if (auto n = r.find("hull")) {
        ObjectReader s(*n);
        at = s.get("points");
        b = worldHull(sceneVec3List(at, 4, kMaxShapeVertices));
        s.finish();
    }
    if (!b.ok()) at.fail(b.message);
    if (b.shape.boundingRadius < kMinSceneSize || b.shape.boundingRadius > 100)
        at.fail("a body's size must be in [1e-5, 100] (world units)");
    return b;
}

// Density, friction and restitution of a body or a lattice, within the physical range.
void readMaterial(ObjectReader& r, WorldBodyDesc& d) {
    if (auto n = r.find("density")) {
        d.density = n->asPositive();
        requireAtMost(*n, d.density, kMaxDensity, "density", "the physical range a world scene accepts");
        requireAtLeast(*n, d.density, kMinDensity, "density", "the solver divides by the mass");
    }
    if (auto n = r.find("friction")) d.friction = n->asNonNegative();
    if (auto n = r.find("restitution")) {
        d.restitution = n->asNonNegative();
        if (d.restitution > 1) n->fail("restitution must be in [0, 1]");
    }
}

WorldBodyDesc readBody(const JsonNode& node) {
    ObjectReader r(node);
    const WorldShapeBuild shape = readShape(r);
    Transform pose;
    if (auto p = r.find("position")) pose.position = sceneVec3(*p);
    if (auto q = r.find("rotation")) pose.rotation = q->asQuat();
    const bool isStatic = r.boolOr("static", false);
    WorldBodyDesc d = worldBody(shape, pose, isStatic);
    const auto speed = [](const JsonNode& n, const Vec3& v) {
        requireAtMost(n, v.norm(), kMaxSpeed, "speed", "the physical range a world scene accepts");
        return v;
    };
    if (auto v = r.find("velocity")) d.linearVelocity = speed(*v, sceneVec3(*v));
    if (auto w = r.find("angular_velocity")) d.angularVelocity = speed(*w, sceneVec3(*w));
    readMaterial(r, d);
    r.finish();
    return d;
}

void readLattice(const JsonNode& node, std::vector<WorldBodyDesc>& bodies) {
    ObjectReader r(node);
    const JsonNode countNode = r.get("count");
    const int count = countNode.asInt(1, kMaxWorldBodies);
    if (bodies.size() + std::size_t(count) > std::size_t(kMaxWorldBodies))
        countNode.fail("at most 2000 bodies in a world scene (" + std::to_string(bodies.size()) + " before the lattice)");
    const int columns = r.get("columns").asInt(1, 200);
    const JsonNode spacingNode = r.get("spacing");
    const double spacing = spacingNode.asPositive();
    if (spacing > 200) spacingNode.fail("spacing must be at most 200 (world units)");
    const Vec3 origin = sceneVec3(r.get("origin"));
    std::vector<std::string> kinds;
    for (const JsonNode& k : r.get("shapes").items()) kinds.push_back(k.asEnum({"box", "sphere", "capsule", "hull"}));
    if (kinds.empty()) r.get("shapes").fail("name at least one shape");
    const JsonNode sizeNode = r.get("size");
    if (sizeNode.size() != 2) sizeNode.fail("size is [smallest, largest]");
    const double lo = sizeNode.at(0).asPositive(), hi = sizeNode.at(1).asPositive();
    if (!(lo <= hi) || lo < kMinSceneSize || hi > 100) sizeNode.fail("size needs 1e-5 <= smallest <= largest <= 100");
    // The lattice's farthest point within the scene's coordinates.
    const double layers = std::ceil(double(count) / (double(columns) * columns));
    if (origin.cwiseAbs().maxCoeff() + spacing * std::max<double>(columns, layers) > kMaxSceneCoordinate)
        r.node().fail("the lattice reaches past 1e5 from the origin");
    const std::uint64_t seed = std::uint64_t(r.get("seed").asInt(0, 1 << 30));
    WorldBodyDesc material;
    readMaterial(r, material);
    r.finish();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < count; ++i) {
        const int layer = i / (columns * columns), cell = i % (columns * columns);
        const double half = 0.5 * spacing * (columns - 1);
        const Vec3 p = origin + Vec3(-half + spacing * (cell % columns), -half + spacing * (cell / columns), spacing * layer);
        const Vec3 axis(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        const Quat q(Eigen::AngleAxisd(3.0 * u(rng), axis.norm() > 1e-3 ? Vec3(axis.normalized()) : Vec3::UnitZ()));
        const auto size = [&] { return lo + (hi - lo) * u(rng); };
        const std::string& kind = kinds[std::size_t(i) % kinds.size()];
        WorldShapeBuild shape;
        if (kind == "box") {
            shape = worldBox(Vec3(size(), size(), size()));
        } else if (kind == "sphere") {
            shape = worldSphere(size());
        } else if (kind == "capsule") {
            const double rr = size();
            shape = worldCapsule(0.8 * rr, rr);
        } else {
            const double rr = size();
            std::vector<Vec3> pts;
            for (int j = 0; j < 12; ++j) pts.push_back(rr * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized());
            shape = worldHull(pts);
            if (!shape.ok()) shape = worldBox(Vec3::Constant(0.6 * rr));  // a flat random draw: never with small seeds
        }
        // No two bodies may start overlapping: each body's farthest point from its centre of mass
        // (where the lattice puts it) within half the spacing.
        if (shape.shape.boundingRadius > 0.5 * spacing) {
            char why[200];
            std::snprintf(why, sizeof why, "a %s reaches %.6g from its centre, more than spacing / 2 = %.6g: lattice bodies would start overlapping",
                          kind.c_str(), shape.shape.boundingRadius, 0.5 * spacing);
            sizeNode.fail(why);
        }
        WorldBodyDesc d = worldBody(shape, Transform{p, q});
        d.density = material.density, d.friction = material.friction, d.restitution = material.restitution;
        bodies.push_back(d);
    }
}

void readBin(const JsonNode& node, std::vector<WorldBodyDesc>& bodies) {
    ObjectReader r(node);
    const JsonNode he = r.get("half_extents");
    if (he.size() != 2) he.fail("half_extents is [hx, hy]");
    const double hx = he.at(0).asPositive(), hy = he.at(1).asPositive();
    const double h = r.get("height").asPositive(), t = r.numberOr("thickness", 0.1);
    if (!(t > 0) || std::max({hx, hy, h, t}) > kMaxSceneCoordinate) r.node().fail("the bin's sizes must be in (0, 1e5]");
    r.finish();
    const auto wall = [&](const Vec3& half, const Vec3& at) {
        bodies.push_back(worldBody(worldBox(half), Transform{at, Quat::Identity()}, true));
    };
    wall(Vec3(0.5 * t, hy + t, 0.5 * h), Vec3(-hx - 0.5 * t, 0, 0.5 * h));
    wall(Vec3(0.5 * t, hy + t, 0.5 * h), Vec3(hx + 0.5 * t, 0, 0.5 * h));
    wall(Vec3(hx, 0.5 * t, 0.5 * h), Vec3(0, -hy - 0.5 * t, 0.5 * h));
    wall(Vec3(hx, 0.5 * t, 0.5 * h), Vec3(0, hy + 0.5 * t, 0.5 * h));
}

WorldOptions readSimulation(ObjectReader& r, int& steps) {
    WorldOptions o;
    double duration = 2.0;
    if (auto s = r.find("simulation")) {
        ObjectReader sr(*s);
        if (auto t = sr.find("time_step")) {
            o.timeStep = t->asPositive();
            if (o.timeStep > 0.1) t->fail("time_step must be at most 0.1 s");
        }
        if (auto t = sr.find("duration")) duration = t->asPositive();
        if (auto t = sr.find("velocity_iterations")) o.velocityIterations = t->asInt(1, 100);
        if (auto t = sr.find("position_iterations")) o.positionIterations = t->asInt(0, 100);
        if (auto t = sr.find("substeps")) o.substeps = t->asInt(1, 16);
        if (auto t = sr.find("slop")) o.slop = t->asNonNegative();
        if (auto t = sr.find("restitution_threshold")) o.restitutionThreshold = t->asNonNegative();
        if (auto t = sr.find("warm_start")) o.warmStart = t->asBool();
        if (auto t = sr.find("broad_phase")) {
            const std::string b = t->asEnum({"sap", "tree", "grid"});
            o.broadPhase = b == "sap" ? BroadPhaseKind::SweepAndPrune : b == "tree" ? BroadPhaseKind::DynamicTree : BroadPhaseKind::Grid;
        }
        if (auto t = sr.find("gravity")) {
            const double g = t->asNonNegative();
            requireAtMost(*t, g, kMaxGravity, "gravity", "the physical range a world scene accepts");
            o.gravity = Vec3(0, 0, -g);
        }
        sr.finish();
    }
    const double n = std::round(duration / o.timeStep);
    if (!(n >= 1 && n <= 20000))
        (r.has("simulation") ? r.get("simulation") : r.node()).fail("duration / time_step must give 1..20000 steps");
    steps = int(n);
    return o;
}

class WorldScene final : public PreparedScene {
public:
    WorldScene(SceneCommon common, std::vector<WorldBodyDesc> bodies, WorldOptions options, int steps, int frameEvery,
               int pipelineStep)
        : PreparedScene(std::move(common)),
          bodies_(std::move(bodies)),
          options_(options),
          steps_(steps),
          frameEvery_(frameEvery),
          pipelineStep_(pipelineStep) {}

    DemoOutput execute(const RunContext& ctx) const override {
        WorldOptions options = options_;
        options.maxPairs = kPairsPerBody * std::int64_t(std::max<std::size_t>(bodies_.size(), 50));
        World world(bodies_, options);
        WorldRun run;
        run.options = world.options();
        for (int i = 0; i < world.bodyCount(); ++i) {
            run.shapes.push_back(world.shape(i));
            run.isStatic.push_back(world.body(i).isStatic());
        }
        DemoOutput out;
        Json steps = Json::array();
        for (int k = 1; k <= steps_; ++k) {
            world.collide();
            const bool frame = (k - 1) % frameEvery_ == 0 && int(run.frames.size()) < kMaxWorldFrames;
            const bool pipeline = k == pipelineStep_;
            StepSnapshot snap;
            if (frame || pipeline) snap = snapshotBefore(world, k, pipeline);
            const WorldStepStats st = world.solve();
            if (!world.ok()) throw InputError(common_.file + ": " + world.message());
            run.stats.push_back(st);
            steps.push_back({{"step", st.step},
                             {"time", st.time},
                             {"broad_pairs", st.broadPairs},
                             {"plane_pairs", st.planePairs},
                             {"narrow_tests", st.narrowTests},
                             {"cached_axis_skips", st.cachedAxisSkips},
                             {"manifolds", st.manifolds},
                             {"contact_points", st.contactPoints},
                             {"warm_started_points", st.warmStartedPoints},
                             {"kinetic", st.kinetic},
                             {"potential", st.potential},
                             {"momentum", vec3Json(st.momentum)},
                             {"deepest_penetration", st.deepestPenetration}});
            if (!frame && !pipeline) continue;
            snapshotAfter(world, st, snap);
            for (const ContactSnapshot& c : snap.contacts) run.maxImpulse = std::max(run.maxImpulse, c.impulse);
            if (frame) run.frames.push_back(snap);
            if (pipeline) run.pipeline = snap, run.hasPipeline = true;
        }
        out.trace = traceJson(world, steps);
        if (numericOnly(ctx, out)) return out;
        for (const WorldShape& s : run.shapes) run.meshes.push_back(bodyMesh(s));
        const int ss = figureScale(common_, ctx);
        for (std::size_t i = 0; i < run.frames.size(); ++i)
            out.frames.push_back(drawWorldFrame(*ctx.gl, ss, common_, run, run.frames[i], int(i)));
        if (run.hasPipeline && common_.hasLayer("pipeline"))
            out.frames.push_back(drawPipelineFrame(*ctx.gl, ss, common_, run));
        else
            out.skipped.push_back("pipeline frame (no pipeline_step or no 'pipeline' layer)");
        if (common_.hasLayer("plot"))
            for (Frame& f : drawWorldPlots(*ctx.gl, ss, common_, run)) out.frames.push_back(std::move(f));
        else
            out.skipped.push_back("per-step plots (no 'plot' layer)");
        return out;
    }

private:
    std::vector<WorldBodyDesc> bodies_;
    WorldOptions options_;
    int steps_, frameEvery_, pipelineStep_;

    StepSnapshot snapshotBefore(const World& w, int k, bool pipeline) const {
        StepSnapshot s;
        s.step = k;
        s.time = (k - 1) * options_.timeStep;
        for (int i = 0; i < w.bodyCount(); ++i) s.poses.push_back(w.body(i).transform());
        if (pipeline) {
            s.grownBoxes = w.grownBoxes();
            s.pairs = w.broadPairs();
        }
        return s;
    }

    static void snapshotAfter(const World& w, const WorldStepStats& st, StepSnapshot& s) {
        s.stats = st;
        s.touching.assign(std::size_t(w.bodyCount()), 0);
        for (std::size_t m = 0; m < w.manifolds().size(); ++m) {
            const WorldManifold& man = w.manifolds()[m];
            for (const WorldContact& c : man.points) {
                s.contacts.push_back({man.a, man.b, 0.5 * (c.point.pointA + c.point.pointB), man.normal,
                                      c.point.separation, c.normalImpulse});
                s.manifoldPairs.push_back(int(m));
                if (c.normalImpulse > 0) s.touching[std::size_t(man.a)] = s.touching[std::size_t(man.b)] = 1;
            }
        }
    }

    Json traceJson(const World& w, Json& steps) const {
        Json t;
        const WorldOptions& o = w.options();
        t["options"] = {{"time_step", o.timeStep},
                        {"velocity_iterations", o.velocityIterations},
                        {"position_iterations", o.positionIterations},
                        {"substeps", o.substeps},
                        {"slop", o.slop},
                        {"speculative_distance", o.speculativeDistance},
                        {"broad_phase", nameOf(o.broadPhase)},
                        {"warm_start", o.warmStart},
                        {"gravity", vec3Json(o.gravity)}};
        t["bodies"] = w.bodyCount();
        t["steps"] = std::move(steps);
        Json finalPoses = Json::array();
        for (int i = 0; i < w.bodyCount(); ++i) {
            const RigidBody& b = w.body(i);
            finalPoses.push_back({{"kind", nameOf(w.shape(i).kind)},
                                  {"position", vec3Json(b.position)},
                                  {"orientation", Json::array({b.orientation.w(), b.orientation.x(), b.orientation.y(),
                                                               b.orientation.z()})},
                                  {"linear_velocity", vec3Json(b.linearVelocity)}});
        }
        t["final"] = std::move(finalPoses);
        return t;
    }
};

class WorldDemo final : public Demo {
public:
    std::string name() const override { return "world"; }
    std::string description() const override {
        return "many bodies together: broad phase, narrow phase, persistent manifolds, sequential impulses";
    }
    SceneFormat sceneFormat() const override { return {kWorldLayers, ImageSettings{1280, 640}, {960, 480}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        std::vector<WorldBodyDesc> bodies;
        if (r.boolOr("ground", true)) bodies.push_back(worldBody(worldPlane(Vec3::UnitZ(), 0.0), Transform{}));
        if (auto b = r.find("bin")) readBin(*b, bodies);
        if (auto b = r.find("bodies"))
            for (const JsonNode& n : b->items()) {
                if (bodies.size() >= std::size_t(kMaxWorldBodies)) n.fail("at most 2000 bodies in a world scene");
                bodies.push_back(readBody(n));
            }
        if (auto l = r.find("lattice")) readLattice(*l, bodies);
        int steps = 0;
        WorldOptions options = readSimulation(r, steps);
        options.speculativeDistance = 4.0 * options.slop;  // Box2D's ratio: contacts this close are kept before they touch
        // The solver's regime: the slop (allowed penetration) below every body's size, and gravity
        // moving a resting body much less than the smallest one in a step (a 1e-5 box at 1000 m/s²
        // walked 9 m and gained energy 28 000-fold: the hostile review).
        double smallest = INFINITY;
        for (const WorldBodyDesc& b : bodies)
            if (b.shape.kind != WorldShape::Kind::Plane) smallest = std::min(smallest, b.shape.boundingRadius);
        const JsonNode& at = r.has("simulation") ? r.get("simulation") : r.node();
        if (smallest < options.slop)
            at.fail("the smallest body (radius " + formatNumber(smallest) + ") is smaller than the slop " +
                    formatNumber(options.slop) + ": set a smaller slop");
        const double fall = options.gravity.norm() * options.timeStep * options.timeStep;
        if (fall > 0.25 * smallest)
            at.fail("gravity moves a body g dt² = " + formatNumber(fall) + " a step, more than a quarter of the smallest body (" +
                    formatNumber(smallest) + "): set a smaller time_step");
        const double sweeps = options.substeps * double(options.velocityIterations + options.positionIterations);
        const double work = double(bodies.size()) * steps * std::max(1.0, sweeps / 14.0);
        if (work > kMaxBodySteps)
            r.node().fail(std::to_string(bodies.size()) + " bodies for " + std::to_string(steps) + " steps" +
                          (sweeps > 14 ? " at " + formatNumber(sweeps) + " sweeps a step (14 by default)" : std::string()) +
                          " is over the 6e5 body-steps a world scene may run");
        int frameEvery = std::max(1, steps / 6);
        if (auto k = r.find("frame_every")) frameEvery = k->asInt(1, 20000);
        if ((steps - 1) / frameEvery + 1 > kMaxWorldFrames)
            r.get("frame_every").fail("frame_every gives more than 12 frames");
        int pipelineStep = 0;
        if (auto p = r.find("pipeline_step")) pipelineStep = p->asInt(0, steps);
        r.finish();
        const World check(bodies, options);  // the world's own checks (options, bodies) before any step
        if (!check.ok()) r.node().fail(check.message());
        common.frames = {kMaxWorldFrames + 4, kMaxWorldFrames + 4, common.image.width};
        return std::make_unique<WorldScene>(std::move(common), std::move(bodies), options, steps, frameEvery,
                                            pipelineStep);
    }
};

}  // namespace

BodyMesh bodyMesh(const WorldShape& shape) {
    BodyMesh m;
    ConvexPolyhedron solid;
    switch (shape.kind) {
        case WorldShape::Kind::Box:
        case WorldShape::Kind::Hull: solid = shape.hull; break;
        case WorldShape::Kind::Sphere: solid = presets::geodesicSphere(1, shape.radius); break;
        case WorldShape::Kind::Capsule: {
            const ConvexPolyhedron ball = presets::geodesicSphere(1, shape.radius);
            std::vector<Vec3> pts;
            for (const Vec3& p : ball.positions()) {
                pts.push_back(p + Vec3(0, shape.halfHeight, 0));
                pts.push_back(p - Vec3(0, shape.halfHeight, 0));
            }
            HullResult h = convexHull(pts);
            if (h.ok()) solid = std::move(h.polyhedron);
            break;
        }
        case WorldShape::Kind::Plane: return m;
    }
    m.vertices = solid.positions();
    for (int f = 0; f < solid.faceCount(); ++f) {
        const std::vector<int> fv = solid.faceVertices(f);
        for (std::size_t i = 1; i + 1 < fv.size(); ++i) m.triangles.emplace_back(fv[0], fv[i], fv[i + 1]);
    }
    if (shape.polytope())
        for (int e = 0; e < solid.edgeCount(); ++e) m.edges.push_back(solid.edgeVertices(e));
    return m;
}

const Demo& worldDemo() {
    static const WorldDemo demo;
    return demo;
}

}  // namespace cdlab::demos
