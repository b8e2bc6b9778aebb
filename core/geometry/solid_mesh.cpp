#include "core/geometry/solid_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace cdlab {

const char* nameOf(SolidMeshStatus status) {
    switch (status) {
        case SolidMeshStatus::Closed: return "closed";
        case SolidMeshStatus::TooFewTriangles: return "too few triangles";
        case SolidMeshStatus::RepeatedVertex: return "repeated vertex";
        case SolidMeshStatus::OpenEdge: return "open edge";
        case SolidMeshStatus::InconsistentOrientation: return "inconsistent orientation";
    }
    return "?";
}

SolidMeshCheck checkSolidMesh(const TriangleMesh& mesh) {
    SolidMeshCheck check;
    if (mesh.triangleCount() < 4) {
        check.status = SolidMeshStatus::TooFewTriangles;
        return check;
    }
    // Directed edges (i, j) packed as i * 2^32 + j with their triangle, sorted: a repeated key is
    // an edge used twice in one direction, a key whose twin (j, i) is absent an open edge.
    struct Edge {
        std::uint64_t key;
        int triangle;
    };
    const auto pack = [](int i, int j) { return (std::uint64_t(std::uint32_t(i)) << 32) | std::uint32_t(j); };
    std::vector<Edge> edges;
    edges.reserve(std::size_t(mesh.triangleCount()) * 3);
    for (int t = 0; t < mesh.triangleCount(); ++t) {
        const std::array<int, 3>& tri = mesh.triangles[std::size_t(t)];
        for (int k = 0; k < 3; ++k) {
            const int i = tri[std::size_t(k)], j = tri[std::size_t((k + 1) % 3)];
            if (i == j) {
                check = {SolidMeshStatus::RepeatedVertex, t, {i, j}};
                return check;
            }
            edges.push_back({pack(i, j), t});
        }
    }
    std::sort(edges.begin(), edges.end(),
              [](const Edge& a, const Edge& b) { return a.key != b.key ? a.key < b.key : a.triangle < b.triangle; });
    const auto unpack = [](std::uint64_t key) { return std::array<int, 2>{int(key >> 32), int(key & 0xffffffffu)}; };
    for (std::size_t e = 0; e + 1 < edges.size(); ++e)
        if (edges[e].key == edges[e + 1].key) {
            check = {SolidMeshStatus::InconsistentOrientation, edges[e + 1].triangle, unpack(edges[e].key)};
            return check;
        }
    for (const Edge& e : edges) {
        const std::array<int, 2> ij = unpack(e.key);
        const std::uint64_t twin = pack(ij[1], ij[0]);
        const auto it = std::lower_bound(edges.begin(), edges.end(), twin,
                                         [](const Edge& x, std::uint64_t k) { return x.key < k; });
        if (it == edges.end() || it->key != twin) {
            check = {SolidMeshStatus::OpenEdge, e.triangle, ij};
            return check;
        }
    }
    return check;
}

namespace {

Vec3 boundsCentre(const TriangleMesh& mesh) {
    if (mesh.vertices.empty()) return Vec3::Zero();
    Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    return 0.5 * (lo + hi);
}

}  // namespace

double signedVolume(const TriangleMesh& mesh) {
    const Vec3 c = boundsCentre(mesh);
    double sixTimes = 0;
    for (int t = 0; t < mesh.triangleCount(); ++t) {
        const Triangle tri = mesh.triangle(t);
        sixTimes += (tri.a - c).dot((tri.b - c).cross(tri.c - c));
    }
    return sixTimes / 6.0;
}

double windingNumber(const TriangleMesh& mesh, const Vec3& p) {
    double total = 0;
    for (int t = 0; t < mesh.triangleCount(); ++t) {
        const Triangle tri = mesh.triangle(t);
        const Vec3 a = tri.a - p, b = tri.b - p, c = tri.c - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double det = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * std::atan2(det, den);  // Van Oosterom & Strackee: the triangle's solid angle
    }
    return total / (4.0 * std::numbers::pi);
}

}  // namespace cdlab
