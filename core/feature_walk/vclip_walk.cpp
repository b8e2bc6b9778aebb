// The V-Clip feature walk: vclip() (seed, state loop, result and trace) here; the five states in
// vclip_walk_states.cpp; clipEdge, the derivative checks and the pair geometry in vclip_walk_internal.h.
// B. Mirtich, "V-Clip: Fast and Robust Polyhedral Collision Detection", ACM TOG 17(3) 1998
// (MERL TR-97-05), §4 (clipping, derivative checks) and §5 (state update rules).
//
// Conventions. Body 0 is A, body 1 is B; X[i] is the current feature of body i. A point of body o
// is tested against a region of body r after mapping it into r's frame (toFrame), as in the
// paper, so world offsets never enter a plane test. Region distances are positive INSIDE the
// region. An edge is e(l) = tail + l (head - tail), l in [0, 1].
//
// Numerics: every branch takes the sign of a plane distance or of a derivative computed in double;
// plane tests use no tolerance, derivatives and distances a rounding floor only (kRound below: a
// value below the rounding of its coordinates has no sign). Regions are closed (distance 0 =
// inside), so every point is in at least one region and ties go to the current feature (no update). Distances that are
// exactly 0 at a clip point or a DONE pair are reported as touching (Penetrating). The walk is
// kept monotone (see below), which makes it terminate in exact arithmetic; the repeated-pair
// detector and the step bound only guard against rounding and never fire in the test suite.
//
// Where cdlab departs from the paper's text (to keep "distance never increases" exact):
//   - V-F with V outside a side plane, E-F with E excluded from VR(F), and E-F with the distance
//     increasing at a clipped end inside VR(F): the face is replaced by its boundary feature
//     nearest to V (resp. E), an edge or, when the nearest point is a corner, a vertex, found by
//     an O(|F|) scan. The paper picks the most violated plane / Nmin, which can be an edge
//     farther than the nearest one (the distance would rise). Taking the corner vertex rather than
//     one of its two edges matters: E-E may raise an edge E' to a face F whose closest point to E
//     is E''s endpoint (distance equal, not smaller), and going back to E' from F would repeat the
//     pair (tests/core/feature_walk/vclip_test.cpp, "642-vertex geodesic sphere ...", checks it ends).
//   - E-E compound exclusion: decided from the closest pair of the two segments (the endpoint
//     vertex if the closest point of E' is an endpoint, else the face whose FE plane the closest
//     point of E violates); the paper's implementation compares face-plane distances there.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/base/tolerances.h"
#include "core/closest/closest_point.h"
#include "core/feature_walk/feature_walk_pair.h"
#include "core/feature_walk/vclip.h"
#include "core/feature_walk/vclip_walk_internal.h"

namespace cdlab {
namespace {

using FT = VClipFeatureType;
using feature_walk::finitePose;
using feature_walk::maxAbs;
using feature_walk::validFeature;
using vclip_internal::kRound;
using vclip_internal::PairClosest;
using vclip_internal::VClipOutcome;
using vclip_internal::VClipWalk;

// The trace step of the pair before it moves: the state, the features and their closest points.
VClipTraceStep* beginTraceStep(VClipTrace* trace, const VClipWalk& w, int step) {
    if (!trace) return nullptr;
    VClipTraceStep* ts = &trace->steps.emplace_back();
    ts->step = step;
    const FT ta = w.X[0].type, tb = w.X[1].type;
    const int lo = std::min(static_cast<int>(ta), static_cast<int>(tb)),
              hi = std::max(static_cast<int>(ta), static_cast<int>(tb));
    ts->state = lo == 1 ? (hi == 1   ? VClipState::VertexVertex
                           : hi == 2 ? VClipState::VertexEdge
                                     : VClipState::VertexFace)
                        : (hi == 2 ? VClipState::EdgeEdge : VClipState::EdgeFace);
    ts->featureA = w.X[0];
    ts->featureB = w.X[1];
    ts->featureAWorld = featureGeometry(*w.P[0], w.pose[0], w.X[0]);
    ts->featureBWorld = featureGeometry(*w.P[1], w.pose[1], w.X[1]);
    int frame = 0;
    const PairClosest pc = w.closest(w.X[0], w.X[1], frame);
    ts->closestA = w.world(frame, pc.p[0]);
    ts->closestB = w.world(frame, pc.p[1]);
    ts->distanceBefore = ts->distanceAfter = pc.distance;
    return ts;
}

// The distance after an update and its sign of change. Equal in exact arithmetic, computed by
// different formulas: allow rounding of ~1e-12 of the size of the bodies (formula errors are
// ~1e-15 of it).
void recordUpdate(VClipTraceStep* ts, const VClipWalk& w, const VClipOutcome& out, const VClipFeature& from, double extent) {
    if (!ts) return;
    ts->updatedBody = out.body;
    ts->from = from;
    ts->to = out.to;
    int frame = 0;
    ts->distanceAfter = w.closest(w.X[0], w.X[1], frame).distance;
    const double tol = 1e-12 * (extent + ts->distanceBefore);
    const double diff = ts->distanceAfter - ts->distanceBefore;
    ts->distanceChange = diff > tol ? 1 : diff < -tol ? -1 : 0;
}

// The answer when the walk stops: penetrating, touching (DONE at a distance below the rounding of
// the features' coordinates) or separated at the closest points.
void finalAnswer(const VClipWalk& w, const VClipOutcome& out, VClipTraceStep* ts, VClipResult& res) {
    if (out.kind == VClipStepKind::Penetration) {
        res.status = VClipStatus::Penetrating;
        res.penetration = out.penetration;
        res.intersect = true;
        res.distance = 0.0;
        res.pointA = res.pointB = w.world(out.pointBody, out.point);
        return;
    }
    int frame = 0;
    const PairClosest pc = w.closest(w.X[0], w.X[1], frame);
    if (pc.distance <= kRound * (maxAbs(pc.p[0]) + maxAbs(pc.p[1]))) {
        res.status = VClipStatus::Penetrating;
        res.penetration = VClipPenetration::Touching;
        res.intersect = true;
        res.pointA = res.pointB = w.world(frame, pc.p[0]);
        if (ts) ts->kind = VClipStepKind::Penetration;
    } else {
        res.status = VClipStatus::Separated;
        res.distance = pc.distance;
        res.pointA = w.world(frame, pc.p[0]);
        res.pointB = w.world(frame, pc.p[1]);
        res.normal = w.Rw[frame] * ((pc.p[1] - pc.p[0]) / pc.distance);
    }
}

}  // namespace

// Mirtich 1998 (see the top of this file): from the seed pair, apply the state's update rule
// until it reports DONE or penetration; a repeated pair or the step bound stops a rounding loop.
VClipResult vclip(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b, const Transform& poseB,
                  VClipCache* cache, const VClipOptions& options, VClipTrace* trace) {
    VClipResult res;
    if (trace) *trace = VClipTrace{};
    auto fail = [&](VClipStatus status, std::string message) {
        res.status = status;
        res.message = std::move(message);
        if (trace) trace->status = status;
        return res;
    };
    if (a.empty() || b.empty()) return fail(VClipStatus::InvalidInput, "vclip: empty polyhedron");
    if (!finitePose(poseA) || !finitePose(poseB)) return fail(VClipStatus::InvalidInput, "vclip: non-finite pose");

    VClipWalk w;
    w.setup(a, poseA, b, poseB);
    // Seed: the cached pair if valid, else vertex 0 of each. F-F is never a state: B's face is
    // replaced by one of its vertices.
    if (cache && validFeature(a, cache->a) && validFeature(b, cache->b)) {
        w.X[0] = cache->a;
        w.X[1] = cache->b;
        if (w.X[0].type == FT::Face && w.X[1].type == FT::Face)
            w.X[1] = VClipFeature::vertex(b.mesh().halfEdge(b.mesh().face(w.X[1].index).halfEdge).origin);
    }

    const long long bound = static_cast<long long>(a.featureCount()) * b.featureCount();
    const long long maxSteps = options.maxSteps > 0 ? options.maxSteps : bound;
    feature_walk::FeaturePairCycle cycle(w.X[0], w.X[1]);
    double extent = 0.0;  // trace only: scale for "equal" distances
    if (trace)
        extent = std::max((a.mesh().boundsMax() - a.mesh().boundsMin()).norm(),
                          (b.mesh().boundsMax() - b.mesh().boundsMin()).norm());

    for (int steps = 0;; ++steps) {
        res.steps = steps;
        res.featureA = w.X[0];
        res.featureB = w.X[1];
        if (options.detectCycles && steps > 0 && cycle.repeats(w.X[0], w.X[1])) {
            if (cache) *cache = VClipCache{w.X[0], w.X[1]};
            if (trace && !trace->steps.empty()) trace->steps.back().kind = VClipStepKind::Aborted;
            return fail(VClipStatus::CycleDetected,
                        "vclip: feature pair " + nameOf(w.X[0]) + "/" + nameOf(w.X[1]) + " repeated");
        }
        if (steps >= maxSteps) {
            if (cache) *cache = VClipCache{w.X[0], w.X[1]};
            return fail(VClipStatus::StepLimit, "vclip: step limit " + std::to_string(maxSteps) + " reached");
        }
        VClipTraceStep* ts = beginTraceStep(trace, w, steps);
        w.ts = ts;
        const VClipOutcome out = w.step();
        if (ts) {
            ts->kind = out.kind;
            ts->rule = out.rule;
            ts->localMinimum = out.localMin;
        }
        if (out.kind == VClipStepKind::Update) {
            const VClipFeature from = w.X[out.body];
            w.X[out.body] = out.to;
            recordUpdate(ts, w, out, from, extent);
            continue;
        }
        if (cache) *cache = VClipCache{w.X[0], w.X[1]};
        finalAnswer(w, out, ts, res);
        if (trace) trace->status = res.status;
        return res;
    }
}

}  // namespace cdlab
