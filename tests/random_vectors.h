// Random vectors shared by the tests.
#pragma once

#include <random>

#include "core/base/types.h"

namespace cdlab::test {

/// A point uniform in the cube [-half, half]^3.
inline Vec3 randomVec(std::mt19937_64& rng, double half) {
    std::uniform_real_distribution<double> u(-half, half);
    return Vec3(u(rng), u(rng), u(rng));
}

}  // namespace cdlab::test
