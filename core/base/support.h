// The support-mapping concept every convex-set algorithm (GJK, EPA, MPR, ...) is written over.
// A support mapping s_C(d) returns a point of the convex set C that is extreme in direction d:
// d · s_C(d) = max over x in C of d · x (van den Bergen, "Collision Detection in Interactive
// 3D Environments", §4.3). Ties may return any extreme point, but must be deterministic.
#pragma once

#include <concepts>

#include "core/base/types.h"

namespace cdlab {

template <class S>
concept SupportMapping = requires(const S& shape, const Vec3& direction) {
    { shape.support(direction) } -> std::convertible_to<Vec3>;
};

}  // namespace cdlab
