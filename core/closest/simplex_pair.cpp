#include "core/closest/simplex_pair.h"

#include <algorithm>
#include <cmath>

#include "core/base/orient.h"
#include "core/closest/feature_distance.h"

namespace cdlab {

namespace {

/// Every vertex, edge and face of a simplex with n vertices (n <= 4), as index lists.
std::vector<SimplexFeature> boundaryFeatures(int n) {
    std::vector<SimplexFeature> out;
    for (int mask = 1; mask < (1 << n); ++mask) {
        SimplexFeature f;
        for (int i = 0; i < n; ++i)
            if (mask & (1 << i)) f.vertices.push_back(i);
        if (f.vertices.size() <= 3) out.push_back(f);
    }
    return out;
}

FeatureGeometry geometryOf(std::span<const Vec3> s, const SimplexFeature& f) {
    FeatureGeometry g;
    g.type = f.vertices.size() == 1 ? FeatureType::Vertex : f.vertices.size() == 2 ? FeatureType::Edge : FeatureType::Face;
    for (int i : f.vertices) g.points.push_back(s[std::size_t(i)]);
    return g;
}

/// p lies in the solid tetrahedron t (exact: on the same side of each face as the opposite vertex, or on it).
bool inTetrahedron(std::span<const Vec3> t, const Vec3& p) {
    static const int kFaces[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};
    for (const auto& f : kFaces) {
        const int side = orient3d(t[std::size_t(f[0])], t[std::size_t(f[1])], t[std::size_t(f[2])], p);
        const int opposite = orient3d(t[std::size_t(f[0])], t[std::size_t(f[1])], t[std::size_t(f[2])], t[std::size_t(f[3])]);
        if (opposite == 0 || side * opposite < 0) return false;  // a flat tetrahedron holds nothing inside
    }
    return true;
}

bool usable(std::span<const Vec3> s) {
    if (s.empty() || s.size() > 4) return false;
    for (const Vec3& p : s)
        if (!p.allFinite()) return false;
    return true;
}

}  // namespace

SimplexPairResult closestFeaturesOfSimplices(std::span<const Vec3> a, std::span<const Vec3> b,
                                             std::vector<SimplexPairCandidate>* candidates) {
    SimplexPairResult r;
    if (!usable(a) || !usable(b)) return r;
    r.valid = true;
    double size = 0.0;
    for (std::span<const Vec3> s : {a, b})
        for (const Vec3& p : s) size = std::max(size, p.cwiseAbs().maxCoeff());
    const double tie = 1e-12 * std::max(size, 1e-300);

    std::vector<SimplexPairCandidate> all;
    for (const SimplexFeature& fa : boundaryFeatures(int(a.size())))
        for (const SimplexFeature& fb : boundaryFeatures(int(b.size()))) {
            const FeatureDistanceResult d = featureDistance(geometryOf(a, fa), geometryOf(b, fb));
            if (!d.valid) continue;  // a degenerate face (collinear corners) is covered by its edges
            all.push_back({fa, fb, d.distance, d.pointA, d.pointB});
        }
    r.pairsTested = int(all.size());
    std::stable_sort(all.begin(), all.end(), [](const SimplexPairCandidate& x, const SimplexPairCandidate& y) {
        return x.distance < y.distance;
    });
    if (all.empty()) {
        r.valid = false;
        return r;
    }
    // Least distance, then least total dimension among the pairs within rounding of it.
    const SimplexPairCandidate* best = &all.front();
    for (const SimplexPairCandidate& c : all) {
        if (c.distance > all.front().distance + tie) break;
        if (c.a.dimension() + c.b.dimension() < best->a.dimension() + best->b.dimension()) best = &c;
    }
    r.distance = best->distance;
    r.pointA = best->pointA;
    r.pointB = best->pointB;
    r.featureA = best->a;
    r.featureB = best->b;
    // Touching within rounding counts as meeting: two segments crossing where no double lies come
    // out ~1e-17 apart.
    r.intersect = best->distance <= tie;
    if (r.intersect) r.distance = 0.0;
    // A tetrahedron holding a vertex of the other: they intersect though no boundary pair may meet.
    for (int k = 0; k < 2 && !r.intersect; ++k) {
        const std::span<const Vec3> outer = k == 0 ? a : b, inner = k == 0 ? b : a;
        if (outer.size() != 4) continue;
        for (std::size_t i = 0; i < inner.size() && !r.intersect; ++i)
            if (inTetrahedron(outer, inner[i])) {
                r.intersect = true;
                r.distance = 0.0;
                r.pointA = r.pointB = inner[i];
                SimplexFeature inside{{0, 1, 2, 3}}, vertex{{int(i)}};
                r.featureA = k == 0 ? inside : vertex;
                r.featureB = k == 0 ? vertex : inside;
            }
    }
    if (candidates) *candidates = std::move(all);
    return r;
}

}  // namespace cdlab
