// Conservative advancement for a rotating and translating convex body against a still one
// (Mirtich, "Impulse-based Dynamic Simulation of Rigid Body Systems", PhD thesis 1996, §2.3.2;
// Ericson, Real-Time Collision Detection §5.5.9 for the translational case).
//
// Body B moves over t in [0, 1]: its pose at time t turns by t·angular (axis-angle, radians, world
// axis through its centre, the pose's position) and moves by t·linear. A is still. At each step the
// distance d between A and B(t) and the closest direction n (from A toward B) come from GJK; no point
// of B can approach A along n faster than
//     μ = max(0, −linear·n) + |angular| · r_max,   r_max = the largest distance of B's points from its
//                                                  turning axis (the line through its centre along angular),
// so B cannot touch A before t + d / μ: the step. Repeat until d <= tolerance (the time of impact, to
// within tolerance / μ), t passes 1 (no contact) or the step budget runs out (reported, never a loop).
// When B does not turn (angular = 0) this is exact-step linear advancement.
#pragma once

#include <vector>

#include "core/base/types.h"
#include "core/geometry/shapes.h"

namespace cdlab {

struct RigidMotion {
    Vec3 linear = Vec3::Zero();   ///< translation of B's centre over t in [0, 1]
    Vec3 angular = Vec3::Zero();  ///< rotation over t in [0, 1]: axis · angle (radians), about B's centre
};

/// B's pose at time t: start turned by t·angular about its own centre, moved by t·linear.
Transform poseAt(const Transform& start, const RigidMotion& motion, double t);

struct AdvancementOptions {
    double tolerance = 1e-6;  ///< world units: contact once the distance is at most this
    /// When the turn dominates μ the steps shrink geometrically near contact (each closes a fraction
    /// of the gap), so reaching a small tolerance can take hundreds of steps.
    int maxSteps = 1000;
};

/// One advancement step, for demos: the state at t and the step it allows.
struct AdvancementStep {
    double t = 0.0;
    double distance = 0.0;
    Vec3 normal = Vec3::Zero();  ///< unit, from A toward B (zero when touching)
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    double speedBound = 0.0;     ///< μ at this step
    double step = 0.0;           ///< d / μ (0 on the last step)
};
struct AdvancementTrace {
    std::vector<AdvancementStep> steps;
};

struct AdvancementResult {
    enum class Outcome {
        Contact,             ///< distance <= tolerance at t (the first contact, conservatively)
        InitiallyTouching,   ///< already within tolerance (or overlapping) at t = 0
        NoContact,           ///< the advancement passed t = 1 with the bodies apart
        StepBudget,          ///< maxSteps ran out before either (t is how far it got, still apart)
        InvalidInput,        ///< empty body, NaN / inf
    };
    Outcome outcome = Outcome::InvalidInput;
    double t = 0.0;
    double distance = 0.0;
    Vec3 normal = Vec3::Zero();
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    int steps = 0;
};
const char* nameOf(AdvancementResult::Outcome outcome);

/// A (world-frame points, still) against B (body-frame points, at `startB`, moving by `motion`).
AdvancementResult conservativeAdvancement(const std::vector<Vec3>& a, const std::vector<Vec3>& bodyB,
                                          const Transform& startB, const RigidMotion& motion,
                                          const AdvancementOptions& options = {}, AdvancementTrace* trace = nullptr);

}  // namespace cdlab
