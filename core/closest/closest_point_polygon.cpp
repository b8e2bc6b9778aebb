#include "core/closest/closest_point_polygon.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

namespace {

/// Newell's normal (Ericson §12.3.2), unit; zero for a polygon without area.
Vec3 newellNormal(std::span<const Vec3> v) {
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < v.size(); ++i) {
        const Vec3& a = v[i];
        const Vec3& b = v[(i + 1) % v.size()];
        n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
    }
    const double len = n.norm();
    return len > 0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
}

std::string vertexName(int i) { return "v" + std::to_string(i); }

}  // namespace

std::string regionName(const ClosestPointPolygonResult& r, int corners) {
    if (!r.valid) return "invalid";
    if (r.dimension == 0) return vertexName(r.index);
    if (r.dimension == 1) return vertexName(r.index) + vertexName((r.index + 1) % corners);
    return "face";
}

ClosestPointPolygonResult closestPointOnConvexPolygon(const Vec3& p, std::span<const Vec3> v) {
    ClosestPointPolygonResult r;
    if (v.size() < 3 || !p.allFinite()) return r;
    for (const Vec3& q : v)
        if (!q.allFinite()) return r;
    const Vec3 N = newellNormal(v);
    if (N.isZero(0.0)) return r;
    const int n = int(v.size());
    // Strictly convex: every corner turns the same way (no repeated or collinear corners, whose
    // zero-length or straight edges would make a vertex test pass off its vertex).
    for (int i = 0; i < n; ++i) {
        const Vec3 before = v[std::size_t(i)] - v[std::size_t((i + n - 1) % n)], after = v[std::size_t((i + 1) % n)] - v[std::size_t(i)];
        if (!(before.cross(after).dot(N) > 0)) return r;
    }
    r.valid = true;
    r.normal = N;
    // Vertex regions: behind both edges meeting at v_i.
    for (int i = 0; i < n; ++i) {
        const Vec3& vi = v[std::size_t(i)];
        const Vec3 next = v[std::size_t((i + 1) % n)] - vi, prev = v[std::size_t((i + n - 1) % n)] - vi;
        const double a = (p - vi).dot(next), b = (p - vi).dot(prev);
        r.tests.push_back({vertexName(i), a, b, a <= 0 && b <= 0});
        if (a <= 0 && b <= 0) {
            r.dimension = 0;
            r.index = i;
            r.point = vi;
            r.distance = (p - vi).norm();
            return r;
        }
    }
    // Edge regions: outside the edge's line, over the edge.
    for (int i = 0; i < n; ++i) {
        const Vec3& vi = v[std::size_t(i)];
        const Vec3 e = v[std::size_t((i + 1) % n)] - vi;
        const Vec3 m = e.cross(N);
        const double outside = (p - vi).dot(m), along = (p - vi).dot(e);
        const bool holds = outside > 0 && along > 0 && along < e.dot(e);
        r.tests.push_back({vertexName(i) + vertexName((i + 1) % n), outside, along, holds});
        if (holds) {
            r.dimension = 1;
            r.index = i;
            r.point = vi + along / e.dot(e) * e;
            r.distance = (p - r.point).norm();
            return r;
        }
    }
    // The face — unless rounding let a point just outside an edge line slip past both the vertex
    // and the edge tests (a point on a region boundary): then the nearest clamped edge point.
    bool inside = true;
    for (int i = 0; i < n && inside; ++i) {
        const Vec3& vi = v[std::size_t(i)];
        inside = (p - vi).dot((v[std::size_t((i + 1) % n)] - vi).cross(N)) <= 0;
    }
    if (!inside) {
        double best = INFINITY;
        for (int i = 0; i < n; ++i) {
            const Vec3& vi = v[std::size_t(i)];
            const Vec3 e = v[std::size_t((i + 1) % n)] - vi;
            const double t = std::clamp((p - vi).dot(e) / e.dot(e), 0.0, 1.0);
            const Vec3 q = vi + t * e;
            if ((p - q).norm() < best) {
                best = (p - q).norm();
                r.point = q;
                r.dimension = t == 0.0 || t == 1.0 ? 0 : 1;
                r.index = t == 1.0 ? (i + 1) % n : i;
            }
        }
        r.distance = best;
        return r;
    }
    const Vec3& o = v[0];  // the projection onto the plane
    r.point = p - (p - o).dot(N) * N;
    r.distance = std::abs((p - o).dot(N));
    return r;
}

PolygonVoronoiDiagram polygonVoronoiRegions(std::span<const Vec3> v, double margin) {
    PolygonVoronoiDiagram d;
    if (v.size() < 3) return d;
    const Vec3 N = newellNormal(v);
    if (N.isZero(0.0)) return d;
    d.normal = N;
    const int n = int(v.size());
    std::vector<Vec3> outward;  // unit m_i
    for (int i = 0; i < n; ++i) outward.push_back((v[std::size_t((i + 1) % n)] - v[std::size_t(i)]).cross(N).normalized());
    for (int i = 0; i < n; ++i) {
        const Vec3& a = v[std::size_t(i)];
        const Vec3& b = v[std::size_t((i + 1) % n)];
        d.edgeRegions.push_back({a, b, b + margin * outward[std::size_t(i)], a + margin * outward[std::size_t(i)]});
        // Vertex i's wedge between the outward normals of the edges before and after it.
        const Vec3 before = outward[std::size_t((i + n - 1) % n)], after = outward[std::size_t(i)];
        Vec3 mid = before + after;
        mid = mid.norm() > 1e-12 ? Vec3(mid.normalized()) : before;
        d.vertexRegions.push_back({a, a + margin * before, a + margin / std::max(mid.dot(before), 0.2) * mid, a + margin * after});
    }
    d.face.assign(v.begin(), v.end());
    return d;
}

}  // namespace cdlab
