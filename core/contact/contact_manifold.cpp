#include "core/contact/contact_manifold.h"

#include <cmath>

namespace cdlab {

std::vector<int> reduceContactPolygon(const std::vector<ContactPoint>& polygon, const Vec3& normal, int maxPoints,
                                      std::vector<ManifoldReductionStep>* steps) {
    const int n = static_cast<int>(polygon.size());
    std::vector<int> keep;
    if (maxPoints <= 0 || maxPoints >= n) {  // keep all, the deepest first
        int deepest = 0;
        for (int i = 1; i < n; ++i)
            if (polygon[i].depth > polygon[deepest].depth) deepest = i;
        if (n > 0) keep.push_back(deepest);
        for (int i = 0; i < n; ++i)
            if (i != deepest) keep.push_back(i);
        return keep;
    }
    // Positions projected onto the plane ⟂ normal (pointB lies on B's surface: use it, then drop
    // the normal component so tilted reference surfaces measure in-plane spread only).
    std::vector<Vec3> q(n);
    for (int i = 0; i < n; ++i) q[i] = polygon[i].pointB - normal.dot(polygon[i].pointB - polygon[0].pointB) * normal;
    const auto record = [&](const char* rule, int i, double score) {
        keep.push_back(i);
        if (steps) steps->push_back({rule, i, score});
    };
    const auto taken = [&](int i) {
        for (int k : keep)
            if (k == i) return true;
        return false;
    };

    // 1. deepest point (first of ties).
    int best = 0;
    for (int i = 1; i < n; ++i)
        if (polygon[i].depth > polygon[best].depth) best = i;
    record("deepest", best, polygon[best].depth);
    if (maxPoints == 1) return keep;

    // 2. farthest from it in the plane.
    const int p0 = keep[0];
    best = -1;
    double bestScore = 0.0;
    for (int i = 0; i < n; ++i) {
        const double d = (q[i] - q[p0]).norm();
        if (!taken(i) && d > bestScore) best = i, bestScore = d;
    }
    if (best < 0) return keep;  // every point coincides with the deepest one
    record("farthest", best, bestScore);
    if (maxPoints == 2) return keep;

    // 3. largest triangle with the first two: |(q1 - q0) x (qi - q0) · normal| (twice the area).
    const int p1 = keep[1];
    best = -1;
    bestScore = 0.0;
    double bestSigned = 0.0;
    for (int i = 0; i < n; ++i) {
        const double a = (q[p1] - q[p0]).cross(q[i] - q[p0]).dot(normal);
        if (!taken(i) && std::abs(a) > bestScore) best = i, bestScore = std::abs(a), bestSigned = a;
    }
    if (best < 0) return keep;  // collinear
    record("max-area triangle", best, bestScore);
    if (maxPoints == 3) return keep;

    // 4. The point adding the most area: for a counter-clockwise triangle (t0, t1, t2) about the
    //    normal, a point outside edge (tj, tk) adds the area of triangle (tj, q, tk) =
    //    -signedArea(tj, tk, q); take the largest over the three edges.
    int t[3] = {p0, p1, keep[2]};
    if (bestSigned < 0) std::swap(t[1], t[2]);
    best = -1;
    bestScore = 0.0;
    for (int i = 0; i < n; ++i) {
        if (taken(i)) continue;
        for (int e = 0; e < 3; ++e) {
            const Vec3& a = q[t[e]];
            const Vec3& b = q[t[(e + 1) % 3]];
            const double added = -(b - a).cross(q[i] - a).dot(normal);
            if (added > bestScore) best = i, bestScore = added;
        }
    }
    if (best < 0) return keep;  // every other point inside the triangle
    record("max-area quad", best, bestScore);
    return keep;
}

}  // namespace cdlab
