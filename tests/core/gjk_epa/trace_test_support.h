// What the GJK and EPA trace tests share: a random polytope pair and the first checks of a trace
// (one step per iteration, the result's termination, the last step marked as the stop).
#pragma once

#include <doctest/doctest.h>

#include <random>

#include "demos/oracles/minkowski_facet_oracle.h"

namespace cdlab::test {

struct PolytopePair {
    PolytopeShape a, b;
};

/// Two random polytopes of `vertices` vertices and size 1: A about the origin, B about `centerB`.
inline PolytopePair randomPolytopePair(unsigned seed, int vertices, const Vec3& centerB) {
    std::mt19937_64 rng(seed);
    PolytopeShape a{randomPolytope(rng, vertices, 1.0, Vec3::Zero())};
    PolytopeShape b{randomPolytope(rng, vertices, 1.0, centerB)};
    return {std::move(a), std::move(b)};
}

template <class Trace, class Result>
void checkTraceEndsLikeResult(const Trace& trace, const Result& r) {
    REQUIRE(static_cast<int>(trace.steps.size()) == r.iterations);
    CHECK(trace.termination == r.termination);
    CHECK(trace.steps.back().terminated);
}

}  // namespace cdlab::test
