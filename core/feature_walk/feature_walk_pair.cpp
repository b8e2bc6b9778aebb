#include "core/feature_walk/feature_walk_pair.h"

namespace cdlab::feature_walk {

void WalkPair::setup(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b,
                     const Transform& poseB) {
    P[0] = &a;
    P[1] = &b;
    M[0] = &a.mesh();
    M[1] = &b.mesh();
    pose[0] = poseA;
    pose[1] = poseB;
    pose[0].rotation.normalize();
    pose[1].rotation.normalize();
    Rw[0] = pose[0].rotation.toRotationMatrix();
    Rw[1] = pose[1].rotation.toRotationMatrix();
    // B -> A: x_A = RA^T (RB x_B + pB - pA); A -> B is its inverse.
    R[1] = Rw[0].transpose() * Rw[1];
    T[1] = Rw[0].transpose() * (pose[1].position - pose[0].position);
    R[0] = R[1].transpose();
    T[0] = -(R[0] * T[1]);
    X[0] = VClipFeature::vertex(0);
    X[1] = VClipFeature::vertex(0);
}

bool validFeature(const VClipPolyhedron& p, const VClipFeature& f) {
    const ConvexPolyhedron& m = p.mesh();
    switch (f.type) {
        case VClipFeatureType::Vertex: return f.index >= 0 && f.index < m.vertexCount();
        case VClipFeatureType::Edge: return f.index >= 0 && f.index < m.edgeCount();
        case VClipFeatureType::Face: return f.index >= 0 && f.index < m.faceCount();
        case VClipFeatureType::None: break;
    }
    return false;
}

bool finitePose(const Transform& t) {
    return t.position.allFinite() && t.rotation.coeffs().allFinite() && t.rotation.norm() > 0.0;
}

}  // namespace cdlab::feature_walk
