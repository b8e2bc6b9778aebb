// Helpers shared by the closest-point tests (one copy for the folder's test executable).
#pragma once

#include <array>
#include <string>

#include "core/base/types.h"
#include "tests/random_vectors.h"

namespace cdlab::test {

/// A region's name as a std::string, for doctest messages.
template <class Region>
std::string N(Region r) {
    return nameOf(r);
}

inline Tetrahedron make(const std::array<Vec3, 4>& v) { return Tetrahedron{v[0], v[1], v[2], v[3]}; }

}  // namespace cdlab::test
