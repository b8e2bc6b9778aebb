// What the GJK and EPA tests share: a random polytope pair, the trials of the random-pair sweeps
// and the first checks of a trace (one step per iteration, the result's termination, the last
// step marked as the stop).
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/base/orient.h"

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

/// The origin against conv(P), exactly (orient3d is an exact predicate, core/base/orient.h): -1
/// outside, 0 on the boundary, 1 inside; 2 if P spans no volume. Brute force over the facets.
inline int exactOriginSide(const std::vector<Vec3>& P) {
    const int n = int(P.size());
    bool any = false, onBoundary = false;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                bool pos = false, neg = false;
                for (int m = 0; m < n; ++m) {
                    const int s = orient3d(P[i], P[j], P[k], P[m]);
                    pos = pos || s > 0, neg = neg || s < 0;
                }
                if (pos == neg) continue;  // not a facet plane (or all coplanar)
                any = true;
                const int o = orient3d(P[i], P[j], P[k], Vec3::Zero());
                if (o == (pos ? -1 : 1)) return -1;
                onBoundary = onBoundary || o == 0;
            }
    return !any ? 2 : onBoundary ? 0 : 1;
}

/// Sliver faces: three nearly collinear points (a face whose computed normal turns by ~1e-16 over
/// its sine, width 1e-1..1e-12) with the origin just off them (1e-2..1e-16 of the size, either
/// side), 2..5 more points behind (a fat body or a flat one), rotated, scaled 1e-3..1e6, shuffled.
class SliverConfigurations {
public:
    explicit SliverConfigurations(unsigned seed) : rng_(seed) {}
    std::vector<Vec3> next(int trial) {
        const double e = std::pow(10.0, -1 - 11 * u_(rng_));                           // the sliver's width
        const double h = (u_(rng_) < 0.5 ? -1 : 1) * std::pow(10.0, -2 - 14 * u_(rng_));  // the origin's offset
        const double scale = std::pow(10.0, -3 + 9 * u_(rng_));
        std::vector<Vec3> v{Vec3(-1 - u_(rng_), 0, 0), Vec3(1 + u_(rng_), 0, 0), Vec3(2 * u_(rng_) - 1, 0, e)};
        const bool fat = u_(rng_) < 0.5;
        for (int k = 0, extra = 2 + trial % 4; k < extra; ++k)
            v.push_back(Vec3(4 * u_(rng_) - 2, -0.2 - 2 * u_(rng_), fat ? 4 * u_(rng_) - 2 : (3 * u_(rng_) - 1) * e));
        double b1 = u_(rng_), b2 = u_(rng_);
        if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
        const Vec3 o = v[0] * (1 - b1 - b2) + v[1] * b1 + v[2] * b2 + Vec3(0, h, 0);
        const Eigen::Matrix3d r = Quat(g_(rng_), g_(rng_), g_(rng_), g_(rng_)).normalized().toRotationMatrix();
        std::vector<Vec3> P;
        for (const Vec3& x : v) P.push_back(scale * (r * (x - o)));
        std::shuffle(P.begin(), P.end(), rng_);
        offset_ = h * scale;
        scale_ = scale;
        return P;
    }
    /// The last configuration's origin offset from the sliver face's plane (> 0 outside: the distance
    /// to the hull, as the origin projects inside that face; < 0 inside), before rounding, and its scale.
    double offset() const { return offset_; }
    double scale() const { return scale_; }

private:
    std::mt19937_64 rng_;
    std::uniform_real_distribution<double> u_{0.0, 1.0};
    std::normal_distribution<double> g_{0.0, 1.0};
    double offset_ = 0.0, scale_ = 1.0;
};

template <class Trace, class Result>
void checkTraceEndsLikeResult(const Trace& trace, const Result& r) {
    REQUIRE(static_cast<int>(trace.steps.size()) == r.iterations);
    CHECK(trace.termination == r.termination);
    CHECK(trace.steps.back().terminated);
}

}  // namespace cdlab::test
