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

#include "verification/minkowski_facet_oracle.h"

namespace cdlab::test {

struct PolytopePair {
    SupportPolytope a, b;
};

/// Two random polytopes of `vertices` vertices and size 1: A about the origin, B about `centerB`.
inline PolytopePair randomPolytopePair(unsigned seed, int vertices, const Vec3& centerB) {
    std::mt19937_64 rng(seed);
    SupportPolytope a{randomPolytope(rng, vertices, 1.0, Vec3::Zero())};
    SupportPolytope b{randomPolytope(rng, vertices, 1.0, centerB)};
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

/// Calls f(i, j, k, pos) for every facet plane of conv(P): three points with every other point on
/// one side of their plane (decided exactly, orient3d: core/base/orient.h), pos = that side is
/// orient3d's positive one. Brute force over the triples.
template <class F>
void forEachFacet(const std::vector<Vec3>& P, F&& f) {
    const int n = int(P.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                bool pos = false, neg = false;
                for (int m = 0; m < n; ++m) {
                    const int s = orient3d(P[i], P[j], P[k], P[m]);
                    pos = pos || s > 0, neg = neg || s < 0;
                }
                if (pos != neg) f(i, j, k, pos);  // else not a facet plane (or all coplanar)
            }
}

/// The origin against conv(P), exactly: -1 outside, 0 on the boundary, 1 inside; 2 if P spans no
/// volume.
inline int exactOriginSide(const std::vector<Vec3>& P) {
    bool any = false, outside = false, onBoundary = false;
    forEachFacet(P, [&](int i, int j, int k, bool pos) {
        any = true;
        const int o = orient3d(P[i], P[j], P[k], Vec3::Zero());
        outside = outside || o == (pos ? -1 : 1);
        onBoundary = onBoundary || o == 0;
    });
    return !any ? 2 : outside ? -1 : onBoundary ? 0 : 1;
}

/// A sliver: the origin 1.1684449461453048e-6 (exact, in rational arithmetic) outside
/// the hull of these six points of size 1550, beyond the face of the first three, a sliver.
inline std::vector<Vec3> reviewSliverBody() {
    return {{264.97053582221525, 124.58940480235432, -174.21658992977368},
            {-716.69356582817238, -336.99000916195735, 471.22184898156507},
            {1192.2611122399185, 560.60233061317388, -783.90470318840426},
            {338.62740919703009, 1195.8704793447503, -167.1981340531562},
            {162.91552540415205, 443.38868693233877, 957.33906197054614},
            {-856.90728348968764, 1550.2287510716089, -1194.8392259070345}};
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
