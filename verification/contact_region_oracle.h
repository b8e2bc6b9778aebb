// Exact contact regions, the oracle of the manifold tests (never the code under test): every
// point a contact manifold may hold, computed in rationals from the input doubles (which are dyadic
// rationals, scaled by a common 2^K to integers; BigInt from verification/closest_oracle.h).
//
//  - Face clip (the reference/incident faces of a SAT face contact; Ericson, "Real-Time Collision
//    Detection" §8.3.4; Gregorius, "Robust Contact Creation", GDC 2015): the incident polygon
//    clipped by the side planes of the reference face (the planes through its edges, parallel to its
//    normal). Each corner of a convex polygon cut by half-planes is where two of the boundary lines
//    meet, so the corners are the points where the incident face's plane meets two of the planes
//    {incident edges' side planes, reference side planes} and that satisfy every constraint: a 3×3
//    system solved by Cramer's rule in integers, the constraints tested exactly. Candidates: the
//    corners with depth >= 0 (on or behind the reference plane), as a manifold keeps them.
//  - Plane region (a polytope against the solid half-space n · x <= d): the vertices on or below the
//    plane and the points where an edge crosses it (depth 0, exact).
// The corners of a region are its candidates' convex hull in the plane ⟂ the normal (exact
// orientation tests; collinear and repeated points are not corners).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "verification/closest_oracle.h"

namespace oracle {

using LVec3 = Eigen::Matrix<long double, 3, 1>;

/// A candidate point of a contact region, rounded from its exact value.
struct RegionPoint {
    LVec3 position = LVec3::Zero();  ///< world
    long double depth = 0;           ///< below the reference plane (> 0 inside), world units
    int depthSign = 0;               ///< the exact sign of the depth
    bool crossing = false;           ///< plane region: where an edge crosses the plane (depth exactly 0)
};

namespace region_detail {
struct Rational;
}

struct ContactRegion {
    std::string error;              ///< non-empty: the input was not what the oracle needs
    LVec3 normal = LVec3::UnitZ();  ///< unit outward normal of the reference face / the plane
    std::vector<RegionPoint> candidates;
    std::vector<int> corners;  ///< indices into candidates: the hull's corners, counter-clockwise about normal
    std::vector<region_detail::Rational> exact;  ///< the candidates' exact values
    BigVec exactNormal;                          ///< the normal, exact (any length)
};

namespace region_detail {

inline BigInt small(long long v) {
    return v == 0 ? BigInt{} : BigInt::fromParts(static_cast<uint64_t>(v < 0 ? -v : v), 0, v < 0);
}
inline int compare(const BigInt& a, const BigInt& b) { return (a - b).sign; }
inline bool equal(const BigInt& a, const BigInt& b) { return compare(a, b) == 0; }
inline BigVec scale(const BigVec& a, const BigInt& s) { return {{a.v[0] * s, a.v[1] * s, a.v[2] * s}}; }
inline BigVec add(const BigVec& a, const BigVec& b) { return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]}}; }
inline long double toLong(const BigInt& a) {
    long double r = 0;
    for (size_t i = a.mag.size(); i-- > 0;) r = r * 4294967296.0L + a.mag[i];
    return a.sign < 0 ? -r : r;
}
inline LVec3 toLong(const BigVec& a) { return {toLong(a.v[0]), toLong(a.v[1]), toLong(a.v[2])}; }

/// The rational point X / D, D > 0, in the scaled units (world = X / (D 2^K)).
struct Rational {
    BigVec X;
    BigInt D;
};
inline bool samePoint(const Rational& a, const Rational& b) {
    for (int i = 0; i < 3; ++i)
        if (!equal(a.X.v[i] * b.D, b.X.v[i] * a.D)) return false;
    return true;
}
/// (b - a) times Da Db (> 0): the direction from a to b in integers.
inline BigVec difference(const Rational& a, const Rational& b) { return sub(scale(b.X, a.D), scale(a.X, b.D)); }
/// Sign of n · x - offset at x = X / D (plane n · x = offset, all in the same scaled units).
inline int side(const BigVec& n, const BigInt& offset, const Rational& x) { return (dotv(n, x.X) - offset * x.D).sign; }

/// A half-space n · x <= offset (scaled units).
struct HalfSpace {
    BigVec n;
    BigInt offset;
};
inline HalfSpace sidePlane(const BigVec& p, const BigVec& q, const BigVec& faceNormal) {
    const BigVec n = cross(sub(q, p), faceNormal);  // outward for a polygon counter-clockwise about faceNormal
    return {n, dotv(n, p)};
}
/// The point on the plane n0 · x = b0 and the boundaries of h1, h2 (Cramer's rule); none when they
/// do not meet in one point.
inline std::optional<Rational> meet(const BigVec& n0, const BigInt& b0, const HalfSpace& h1, const HalfSpace& h2) {
    const BigVec c12 = cross(h1.n, h2.n), c20 = cross(h2.n, n0), c01 = cross(n0, h1.n);
    BigInt D = dotv(n0, c12);
    if (D.sign == 0) return std::nullopt;
    BigVec X = add(add(scale(c12, b0), scale(c20, h1.offset)), scale(c01, h2.offset));
    if (D.sign < 0) {
        D = -D;
        for (auto& c : X.v) c = -c;
    }
    return Rational{X, D};
}

/// Exact convex hull (Jarvis march) of the points projected along N: indices, counter-clockwise
/// about N, collinear points left out, one index per corner where several points project onto it.
inline std::vector<int> hullAbout(const std::vector<Rational>& p, const BigVec& N) {
    const int n = static_cast<int>(p.size());
    if (n == 0) return {};
    // orient(a, b, c) = sign of N · ((b - a) x (c - a)); "farther" compares projected lengths.
    auto orient = [&](int a, int b, int c) { return dotv(N, cross(difference(p[a], p[b]), difference(p[a], p[c]))).sign; };
    auto projected = [&](const BigVec& v) { return cross(v, N); };  // |N| times the projection, turned
    auto fartherThan = [&](int a, int r, int q) {  // r beyond q on the ray from a (r, q collinear with a)
        return dotv(projected(difference(p[q], p[r])), projected(difference(p[a], p[q]))).sign > 0;
    };
    auto sameProjected = [&](int a, int b) {  // one point seen along N (a vertical edge's two ends)
        const BigVec v = projected(difference(p[a], p[b]));
        return v.v[0].sign == 0 && v.v[1].sign == 0 && v.v[2].sign == 0;
    };
    // Start: extreme along e1 ⟂ N (ties: along e2), a hull corner.
    BigVec axis{{small(1), BigInt{}, BigInt{}}};
    const LVec3 nl = toLong(N).cwiseAbs();
    if (nl.x() >= nl.y() && nl.x() >= nl.z()) axis = BigVec{{BigInt{}, small(1), BigInt{}}};
    const BigVec e1 = cross(N, axis), e2 = cross(N, e1);
    auto before = [&](int a, int b) {
        const int c1 = compare(dotv(e1, p[a].X) * p[b].D, dotv(e1, p[b].X) * p[a].D);
        if (c1 != 0) return c1 < 0;
        return compare(dotv(e2, p[a].X) * p[b].D, dotv(e2, p[b].X) * p[a].D) < 0;
    };
    int start = 0;
    for (int i = 1; i < n; ++i)
        if (before(i, start)) start = i;
    std::vector<int> hull;
    int current = start;
    do {
        hull.push_back(current);
        int next = -1;
        for (int r = 0; r < n; ++r) {
            if (sameProjected(r, current)) continue;
            if (next < 0) {
                next = r;
                continue;
            }
            const int o = orient(current, next, r);
            if (o < 0 || (o == 0 && fartherThan(current, r, next))) next = r;
        }
        if (next < 0) break;  // every point coincides
        current = next;
    } while (!sameProjected(current, start) && hull.size() <= p.size());
    return hull;
}

inline LVec3 toWorld(const Rational& x, int K) {
    const long double d = toLong(x.D);
    return toLong(x.X) / d * std::ldexp(1.0L, -K);
}

}  // namespace region_detail

/// The face clip of `incident` (a convex planar polygon, counter-clockwise seen from its outside)
/// by the side planes of `reference` (likewise, the reference body's face: its outward normal is
/// its counter-clockwise area normal), with each corner's depth behind the reference plane.
/// Candidates: the corners with depth >= 0. A face without area or not exactly planar: error.
inline ContactRegion exactFaceClipRegion(const std::vector<Vec3>& reference, const std::vector<Vec3>& incident) {
    using namespace region_detail;
    ContactRegion out;
    if (reference.size() < 3 || incident.size() < 3) {
        out.error = "a face needs 3 corners";
        return out;
    }
    int K = 0;
    for (const auto* face : {&reference, &incident})
        for (const Vec3& v : *face) K = std::max(K, commonShift({v}));
    std::vector<BigVec> R, I;
    for (const Vec3& v : reference) R.push_back(toBig(v, K));
    for (const Vec3& v : incident) I.push_back(toBig(v, K));
    // Area normals (sum of the fan's cross products): non-zero for any polygon with area, even
    // when its first three corners are collinear.
    const auto areaNormal = [](const std::vector<BigVec>& P) {
        BigVec n{};
        for (std::size_t i = 1; i + 1 < P.size(); ++i) n = add(n, cross(sub(P[i], P[0]), sub(P[i + 1], P[0])));
        return n;
    };
    const BigVec nR = areaNormal(R), nI = areaNormal(I);
    const auto zero = [](const BigVec& v) { return v.v[0].sign == 0 && v.v[1].sign == 0 && v.v[2].sign == 0; };
    if (zero(nR) || zero(nI)) {
        out.error = "a face has no area";
        return out;
    }
    const BigInt dR = dotv(nR, R[0]), dI = dotv(nI, I[0]);
    for (const BigVec& r : R)
        if (!equal(dotv(nR, r), dR)) out.error = "the reference face is not exactly planar";
    for (const BigVec& v : I)
        if (!equal(dotv(nI, v), dI)) out.error = "the incident face is not exactly planar";
    if (!out.error.empty()) return out;
    std::vector<HalfSpace> constraints;
    for (size_t j = 0; j < I.size(); ++j) constraints.push_back(sidePlane(I[j], I[(j + 1) % I.size()], nI));
    for (size_t i = 0; i < R.size(); ++i) constraints.push_back(sidePlane(R[i], R[(i + 1) % R.size()], nR));

    std::vector<Rational> points;
    for (size_t a = 0; a < constraints.size(); ++a)
        for (size_t b = a + 1; b < constraints.size(); ++b) {
            const std::optional<Rational> x = meet(nI, dI, constraints[a], constraints[b]);
            if (!x) continue;
            bool inside = true;
            for (const HalfSpace& h : constraints) inside = inside && side(h.n, h.offset, *x) <= 0;
            bool repeated = false;
            for (const Rational& q : points) repeated = repeated || samePoint(q, *x);
            if (inside && !repeated) points.push_back(*x);
        }
    // Depth behind the reference plane: (dR - nR · x) / |nR|, world units.
    const long double nRLength = toLong(nR).norm();
    std::vector<Rational> kept;
    for (const Rational& x : points) {
        const BigInt g = dotv(nR, x.X) - dR * x.D;  // > 0: in front of the reference face
        if (g.sign > 0) continue;
        RegionPoint c;
        c.position = toWorld(x, K);
        c.depth = -toLong(g) / toLong(x.D) / nRLength * std::ldexp(1.0L, -K);
        c.depthSign = -g.sign;
        out.candidates.push_back(c);
        kept.push_back(x);
    }
    out.normal = toLong(nR).normalized();
    out.corners = hullAbout(kept, nR);
    out.exact = kept;
    out.exactNormal = nR;
    return out;
}

/// The contact region of a polytope (world vertices, edges as vertex pairs) against the solid
/// half-space n · x <= d: the vertices on or below the plane, and the edge crossings.
inline ContactRegion exactPlaneRegion(const std::vector<Vec3>& vertices, const std::vector<std::pair<int, int>>& edges,
                                      const Vec3& n, double d) {
    using namespace region_detail;
    ContactRegion out;
    int K = commonShift({n, Vec3(d, 0, 0)});
    for (const Vec3& v : vertices) K = std::max(K, commonShift({v}));
    const BigVec N = toBig(n, K);
    if (N.v[0].sign == 0 && N.v[1].sign == 0 && N.v[2].sign == 0) {
        out.error = "the plane's normal is zero";
        return out;
    }
    const BigInt offset = toBig(d, K) * BigInt::fromParts(1, K, false);  // d in the units of N · X
    const long double length = toLong(N).norm();
    std::vector<Rational> points;
    std::vector<BigInt> s;  // N · X - offset per vertex: > 0 above the plane
    for (const Vec3& v : vertices) s.push_back(dotv(N, toBig(v, K)) - offset);
    auto add = [&](const Rational& x, const BigInt& g, bool crossing) {
        RegionPoint c;
        c.position = toWorld(x, K);
        c.depth = -toLong(g) / toLong(x.D) / length * std::ldexp(1.0L, -K);
        c.depthSign = -g.sign;
        c.crossing = crossing;
        out.candidates.push_back(c);
        points.push_back(x);
    };
    for (size_t i = 0; i < vertices.size(); ++i)
        if (s[i].sign <= 0) add(Rational{toBig(vertices[i], K), small(1)}, s[i], false);
    for (const auto& [i, j] : edges) {
        if (s[i].sign * s[j].sign >= 0) continue;  // not strictly crossing
        // x = (s_i X_j - s_j X_i) / (s_i - s_j): the point of the edge where s = 0.
        Rational x{sub(scale(toBig(vertices[j], K), s[i]), scale(toBig(vertices[i], K), s[j])), s[i] - s[j]};
        if (x.D.sign < 0) {
            x.D = -x.D;
            for (auto& c : x.X.v) c = -c;
        }
        add(x, BigInt{}, true);
    }
    out.normal = toLong(N).normalized();
    out.corners = hullAbout(points, N);
    out.exact = points;
    out.exactNormal = N;
    return out;
}

/// The corners of the hull of some of a region's candidates (indices into candidates), exact.
inline std::vector<int> hullCorners(const ContactRegion& region, const std::vector<int>& subset) {
    std::vector<region_detail::Rational> points;
    for (int i : subset) points.push_back(region.exact[i]);
    std::vector<int> corners;
    for (int k : region_detail::hullAbout(points, region.exactNormal)) corners.push_back(subset[k]);
    return corners;
}

}  // namespace oracle
