// What the GJK and EPA tests share: a random polytope pair, the trials of the random-pair sweeps
// and the first checks of a trace (one step per iteration, the result's termination, the last
// step marked as the stop).
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

/// Trial k of a random-pair sweep: sizes 1e-3, 1 and 1e3 in turn, each at offsets 0, 1e3 and 1e6
/// from the origin in a random direction (drawn from rng).
struct SweepTrial {
    double size, offset;
    Vec3 origin;
};
inline SweepTrial sweepTrial(int k, std::mt19937_64& rng) {
    constexpr double kSizes[] = {1e-3, 1.0, 1e3};
    constexpr double kOffsets[] = {0.0, 1e3, 1e6};
    const double offset = kOffsets[(k / 3) % 3];
    return {kSizes[k % 3], offset, offset * randomUnit(rng)};
}

template <class Trace, class Result>
void checkTraceEndsLikeResult(const Trace& trace, const Result& r) {
    REQUIRE(static_cast<int>(trace.steps.size()) == r.iterations);
    CHECK(trace.termination == r.termination);
    CHECK(trace.steps.back().terminated);
}

}  // namespace cdlab::test
