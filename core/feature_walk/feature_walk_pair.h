// What V-Clip (vclip_walk.cpp) and Lin–Canny (lin_canny.cpp) share: the two bodies and their
// relative frames, the checks on their input, and the detector of a repeated feature pair.
#pragma once

#include "core/base/types.h"
#include "core/feature_walk/vclip.h"

namespace cdlab::feature_walk {

/// The pair of bodies a walk runs on: meshes, poses (rotations normalised), the rotation
/// matrices, the relative frames and the current pair of features X[0] on A, X[1] on B.
struct WalkPair {
    const VClipPolyhedron* P[2] = {nullptr, nullptr};
    const ConvexPolyhedron* M[2] = {nullptr, nullptr};
    Transform pose[2];
    Mat3 Rw[2];  // rotation of pose[i] as a matrix (world mapping without quaternion products)
    Mat3 R[2];   // R[i], T[i]: body i frame -> frame of body 1 - i
    Vec3 T[2];
    VClipFeature X[2];

    /// Bodies, poses and frames; the features start at vertex 0 of each.
    void setup(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b, const Transform& poseB);
    Vec3 toFrame(int from, const Vec3& x) const { return R[from] * x + T[from]; }
    const Vec3& pos(int i, int v) const { return M[i]->position(v); }
};

/// A feature that names an element of the body (a cache from another body is refused).
bool validFeature(const VClipPolyhedron& p, const VClipFeature& f);
/// Finite position and rotation, the rotation not zero.
bool finitePose(const Transform& t);
/// max |x_i|.
inline double maxAbs(const Vec3& v) { return v.cwiseAbs().maxCoeff(); }

/// Brent's cycle finding (R. P. Brent, "An improved Monte Carlo factorization algorithm", BIT 20,
/// 1980) over the walk's feature pairs. A step is a pure function of the pair (the poses are
/// fixed), so one repeated pair means an endless cycle. Each pair is compared with one saved
/// pair, re-saved after 1, 2, 4, 8, ... further steps (at steps 0, 1, 3, 7, 15, ...): any cycle is
/// found within about twice (steps before it + its length), O(1) time and memory per step.
class FeaturePairCycle {
public:
    FeaturePairCycle(const VClipFeature& a, const VClipFeature& b) : savedA_(a), savedB_(b) {}
    /// The pair after one more step: true when it equals the saved pair, cycleLength() steps ago.
    bool repeats(const VClipFeature& a, const VClipFeature& b) {
        ++sinceSave_;
        if (a == savedA_ && b == savedB_) return true;
        if (sinceSave_ == saveInterval_) {
            savedA_ = a;
            savedB_ = b;
            saveInterval_ *= 2;
            sinceSave_ = 0;
        }
        return false;
    }
    long long cycleLength() const { return sinceSave_; }

private:
    VClipFeature savedA_, savedB_;
    long long saveInterval_ = 1, sinceSave_ = 0;
};

}  // namespace cdlab::feature_walk
