#include "core/bounding/kdop.h"

#include <algorithm>
#include <cmath>

#include "core/base/tolerances.h"
#include "core/geometry/convex_hull.h"

namespace cdlab {

namespace {


// Ericson §4.6: the 13 directions, axes first, then the 4 cube diagonals, then the 6 edge
// diagonals (see the table in kdop.h).
const std::array<Vec3, 13> kAllDirections = {Vec3(1, 0, 0), Vec3(0, 1, 0),  Vec3(0, 0, 1),                   // 6-DOP
                                             Vec3(1, 1, 1), Vec3(1, 1, -1), Vec3(1, -1, 1), Vec3(-1, 1, 1),  // corners
                                             Vec3(1, 1, 0), Vec3(1, -1, 0), Vec3(1, 0, 1),  Vec3(1, 0, -1),
                                             Vec3(0, 1, 1),  // edges
                                             Vec3(0, 1, -1)};

// Directions of a K-DOP: which of the 13 it uses, in slab order.
template <int K>
const std::array<Vec3, K / 2>& directionsOf() {
    static const std::array<Vec3, K / 2> dirs = [] {
        std::array<Vec3, K / 2> d;
        int n = 0;
        for (int i = 0; i < 13; ++i) {
            const bool axis = i < 3, corner = i >= 3 && i < 7, edge = i >= 7;
            if (axis || (corner && (K == 14 || K == 26)) || (edge && (K == 18 || K == 26))) d[n++] = kAllDirections[i];
        }
        return d;
    }();
    return dirs;
}

// Rounding pad of a diagonal slab. d . p with components in {0, +-1} is a sum of two or three
// coordinates: each addition rounds by at most half an ulp of the partial sum, so the computed
// value is within 2 eps (|x| + |y| + |z|) of the exact one. Widening by that keeps every point
// inside in exact arithmetic too. The axis slabs are exact (no arithmetic) and get no pad.
double roundingPad(const Vec3& p) { return 2.0 * kMachineEpsilon * p.cwiseAbs().sum(); }

template <int K, class ForEach>
Kdop<K> fit(ForEach forEach) {
    const auto& dirs = directionsOf<K>();
    Kdop<K> dop;
    double pad = 0.0;
    forEach([&](const Vec3& p) {
        if (!p.allFinite()) return;
        pad = std::max(pad, roundingPad(p));
        for (int i = 0; i < K / 2; ++i) {
            const double s = dirs[i].dot(p);
            dop.min[i] = std::min(dop.min[i], s);
            dop.max[i] = std::max(dop.max[i], s);
        }
    });
    for (int i = 3; i < K / 2; ++i) {
        dop.min[i] -= pad;
        dop.max[i] += pad;
    }
    return dop;
}

bool valid(std::span<const double> lo, std::span<const double> hi) {
    for (size_t i = 0; i < lo.size(); ++i)
        if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]) || lo[i] > hi[i]) return false;
    return true;
}

}  // namespace

template <int K>
std::span<const Vec3> kdopDirections() {
    const auto& d = directionsOf<K>();
    return std::span<const Vec3>(d.data(), d.size());
}

template <int K>
Kdop<K> fitKdop(std::span<const Vec3> points) {
    return fit<K>([&](auto&& f) {
        for (const Vec3& p : points) f(p);
    });
}

template <int K>
Kdop<K> fitKdop(std::span<const Triangle> triangles) {
    return fit<K>([&](auto&& f) {
        for (const Triangle& t : triangles) {
            if (!(t.a.allFinite() && t.b.allFinite() && t.c.allFinite())) continue;
            f(t.a);
            f(t.b);
            f(t.c);
        }
    });
}

template <int K>
KdopOverlapResult testKdopKdop(const Kdop<K>& a, const Kdop<K>& b) {
    KdopOverlapResult result;
    for (int i = 0; i < K / 2; ++i) {
        // Written as "not overlapping" so that a NaN bound separates (no hit for NaN input).
        if (!(a.min[i] <= b.max[i] && b.min[i] <= a.max[i])) {
            result.separatingSlab = i;
            return result;
        }
    }
    result.hit = true;
    return result;
}

template <int K>
bool contains(const Kdop<K>& dop, const Vec3& p) {
    const auto& dirs = directionsOf<K>();
    for (int i = 0; i < K / 2; ++i) {
        const double s = dirs[i].dot(p);
        if (!(s >= dop.min[i] && s <= dop.max[i])) return false;
    }
    return true;
}

template <int K>
ConvexPolyhedron kdopPolytope(const Kdop<K>& dop) {
    if (!valid(dop.min, dop.max)) return {};
    const auto& dirs = directionsOf<K>();
    // Work relative to the center of the axis slabs (the AABB) so that large offsets cancel.
    const Vec3 ref(0.5 * (dop.min[0] + dop.max[0]), 0.5 * (dop.min[1] + dop.max[1]), 0.5 * (dop.min[2] + dop.max[2]));
    const Vec3 size(dop.max[0] - dop.min[0], dop.max[1] - dop.min[1], dop.max[2] - dop.min[2]);
    if (!(size.minCoeff() > 0.0)) return {};  // flat along an axis
    // Half-spaces n . x <= c (local): slab i gives d_i . x <= max_i and -d_i . x <= -min_i.
    std::vector<Vec3> normals;
    std::vector<double> offsets;
    for (int i = 0; i < K / 2; ++i) {
        const double shift = dirs[i].dot(ref);
        normals.push_back(dirs[i]);
        offsets.push_back(dop.max[i] - shift);
        normals.push_back(-dirs[i]);
        offsets.push_back(shift - dop.min[i]);
    }
    // A corner candidate may violate another slab by rounding only (kKdopCornerRelative).
    const double tol = kKdopCornerRelative * size.maxCoeff();
    const int m = static_cast<int>(normals.size());
    std::vector<Vec3> corners;
    for (int a = 0; a < m; ++a)
        for (int b = a + 1; b < m; ++b)
            for (int c = b + 1; c < m; ++c) {
                Mat3 n;
                n.row(0) = normals[a];
                n.row(1) = normals[b];
                n.row(2) = normals[c];
                // Integer matrix: the determinant is exact, 0 means the three planes do not meet
                // in one point.
                const double det = n.determinant();
                if (det == 0.0) continue;
                const Vec3 x = n.inverse() * Vec3(offsets[a], offsets[b], offsets[c]);
                bool inside = true;
                for (int j = 0; j < m && inside; ++j)
                    inside = normals[j].dot(x) <= offsets[j] + tol * normals[j].norm();
                if (inside) corners.push_back(x);
            }
    const HullResult hull = convexHull(corners);
    if (hull.status != HullStatus::Ok) return {};
    PolyhedronBuild build = hull.polyhedron.translated(ref);
    return build.ok() ? build.polyhedron : ConvexPolyhedron{};
}

template <int K>
double volume(const Kdop<K>& dop) {
    const ConvexPolyhedron poly = kdopPolytope(dop);
    return poly.empty() ? 0.0 : poly.volume();
}

#define CDLAB_INSTANTIATE_KDOP(K)                                               \
    template std::span<const Vec3> kdopDirections<K>();                         \
    template Kdop<K> fitKdop<K>(std::span<const Vec3>);                         \
    template Kdop<K> fitKdop<K>(std::span<const Triangle>);                     \
    template KdopOverlapResult testKdopKdop<K>(const Kdop<K>&, const Kdop<K>&); \
    template bool contains<K>(const Kdop<K>&, const Vec3&);                     \
    template ConvexPolyhedron kdopPolytope<K>(const Kdop<K>&);                  \
    template double volume<K>(const Kdop<K>&);

CDLAB_INSTANTIATE_KDOP(6)
CDLAB_INSTANTIATE_KDOP(14)
CDLAB_INSTANTIATE_KDOP(18)
CDLAB_INSTANTIATE_KDOP(26)

#undef CDLAB_INSTANTIATE_KDOP

}  // namespace cdlab
