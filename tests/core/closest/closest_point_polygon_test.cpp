// Closest point on a convex polygon in 3D with its Voronoi region (core/closest/closest_point_polygon.h).
// Oracle, in long double and without region tests: the distance is |height| when the point's
// projection falls inside one of the fan triangles (barycentric signs), else the least distance to
// the edges (clamped projections). The region is checked against where the closest point lies: on a
// corner, inside an edge, or inside the face.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/closest/closest_point_polygon.h"

using namespace cdlab;

namespace {

using LD = long double;

LD pointSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    LD t = LD((p - a).dot(ab)) / LD(ab.dot(ab));
    t = std::clamp<LD>(t, 0, 1);
    const LD x = LD(p.x()) - (LD(a.x()) + t * LD(ab.x())), y = LD(p.y()) - (LD(a.y()) + t * LD(ab.y())),
             z = LD(p.z()) - (LD(a.z()) + t * LD(ab.z()));
    return std::sqrt(x * x + y * y + z * z);
}

/// The projection of p falls in one of the fan triangles (barycentric signs about n).
bool projectsInside(const Vec3& p, const std::vector<Vec3>& v, const Vec3& n) {
    const Vec3 q = p - (p - v[0]).dot(n) * n;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
        const Vec3 a = v[0], b = v[i], c = v[i + 1];
        const LD w0 = LD((b - q).cross(c - q).dot(n)), w1 = LD((c - q).cross(a - q).dot(n)), w2 = LD((a - q).cross(b - q).dot(n));
        if (w0 >= 0 && w1 >= 0 && w2 >= 0) return true;
    }
    return false;
}

LD oracleDistance(const Vec3& p, const std::vector<Vec3>& v, const Vec3& n) {
    if (projectsInside(p, v, n)) return std::abs(LD((p - v[0]).dot(n)));
    LD best = INFINITY;
    for (std::size_t i = 0; i < v.size(); ++i) best = std::min(best, pointSegment(p, v[i], v[(i + 1) % v.size()]));
    return best;
}

}  // namespace

TEST_CASE("closest point on a convex polygon in 3D: distance, point and region against the oracle") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int byDimension[3] = {0, 0, 0};
    for (int round = 0; round < 500; ++round) {
        // A regular n-gon stretched in its plane (an affine image of a convex polygon stays convex), turned in 3D.
        const int n = 3 + round % 6;
        const Mat3 R = Quat(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
        const double sx = 0.5 + std::abs(u(rng)), sy = 0.5 + std::abs(u(rng));
        std::vector<Vec3> v;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n;
            v.push_back(R * Vec3(sx * std::cos(a), sy * std::sin(a), 0) + Vec3(0.3, -0.2, 0.1));
        }
        const Vec3 p(2 * u(rng), 2 * u(rng), 2 * u(rng));
        const ClosestPointPolygonResult r = closestPointOnConvexPolygon(p, v);
        REQUIRE(r.valid);
        CHECK(std::abs(r.normal.dot(R.col(2))) == doctest::Approx(1.0));
        const double oracle = double(oracleDistance(p, v, R.col(2)));
        CHECK(r.distance == doctest::Approx(oracle).epsilon(1e-12));
        CHECK((p - r.point).norm() == doctest::Approx(r.distance).epsilon(1e-12));
        ++byDimension[r.dimension];
        CHECK((r.dimension == 2) == projectsInside(p, v, R.col(2)));  // the face region: over the polygon
        if (r.dimension == 0) CHECK(r.point == v[std::size_t(r.index)]);
        if (r.dimension == 1) {
            const Vec3 a = v[std::size_t(r.index)], b = v[std::size_t((r.index + 1) % n)];
            CHECK(double(pointSegment(r.point, a, b)) <= 1e-12);
            CHECK((r.point - a).norm() > 0);
            CHECK((r.point - b).norm() > 0);
        }
    }
    for (int d = 0; d < 3; ++d) CHECK(byDimension[d] > 30);
}

TEST_CASE("polygon regions: names, the in-plane diagram, degenerate input") {
    const std::vector<Vec3> square = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    ClosestPointPolygonResult r = closestPointOnConvexPolygon(Vec3(3, 3, 1), square);
    CHECK(regionName(r, 4) == "v2");
    r = closestPointOnConvexPolygon(Vec3(1, -1, 0), square);
    CHECK(regionName(r, 4) == "v0v1");
    CHECK(r.point == Vec3(1, 0, 0));
    r = closestPointOnConvexPolygon(Vec3(1, 1, -3), square);
    CHECK(regionName(r, 4) == "face");
    CHECK(r.distance == 3);
    CHECK(regionName(closestPointOnConvexPolygon(Vec3(2, -1, 0), square), 4) == "v1");  // on the boundary: the vertex
    const PolygonVoronoiDiagram d = polygonVoronoiRegions(square, 1.0);
    CHECK(d.vertexRegions.size() == 4);
    CHECK(d.edgeRegions.size() == 4);
    CHECK(d.edgeRegions[0][3] == Vec3(0, -1, 0));  // edge v0v1's strip reaches out along −y
    CHECK_FALSE(closestPointOnConvexPolygon(Vec3::Zero(), std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}).valid);
    CHECK_FALSE(closestPointOnConvexPolygon(Vec3(NAN, 0, 0), square).valid);
    // A collinear or a repeated corner would let a vertex test pass off its vertex: refused.
    CHECK_FALSE(closestPointOnConvexPolygon(Vec3(1, 1, 5), std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}).valid);
    CHECK_FALSE(closestPointOnConvexPolygon(Vec3(1, 0.5, 0), std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}).valid);
}
