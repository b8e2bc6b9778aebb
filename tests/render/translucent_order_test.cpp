// Back-to-front order of translucent meshes (render/translucent_order): checked by casting rays
// through the ordered pieces, an oracle independent of the partition: along every ray, the pieces
// it passes through must be drawn farthest first.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "render/translucent_order.h"

using namespace cdlab::render;
using Eigen::Vector3d;
using Eigen::Vector3i;

namespace {

struct Mesh {
    std::vector<Vector3d> vertices;
    std::vector<Vector3i> triangles;
    TranslucentMesh view() const { return {vertices, triangles}; }
};

// A box of half extents `h`, rotated by `r` and moved to `c`: 8 shared vertices, 12 triangles.
Mesh box(const Vector3d& h, const Eigen::Matrix3d& r, const Vector3d& c) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.push_back(c + r * Vector3d((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

// A UV sphere: `rings` x `segments` quads split into triangles, shared vertices.
Mesh sphere(const Vector3d& c, double radius, int rings, int segments) {
    Mesh m;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double th = std::numbers::pi * i / rings, ph = 2 * std::numbers::pi * j / segments;
            m.vertices.push_back(c + radius * Vector3d(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)));
        }
    const auto at = [&](int i, int j) { return i * segments + (j % segments); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            if (i > 0) m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i, j + 1));
            if (i + 1 < rings) m.triangles.emplace_back(at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
        }
    return m;
}

// A torus around y: not convex.
Mesh torus(const Vector3d& c, double big, double small, int n, int k) {
    Mesh m;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < k; ++j) {
            const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / k;
            const double r = big + small * std::cos(v);
            m.vertices.push_back(c + Vector3d(r * std::cos(u), small * std::sin(v), r * std::sin(u)));
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < k; ++j) {
            const int a = i * k + j, b = ((i + 1) % n) * k + j, cc = ((i + 1) % n) * k + (j + 1) % k, d = i * k + (j + 1) % k;
            m.triangles.emplace_back(a, b, cc);
            m.triangles.emplace_back(a, cc, d);
        }
    return m;
}

// The same triangles, each with its own copies of its corners (no shared vertices).
Mesh soup(const Mesh& in) {
    Mesh m;
    for (const Vector3i& t : in.triangles) {
        const int base = int(m.vertices.size());
        for (int k = 0; k < 3; ++k) m.vertices.push_back(in.vertices[std::size_t(t[k])]);
        m.triangles.emplace_back(base, base + 1, base + 2);
    }
    return m;
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

Vector3d newellNormal(const std::vector<Vector3d>& p) {
    Vector3d n = Vector3d::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) n += p[i].cross(p[(i + 1) % p.size()]);
    return n;
}

double area(const std::vector<Vector3d>& p) { return 0.5 * newellNormal(p).norm(); }

// Where the ray origin + t dir passes through the convex piece at least `margin` inside its
// edges (a ray grazing an edge is ambiguous between neighbouring pieces): its t, else NaN.
double hit(const std::vector<Vector3d>& p, const Vector3d& origin, const Vector3d& dir, double margin) {
    const Vector3d n = newellNormal(p).normalized();
    const double denom = n.dot(dir);
    if (std::abs(denom) < 1e-6) return NAN;
    const double t = n.dot(p[0] - origin) / denom;
    const Vector3d x = origin + t * dir;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vector3d e = p[(i + 1) % p.size()] - p[i];
        if (e.cross(x - p[i]).dot(n) < margin * e.norm()) return NAN;
    }
    return t;
}

struct RayCheck {
    int rays = 0, crossings = 0, violations = 0;
};

// Along random rays through the scene's bounding box: pieces drawn later must be nearer.
RayCheck castRays(const std::vector<OrderedPiece>& pieces, const Viewer& viewer, const Vector3d& lo, const Vector3d& hi,
                  std::mt19937& rng, int rays) {
    std::uniform_real_distribution<double> u(0, 1);
    RayCheck check;
    const double size = (hi - lo).norm();
    for (int r = 0; r < rays; ++r) {
        const Vector3d target = lo + (hi - lo).cwiseProduct(Vector3d(u(rng), u(rng), u(rng)));
        const Vector3d origin = viewer.orthographic ? Vector3d(target + 10 * size * viewer.towardsEye) : viewer.eye;
        const Vector3d dir = (target - origin).normalized();
        double nearestSoFar = INFINITY;  // t of the pieces drawn so far along this ray
        int hits = 0;
        for (const OrderedPiece& p : pieces) {
            const double t = hit(p.corners, origin, dir, 1e-7 * size);
            if (!(t > 0)) continue;
            ++hits;
            // Drawn after a nearer piece while lying behind it (beyond rounding).
            if (t > nearestSoFar + 1e-9 * size) ++check.violations;
            nearestSoFar = std::min(nearestSoFar, t);
        }
        ++check.rays;
        check.crossings += hits > 1 ? 1 : 0;
    }
    return check;
}

// The painter's order this replaces: whole triangles by centroid distance, farthest first.
std::vector<OrderedPiece> byCentroidDepth(const std::vector<Mesh>& meshes, const Viewer& viewer) {
    std::vector<std::pair<double, OrderedPiece>> keyed;
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (std::size_t i = 0; i < meshes[m].triangles.size(); ++i) {
            OrderedPiece p{{}, int(m), int(i)};
            for (int k = 0; k < 3; ++k) p.corners.push_back(meshes[m].vertices[std::size_t(meshes[m].triangles[i][k])]);
            const Vector3d c = (p.corners[0] + p.corners[1] + p.corners[2]) / 3;
            keyed.emplace_back(viewer.orthographic ? -c.dot(viewer.towardsEye) : (c - viewer.eye).norm(), p);
        }
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    std::vector<OrderedPiece> out;
    for (auto& [key, p] : keyed) out.push_back(p);
    return out;
}

std::vector<OrderedPiece> order(const std::vector<Mesh>& meshes, const Viewer& viewer, TranslucentOrderStats* stats = nullptr) {
    std::vector<TranslucentMesh> views;
    for (const Mesh& m : meshes) views.push_back(m.view());
    return backToFront(views, viewer, stats);
}

// Every input triangle's area is covered by its pieces exactly once.
void checkAreas(const std::vector<Mesh>& meshes, const std::vector<OrderedPiece>& pieces) {
    std::map<std::pair<int, int>, double> covered;
    for (const OrderedPiece& p : pieces) {
        REQUIRE(p.corners.size() >= 3);
        covered[{p.mesh, p.triangle}] += area(p.corners);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (std::size_t i = 0; i < meshes[m].triangles.size(); ++i) {
            const Vector3i& t = meshes[m].triangles[i];
            const double a = area({meshes[m].vertices[std::size_t(t[0])], meshes[m].vertices[std::size_t(t[1])],
                                   meshes[m].vertices[std::size_t(t[2])]});
            CHECK(covered[{int(m), int(i)}] == doctest::Approx(a).epsilon(1e-9));
        }
}

Viewer perspectiveFrom(const Vector3d& eye, const Vector3d& target) {
    return {eye, (eye - target).normalized(), false};
}

}  // namespace

TEST_CASE("a convex surface is told from a non-convex one, whatever the winding or vertex sharing") {
    std::mt19937 rng(7);
    const Mesh cube = box({1, 0.5, 0.25}, randomRotation(rng), {3, -1, 2});
    CHECK(isConvexSurface(cube.view()));
    CHECK(isConvexSurface(soup(cube).view()));
    Mesh flipped = cube;  // some faces wound the other way
    for (std::size_t i = 0; i < flipped.triangles.size(); i += 3) std::swap(flipped.triangles[i][0], flipped.triangles[i][1]);
    CHECK(isConvexSurface(flipped.view()));
    CHECK(isConvexSurface(sphere({0, 0, 0}, 2, 16, 32).view()));
    Mesh open = cube;  // an open box (top removed) is part of a convex surface
    open.triangles.resize(10);
    CHECK(isConvexSurface(open.view()));
    const Mesh quad{{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{0, 1, 2}, {0, 2, 3}}};
    CHECK(isConvexSurface(quad.view()));

    Mesh dented = cube;  // one corner pushed in past the centre of its faces
    dented.vertices[7] = 0.2 * dented.vertices[7] + 0.8 * Vector3d(3, -1, 2);
    CHECK_FALSE(isConvexSurface(dented.view()));
    CHECK_FALSE(isConvexSurface(soup(dented).view()));
    CHECK_FALSE(isConvexSurface(torus({0, 0, 0}, 2, 0.5, 24, 12).view()));
    CHECK_FALSE(isConvexSurface(soup(torus({0, 0, 0}, 2, 0.5, 24, 12)).view()));
}

TEST_CASE("a thin slab through a box: every ray sees the pieces drawn farthest first (the painter's sort does not)") {
    const Mesh boxA = box({0.5, 0.5, 0.5}, Eigen::Matrix3d::Identity(), {0, 0, 0});
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.3, Vector3d(1, 0, 1).normalized()).toRotationMatrix();
    const Mesh slab = box({0.8, 0.01, 0.4}, tilt, {0.4, 0.35, 0.1});
    const std::vector<Mesh> meshes{boxA, slab};
    std::mt19937 rng(11);
    int naiveViolations = 0;
    for (const Viewer& viewer : {perspectiveFrom({3, 2.5, 4}, {0, 0, 0}), perspectiveFrom({-2, 1, 3}, {0, 0, 0}),
                                 Viewer{{0, 0, 0}, Vector3d(1, 2, 2).normalized(), true}}) {
        TranslucentOrderStats stats;
        const auto pieces = order(meshes, viewer, &stats);
        CHECK(stats.convexMeshes == 2);
        CHECK(stats.cuts > 0);
        CHECK_FALSE(stats.budgetHit);
        checkAreas(meshes, pieces);
        const RayCheck check = castRays(pieces, viewer, {-1, -1, -1}, {1.3, 1, 1}, rng, 2000);
        CHECK(check.crossings > 500);
        CHECK(check.violations == 0);
        naiveViolations += castRays(byCentroidDepth(meshes, viewer), viewer, {-1, -1, -1}, {1.3, 1, 1}, rng, 2000).violations;
    }
    CHECK(naiveViolations > 0);  // the oracle sees what the old order got wrong
}

TEST_CASE("random boxes, a sphere sunk into them and a torus: right order from any viewpoint, in both projections") {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 12; ++trial) {
        std::vector<Mesh> meshes;
        for (int b = 0; b < 3; ++b)
            meshes.push_back(box(Vector3d(0.2 + 0.5 * std::abs(u(rng)), 0.05 + 0.5 * std::abs(u(rng)), 0.3 + 0.3 * std::abs(u(rng))),
                                 randomRotation(rng), 0.5 * Vector3d(u(rng), u(rng), u(rng))));
        meshes.push_back(sphere(0.4 * Vector3d(u(rng), u(rng), u(rng)), 0.6, 8, 16));
        if (trial % 3 == 0) meshes.push_back(torus(0.3 * Vector3d(u(rng), u(rng), u(rng)), 0.7, 0.2, 16, 8));
        const Vector3d dir = Vector3d(u(rng), u(rng), u(rng)).normalized();
        const Viewer viewer = trial % 2 ? Viewer{{0, 0, 0}, dir, true} : perspectiveFrom(5 * dir, {0, 0, 0});
        TranslucentOrderStats stats;
        const auto pieces = order(meshes, viewer, &stats);
        CHECK(stats.convexMeshes == 4);
        CHECK_FALSE(stats.budgetHit);
        checkAreas(meshes, pieces);
        const RayCheck check = castRays(pieces, viewer, {-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2}, rng, 1500);
        CHECK(check.crossings > 300);
        CHECK(check.violations == 0);
    }
}

TEST_CASE("faces in one plane keep their input order, a big tessellated sphere beside a box is cut only where needed") {
    // Two coplanar squares overlapping (touching bodies' faces): drawn mesh 0 then mesh 1, seen from either side.
    const Mesh a{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
    const Mesh b{{{0.5, 0.5, 0}, {1.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 1.5, 0}}, {{0, 1, 2}, {0, 2, 3}}};
    for (const double side : {1.0, -1.0}) {
        const auto pieces = order({a, b}, perspectiveFrom({0.5, 0.5, 3 * side}, {0.5, 0.5, 0}));
        REQUIRE(pieces.size() == 4);
        CHECK(pieces[0].mesh == 0);
        CHECK(pieces[1].mesh == 0);
        CHECK(pieces[2].mesh == 1);
        CHECK(pieces[3].mesh == 1);
    }
    // A sphere of 3000 triangles sunk into a box: a few cuts, not one per sphere triangle.
    const std::vector<Mesh> meshes{sphere({0.5, 0, 0}, 1, 40, 40), box({0.5, 0.5, 0.5}, Eigen::Matrix3d::Identity(), {-0.6, 0, 0})};
    const Viewer viewer = perspectiveFrom({2, 3, 5}, {0, 0, 0});
    TranslucentOrderStats stats;
    const auto pieces = order(meshes, viewer, &stats);
    CHECK(stats.items == 2);
    CHECK(stats.cuts < 400);
    checkAreas(meshes, pieces);
    std::mt19937 rng(3);
    CHECK(castRays(pieces, viewer, {-1.2, -1, -1}, {1.5, 1, 1}, rng, 1500).violations == 0);
}

TEST_CASE("hundreds of large random triangles through each other: past the cut budget every piece is still drawn once") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    Mesh m;
    for (int i = 0; i < 400; ++i) {
        const Vector3d c(u(rng), u(rng), u(rng));
        const int base = int(m.vertices.size());
        for (int k = 0; k < 3; ++k) m.vertices.push_back(c + 1.5 * Vector3d(u(rng), u(rng), u(rng)));
        m.triangles.emplace_back(base, base + 1, base + 2);
    }
    TranslucentOrderStats stats;
    const auto pieces = order({m}, perspectiveFrom({4, 3, 5}, {0, 0, 0}), &stats);
    CHECK(stats.budgetHit);
    CHECK(stats.convexMeshes == 0);
    checkAreas({m}, pieces);
}

TEST_CASE("a large open curved sheet of single-triangle items: bounded work and depth, every piece drawn once") {
    // A paraboloid cap z = x^2 + y^2 over a 64 x 64 grid (8192 triangles): open, too large for the
    // all-pairs convexity check, so each triangle is its own item and the partition peels one face
    // per level under its own faces' planes: planes across the middle keep it shallow and fast.
    Mesh m;
    const int n = 64;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
            m.vertices.emplace_back(x, y, x * x + y * y);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
            m.triangles.emplace_back(a, c, d);
            m.triangles.emplace_back(a, d, b);
        }
    TranslucentOrderStats stats;
    const auto pieces = order({m, box({0.3, 0.3, 0.3}, Eigen::Matrix3d::Identity(), {0, 0, 0.5})},
                              perspectiveFrom({2, -3, 4}, {0, 0, 0.5}), &stats);
    CHECK(stats.convexMeshes == 1);  // the box
    CHECK_FALSE(stats.budgetHit);     // planes across the middle split the sheet in halves
    checkAreas({m, box({0.3, 0.3, 0.3}, Eigen::Matrix3d::Identity(), {0, 0, 0.5})}, pieces);
    std::mt19937 rng(13);
    const RayCheck check = castRays(pieces, perspectiveFrom({2, -3, 4}, {0, 0, 0.5}), {-1, -1, 0}, {1, 1, 2}, rng, 1500);
    CHECK(check.crossings > 300);
    CHECK(check.violations == 0);
}

TEST_CASE("a polygon fan with a corner on an edge (a needle triangle) through a box: no endless peeling, right order") {
    // drawPolygon fans from corner 0: with corner 1 on the edge from corner 0 to corner 2, the first
    // fan triangle is a needle whose rounded normal would leave its own corners off its plane.
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.37, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    Mesh fan;
    for (const Vector3d& c : {Vector3d(-1, -1, 0.1), Vector3d(0.3, -1, 0.1), Vector3d(1, -1, 0.1), Vector3d(1, 1, 0.1),
                              Vector3d(-1, 1, 0.1)})
        fan.vertices.push_back(tilt * c);
    for (int k = 1; k + 1 < 5; ++k) fan.triangles.emplace_back(0, k, k + 1);
    const std::vector<Mesh> meshes{fan, box({0.5, 0.5, 0.5}, tilt, Vector3d::Zero())};
    std::mt19937 rng(17);
    for (const Viewer& viewer : {perspectiveFrom({2, 3, 4}, {0, 0, 0}), Viewer{{0, 0, 0}, Vector3d(-1, 1, 2).normalized(), true}}) {
        TranslucentOrderStats stats;
        const auto pieces = order(meshes, viewer, &stats);
        CHECK(stats.convexMeshes == 2);
        CHECK_FALSE(stats.budgetHit);
        checkAreas(meshes, pieces);
        CHECK(castRays(pieces, viewer, {-1, -1, -1}, {1, 1, 1}, rng, 1500).violations == 0);
    }
}

TEST_CASE("a sheet of separate two-triangle tiles (items of two pieces): planes across the middle, not peeling") {
    std::vector<Mesh> tiles;
    const int n = 40;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Mesh t;
            for (const auto& [di, dj] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 1}}) {
                const double x = -1 + 2.0 * (i + di) / n, y = -1 + 2.0 * (j + dj) / n;
                t.vertices.emplace_back(x, y, x * x + y * y);
            }
            t.triangles = {{0, 1, 2}, {0, 2, 3}};
            tiles.push_back(t);
        }
    tiles.push_back(box({0.3, 0.3, 0.3}, Eigen::Matrix3d::Identity(), {0, 0, 0.5}));
    const Viewer viewer = perspectiveFrom({2, -3, 4}, {0, 0, 0.5});
    TranslucentOrderStats stats;
    const auto pieces = order(tiles, viewer, &stats);
    CHECK_FALSE(stats.budgetHit);
    CHECK(stats.cuts < 4 * 2 * n * n);
    checkAreas(tiles, pieces);
    std::mt19937 rng(19);
    CHECK(castRays(pieces, viewer, {-1, -1, 0}, {1, 1, 2}, rng, 1500).violations == 0);
}

TEST_CASE("the same scenes a million units from the origin: eps follows the scene, not the coordinates alone") {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(-1, 1);
    for (const double far : {1e6, 1e7}) {
        const Vector3d offset = far * Vector3d(0.6, -0.64, 0.48);
        std::vector<Mesh> meshes;
        for (int b = 0; b < 3; ++b)
            meshes.push_back(box(Vector3d(0.2 + 0.5 * std::abs(u(rng)), 0.05 + 0.5 * std::abs(u(rng)), 0.3),
                                 randomRotation(rng), offset + 0.5 * Vector3d(u(rng), u(rng), u(rng))));
        meshes.push_back(sphere(offset + 0.4 * Vector3d(u(rng), u(rng), u(rng)), 0.6, 8, 16));
        const Viewer viewer = perspectiveFrom(offset + Vector3d(3, 2, 4), offset);
        TranslucentOrderStats stats;
        auto pieces = order(meshes, viewer, &stats);
        CHECK(stats.convexMeshes == 4);
        CHECK_FALSE(stats.budgetHit);
        // The oracle in the scene's own frame (its ray tests lose precision at 1e6).
        for (OrderedPiece& p : pieces)
            for (Vector3d& c : p.corners) c -= offset;
        const Viewer local{viewer.eye - offset, viewer.towardsEye, false};
        const RayCheck check = castRays(pieces, local, {-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2}, rng, 1500);
        CHECK(check.crossings > 300);
        CHECK(check.violations == 0);
    }
}
