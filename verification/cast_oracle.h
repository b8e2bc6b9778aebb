// Independent oracles for ray casts and times of impact (tests of core/cast/ and of `cdlab query`
// raycast / time_of_impact). They share no code with core/cast/, core/gjk_epa/ or the hull:
//  - a polytope conv(P): its facet planes by brute force over every triple of P in long double (a
//    triple is a facet when no point lies outside its plane), then Cyrus–Beck clipping of the ray
//    against those half-spaces (Cyrus & Beck 1978; Ericson §5.3.8): the entry t and its margin;
//  - any convex shape with a long-double distance function: f(t) = dist(ray(t), S) − r is convex
//    in t, so its first root is found by ternary search for the minimum and bisection below it.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "core/base/types.h"
#include "verification/long_double_geometry.h"

namespace cdlab::demos::cast_oracle {

using long_double::LVec;
using long_double::toL;

struct FacetPlane {
    LVec n;  // unit, outward
    long double offset;
};

/// Facet planes of conv(points) (duplicates of a plane kept: harmless for clipping). Empty when the
/// points span no volume.
inline std::vector<FacetPlane> facetPlanes(const std::vector<Vec3>& points) {
    std::vector<LVec> p;
    long double scale = 0;
    for (const Vec3& v : points) p.push_back(toL(v)), scale = std::max(scale, (long double)v.cwiseAbs().maxCoeff());
    const long double eps = 1e-15L * (scale + 1e-300L);
    std::vector<FacetPlane> out;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                LVec nn = (p[j] - p[i]).cross(p[k] - p[i]);
                const long double len = nn.norm();
                if (!(len > eps * scale)) continue;
                nn /= len;
                const long double off = nn.dot(p[i]);
                bool above = false, below = false;
                for (std::size_t m = 0; m < n && !(above && below); ++m) {
                    const long double s = nn.dot(p[m]) - off;
                    if (s > eps) above = true;
                    if (s < -eps) below = true;
                }
                if (above && below) continue;
                if (above) out.push_back({-nn, -off});
                else out.push_back({nn, off});
            }
    return out;
}

struct PolytopeCast {
    bool valid = false;        // the points span a volume
    bool inside = false;       // the origin is inside or on the polytope (within rounding)
    bool hit = false;          // entry t <= exit t
    long double tEnter = 0;    // first contact (when hit)
    long double margin = 0;    // how far the ray is from missing: exit − entry (a graze has ~0)
    std::vector<LVec> normals;  // normals of the facets whose plane the entry point lies on
};

/// Cyrus–Beck of ray o + t d, t >= 0, against the facet half-spaces of conv(points).
inline PolytopeCast castRayPolytope(const Vec3& o, const Vec3& d, const std::vector<Vec3>& points) {
    PolytopeCast out;
    const std::vector<FacetPlane> planes = facetPlanes(points);
    if (planes.size() < 4) return out;
    out.valid = true;
    const LVec lo = toL(o), ld = toL(d);
    long double enter = 0, exit = std::numeric_limits<long double>::infinity();
    long double worstSide = -std::numeric_limits<long double>::infinity();
    for (const FacetPlane& f : planes) {
        const long double s0 = f.n.dot(lo) - f.offset, rate = f.n.dot(ld);
        worstSide = std::max(worstSide, s0);
        if (rate == 0) {
            if (s0 > 0) exit = -1;  // parallel outside this facet: never enters (margin −s0 below)
            continue;
        }
        const long double t = -s0 / rate;
        if (rate < 0) enter = std::max(enter, t);
        else exit = std::min(exit, t);
    }
    out.inside = worstSide <= 0;
    out.hit = enter <= exit;
    out.tEnter = enter;
    out.margin = exit - enter;
    const LVec at = lo + enter * ld;
    const long double tol = 1e-12L * (at.cwiseAbs().maxCoeff() + 1);
    for (const FacetPlane& f : planes)
        if (std::abs(f.n.dot(at) - f.offset) <= tol) out.normals.push_back(f.n);
    return out;
}

struct ConvexMinimum {
    long double t, value;
};

/// Minimum of a convex f on [0, tMax] by ternary search.
inline ConvexMinimum minimumOfConvex(const std::function<long double(long double)>& f, long double tMax) {
    long double lo = 0, hi = tMax;
    for (int i = 0; i < 200; ++i) {
        const long double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) < f(m2)) hi = m2;
        else lo = m1;
    }
    const long double t = (lo + hi) / 2;
    return {t, f(t)};
}

/// First t in [0, tMax] with f(t) <= 0 for a convex f, or −1 when f > 0 on all of [0, tMax].
inline long double firstRootOfConvex(const std::function<long double(long double)>& f, long double tMax) {
    if (f(0) <= 0) return 0;
    const ConvexMinimum m = minimumOfConvex(f, tMax);
    if (m.value > 0) return -1;
    long double a = 0, b = m.t;  // f(a) > 0 >= f(b)
    for (int i = 0; i < 200; ++i) {
        const long double mid = (a + b) / 2;
        if (f(mid) > 0) a = mid;
        else b = mid;
    }
    return b;
}

/// |x − segment pq| in long double.
inline long double pointSegmentDistance(const LVec& x, const LVec& p, const LVec& q) {
    return long_double::segmentDistanceL(p - x, q - x);
}

/// |segment pq − segment rs| in long double: the distance from p + s (q − p) to rs is convex in s,
/// minimised by ternary search (robust for parallel segments).
inline long double segmentSegmentDistance(const LVec& p, const LVec& q, const LVec& r, const LVec& s) {
    const auto f = [&](long double u) { return pointSegmentDistance(p + u * (q - p), r, s); };
    return minimumOfConvex(f, 1.0L).value;
}

/// |x − box [lo, hi]| in long double (0 inside).
inline long double pointBoxDistance(const LVec& x, const LVec& lo, const LVec& hi) {
    const LVec c = x.cwiseMax(lo).cwiseMin(hi);
    return (x - c).norm();
}

}  // namespace cdlab::demos::cast_oracle
