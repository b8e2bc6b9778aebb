// Independent brute-force oracle for V-Clip tests: distances between convex polyhedra and
// between their features by exhaustive enumeration of point/segment/triangle pairs in long
// double (Ericson, "Real-Time Collision Detection" §5.1.2, §5.1.5 written afresh here; no code
// shared with core/vclip*.cpp or core/closest/closest_point.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab::test {

using LD = long double;

struct WalkVec {
    LD x = 0, y = 0, z = 0;
    WalkVec() = default;
    WalkVec(LD a, LD b, LD c) : x(a), y(b), z(c) {}
    explicit WalkVec(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
    WalkVec operator+(const WalkVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
    WalkVec operator-(const WalkVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
    WalkVec operator*(LD s) const { return {x * s, y * s, z * s}; }
    LD dot(const WalkVec& o) const { return x * o.x + y * o.y + z * o.z; }
    WalkVec cross(const WalkVec& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
    LD norm2() const { return dot(*this); }
};

/// Squared distance point p to segment ab.
inline LD pointSegment2(const WalkVec& p, const WalkVec& a, const WalkVec& b) {
    const WalkVec ab = b - a;
    const LD den = ab.norm2();
    LD t = den > 0 ? (p - a).dot(ab) / den : 0;
    t = std::clamp<LD>(t, 0, 1);
    return (a + ab * t - p).norm2();
}

/// Squared distance point p to triangle abc (closest point by regions, Ericson §5.1.5).
inline LD pointTriangle2(const WalkVec& p, const WalkVec& a, const WalkVec& b, const WalkVec& c) {
    const WalkVec n = (b - a).cross(c - a);
    const LD nn = n.norm2();
    if (nn > 0) {
        // Inside the prism over the triangle: the plane distance.
        const bool inside =
            (b - a).cross(p - a).dot(n) >= 0 && (c - b).cross(p - b).dot(n) >= 0 && (a - c).cross(p - c).dot(n) >= 0;
        if (inside) {
            const LD h = (p - a).dot(n);
            return h * h / nn;
        }
    }
    return std::min({pointSegment2(p, a, b), pointSegment2(p, b, c), pointSegment2(p, c, a)});
}

/// Squared distance between segments ab and cd: the best endpoint-to-segment pair, or the
/// closest points of the two lines when both fall inside their segments.
inline LD segmentSegment2(const WalkVec& a, const WalkVec& b, const WalkVec& c, const WalkVec& d) {
    LD best =
        std::min({pointSegment2(a, c, d), pointSegment2(b, c, d), pointSegment2(c, a, b), pointSegment2(d, a, b)});
    const WalkVec u = b - a, v = d - c, w = a - c;
    const LD uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
    const LD den = uu * vv - uv * uv;
    if (den > 1e-30L * uu * vv) {
        const LD s = (uv * vw - vv * uw) / den, t = (uu * vw - uv * uw) / den;
        if (s > 0 && s < 1 && t > 0 && t < 1) best = std::min(best, (w + u * s - v * t).norm2());
    }
    return best;
}

/// Squared distance segment ab to triangle pqr (0 if it crosses the triangle).
inline LD segmentTriangle2(const WalkVec& a, const WalkVec& b, const WalkVec& p, const WalkVec& q, const WalkVec& r) {
    const WalkVec n = (q - p).cross(r - p);
    const LD ha = (a - p).dot(n), hb = (b - p).dot(n);
    if ((ha <= 0 && hb >= 0) || (ha >= 0 && hb <= 0)) {
        const LD w = ha == hb ? 0 : ha / (ha - hb);
        const WalkVec x = a + (b - a) * w;
        if ((q - p).cross(x - p).dot(n) >= 0 && (r - q).cross(x - q).dot(n) >= 0 && (p - r).cross(x - r).dot(n) >= 0)
            return 0;
    }
    return std::min({pointTriangle2(a, p, q, r), pointTriangle2(b, p, q, r), segmentSegment2(a, b, p, q),
                     segmentSegment2(a, b, q, r), segmentSegment2(a, b, r, p)});
}

/// World-frame vertices of a posed polyhedron in long double (rotation applied in long double
/// from the double quaternion's matrix).
inline std::vector<WalkVec> worldVertices(const ConvexPolyhedron& p, const Transform& pose) {
    const Mat3 r = pose.rotation.normalized().toRotationMatrix();
    std::vector<WalkVec> out;
    for (const Vec3& v : p.positions()) {
        WalkVec w;
        LD c[3];
        for (int i = 0; i < 3; ++i)
            c[i] = static_cast<LD>(r(i, 0)) * v.x() + static_cast<LD>(r(i, 1)) * v.y() +
                   static_cast<LD>(r(i, 2)) * v.z() + static_cast<LD>(pose.position[i]);
        out.push_back({c[0], c[1], c[2]});
    }
    return out;
}

/// A feature as a point set: 1 point, a segment, or a polygon (fan-triangulated).
struct OracleFeature {
    int dim = 0;
    std::vector<WalkVec> pts;
};

/// type 0 vertex, 1 edge, 2 face (as VClipFeature::dimension()).
inline OracleFeature oracleFeature(const ConvexPolyhedron& p, const std::vector<WalkVec>& world, int dim, int index) {
    OracleFeature f;
    f.dim = dim;
    if (dim == 0) f.pts = {world[index]};
    if (dim == 1) {
        const int h = p.edge(index).halfEdge;
        f.pts = {world[p.halfEdge(h).origin], world[p.halfEdgeDestination(h)]};
    }
    if (dim == 2)
        for (int v : p.faceVertices(index)) f.pts.push_back(world[v]);
    return f;
}

/// Squared distance between two features (point sets).
inline LD featureDistance2(const OracleFeature& a, const OracleFeature& b) {
    if (a.dim > b.dim) return featureDistance2(b, a);
    LD best = std::numeric_limits<LD>::infinity();
    if (a.dim == 0 && b.dim == 0) return (a.pts[0] - b.pts[0]).norm2();
    if (a.dim == 0 && b.dim == 1) return pointSegment2(a.pts[0], b.pts[0], b.pts[1]);
    if (a.dim == 1 && b.dim == 1) return segmentSegment2(a.pts[0], a.pts[1], b.pts[0], b.pts[1]);
    if (b.dim == 2) {
        for (size_t i = 1; i + 1 < b.pts.size(); ++i) {
            const WalkVec &p = b.pts[0], &q = b.pts[i], &r = b.pts[i + 1];
            if (a.dim == 0) best = std::min(best, pointTriangle2(a.pts[0], p, q, r));
            if (a.dim == 1) best = std::min(best, segmentTriangle2(a.pts[0], a.pts[1], p, q, r));
            if (a.dim == 2)
                for (size_t j = 1; j + 1 < a.pts.size(); ++j)
                    for (int k = 0; k < 3; ++k) {
                        const WalkVec* t[3] = {&a.pts[0], &a.pts[j], &a.pts[j + 1]};
                        best = std::min(best, segmentTriangle2(*t[k], *t[(k + 1) % 3], p, q, r));
                    }
        }
    }
    return best;
}

/// Is world point x inside (or on) the posed polyhedron, up to `tol` (plane distances)?
inline bool insideWorld(const ConvexPolyhedron& p, const std::vector<WalkVec>& world, const WalkVec& x, LD tol) {
    for (int f = 0; f < p.faceCount(); ++f) {
        const std::vector<int> vs = p.faceVertices(f);
        WalkVec n;
        for (size_t i = 0; i < vs.size(); ++i) n = n + world[vs[i]].cross(world[vs[(i + 1) % vs.size()]]);
        const LD len = std::sqrt(n.norm2());
        if ((x - world[vs[0]]).dot(n) / len > tol) return false;
    }
    return true;
}

/// Brute-force distance of two posed convex polyhedra: 0 if they intersect (some vertex inside
/// the other or some edge crossing a face), else min over vertex-face and edge-edge pairs.
struct OracleDistance {
    LD distance = 0;
    bool intersect = false;
};

inline OracleDistance oracleDistance(const ConvexPolyhedron& a, const Transform& pa, const ConvexPolyhedron& b,
                                     const Transform& pb) {
    const std::vector<WalkVec> wa = worldVertices(a, pa), wb = worldVertices(b, pb);
    LD best = std::numeric_limits<LD>::infinity();
    auto faces = [](const ConvexPolyhedron& p, const std::vector<WalkVec>& w) {
        std::vector<OracleFeature> out;
        for (int f = 0; f < p.faceCount(); ++f) out.push_back(oracleFeature(p, w, 2, f));
        return out;
    };
    const std::vector<OracleFeature> fa = faces(a, wa), fb = faces(b, wb);
    // Bounding balls (centre = first point, radius = farthest point) to skip pairs that cannot
    // beat the best distance so far; exact pruning (a ball around a set contains it).
    struct Ball {
        WalkVec c;
        LD r = 0;
    };
    auto ball = [](const OracleFeature& f) {
        Ball b{f.pts[0], 0};
        for (const WalkVec& p : f.pts) b.r = std::max(b.r, std::sqrt((p - b.c).norm2()));
        return b;
    };
    auto far = [&](const Ball& x, const Ball& y) {
        const LD gap = std::sqrt((x.c - y.c).norm2()) - x.r - y.r;
        return gap > 0 && gap * gap > best;
    };
    std::vector<Ball> ba, bb;
    for (const OracleFeature& f : fa) ba.push_back(ball(f));
    for (const OracleFeature& f : fb) bb.push_back(ball(f));
    for (const WalkVec& v : wa)
        for (size_t k = 0; k < fb.size(); ++k)
            if (!far(Ball{v, 0}, bb[k])) best = std::min(best, featureDistance2(OracleFeature{0, {v}}, fb[k]));
    for (const WalkVec& v : wb)
        for (size_t k = 0; k < fa.size(); ++k)
            if (!far(Ball{v, 0}, ba[k])) best = std::min(best, featureDistance2(OracleFeature{0, {v}}, fa[k]));
    std::vector<OracleFeature> eb;
    std::vector<Ball> beb;
    for (int j = 0; j < b.edgeCount(); ++j) {
        eb.push_back(oracleFeature(b, wb, 1, j));
        beb.push_back(ball(eb.back()));
    }
    for (int i = 0; i < a.edgeCount(); ++i) {
        const OracleFeature ea = oracleFeature(a, wa, 1, i);
        const Ball bea = ball(ea);
        for (size_t j = 0; j < eb.size(); ++j)
            if (!far(bea, beb[j]))
                best = std::min(best, segmentSegment2(ea.pts[0], ea.pts[1], eb[j].pts[0], eb[j].pts[1]));
        for (size_t k = 0; k < fb.size() && best > 0; ++k)
            if (!far(bea, bb[k]) && featureDistance2(ea, fb[k]) == 0) best = 0;
    }
    for (size_t j = 0; j < eb.size() && best > 0; ++j)
        for (size_t k = 0; k < fa.size() && best > 0; ++k)
            if (!far(beb[j], ba[k]) && featureDistance2(eb[j], fa[k]) == 0) best = 0;
    OracleDistance out;
    // One body inside the other: a vertex strictly inside.
    if (best > 0 && (insideWorld(b, wb, wa[0], 0) || insideWorld(a, wa, wb[0], 0))) best = 0;
    out.distance = std::sqrt(best);
    out.intersect = best == 0;
    return out;
}

}  // namespace cdlab::test
