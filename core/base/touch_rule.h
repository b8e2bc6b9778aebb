// The one touching rule of core's pair queries (core/query, core/gjk_epa/margins.h): a pair is
// touching or overlapping, not separated, when its computed distance is at most
//     kTouchRelative · (W + rA + rB),     W = max |a_i − b_i| over a in A's core, b in B's core,
// the extent of the Minkowski difference of the cores (minkowskiExtent), rA, rB the radii added in
// closed form.
//
// Why relative to the extent of A − B and not to the coordinates: every distance method works on
// differences of the shapes' points (GJK on w = a − b, V-Clip and SAT in a frame local to the
// bodies), and fl(a − b) has an error below u·|a − b| whatever |a| and |b| are. So a computed
// distance is right to a few ulps of W, not of the coordinates. Two unit boxes 5e-5 apart at
// x = 1e9 have W ≈ 2, and their gap is 1e11 times larger than the rounding: they are separated.
// kTouchRelative = 1e-13 (~450 ulps) is well above the errors measured for GJK / EPA, V-Clip,
// Lin–Canny and the SAT (a few to ~64 ulps of W) and far below any gap a user means
// (tests/core/query/pair_query_test.cpp "the touching rule").
//
// A plane is the exception: n̂·x − d̂ is computed from the coordinates themselves, so its rounding is
// relative to the coordinates and to the plane's offset (core/query/touch.h, planeTouchTolerance).
#pragma once

#include <algorithm>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// Distances at or below kTouchRelative · (W + rA + rB) are touching (see the file comment).
inline constexpr double kTouchRelative = 1e-13;

/// max over the axes of |a_i − b_i| for a in conv(a), b in conv(b): a bound on the coordinates of
/// every point of A − B (the bounding box of the Minkowski difference). 0 when either is empty.
inline double minkowskiExtent(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.empty() || b.empty()) return 0.0;
    Vec3 loA = a.front(), hiA = a.front(), loB = b.front(), hiB = b.front();
    for (const Vec3& v : a) loA = loA.cwiseMin(v), hiA = hiA.cwiseMax(v);
    for (const Vec3& v : b) loB = loB.cwiseMin(v), hiB = hiB.cwiseMax(v);
    return std::max((hiA - loB).cwiseAbs().maxCoeff(), (loA - hiB).cwiseAbs().maxCoeff());
}

/// The same extent from two support mappings (their values along ±x, ±y, ±z are the boxes' faces).
template <class A, class B>
double minkowskiExtentOfSupports(const A& a, const B& b) {
    Vec3 loA, hiA, loB, hiB;
    for (int i = 0; i < 3; ++i) {
        const Vec3 e = Vec3::Unit(i);
        hiA[i] = Vec3(a.support(e))[i];
        loA[i] = Vec3(a.support(Vec3(-e)))[i];
        hiB[i] = Vec3(b.support(e))[i];
        loB[i] = Vec3(b.support(Vec3(-e)))[i];
    }
    return std::max((hiA - loB).cwiseAbs().maxCoeff(), (loA - hiB).cwiseAbs().maxCoeff());
}

}  // namespace cdlab
