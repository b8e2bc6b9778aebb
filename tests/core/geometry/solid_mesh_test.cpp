// Closed-mesh checks, signed volume and winding-number containment, against closed forms (cube,
// L-shaped prism) and an independent crossing-number test (a ray's crossings with the triangles,
// counted in long double).
#include <doctest/doctest.h>

#include <random>

#include "core/geometry/solid_mesh.h"

using namespace cdlab;

namespace {

// The box [lo, hi] as 12 triangles, counter-clockwise from outside (corner k: bit i for +axis i).
TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi) {
    TriangleMesh m;
    for (int k = 0; k < 8; ++k) m.vertices.push_back(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
    }
    return m;
}

// The L-shaped prism {(x, y) in [0,2]^2 minus (1,2]^2} x [0, 1].
TriangleMesh lPrism() {
    const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    TriangleMesh m;
    for (double z : {0.0, 1.0})
        for (const auto& p : xy) m.vertices.push_back(Vec3(p[0], p[1], z));
    const int n = 6;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        m.triangles.push_back({i, j, n + j});
        m.triangles.push_back({i, n + j, n + i});
    }
    const int fan[4][3] = {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}};  // from the reflex corner
    for (const auto& t : fan) {
        m.triangles.push_back({n + t[0], n + t[1], n + t[2]});  // top, counter-clockwise from +z
        m.triangles.push_back({t[0], t[2], t[1]});              // bottom, reversed
    }
    return m;
}

bool insideL(const Vec3& p) {
    const bool inSquare = p.x() > 0 && p.x() < 2 && p.y() > 0 && p.y() < 2 && p.z() > 0 && p.z() < 1;
    return inSquare && !(p.x() > 1 && p.y() > 1);
}

// Crossing number along a fixed irrational direction (Möller–Trumbore in long double).
bool insideByCrossings(const TriangleMesh& m, const Vec3& p) {
    using LVec = Eigen::Matrix<long double, 3, 1>;
    const LVec d(0.5773502691896257L, 0.6123724356957945L, 0.5400617248673217L);
    const LVec o = p.cast<long double>();
    int crossings = 0;
    for (int t = 0; t < m.triangleCount(); ++t) {
        const Triangle tri = m.triangle(t);
        const LVec a = tri.a.cast<long double>(), e1 = tri.b.cast<long double>() - a, e2 = tri.c.cast<long double>() - a;
        const LVec h = d.cross(e2);
        const long double det = e1.dot(h);
        if (det == 0) continue;
        const LVec s = o - a;
        const long double u = s.dot(h) / det;
        const LVec q = s.cross(e1);
        const long double v = d.dot(q) / det;
        const long double tt = e2.dot(q) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && tt > 0) ++crossings;
    }
    return crossings % 2 == 1;
}

}  // namespace

TEST_CASE("solid mesh: a box and an L-shaped prism are closed, with their volumes") {
    const TriangleMesh box = boxMesh(Vec3(-1, -2, -3), Vec3(1, 2, 3));
    CHECK(checkSolidMesh(box).status == SolidMeshStatus::Closed);
    CHECK(signedVolume(box) == doctest::Approx(48.0).epsilon(1e-14));
    const TriangleMesh l = lPrism();
    CHECK(checkSolidMesh(l).status == SolidMeshStatus::Closed);
    CHECK(signedVolume(l) == doctest::Approx(3.0).epsilon(1e-14));
    // Far from the origin the volume keeps its precision (summed from the bounds' centre).
    TriangleMesh far = l;
    for (Vec3& v : far.vertices) v += Vec3(1e8, -3e8, 2e8);
    CHECK(signedVolume(far) == doctest::Approx(3.0).epsilon(1e-12));
}

TEST_CASE("solid mesh: open, inconsistent and degenerate soups are named with their edge") {
    TriangleMesh open = lPrism();
    open.triangles.pop_back();
    SolidMeshCheck c = checkSolidMesh(open);
    CHECK(c.status == SolidMeshStatus::OpenEdge);
    CHECK(c.triangle >= 0);

    TriangleMesh flipped = lPrism();
    std::swap(flipped.triangles[4][1], flipped.triangles[4][2]);
    c = checkSolidMesh(flipped);
    CHECK(c.status == SolidMeshStatus::InconsistentOrientation);

    TriangleMesh repeated = lPrism();
    repeated.triangles[2] = {3, 3, 4};
    CHECK(checkSolidMesh(repeated).status == SolidMeshStatus::RepeatedVertex);

    TriangleMesh few = lPrism();
    few.triangles.resize(3);
    CHECK(checkSolidMesh(few).status == SolidMeshStatus::TooFewTriangles);

    // Every triangle reversed: still closed and consistent, the volume negative.
    TriangleMesh inward = lPrism();
    for (auto& t : inward.triangles) std::swap(t[1], t[2]);
    CHECK(checkSolidMesh(inward).status == SolidMeshStatus::Closed);
    CHECK(signedVolume(inward) == doctest::Approx(-3.0).epsilon(1e-14));
}

TEST_CASE("solid mesh: winding number against the closed form and the crossing number") {
    const TriangleMesh l = lPrism();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.5, 2.5), uz(-0.5, 1.5);
    int inside = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p(u(rng), u(rng), uz(rng));
        const double w = windingNumber(l, p);
        const bool in = w > 0.5;
        CHECK(in == insideL(p));
        CHECK(in == insideByCrossings(l, p));
        CHECK(std::abs(w - (in ? 1.0 : 0.0)) < 1e-9);
        inside += in;
    }
    CHECK(inside > 200);  // the sample covers both sides
    TriangleMesh inward = l;
    for (auto& t : inward.triangles) std::swap(t[1], t[2]);
    CHECK(windingNumber(inward, Vec3(0.5, 0.5, 0.5)) == doctest::Approx(-1.0).epsilon(1e-12));
    const TriangleMesh torus = torusMesh(2.0, 0.5, 24, 12);
    CHECK(checkSolidMesh(torus).status == SolidMeshStatus::Closed);
    CHECK(windingNumber(torus, Vec3(0, 0, 0)) == doctest::Approx(0.0).epsilon(1e-12));  // the hole
    CHECK(windingNumber(torus, Vec3(2, 0, 0)) == doctest::Approx(1.0).epsilon(1e-12));  // the tube
}
