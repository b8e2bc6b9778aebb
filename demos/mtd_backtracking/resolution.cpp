#include "demos/mtd_backtracking/resolution.h"

#include <algorithm>
#include <cmath>

#include "core/cast/time_of_impact.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"

namespace cdlab::demos {

namespace {

Json vec2Json(const Vec3& v) { return Json::array({v.x() + 0.0, v.y() + 0.0}); }  // + 0.0: no "-0" in the trace

Json poseJson(const Transform& pose) {
    return {{"position", vec2Json(pose.position)}, {"angle_degrees", angleDegrees(pose)}};
}

}  // namespace

std::vector<Vec3> prismOf(const std::vector<Vec2>& polygon, double halfThickness) {
    std::vector<Vec3> v;
    for (const Vec2& p : polygon)
        for (double z : {-halfThickness, halfThickness}) v.emplace_back(p.x(), p.y(), z);
    return v;
}

std::vector<Vec3> outlineAt(const std::vector<Vec2>& body, const Transform& pose) {
    std::vector<Vec3> out;
    for (const Vec2& p : body) out.push_back(pose.apply(Vec3(p.x(), p.y(), 0)));
    return out;
}

double angleDegrees(const Transform& pose) {
    return 2.0 * std::atan2(pose.rotation.z(), pose.rotation.w()) * 180.0 / M_PI;
}

ResolutionRun runResolution(const ResolutionInput& in) {
    ResolutionRun run;
    run.end = poseAt(in.start, in.motion, 1.0);
    // Prisms ten times thicker than the scene is wide: EPA's least-depth direction and GJK's closest
    // one stay in the plane (leaving through a z face would need more than the scene's size).
    double extent = in.motion.linear.norm() + in.start.position.norm();
    for (const std::vector<Vec2>* poly : {&in.a, &in.b})
        for (const Vec2& p : *poly) extent = std::max(extent, p.norm());
    const double half = 10.0 * (extent + 1e-3);
    const std::vector<Vec3> a = prismOf(in.a, half), bodyB = prismOf(in.b, half);
    std::vector<Vec3> bEnd;
    for (const Vec3& p : bodyB) bEnd.push_back(run.end.apply(p));

    // 1. EPA at the end pose (Ericson §9.5 / van den Bergen 2001): B moves by depth · n.
    const EpaResult e = penetration(PolytopeShape(a), PolytopeShape(bEnd));
    run.penetrating = e.status == EpaStatus::Penetrating;
    run.mtd = run.end;
    if (run.penetrating) {
        run.depth = e.depth;
        run.normal = Vec3(e.normal.x(), e.normal.y(), 0.0).normalized();  // the prisms' z answers are 0
        run.pointA = Vec3(e.pointA.x(), e.pointA.y(), 0.0);
        run.pointB = Vec3(e.pointB.x(), e.pointB.y(), 0.0);
        run.mtd.position += run.depth * run.normal;
    }

    // 2. Backtracking: the linear cast from the start position, turned as at the end (van den Bergen 2004).
    Transform turned = run.end;
    turned.position = in.start.position;
    std::vector<Vec3> bStart;
    for (const Vec3& p : bodyB) bStart.push_back(turned.apply(p));
    const TimeOfImpactResult toi = translationalTimeOfImpact(a, 0.0, Vec3::Zero(), bStart, 0.0, in.motion.linear);
    run.backtrackHit = toi.hit;
    run.backtrackAtStart = toi.initiallyOverlapping;
    run.backtrackT = toi.hit ? toi.t : 1.0;
    run.backtrackNormal = Vec3(toi.normal.x(), toi.normal.y(), 0.0);
    run.backtrackPoint = Vec3(toi.pointA.x(), toi.pointA.y(), 0.0);
    run.backtrack = turned;
    run.backtrack.position += run.backtrackT * in.motion.linear;

    // 3. Conservative advancement along the true motion (Mirtich 1996).
    AdvancementOptions options;
    options.tolerance = in.tolerance;
    run.advance = conservativeAdvancement(a, bodyB, in.start, in.motion, options, &run.advanceTrace);
    for (AdvancementStep& s : run.advanceTrace.steps) {  // the plane's points (the prisms' z is arbitrary)
        s.pointA.z() = 0.0;
        s.pointB.z() = 0.0;
    }
    run.advanced = poseAt(in.start, in.motion, run.advance.t);
    return run;
}

Json resolutionJson(const ResolutionRun& run) {
    Json steps = Json::array();
    for (const AdvancementStep& s : run.advanceTrace.steps)
        steps.push_back({{"t", s.t},
                         {"distance", s.distance},
                         {"normal", vec2Json(s.normal)},
                         {"speed_bound", s.speedBound},
                         {"step", std::isfinite(s.step) ? Json(s.step) : Json(nullptr)}});
    Json j;
    j["end_pose"] = poseJson(run.end);
    j["mtd"] = {{"penetrating", run.penetrating}};
    if (run.penetrating) {
        j["mtd"]["depth"] = run.depth;
        j["mtd"]["normal"] = vec2Json(run.normal);
        j["mtd"]["point_a"] = vec2Json(run.pointA);
        j["mtd"]["point_b"] = vec2Json(run.pointB);
        j["mtd"]["pose"] = poseJson(run.mtd);
    }
    j["backtrack"] = {{"hit", run.backtrackHit}, {"initially_overlapping", run.backtrackAtStart}};
    if (run.backtrackHit) {
        j["backtrack"]["t"] = run.backtrackT;
        j["backtrack"]["pose"] = poseJson(run.backtrack);
        if (!run.backtrackAtStart) j["backtrack"]["normal"] = vec2Json(run.backtrackNormal);
    }
    j["advance"] = {{"outcome", nameOf(run.advance.outcome)},
                    {"t", run.advance.t},
                    {"distance", run.advance.distance},
                    {"steps", steps},
                    {"pose", poseJson(run.advanced)}};
    return j;
}

}  // namespace cdlab::demos
