// Random poses for the contact tests: a uniformly random rotation (a normalised Gaussian
// quaternion) and a position spread about a centre; and whether a point lies in a posed body.
#pragma once

#include <random>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab::test {

inline Transform randomPose(std::mt19937_64& rng, const Vec3& center, double spread) {
    std::normal_distribution<double> g(0.0, 1.0);
    Transform t;
    t.rotation = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
    t.position = center + spread * Vec3(g(rng), g(rng), g(rng));
    return t;
}

/// x within tol of every face plane of body b posed by t.
inline bool insideBody(const ConvexPolyhedron& b, const Transform& t, const Vec3& x, double tol) {
    const Vec3 xb = t.applyInverse(x);
    for (int f = 0; f < b.faceCount(); ++f)
        if (b.planeDistance(f, xb) > tol) return false;
    return true;
}

}  // namespace cdlab::test
