// Ready-made convex polyhedra (body frame, centred at the origin, length units) and a portable
// pseudo-random generator for reproducible random hulls.
//
// Platonic solids: coordinates from Coxeter, "Regular Polytopes", §3.7 (icosahedron from golden
// rectangles, dodecahedron from the cube plus golden-ratio points). Solids with polygon faces built
// by convexHull() have their coplanar triangles merged (pentagons for the dodecahedron).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/polyhedron.h"

namespace cdlab::presets {

/// disk()'s default half thickness, relative to its radius: thick enough that the face planes are
/// well conditioned in double, thin enough to look and collide like a disk.
inline constexpr double kDiskHalfThicknessRatio = 1e-4;

/// splitmix64 (Steele, Lea, Flood, OOPSLA 2014): identical sequence on every platform and
/// standard library (std:: distributions are not). Doubles are built from the top 53 bits.
struct SplitMix64 {
    std::uint64_t state = 0;
    explicit SplitMix64(std::uint64_t seed) : state(seed) {}
    std::uint64_t next();
    /// Uniform in [0, 1), multiples of 2^-53.
    double nextDouble();
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * nextDouble(); }
    /// Uniform in the unit ball (rejection from the cube [-1,1]^3; only +,*,compare: portable).
    Vec3 inUnitBall();
    /// Uniform on the unit sphere (inUnitBall() normalized; sqrt is correctly rounded, so portable).
    Vec3 onUnitSphere();
};

/// Regular tetrahedron with the given circumradius (vertices (±1,±1,±1) with even sign parity, scaled).
ConvexPolyhedron tetrahedron(double circumradius = 1.0);
/// Axis-aligned box [-h, h] (6 quads, 8 vertices). Every half extent must be > 0.
ConvexPolyhedron box(const Vec3& halfExtents);
/// Regular octahedron with vertices at ±circumradius on each axis.
ConvexPolyhedron octahedron(double circumradius = 1.0);
/// Regular icosahedron (12 vertices, 20 triangles) with the given circumradius.
ConvexPolyhedron icosahedron(double circumradius = 1.0);
/// Regular dodecahedron (20 vertices, 12 pentagons) with the given circumradius.
ConvexPolyhedron dodecahedron(double circumradius = 1.0);
/// Right prism over a regular n-gon (n >= 3, clamped) in the xz plane with circumradius `radius`,
/// axis y, from y = -halfHeight to +halfHeight: n quads + 2 n-gon caps. Vertex i (bottom) and
/// n + i (top) sit at (radius cos a, -+halfHeight, -radius sin a), a = 2 pi i / n (counter-clockwise
/// seen from +y). Built from explicit faces (no hull).
ConvexPolyhedron prism(int n, double radius, double halfHeight);
/// A flat regular n-gon "disk" as a very thin prism: a flat polygon has no volume, so it cannot be
/// a closed convex polyhedron. halfThickness (std::nullopt, or a value <= 0: automatic) defaults to
/// kDiskHalfThicknessRatio * radius. For a truly flat polygon use regularPolygon() with
/// PolytopeShape (support mappings need no faces).
ConvexPolyhedron disk(int n, double radius, std::optional<double> halfThickness = std::nullopt);
/// The n vertices (n >= 3, clamped) of a regular polygon of circumradius `radius` in the plane y = 0,
/// counter-clockwise seen from +y (same angles as prism()).
std::vector<Vec3> regularPolygon(int n, double radius);
/// Geodesic sphere: the icosahedron with each triangle split into 4 `level` times, vertices
/// projected onto the sphere; 10 * 4^level + 2 vertices, 20 * 4^level triangles. level is clamped
/// to [0, 6].
ConvexPolyhedron geodesicSphere(int level, double radius = 1.0);

enum class RandomHullKind {
    OnSphere,  ///< points on the sphere: (almost) every point becomes a vertex
    InBall,    ///< points inside the ball: a few percent become vertices
};
/// Convex hull of n (>= 4, clamped) SplitMix64(seed) points on / in a ball of the given radius.
/// Deterministic for (n, seed, kind, radius) on every platform.
ConvexPolyhedron randomHull(int n, std::uint64_t seed, RandomHullKind kind = RandomHullKind::OnSphere,
                            double radius = 1.0);

}  // namespace cdlab::presets
