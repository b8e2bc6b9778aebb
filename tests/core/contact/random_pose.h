// Random poses for the contact tests: a uniformly random rotation (a normalised Gaussian
// quaternion) and a position spread about a centre.
#pragma once

#include <random>

#include "core/base/types.h"

namespace cdlab::test {

inline Transform randomPose(std::mt19937_64& rng, const Vec3& center, double spread) {
    std::normal_distribution<double> g(0.0, 1.0);
    Transform t;
    t.rotation = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
    t.position = center + spread * Vec3(g(rng), g(rng), g(rng));
    return t;
}

}  // namespace cdlab::test
