#include "core/contact/contact_manifold.h"

#include <algorithm>
#include <cmath>
#include <memory_resource>
#include <utility>

#include "core/base/stack_arena.h"
#include "core/contact/contact_tolerances.h"

namespace cdlab {

namespace {

// Scratch of one reduction, sized by the caller: on the stack for polygons up to kMaxContactPoints
// points (no allocator at all), on a stack arena beyond. Raw arrays: the reduction of a box's 4 to
// 10 candidates is a few hundred instructions, which container bookkeeping would double.
struct Scratch {
    Vec3* q;      // positions projected onto the plane, one per input point
    int* kept;    // the points left by rule 0, input order
    int* deep;    // the submerged points (depth above the surface band), input order
    unsigned char* taken;  // chosen so far (0 / 1), one per input point
    int* hull;    // the chosen points' hull, up to 2 kMaxContactPoints + 2
};

// A score replaces the best so far only when larger by more than rounding (kManifoldTieRelative): exact
// ties are common (a clipped rectangle has parallel sides, so two points make the same triangle
// with the first two; a face-on box has four corners at one depth), and the first in input order
// must win them whatever the rounding, or the manifold flickers between frames and between two
// computations of the same contact (the box fast paths and the general ones).
bool clearlyGreater(double score, double best) { return score > best + kManifoldTieRelative * std::abs(best); }

// Rule 0. Points at depth 0 (where an edge crosses the plane or the reference face's side) that lie
// within the deepest depth, in the plane, of a submerged point are the rim of that corner, on edges
// leaving it steeper than 45° (a cone of half-angle up to 45° on its apex: its crossings ring the
// apex). They add no support a solver can use and are dropped before the rules. Touching contacts
// (every depth 0) keep theirs. Returns how many points are kept (written to s.kept).
int supportingPoints(std::span<const ContactPoint> polygon, double deepest, const Scratch& s) {
    const int n = static_cast<int>(polygon.size());
    const double surface = kSurfaceBandRelative * deepest;  // at the surface, up to rounding of the depths
    const double reach = deepest * deepest;
    int deep = 0;
    for (int j = 0; j < n; ++j)
        if (polygon[j].depth > surface) s.deep[deep++] = j;
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        bool rim = false;
        if (polygon[i].depth <= surface)
            for (int k = 0; k < deep && !rim; ++k) rim = (s.q[i] - s.q[s.deep[k]]).squaredNorm() <= reach;
        if (!rim) s.kept[kept++] = i;
    }
    return kept;
}

// Twice the area a point q adds to the convex polygon `hull` (counter-clockwise about the normal):
// the largest triangle it forms with an edge it lies outside of; 0 inside or on the polygon.
double addedArea(const Vec3* q, const int* hull, int hullSize, int i, const Vec3& normal) {
    double best = 0.0;
    for (int e = 0; e < hullSize; ++e) {
        const Vec3& a = q[hull[e]];
        const Vec3& b = q[hull[e + 1 == hullSize ? 0 : e + 1]];
        best = std::max(best, -(b - a).cross(q[i] - a).dot(normal));
    }
    return best;
}

// The chosen points' convex hull in the plane, counter-clockwise about the normal (Andrew's
// monotone chain in a plane basis), written to h; returns its size (the chosen points as given
// when fewer than 3 are on it).
int planeHull(const Vec3* q, const ContactIndices& chosen, const Vec3& normal, int* h) {
    const Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
    const Vec3& o = q[chosen[0]];
    const auto key = [&](int i) { return std::pair<double, double>(u.dot(q[i] - o), w.dot(q[i] - o)); };
    ContactIndices points = chosen;
    std::sort(points.begin(), points.end(), [&](int a, int b) { return key(a) < key(b); });
    const auto turn = [&](int o, int a, int b) { return (q[a] - q[o]).cross(q[b] - q[o]).dot(normal); };
    int k = 0;
    for (int p : points) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], p) <= 0) --k;
        h[k++] = p;
    }
    for (int i = static_cast<int>(points.size()) - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(h[k - 2], h[k - 1], points[i]) <= 0) --k;
        h[k++] = points[i];
    }
    if (k > 1) --k;  // the last point repeats the first
    if (k < 3) {
        k = 0;
        for (int i : chosen) h[k++] = i;
    }
    return k;
}

// The deepest of `indices` first (first of ties), then the others in input order.
ContactIndices deepestFirst(std::span<const ContactPoint> polygon, const int* indices, int count) {
    ContactIndices keep;
    if (count == 0) return keep;
    int deepest = indices[0];
    for (int k = 1; k < count; ++k)
        if (clearlyGreater(polygon[indices[k]].depth, polygon[deepest].depth)) deepest = indices[k];
    keep.push_back(deepest);
    for (int k = 0; k < count; ++k)
        if (indices[k] != deepest) keep.push_back(indices[k]);
    return keep;
}

// The rules of the file comment, after the maxPoints <= 0 case.
ContactIndices reduceWith(std::span<const ContactPoint> polygon, const Vec3& normal, int maxPoints,
                          std::vector<ManifoldReductionStep>* steps, const Scratch& s) {
    const int n = static_cast<int>(polygon.size());
    // Positions projected onto the plane ⟂ normal (pointB lies on B's surface: use it, then drop
    // the normal component so tilted reference surfaces measure in-plane spread only).
    double deepest = 0.0;
    for (int i = 0; i < n; ++i) {
        s.q[i] = polygon[i].pointB - normal.dot(polygon[i].pointB - polygon[0].pointB) * normal;
        s.taken[i] = 0;
        deepest = std::max(deepest, polygon[i].depth);
    }
    const int count = supportingPoints(polygon, deepest, s);
    if (maxPoints >= count) return deepestFirst(polygon, s.kept, count);

    ContactIndices keep;
    const auto record = [&](const char* rule, int i, double score) {
        keep.push_back(i);
        s.taken[i] = 1;
        if (steps) steps->push_back({rule, i, score});
    };

    // Each rule below picks among the submerged points first and turns to the depth-0 ones only when
    // no submerged point scores: a crossing never displaces a full-depth corner. (Rule 0 keeps the
    // deepest point, so `deepest` is also the deepest kept depth.)
    const auto submerged = [&](int i) { return polygon[i].depth > kSurfaceBandRelative * deepest; };
    const auto pick = [&](const auto& score, double& bestScore) {
        for (bool tier : {true, false}) {
            int chosen = -1;
            bestScore = 0.0;
            for (int k = 0; k < count; ++k) {
                const int i = s.kept[k];
                if (s.taken[i] || submerged(i) != tier) continue;
                const double sc = score(i);
                if (clearlyGreater(sc, bestScore)) chosen = i, bestScore = sc;
            }
            if (chosen >= 0) return chosen;
        }
        return -1;
    };
    const Vec3* q = s.q;

    // 1. deepest point (first of ties).
    int best = s.kept[0];
    for (int k = 1; k < count; ++k)
        if (clearlyGreater(polygon[s.kept[k]].depth, polygon[best].depth)) best = s.kept[k];
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
    int hullSize = 3;
    s.hull[0] = p0;
    s.hull[1] = bestSigned < 0 ? keep[2] : p1;
    s.hull[2] = bestSigned < 0 ? p1 : keep[2];
    while (static_cast<int>(keep.size()) < maxPoints) {
        best = pick([&](int i) { return addedArea(q, s.hull, hullSize, i, normal); }, bestScore);
        if (best < 0) break;  // every other point inside the hull of the kept ones
        record(keep.size() == 3 ? "max-area quad" : "max-area polygon", best, bestScore);
        if (static_cast<int>(keep.size()) < maxPoints) hullSize = planeHull(q, keep, normal, s.hull);  // for the next pick
    }
    return keep;
}

}  // namespace

ContactIndices reduceContactPolygon(std::span<const ContactPoint> polygon, const Vec3& normal, int maxPoints,
                                    std::vector<ManifoldReductionStep>* steps) {
    const int n = static_cast<int>(polygon.size());
    if (maxPoints <= 0 && n <= kMaxContactPoints) return deepestFirst(polygon);  // every point, rim included
    if (maxPoints <= 0 || maxPoints > kMaxContactPoints) maxPoints = kMaxContactPoints;
    constexpr int kHull = 2 * kMaxContactPoints + 2;
    if (n <= kMaxContactPoints) {
        Vec3 q[kMaxContactPoints];
        int kept[kMaxContactPoints], deep[kMaxContactPoints], hull[kHull];
        unsigned char taken[kMaxContactPoints];
        return reduceWith(polygon, normal, maxPoints, steps, Scratch{q, kept, deep, taken, hull});
    }
    StackArena<4096> arena;
    std::pmr::vector<Vec3> q(n, arena.resource());
    std::pmr::vector<int> kept(n, arena.resource()), deep(n, arena.resource()), hull(kHull, arena.resource());
    std::pmr::vector<unsigned char> taken(n, arena.resource());
    return reduceWith(polygon, normal, maxPoints, steps,
                      Scratch{q.data(), kept.data(), deep.data(), taken.data(), hull.data()});
}

ContactIndices deepestFirst(std::span<const ContactPoint> points) {
    const int n = static_cast<int>(std::min(points.size(), std::size_t(kMaxContactPoints)));
    int all[kMaxContactPoints];
    for (int i = 0; i < n; ++i) all[i] = i;
    return deepestFirst(points, all, n);
}

}  // namespace cdlab
