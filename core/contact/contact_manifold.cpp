#include "core/contact/contact_manifold.h"

#include <algorithm>
#include <cmath>
#include <memory_resource>
#include <utility>

#include "core/base/stack_arena.h"

namespace cdlab {

namespace {

// The scratch containers are template parameters: FixedCapacityVector for polygons up to
// kMaxContactPoints points (no allocator at all), std::pmr::vector on a stack arena beyond.

// Points at depth 0 (where an edge crosses the plane or the reference face's side) that lie within
// the deepest depth, in the plane, of a submerged point are the rim of that corner, on edges leaving
// it steeper than 45° (a cone of half-angle up to 45° on its apex: its crossings ring the apex). They
// add no support a solver can use and are dropped before the rules. Touching contacts (every depth
// 0) keep theirs.
template <class Points, class Indices>
void supportingPoints(std::span<const ContactPoint> polygon, const Points& q, Indices& kept) {
    double deepest = 0.0;
    for (const ContactPoint& c : polygon) deepest = std::max(deepest, c.depth);
    const double surface = 1e-9 * deepest;  // at the surface, up to rounding of the depths
    for (int i = 0; i < static_cast<int>(polygon.size()); ++i) {
        bool rim = false;
        if (polygon[i].depth <= surface)
            for (int j = 0; j < static_cast<int>(polygon.size()) && !rim; ++j)
                rim = polygon[j].depth > surface && (q[i] - q[j]).squaredNorm() <= deepest * deepest;
        if (!rim) kept.push_back(i);
    }
}

// A score replaces the best so far only when larger by more than rounding (1e-9 relative): exact
// ties are common (a clipped rectangle has parallel sides, so two points make the same triangle
// with the first two; a face-on box has four corners at one depth), and the first in input order
// must win them whatever the rounding, or the manifold flickers between frames and between two
// computations of the same contact (the box fast path and the general SAT).
bool clearlyGreater(double score, double best) { return score > best + 1e-9 * std::abs(best); }

// Twice the area a point q adds to the convex polygon `hull` (counter-clockwise about the normal):
// the largest triangle it forms with an edge it lies outside of; 0 inside or on the polygon.
template <class Points, class Indices>
double addedArea(const Points& q, const Indices& hull, int i, const Vec3& normal) {
    double best = 0.0;
    for (size_t e = 0; e < hull.size(); ++e) {
        const Vec3& a = q[hull[e]];
        const Vec3& b = q[hull[(e + 1) % hull.size()]];
        best = std::max(best, -(b - a).cross(q[i] - a).dot(normal));
    }
    return best;
}

// The kept points' convex hull in the plane, counter-clockwise about the normal (Andrew's monotone
// chain in a plane basis), written to `h` (the kept points as given when fewer than 3 are on it).
template <class Points, class Indices>
void planeHull(const Points& q, const ContactIndices& kept, const Vec3& normal, Indices& h) {
    const Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
    const Vec3& o = q[kept[0]];
    const auto key = [&](int i) { return std::pair<double, double>(u.dot(q[i] - o), w.dot(q[i] - o)); };
    ContactIndices points = kept;
    std::sort(points.begin(), points.end(), [&](int a, int b) { return key(a) < key(b); });
    const auto turn = [&](int o, int a, int b) { return (q[a] - q[o]).cross(q[b] - q[o]).dot(normal); };
    h.clear();
    for (size_t i = 0; i < points.size(); ++i) {
        while (h.size() >= 2 && turn(h[h.size() - 2], h.back(), points[i]) <= 0) h.pop_back();
        h.push_back(points[i]);
    }
    for (size_t i = points.size() - 1, lower = h.size() + 1; i-- > 0;) {
        while (h.size() >= lower && turn(h[h.size() - 2], h.back(), points[i]) <= 0) h.pop_back();
        h.push_back(points[i]);
    }
    if (h.size() > 1) h.pop_back();  // the last point repeats the first
    if (h.size() < 3) {
        h.clear();
        for (int k : kept) h.push_back(k);
    }
}

// The deepest of `indices` first (first of ties), then the others in input order.
template <class Range>
ContactIndices deepestFirst(std::span<const ContactPoint> polygon, const Range& indices) {
    ContactIndices keep;
    if (indices.empty()) return keep;
    int deepest = *indices.begin();
    for (int i : indices)
        if (clearlyGreater(polygon[i].depth, polygon[deepest].depth)) deepest = i;
    keep.push_back(deepest);
    for (int i : indices)
        if (i != deepest) keep.push_back(i);
    return keep;
}

// The rules of the file comment, after the maxPoints <= 0 case; scratch in q, candidates, hull (empty).
template <class Points, class Candidates, class Hull>
ContactIndices reduceWith(std::span<const ContactPoint> polygon, const Vec3& normal, int maxPoints,
                          std::vector<ManifoldReductionStep>* steps, Points& q, Candidates& candidates, Hull& hull) {
    const int n = static_cast<int>(polygon.size());
    // Positions projected onto the plane ⟂ normal (pointB lies on B's surface: use it, then drop
    // the normal component so tilted reference surfaces measure in-plane spread only).
    for (int i = 0; i < n; ++i)
        q.push_back(polygon[i].pointB - normal.dot(polygon[i].pointB - polygon[0].pointB) * normal);
    supportingPoints(polygon, q, candidates);
    if (maxPoints >= static_cast<int>(candidates.size())) return deepestFirst(polygon, candidates);

    ContactIndices keep;
    const auto record = [&](const char* rule, int i, double score) {
        keep.push_back(i);
        if (steps) steps->push_back({rule, i, score});
    };
    const auto taken = [&](int i) { return std::find(keep.begin(), keep.end(), i) != keep.end(); };

    // Each rule below picks among the submerged points first and turns to the depth-0 ones only when
    // no submerged point scores: a crossing never displaces a full-depth corner.
    double deepestDepth = 0.0;
    for (int i : candidates) deepestDepth = std::max(deepestDepth, polygon[i].depth);
    const auto submerged = [&](int i) { return polygon[i].depth > 1e-9 * deepestDepth; };
    const auto pick = [&](const auto& score, double& bestScore) {
        for (bool tier : {true, false}) {
            int chosen = -1;
            bestScore = 0.0;
            for (int i : candidates) {
                if (taken(i) || submerged(i) != tier) continue;
                const double sc = score(i);
                if (clearlyGreater(sc, bestScore)) chosen = i, bestScore = sc;
            }
            if (chosen >= 0) return chosen;
        }
        return -1;
    };

    // 1. deepest point (first of ties).
    int best = candidates[0];
    for (int i : candidates)
        if (clearlyGreater(polygon[i].depth, polygon[best].depth)) best = i;
    record("deepest", best, polygon[best].depth);
    if (maxPoints == 1) return keep;

    // 2. farthest from it in the plane.
    const int p0 = keep[0];
    double bestScore = 0.0;
    best = pick([&](int i) { return (q[i] - q[p0]).squaredNorm(); }, bestScore);  // no sqrt per point
    if (best < 0) return keep;  // every point coincides with the deepest one
    record("farthest", best, std::sqrt(bestScore));
    if (maxPoints == 2) return keep;

    // 3. largest triangle with the first two: |(q1 - q0) x (qi - q0) · normal| (twice the area).
    const int p1 = keep[1];
    const auto signedArea = [&](int i) { return (q[p1] - q[p0]).cross(q[i] - q[p0]).dot(normal); };
    best = pick([&](int i) { return std::abs(signedArea(i)); }, bestScore);
    if (best < 0) return keep;  // collinear
    const double bestSigned = signedArea(best);
    record("max-area triangle", best, bestScore);
    if (maxPoints == 3) return keep;

    // 4. The point adding the most area: for a counter-clockwise triangle (t0, t1, t2) about the
    //    normal, a point outside edge (tj, tk) adds the area of triangle (tj, q, tk) =
    //    -signedArea(tj, tk, q); take the largest over the three edges.
    // 5. and on, while maxPoints allows: the same rule on the hull of the points kept so far, so that
    //    asking for more points never returns fewer, and every corner comes back once maxPoints
    //    reaches their count (a corner is outside the hull of the others until it is kept).
    hull.push_back(p0);
    hull.push_back(bestSigned < 0 ? keep[2] : p1);
    hull.push_back(bestSigned < 0 ? p1 : keep[2]);
    while (static_cast<int>(keep.size()) < maxPoints) {
        best = pick([&](int i) { return addedArea(q, hull, i, normal); }, bestScore);
        if (best < 0) break;  // every other point inside the hull of the kept ones
        record(keep.size() == 3 ? "max-area quad" : "max-area polygon", best, bestScore);
        if (static_cast<int>(keep.size()) < maxPoints) planeHull(q, keep, normal, hull);  // for the next pick
    }
    return keep;
}

}  // namespace

ContactIndices reduceContactPolygon(std::span<const ContactPoint> polygon, const Vec3& normal, int maxPoints,
                                    std::vector<ManifoldReductionStep>* steps) {
    const int n = static_cast<int>(polygon.size());
    if (maxPoints <= 0 && n <= kMaxContactPoints) {  // every point, rim included, the deepest first
        ContactIndices all;
        for (int i = 0; i < n; ++i) all.push_back(i);
        return deepestFirst(polygon, all);
    }
    if (maxPoints <= 0 || maxPoints > kMaxContactPoints) maxPoints = kMaxContactPoints;
    if (n <= kMaxContactPoints) {
        FixedCapacityVector<Vec3, kMaxContactPoints> q;
        FixedCapacityVector<int, kMaxContactPoints> candidates;
        FixedCapacityVector<int, 2 * kMaxContactPoints + 2> hull;
        return reduceWith(polygon, normal, maxPoints, steps, q, candidates, hull);
    }
    StackArena<4096> arena;
    std::pmr::vector<Vec3> q(arena.resource());
    std::pmr::vector<int> candidates(arena.resource()), hull(arena.resource());
    q.reserve(n);
    candidates.reserve(n);
    hull.reserve(2 * kMaxContactPoints + 2);
    return reduceWith(polygon, normal, maxPoints, steps, q, candidates, hull);
}

}  // namespace cdlab
