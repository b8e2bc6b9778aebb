// Convex decomposition by BSP cells: the pieces are convex (each is its own hull), tile the solid
// (their volumes sum to the mesh's, and a point is in some piece exactly when it is in the solid
// by the closed form), for an L-shaped prism, a torus and a noisy blob far from the origin.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/solid_mesh.h"
#include "core/spatial/convex_decomposition.h"

using namespace cdlab;

namespace {

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
    const int fan[4][3] = {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}};
    for (const auto& t : fan) {
        m.triangles.push_back({n + t[0], n + t[1], n + t[2]});
        m.triangles.push_back({t[0], t[2], t[1]});
    }
    return m;
}

struct Piece {
    ConvexPolyhedron hull;
    double volume = 0;
};

std::vector<Piece> hullsOf(const ConvexDecomposition& d) {
    std::vector<Piece> out;
    for (const auto& corners : d.pieces) {
        HullResult h = convexHull(corners);
        REQUIRE(h.ok());
        // Every corner is on the boundary of its piece's hull (a corner, or on an edge where a cut
        // crossed it): none inside, which a non-convex cell would give.
        CHECK(h.polyhedron.vertexCount() >= 4);
        double size = 0;
        for (const Vec3& c : corners) size = std::max(size, (c - corners[0]).norm());
        for (const Vec3& c : corners) {
            double nearest = -INFINITY;
            for (int f = 0; f < h.polyhedron.faceCount(); ++f) nearest = std::max(nearest, h.polyhedron.planeDistance(f, c));
            CHECK(nearest > -1e-9 * size);
        }
        const MassProperties mp = computeMassProperties(h.polyhedron);
        REQUIRE(mp.ok());
        out.push_back({h.polyhedron, mp.volume});
    }
    return out;
}

bool inPiece(const Piece& p, const Vec3& x, double eps) {
    for (int f = 0; f < p.hull.faceCount(); ++f) {
        if (p.hull.planeDistance(f, x) > eps) return false;
    }
    return true;
}

double totalVolume(const std::vector<Piece>& pieces) {
    double v = 0;
    for (const Piece& p : pieces) v += p.volume;
    return v;
}

}  // namespace

TEST_CASE("convex decomposition: an L-shaped prism tiles into convex pieces") {
    const TriangleMesh l = lPrism();
    const ConvexDecomposition d = decomposeIntoConvexPieces(l);
    CHECK(d.status == BspStatus::Ok);
    REQUIRE(d.pieces.size() >= 2);  // not convex: one piece cannot do
    const std::vector<Piece> pieces = hullsOf(d);
    CHECK(totalVolume(pieces) == doctest::Approx(3.0).epsilon(1e-12));
    // Every corner is one of the mesh's points or on its surface: snapped corners are exact.
    int exact = 0;
    for (const auto& corners : d.pieces)
        for (const Vec3& c : corners)
            for (const Vec3& v : l.vertices) exact += c == v;
    CHECK(exact >= 12);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-0.5, 2.5), uz(-0.5, 1.5);
    for (int k = 0; k < 3000; ++k) {
        const Vec3 x(u(rng), u(rng), uz(rng));
        const bool inL = x.x() > 0 && x.x() < 2 && x.y() > 0 && x.y() < 2 && x.z() > 0 && x.z() < 1 &&
                         !(x.x() > 1 && x.y() > 1);
        bool inAny = false;
        for (const Piece& p : pieces) inAny = inAny || inPiece(p, x, 1e-12);
        CHECK(inAny == inL);
    }
}

TEST_CASE("convex decomposition: a torus and a noisy blob far from the origin keep their volume") {
    for (int which = 0; which < 2; ++which) {
        TriangleMesh m = which == 0 ? torusMesh(2.0, 0.6, 16, 8) : noisyBlobMesh(1.0, 0.3, 12, 8, 11);
        if (which == 1)
            for (Vec3& v : m.vertices) v += Vec3(1e5, -2e5, 3e4);
        REQUIRE(checkSolidMesh(m).status == SolidMeshStatus::Closed);
        const ConvexDecomposition d = decomposeIntoConvexPieces(m);
        CHECK(d.status == BspStatus::Ok);
        const std::vector<Piece> pieces = hullsOf(d);
        CHECK(totalVolume(pieces) == doctest::Approx(signedVolume(m)).epsilon(1e-9));
        // Points inside by the winding number are in some piece.
        Vec3 lo = m.vertices[0], hi = lo;
        for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        std::mt19937_64 rng(5 + which);
        std::uniform_real_distribution<double> u(0, 1);
        int checked = 0;
        for (int k = 0; k < 400; ++k) {
            const Vec3 x = lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo);
            const double w = windingNumber(m, x);
            if (std::abs(w - 0.5) < 0.4) continue;  // within rounding of the surface
            bool inAny = false;
            for (const Piece& p : pieces) inAny = inAny || inPiece(p, x, 1e-9 * (hi - lo).maxCoeff());
            CHECK(inAny == (w > 0.5));
            ++checked;
        }
        CHECK(checked > 300);
    }
}
