// Lin–Canny closest-feature tracking: the predecessor of V-Clip, on the same polyhedra and features.
//
// Sources: M. C. Lin, J. F. Canny, "A Fast Algorithm for Incremental Distance Calculation",
// IEEE ICRA 1991; M. C. Lin, "Efficient Collision Detection for Animation and Robotics", PhD
// thesis, UC Berkeley 1993, ch. 3; the summary in B. Mirtich, "V-Clip", ACM TOG 17(3) 1998, §2.
//
// Outline (one step):
//   1. Closest points of the current feature pair (XA, XB): point–point, point–segment,
//      segment–segment, point–polygon, segment–polygon or polygon–polygon (all six pairs, F-F
//      included; V-Clip never needs the last three). Computed in A's body frame.
//   2. Applicability test: the point of XB must lie in VR(XA) and the point of XA in VR(XB). A
//      region is the intersection of half-spaces bounded by the same VE / FE planes V-Clip uses
//      (VClipPolyhedron::planes()); a face region is also bounded below by the face plane.
//   3. If a plane of VR(XA) is violated, XA is replaced by the neighbour across the most
//      violated plane (then the same for XB); if both points pass, the pair is the closest pair
//      and the distance is |pA - pB| (Lin & Canny, Thm. 1: points in each other's regions).
//   4. A point behind the plane of face F while inside F's side planes has no neighbour of F to go
//      to (Lin 1993 §3.3 "local minimum"): F is replaced by the face of that body whose plane the
//      point lies farthest in front of (or least behind: the original has no inside test; with
//      LinCannyOptions::insideTest a point behind every face plane is reported as penetration).
// The distance decreases strictly at every update on separated bodies (Lin & Canny §4) up to the
// local-minimum jumps and the tolerances below. What the original lacks is a penetration test for
// the general case: on interpenetrating bodies the pair distance is no longer monotone and the walk
// can go round a cycle of feature pairs for ever (Mirtich §2: 4,489 cycles in 10^5 degenerate
// trials). cdlab detects that: the walk is a deterministic function of the pair, so a repeated pair
// IS a cycle; Brent's algorithm (R. P. Brent, "An improved Monte Carlo factorization algorithm",
// BIT 20, 1980) finds it in O(1) memory within ~2 x (tail + cycle length) steps, and a step bound
// backs it up. A cycle is reported as CycleDetected, never as a distance.
//
// Tolerances (all relative to `scale`, the largest coordinate magnitude in A's frame): see
// LinCannyOptions and the comments at each use in lin_canny.cpp.
//
// Warm start (coherence): pass a LinCannyCache (same as V-Clip's); the final pair seeds the next call.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/tolerances.h"
#include "core/base/types.h"
#include "core/closest/feature_distance.h"
#include "core/feature_walk/vclip.h"

namespace cdlab {

enum class LinCannyStatus {
    Separated,      ///< distance > 0; points, features and distance meaningful
    Penetrating,    ///< the bodies intersect or touch; see LinCannyResult::penetration
    CycleDetected,  ///< a feature pair repeated: the walk would loop for ever (typically penetration)
    StepLimit,      ///< more than maxSteps updates without a detected cycle (detectCycles off)
    InvalidInput,   ///< empty polyhedron, non-finite pose, or a seed feature out of range
};

/// "Separated", "Penetrating", "CycleDetected", "StepLimit", "InvalidInput".
const char* nameOf(LinCannyStatus status);

/// How a penetration was found.
enum class LinCannyPenetration : std::uint8_t {
    None,
    FeaturesMeet,  ///< the current pair is at distance <= the touching tolerance (touching counts)
    PointInside,   ///< a closest point of one body lies behind every face plane of the other
};

/// "None", "FeaturesMeet", "PointInside".
const char* nameOf(LinCannyPenetration how);

/// Seed pair in, final pair out; same type as V-Clip's (invalid = cold start from vertex 0 / 0).
using LinCannyCache = VClipCache;

struct LinCannyOptions {
    /// Update cap; <= 0 means (VA+EA+FA)(VB+EB+FB), the number of feature pairs (a walk without a
    /// repeat can never be longer).
    int maxSteps = 0;
    /// Brent cycle detection on the feature pair. Off: only maxSteps stops a cycling walk (shows
    /// what the original does).
    bool detectCycles = true;
    /// cdlab's addition: stop with Penetrating (PointInside) when a closest point lies behind every
    /// face plane of the other body (V-Clip's handleLocalMin test, Mirtich §5.4). Off (default):
    /// the original rule, the local-minimum jump goes to the least-behind face, and penetrating
    /// bodies may cycle (then CycleDetected).
    bool insideTest = false;
    /// Applicability tolerance, relative to scale: a point counts as inside a region plane unless it
    /// is more than applicability * scale outside it. Guards the rounding of the closest points
    /// (computed by another formula than the plane test, and mapped between body frames): a closest
    /// point that lies ON a region boundary in exact arithmetic (an edge's clamped endpoint, a
    /// projection onto a face boundary) may land on either side in double, and without slack the
    /// walk can step to the neighbour and straight back. Lin & Canny's implementation has such a
    /// tolerance; 1e-12 is ~4500 ulps, far above the rounding (~10 ulps) and far below any feature.
    /// A negative value makes boundary points violate both neighbouring regions: the walk then
    /// cycles (the tests use that to exercise the cycle detection).
    double applicability = 1e-12;
    /// Touching tolerance, relative to scale: a pair whose closest points are this close is
    /// reported as Penetrating (FeaturesMeet). 16 DBL_EPSILON: the rounding floor of a distance
    /// computed from coordinates of that magnitude (below it the sign of the gap is noise).
    double touching = 16.0 * kMachineEpsilon;
};

struct LinCannyResult {
    LinCannyStatus status = LinCannyStatus::InvalidInput;
    LinCannyPenetration penetration = LinCannyPenetration::None;
    bool intersect = false;      ///< status == Penetrating
    double distance = 0.0;       ///< Separated: the distance (world units); else 0
    Vec3 pointA = Vec3::Zero();  ///< Separated: closest point on A, world. Penetrating: a common
    Vec3 pointB = Vec3::Zero();  ///<   point (FeaturesMeet: the pair's midpoint; PointInside: the point)
    Vec3 normal = Vec3::Zero();  ///< Separated: unit (pointB - pointA) / distance, else zero
    VClipFeature featureA;       ///< final features (closest features when Separated)
    VClipFeature featureB;
    int steps = 0;        ///< updates made (0: the seed pair was already closest)
    int cycleLength = 0;  ///< CycleDetected: number of pairs in the cycle
    std::string message;  ///< InvalidInput / CycleDetected / StepLimit: why
};

// ---------------------------------------------------------------------------------------------
// Trace (optional, recorded in every build type). Same shape as VClipTrace where the concepts
// match; everything a demo draws is in WORLD frame.

struct LinCannyTraceStep {
    int step = 0;                         ///< 0-based
    ContactType state = ContactType::VV;  ///< the pair's type (lower dimension first); F-F allowed
    VClipFeature featureA, featureB;      ///< features at the start of the step
    std::vector<Vec3> featureAWorld;      ///< their geometry: 1 point, 2 endpoints or the face polygon
    std::vector<Vec3> featureBWorld;
    Vec3 closestA = Vec3::Zero();  ///< closest points of the pair (the points tested), world
    Vec3 closestB = Vec3::Zero();
    /// Plane tests in the order made: closestB against VR(featureA) (regionBody 0), then closestA
    /// against VR(featureB) (regionBody 1) if the first passed. The face plane itself is recorded
    /// with plane = -1 and neighbor = None (inside = in front of the face). `maximal` marks the
    /// plane whose neighbour was taken.
    std::vector<VClipPlaneTest> planes;
    VClipStepKind kind = VClipStepKind::Update;
    int updatedBody = -1;         ///< Update: 0 = A's feature replaced, 1 = B's
    VClipFeature from, to;        ///< Update: replaced feature and replacement
    std::string rule;             ///< e.g. "pB violates VE(E3 | V1)", "local minimum: F2 -> F5"
    bool localMinimum = false;    ///< the update was a local-minimum face jump
    double distanceBefore = 0.0;  ///< pair distance before / after the update, world units
    double distanceAfter = 0.0;
    int distanceChange = 0;  ///< sign of after - before (1e-12 relative dead band)
};

struct LinCannyTrace {
    std::vector<LinCannyTraceStep> steps;
    LinCannyStatus status = LinCannyStatus::InvalidInput;
    int cycleLength = 0;  ///< CycleDetected: the last cycleLength steps form the cycle
};

/// Closest features and distance of convex polyhedra A and B placed by poseA and poseB
/// (x_world = pose.apply(x_body)) by Lin–Canny feature tracking. cache: seed pair in, final pair
/// out (nullptr: cold start from vertex 0 of each). Outputs in world frame and units; see
/// LinCannyResult for what is meaningful when. Never loops: cycles end with CycleDetected.
LinCannyResult linCanny(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b,
                        const Transform& poseB, LinCannyCache* cache = nullptr, const LinCannyOptions& options = {},
                        LinCannyTrace* trace = nullptr);

}  // namespace cdlab
