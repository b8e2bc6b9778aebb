#include "core/cast/conservative_advancement.h"

#include <algorithm>
#include <cmath>

#include "core/gjk_epa/gjk.h"

namespace cdlab {

Transform poseAt(const Transform& start, const RigidMotion& motion, double t) {
    Transform pose = start;
    const double angle = t * motion.angular.norm();
    if (angle > 0.0) pose.rotation = (Quat(Eigen::AngleAxisd(angle, motion.angular.normalized())) * start.rotation).normalized();
    pose.position = start.position + t * motion.linear;
    return pose;
}

const char* nameOf(AdvancementResult::Outcome outcome) {
    using O = AdvancementResult::Outcome;
    switch (outcome) {
        case O::Contact: return "contact";
        case O::InitiallyTouching: return "initially touching";
        case O::NoContact: return "no contact";
        case O::StepBudget: return "step budget";
        case O::InvalidInput: return "invalid input";
    }
    return "?";
}

AdvancementResult conservativeAdvancement(const std::vector<Vec3>& a, const std::vector<Vec3>& bodyB,
                                          const Transform& startB, const RigidMotion& motion,
                                          const AdvancementOptions& options, AdvancementTrace* trace) {
    using O = AdvancementResult::Outcome;
    AdvancementResult result;
    if (a.empty() || bodyB.empty() || !allFinite(a) || !allFinite(bodyB) || !startB.position.allFinite() ||
        !startB.rotation.coeffs().allFinite() || !motion.linear.allFinite() || !motion.angular.allFinite() ||
        !(options.tolerance >= 0.0))
        return result;
    // r_max: B's points are at most this far from its turning axis (through its centre, the pose's
    // origin, along angular: the axis is fixed in the world and in B alike). Only that part of a point's
    // offset moves it: ω × r = ω × r⊥.
    const double spin = motion.angular.norm();
    const Vec3 axis = spin > 0.0 ? Vec3(startB.rotateInverse(motion.angular / spin)) : Vec3::Zero();  // in B's frame
    double rMax = 0.0;
    for (const Vec3& p : bodyB) rMax = std::max(rMax, (p - p.dot(axis) * axis).norm());
    const PolytopeShape shapeA(a);
    double t = 0.0;
    for (int step = 0; step < std::max(options.maxSteps, 1); ++step) {
        const Transform pose = poseAt(startB, motion, t);
        std::vector<Vec3> b;
        for (const Vec3& p : bodyB) b.push_back(pose.apply(p));
        const GjkResult g = gjkDistance(shapeA, PolytopeShape(b));
        AdvancementStep s;
        s.t = t;
        s.distance = g.intersect() ? 0.0 : g.distance;
        s.normal = g.intersect() ? Vec3::Zero() : g.separatingAxis;
        s.pointA = g.pointA;
        s.pointB = g.pointB;
        result.t = t;
        result.distance = s.distance;
        result.normal = s.normal;
        result.pointA = g.pointA;
        result.pointB = g.pointB;
        result.steps = step + 1;
        if (s.distance <= options.tolerance) {
            result.outcome = step == 0 ? O::InitiallyTouching : O::Contact;
            if (trace) trace->steps.push_back(s);
            return result;
        }
        // How fast can B close the gap along n: its centre's approach plus the fastest turning point.
        s.speedBound = std::max(0.0, -motion.linear.dot(s.normal)) + spin * rMax;
        s.step = s.speedBound > 0.0 ? s.distance / s.speedBound : INFINITY;
        if (trace) trace->steps.push_back(s);
        if (!(t + s.step <= 1.0)) {
            result.outcome = O::NoContact;
            return result;
        }
        t += s.step;
    }
    result.outcome = O::StepBudget;
    return result;
}

}  // namespace cdlab
