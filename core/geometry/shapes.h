// Convex shapes as support mappings (core/base/support.h): s(d) is a point of the shape with maximal
// d · s(d). Body frame unless wrapped in Transformed<>. van den Bergen, "Collision Detection in
// Interactive 3D Environments" (2003), §4.3 gives the mappings of the primitives used here; the
// polytope's hill climbing is §4.3.4 / Cameron, "Enhancing GJK" (1997).
//
// Conventions shared by every shape:
//   - support(d) never returns NaN: for d = 0, NaN or Inf it returns a fixed point of the shape
//     (documented per shape), because every point maximizes 0 · x.
//   - Ties are broken deterministically (first vertex / the +side for d_i = 0).
//   - Margins: support(d) == supportCore(d) + margin() * d / |d|. GJK can run on supportCore()
//     and add the margins afterwards (sphere: core = centre point, capsule: core = segment,
//     RoundedShape<S>: core = S's core, margin = radius + S's margin). Shapes without a rounded
//     part have margin() == 0 and supportCore == support.
//   - boundingRadius(): radius of a ball about the body origin containing the shape (upper bound).
//     supportBounds(shape) gives the exact axis-aligned box from six support queries.
// Names end in "Shape": Sphere, Capsule, Aabb, Obb, Ray are primitive-test structs of core/base/primitives.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "core/base/support.h"
#include "core/base/types.h"

namespace cdlab {

class ConvexPolyhedron;

namespace shape_detail {
/// d / |d| without overflow or underflow (scaled by the largest component first); false for a
/// zero, NaN or infinite d, in which case u is left untouched.
inline bool unitDirection(const Vec3& d, Vec3& u) {
    const double m = d.cwiseAbs().maxCoeff();
    if (!(m > 0.0) || !std::isfinite(m)) return false;  // NaN fails the first test
    const Vec3 s = d / m;
    u = s / s.norm();
    return true;
}
/// Unit vector of (x, z) in the plane, or false when both are 0 / not finite.
inline bool unitPlanar(double x, double z, double& ux, double& uz) {
    const double m = std::max(std::abs(x), std::abs(z));
    if (!(m > 0.0) || !std::isfinite(m)) return false;
    const double sx = x / m, sz = z / m, len = std::sqrt(sx * sx + sz * sz);
    ux = sx / len;
    uz = sz / len;
    return true;
}
}  // namespace shape_detail

/// Support of the core of a shape (the shape without its margin): shape.supportCore(d) if the
/// shape has one, else shape.support(d).
template <SupportMapping S>
Vec3 coreSupport(const S& shape, const Vec3& d) {
    if constexpr (requires { shape.supportCore(d); }) {
        return shape.supportCore(d);
    } else {
        return shape.support(d);
    }
}
/// Margin (radius of the sphere Minkowski-added to the core): shape.margin() if present, else 0.
template <SupportMapping S>
double marginOf(const S& shape) {
    if constexpr (requires { shape.margin(); }) {
        return shape.margin();
    } else {
        return 0.0;
    }
}

/// Axis-aligned bounds of a convex set, min and max corner.
struct ShapeBounds {
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();
};
/// Exact axis-aligned bounds from six support queries (frame of the shape's support mapping).
template <SupportMapping S>
ShapeBounds supportBounds(const S& shape) {
    ShapeBounds b;
    for (int i = 0; i < 3; ++i) {
        Vec3 d = Vec3::Zero();
        d[i] = 1.0;
        b.max[i] = Vec3(shape.support(d))[i];
        d[i] = -1.0;
        b.min[i] = Vec3(shape.support(d))[i];
    }
    return b;
}
/// shape.boundingRadius() if present, else the largest corner of supportBounds() (about the origin).
template <SupportMapping S>
double boundingRadiusOf(const S& shape) {
    if constexpr (requires { shape.boundingRadius(); }) {
        return shape.boundingRadius();
    } else {
        const ShapeBounds b = supportBounds(shape);
        return b.min.cwiseAbs().cwiseMax(b.max.cwiseAbs()).norm();
    }
}

/// A single point.
struct PointShape {
    Vec3 point = Vec3::Zero();
    /// Always `point`.
    Vec3 support(const Vec3&) const { return point; }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return point.norm(); }
};

/// Segment a-b. Tie (d ⊥ b - a, or d = 0 / NaN): a.
struct SegmentShape {
    Vec3 a = Vec3::Zero();
    Vec3 b = Vec3::Zero();
    Vec3 support(const Vec3& d) const { return d.dot(b) > d.dot(a) ? b : a; }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return std::max(a.norm(), b.norm()); }
};

/// Triangle abc (any winding, zero area allowed). Ties: the first of a, b, c.
struct TriangleShape {
    Vec3 a = Vec3::Zero();
    Vec3 b = Vec3::Zero();
    Vec3 c = Vec3::Zero();
    Vec3 support(const Vec3& d) const {
        const double da = d.dot(a), db = d.dot(b), dc = d.dot(c);
        if (db > da) return dc > db ? c : b;
        return dc > da ? c : a;
    }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return std::max({a.norm(), b.norm(), c.norm()}); }
};

/// Ball of the given radius about the origin. d = 0 / NaN: (radius, 0, 0).
/// Core: the centre point; margin: radius.
struct SphereShape {
    double radius = 1.0;
    Vec3 support(const Vec3& d) const {
        Vec3 u;
        return shape_detail::unitDirection(d, u) ? Vec3(radius * u) : Vec3(radius, 0.0, 0.0);
    }
    Vec3 supportCore(const Vec3&) const { return Vec3::Zero(); }
    double margin() const { return radius; }
    double boundingRadius() const { return radius; }
};

/// Axis-aligned box [-h, h] about the origin. d_i = 0 (or NaN) picks +h_i: d = 0 gives +h.
struct BoxShape {
    Vec3 halfExtents = Vec3::Ones();
    Vec3 support(const Vec3& d) const {
        return Vec3(d.x() < 0.0 ? -halfExtents.x() : halfExtents.x(), d.y() < 0.0 ? -halfExtents.y() : halfExtents.y(),
                    d.z() < 0.0 ? -halfExtents.z() : halfExtents.z());
    }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return halfExtents.norm(); }
};

/// Capsule: segment a-b swept by a ball of `radius`. Core: the segment; margin: radius.
/// d = 0 / NaN: a + (radius, 0, 0).
struct CapsuleShape {
    Vec3 a = Vec3(0.0, -0.5, 0.0);
    Vec3 b = Vec3(0.0, 0.5, 0.0);
    double radius = 0.5;
    /// Capsule along y: segment from (0, -halfHeight, 0) to (0, halfHeight, 0) (caps excluded from halfHeight).
    static CapsuleShape alongY(double halfHeight, double radius) {
        return CapsuleShape{Vec3(0.0, -halfHeight, 0.0), Vec3(0.0, halfHeight, 0.0), radius};
    }
    Vec3 supportCore(const Vec3& d) const { return d.dot(b) > d.dot(a) ? b : a; }
    Vec3 support(const Vec3& d) const { return supportCore(d) + SphereShape{radius}.support(d); }
    double margin() const { return radius; }
    double boundingRadius() const { return std::max(a.norm(), b.norm()) + radius; }
};

/// Solid cylinder with axis y, |y| <= halfHeight, x^2 + z^2 <= radius^2. d along ±y (no xz part):
/// the cap centre (0, ±halfHeight, 0); d_y = 0 picks +halfHeight.
struct CylinderShape {
    double halfHeight = 0.5;
    double radius = 0.5;
    Vec3 support(const Vec3& d) const {
        const double y = d.y() < 0.0 ? -halfHeight : halfHeight;
        double ux, uz;
        if (!shape_detail::unitPlanar(d.x(), d.z(), ux, uz)) return Vec3(0.0, y, 0.0);
        return Vec3(radius * ux, y, radius * uz);
    }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return std::sqrt(halfHeight * halfHeight + radius * radius); }
};

/// Solid cone with axis y: apex (0, halfHeight, 0), base disc of `radius` at y = -halfHeight.
/// Returns whichever of apex and base-rim point is higher along d (tie: apex); d along -y: base centre.
struct ConeShape {
    double halfHeight = 0.5;
    double radius = 0.5;
    Vec3 support(const Vec3& d) const {
        const Vec3 apex(0.0, halfHeight, 0.0);
        double ux, uz;
        Vec3 rim(0.0, -halfHeight, 0.0);
        if (shape_detail::unitPlanar(d.x(), d.z(), ux, uz)) rim = Vec3(radius * ux, -halfHeight, radius * uz);
        return d.dot(rim) > d.dot(apex) ? rim : apex;
    }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return std::sqrt(halfHeight * halfHeight + radius * radius); }
};

/// Convex polytope given by its vertices (body frame). Support: for <= kLoopMaxVertices vertices
/// (or without adjacency) a tight loop over a contiguous vertex array returning the first maximal
/// vertex; otherwise steepest-ascent hill climbing over the vertex adjacency of a ConvexPolyhedron,
/// started from the best of the six axis-extreme vertices or from a caller's warm-start vertex.
/// Plateaus (neighbours with exactly equal d · x) are explored breadth-first so that an uphill edge
/// leaving any plateau vertex is found: the climb stops only at a vertex set with no uphill
/// neighbour, which on a convex polytope is the global maximum; of that plateau the lowest index
/// is returned (= the loop's answer whenever the maximal vertices form a connected plateau).
/// Empty polytope: support returns the origin, supportIndex -1. d = 0 / NaN: vertex 0.
class PolytopeShape {
public:
    /// Up to this many vertices the loop beats climbing even with adjacency: on random hulls of
    /// points on ellipsoids (every point a vertex) GJK distance took 1.8 µs with the loop against
    /// 3.6 µs climbing at 64 vertices, 3.0 against 7.3 at 128, 7.0 against 10.7 at 256, and the
    /// two met near 512 (one driver, interleaved rounds, 2026-11-27): the loop is branch-light
    /// and streams a contiguous array, each climbing step chases neighbour indices.
    static constexpr int kLoopMaxVertices = 256;

    PolytopeShape() = default;
    /// Vertices only (no adjacency): always the loop. Non-extreme points are harmless.
    explicit PolytopeShape(std::vector<Vec3> vertices);
    /// Vertices and adjacency of a convex polyhedron (vertex order kept: index i is poly vertex i).
    explicit PolytopeShape(const ConvexPolyhedron& polyhedron);

    Vec3 support(const Vec3& d) const {
        const int i = supportIndex(d);
        return i >= 0 ? vertices_[i] : Vec3::Zero();
    }
    /// Same point as support(d) up to ties, with a caller-held hint for frame / iteration coherence
    /// (GJK keeps one per shape): hill climbing starts at `hint` or at the best axis-extreme seed,
    /// whichever is higher along d (a hint from a very different direction, as in GJK's first
    /// iterations, would cost a long climb), and the answer's index is written back (-1: no hint).
    /// Small polytopes (or no adjacency) ignore it and loop.
    Vec3 support(const Vec3& d, int& hint) const {
        int i;
        if (adjacencyStart_.empty() || vertices_.size() <= static_cast<size_t>(kLoopMaxVertices)) {
            i = supportIndexLoop(d);
        } else {
            int start = seedVertex(d);
            if (hint >= 0 && hint < vertexCount() && d.dot(vertices_[hint]) > d.dot(vertices_[start])) start = hint;
            i = supportIndexClimb(d, start);
        }
        hint = i;
        return i >= 0 ? vertices_[i] : Vec3::Zero();
    }
    Vec3 supportCore(const Vec3& d) const { return support(d); }
    double margin() const { return 0.0; }
    double boundingRadius() const { return boundingRadius_; }

    /// Index of a maximal vertex for d (loop or climb as described above); -1 if empty.
    int supportIndex(const Vec3& d) const { return supportIndex(d, -1); }
    /// Same, hill climbing from startVertex (e.g. the previous answer: warm start) when there is
    /// adjacency and more than kLoopMaxVertices vertices; an invalid start falls back to the seeds.
    int supportIndex(const Vec3& d, int startVertex) const {
        // Inline dispatch: GJK's inner loop pays one call, not two.
        if (adjacencyStart_.empty() || vertices_.size() <= static_cast<size_t>(kLoopMaxVertices))
            return supportIndexLoop(d);
        return supportIndexClimb(d, startVertex);
    }
    /// Brute-force loop over all vertices: first maximal vertex; -1 if empty.
    int supportIndexLoop(const Vec3& d) const;
    /// Hill climbing from startVertex (requires adjacency); the loop if there is none.
    int supportIndexClimb(const Vec3& d, int startVertex) const;

    int vertexCount() const { return static_cast<int>(vertices_.size()); }
    const Vec3& vertex(int i) const { return vertices_[i]; }
    const std::vector<Vec3>& vertices() const { return vertices_; }
    bool hasAdjacency() const { return !adjacencyStart_.empty(); }
    /// Neighbours of vertex i (counter-clockwise seen from outside); empty without adjacency.
    std::span<const int> neighbors(int i) const;

private:
    int seedVertex(const Vec3& d) const;

    std::vector<Vec3> vertices_;
    std::vector<int> adjacencyStart_;  // CSR: neighbours of i are adjacency_[start[i] .. start[i+1])
    std::vector<int> adjacency_;
    std::array<int, 6> axisExtremes_{};  // argmax/argmin of x, y, z: cold-start seeds
    double boundingRadius_ = 0.0;
};

/// S placed by a rigid transform: support(d) = T(s(R^T d)), in the transform's parent (world) frame.
template <SupportMapping S>
struct Transformed {
    S shape;
    Transform transform;
    Vec3 support(const Vec3& d) const { return transform.apply(Vec3(shape.support(transform.rotateInverse(d)))); }
    /// Hinted support (see PolytopeShape::support(d, hint)), forwarded when S has one.
    Vec3 support(const Vec3& d, int& hint) const requires requires(const S& s, const Vec3& v, int& h) {
        s.support(v, h);
    }
    { return transform.apply(Vec3(shape.support(transform.rotateInverse(d), hint))); }
    Vec3 supportCore(const Vec3& d) const { return transform.apply(coreSupport(shape, transform.rotateInverse(d))); }
    double margin() const { return marginOf(shape); }
    /// About the parent-frame origin: |position| + the body's radius.
    double boundingRadius() const { return transform.position.norm() + boundingRadiusOf(shape); }
};

/// A ⊕ B = {a + b}: support_A(d) + support_B(d). Cores add, margins add.
template <SupportMapping A, SupportMapping B>
struct MinkowskiSum {
    A a;
    B b;
    Vec3 support(const Vec3& d) const { return Vec3(a.support(d)) + Vec3(b.support(d)); }
    Vec3 supportCore(const Vec3& d) const { return coreSupport(a, d) + coreSupport(b, d); }
    double margin() const { return marginOf(a) + marginOf(b); }
    double boundingRadius() const { return boundingRadiusOf(a) + boundingRadiusOf(b); }
};

/// S ⊕ ball(radius) (rounded box, rounded polytope...). core(): S itself; supportCore(): S's core;
/// margin(): radius + S's margin, so GJK on supportCore() plus margin() reproduces support().
template <SupportMapping S>
struct RoundedShape {
    S inner;
    double radius = 0.0;
    const S& core() const { return inner; }
    Vec3 support(const Vec3& d) const { return Vec3(inner.support(d)) + SphereShape{radius}.support(d); }
    Vec3 supportCore(const Vec3& d) const { return coreSupport(inner, d); }
    double margin() const { return radius + marginOf(inner); }
    double boundingRadius() const { return boundingRadiusOf(inner) + radius; }
};

}  // namespace cdlab
