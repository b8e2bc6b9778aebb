#include "core/geometry/polyhedron_presets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "core/geometry/convex_hull.h"

namespace cdlab::presets {

namespace {

ConvexPolyhedron hullOf(const std::vector<Vec3>& points) {
    HullResult r = convexHull(points);
    return r.ok() ? std::move(r.polyhedron) : ConvexPolyhedron{};
}

ConvexPolyhedron fromFacesOrEmpty(std::vector<Vec3> positions, const std::vector<std::vector<int>>& faces) {
    PolyhedronBuild b = ConvexPolyhedron::fromFaces(std::move(positions), faces);
    return b.ok() ? std::move(b.polyhedron) : ConvexPolyhedron{};
}

std::vector<Vec3> scaledTo(std::vector<Vec3> points, double circumradius) {
    for (Vec3& p : points) p *= circumradius / p.norm();
    return points;
}

std::vector<Vec3> icosahedronPoints() {
    const double phi = std::numbers::phi;
    std::vector<Vec3> pts;
    for (double s : {-1.0, 1.0}) {
        for (double t : {-1.0, 1.0}) {
            pts.emplace_back(0.0, s, t * phi);  // golden rectangles in the three coordinate planes
            pts.emplace_back(s, t * phi, 0.0);
            pts.emplace_back(t * phi, 0.0, s);
        }
    }
    return pts;
}

}  // namespace

std::uint64_t SplitMix64::next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double SplitMix64::nextDouble() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

Vec3 SplitMix64::inUnitBall() {
    for (;;) {  // acceptance probability pi/6 per try
        const Vec3 p(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0));
        if (p.squaredNorm() <= 1.0) return p;
    }
}

Vec3 SplitMix64::onUnitSphere() {
    for (;;) {
        const Vec3 p = inUnitBall();
        const double n2 = p.squaredNorm();
        // 1e-6: reject points so close to the centre that normalizing amplifies their rounding.
        if (n2 > 1e-6) return p / std::sqrt(n2);
    }
}

ConvexPolyhedron tetrahedron(double circumradius) {
    return hullOf(scaledTo({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, circumradius));
}

ConvexPolyhedron box(const Vec3& h) {
    std::vector<Vec3> v(8);
    for (int i = 0; i < 8; ++i) {
        v[i] = Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    }
    // Vertex i has bit 0 = +x, bit 1 = +y, bit 2 = +z. Faces counter-clockwise from outside.
    return fromFacesOrEmpty(std::move(v),
                            {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}});
}

ConvexPolyhedron octahedron(double r) {
    return hullOf({{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}});
}

ConvexPolyhedron icosahedron(double circumradius) { return hullOf(scaledTo(icosahedronPoints(), circumradius)); }

ConvexPolyhedron dodecahedron(double circumradius) {
    const double phi = std::numbers::phi, inv = 1.0 / phi;
    std::vector<Vec3> pts;
    for (double x : {-1.0, 1.0})
        for (double y : {-1.0, 1.0})
            for (double z : {-1.0, 1.0}) pts.emplace_back(x, y, z);
    for (double s : {-1.0, 1.0}) {
        for (double t : {-1.0, 1.0}) {
            pts.emplace_back(0.0, s * inv, t * phi);
            pts.emplace_back(s * inv, t * phi, 0.0);
            pts.emplace_back(t * phi, 0.0, s * inv);
        }
    }
    return hullOf(scaledTo(std::move(pts), circumradius));
}

std::vector<Vec3> regularPolygon(int n, double radius) {
    n = std::max(n, 3);
    std::vector<Vec3> pts(n);
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        pts[i] = Vec3(radius * std::cos(a), 0.0, -radius * std::sin(a));
    }
    return pts;
}

ConvexPolyhedron prism(int n, double radius, double halfHeight) {
    n = std::max(n, 3);
    const std::vector<Vec3> ring = regularPolygon(n, radius);
    std::vector<Vec3> v;
    for (const Vec3& p : ring) v.emplace_back(p.x(), -halfHeight, p.z());
    for (const Vec3& p : ring) v.emplace_back(p.x(), halfHeight, p.z());
    std::vector<std::vector<int>> faces;
    std::vector<int> top, bottom;
    for (int i = 0; i < n; ++i) {
        top.push_back(n + i);
        bottom.push_back(n - 1 - i);
        const int j = (i + 1) % n;
        faces.push_back({i, j, n + j, n + i});
    }
    faces.push_back(top);
    faces.push_back(bottom);
    return fromFacesOrEmpty(std::move(v), faces);
}

ConvexPolyhedron disk(int n, double radius, std::optional<double> halfThickness) {
    return prism(n, radius, halfThickness && *halfThickness > 0.0 ? *halfThickness : kDiskHalfThicknessRatio * radius);
}

ConvexPolyhedron geodesicSphere(int level, double radius) {
    level = std::clamp(level, 0, 6);
    std::vector<Vec3> pts = scaledTo(icosahedronPoints(), 1.0);
    const ConvexPolyhedron ico = hullOf(pts);
    std::vector<std::array<int, 3>> tris;
    std::vector<Vec3> verts = ico.positions();
    for (int f = 0; f < ico.faceCount(); ++f) {
        const std::vector<int> l = ico.faceVertices(f);
        tris.push_back({l[0], l[1], l[2]});
    }
    for (int it = 0; it < level; ++it) {
        std::map<std::pair<int, int>, int> midpoint;
        auto mid = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto found = midpoint.find(key);
            if (found != midpoint.end()) return found->second;
            verts.push_back((verts[a] + verts[b]).normalized());
            midpoint.emplace(key, static_cast<int>(verts.size()) - 1);
            return static_cast<int>(verts.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& t : tris) {
            const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        tris = std::move(next);
    }
    // The hull (not the subdivision's triangles) defines the faces, so convexity is guaranteed.
    for (Vec3& p : verts) p *= radius;
    return hullOf(verts);
}

ConvexPolyhedron randomHull(int n, std::uint64_t seed, RandomHullKind kind, double radius) {
    n = std::max(n, 4);
    SplitMix64 rng(seed);
    std::vector<Vec3> pts(n);
    for (Vec3& p : pts) p = radius * (kind == RandomHullKind::OnSphere ? rng.onUnitSphere() : rng.inUnitBall());
    return hullOf(pts);
}

}  // namespace cdlab::presets
