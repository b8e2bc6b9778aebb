#include "verification/minkowski_hull_oracle.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/convex_hull.h"
#include "verification/long_double_geometry.h"

namespace cdlab::demos {

namespace {

using long_double::LVec;
using long_double::polygonDistanceL;
using long_double::segmentDistanceL;
using long_double::toL;
using long_double::triangleDistanceL;

// |segment pq - segment rs|: t -> |p + t (q - p) - segment rs| is convex (the distance to a
// convex set along a line), so a ternary search on [0, 1] finds its minimum; 90 steps shrink the
// interval by (2/3)^90 ~ 1e-16 relative. No 2x2 solve: for nearly parallel segments its
// determinant a c - b^2 cancels catastrophically, while the search only evaluates distances.
long double segmentSegmentDistance(const LVec& p, const LVec& q, const LVec& r, const LVec& s) {
    auto f = [&](long double t) {
        const LVec x = p + t * (q - p);
        return segmentDistanceL(r - x, s - x);
    };
    long double lo = 0, hi = 1;
    for (int i = 0; i < 90; ++i) {
        const long double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) <= f(m2)) hi = m2;
        else lo = m1;
    }
    return std::min({f(0), f(1), f(0.5L * (lo + hi))});
}

}  // namespace

double oracleDistanceBruteForce(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    std::vector<LVec> la, lb;
    for (const Vec3& x : a) la.push_back(toL(x));
    for (const Vec3& x : b) lb.push_back(toL(x));
    long double best = INFINITY;
    // Vertex of one set against every triangle (and, through it, every edge and vertex) of the other.
    auto pointTriangles = [&](const std::vector<LVec>& pts, const std::vector<LVec>& tri) {
        const size_t n = tri.size();
        for (const LVec& x : pts)
            for (size_t i = 0; i < n; ++i)
                for (size_t j = i; j < n; ++j)
                    for (size_t k = j; k < n; ++k)
                        best = std::min(best, triangleDistanceL(tri[i] - x, tri[j] - x, tri[k] - x));
    };
    pointTriangles(la, lb);
    pointTriangles(lb, la);
    for (size_t i = 0; i < la.size(); ++i)
        for (size_t j = i + 1; j < la.size(); ++j)
            for (size_t k = 0; k < lb.size(); ++k)
                for (size_t l = k + 1; l < lb.size(); ++l)
                    best = std::min(best, segmentSegmentDistance(la[i], la[j], lb[k], lb[l]));
    return static_cast<double>(best);
}

MinkowskiOracle minkowskiOracle(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    MinkowskiOracle o;
    std::vector<Vec3> points;
    points.reserve(a.size() * b.size());
    for (const Vec3& x : a)
        for (const Vec3& y : b) points.push_back(x - y);
    HullOptions options;
    options.mergeCoplanarFaces = true;
    const HullResult hull = convexHull(points, options);
    if (!hull.ok()) return o;
    const ConvexPolyhedron& poly = hull.polyhedron;
    o.ok = true;
    o.inside = true;
    long double minDistance = INFINITY;
    long double minOffset = INFINITY;
    for (int f = 0; f < poly.faceCount(); ++f) {
        std::vector<LVec> v;
        for (int i : poly.faceVertices(f)) v.push_back(toL(poly.position(i)));
        if (v.size() < 3) continue;
        // Newell's normal of the (CCW from outside) polygon: outward, robust for any vertex count.
        LVec n = LVec::Zero();
        for (size_t i = 0; i < v.size(); ++i) {
            const LVec& p = v[i];
            const LVec& q = v[(i + 1) % v.size()];
            n += LVec((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                      (p.x() - q.x()) * (p.y() + q.y()));
        }
        const long double len = n.norm();
        if (!(len > 0)) continue;
        n /= len;
        ++o.faces;
        // Offset from the face centroid: averages the vertices' rounding.
        LVec centroid = LVec::Zero();
        for (const LVec& p : v) centroid += p;
        centroid /= static_cast<long double>(v.size());
        const long double offset = n.dot(centroid);
        if (offset <= 0) o.inside = false;
        if (offset < minOffset) {
            minOffset = offset;
            o.normal = Vec3(static_cast<double>(n.x()), static_cast<double>(n.y()), static_cast<double>(n.z()));
        }
        minDistance = std::min(minDistance, polygonDistanceL(v, n));
    }
    o.depth = o.inside ? static_cast<double>(minOffset) : 0.0;
    o.distance = o.inside ? 0.0 : static_cast<double>(minDistance);
    return o;
}

double oracleSegmentDistance(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
    return static_cast<double>(segmentSegmentDistance(toL(p), toL(q), toL(r), toL(s)));
}

double oracleDistanceToTriangle(const Vec3& p, const Triangle& t) {
    const LVec q = toL(p);
    return static_cast<double>(triangleDistanceL(toL(t.a) - q, toL(t.b) - q, toL(t.c) - q));
}

double oracleDistanceToTetrahedron(const Vec3& p, const Tetrahedron& t) {
    const LVec q = toL(p);
    const LVec v[4] = {toL(t.a) - q, toL(t.b) - q, toL(t.c) - q, toL(t.d) - q};
    // Inside iff the origin is on the inner side of all four faces (signed volumes, long double).
    auto vol = [](const LVec& a, const LVec& b, const LVec& c, const LVec& d) {
        return (b - a).dot((c - a).cross(d - a));
    };
    const long double total = vol(v[0], v[1], v[2], v[3]);
    const LVec o = LVec::Zero();
    const long double s[4] = {vol(o, v[1], v[2], v[3]), vol(v[0], o, v[2], v[3]), vol(v[0], v[1], o, v[3]),
                              vol(v[0], v[1], v[2], o)};
    if (total != 0 && std::all_of(s, s + 4, [&](long double x) { return x * total >= 0; })) return 0.0;
    return static_cast<double>(std::min({triangleDistanceL(v[1], v[2], v[3]), triangleDistanceL(v[0], v[2], v[3]),
                                         triangleDistanceL(v[0], v[1], v[3]), triangleDistanceL(v[0], v[1], v[2])}));
}

}  // namespace cdlab::demos
