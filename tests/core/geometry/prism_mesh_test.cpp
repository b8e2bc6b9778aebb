// prismMesh (core/geometry/triangle_mesh.h): a simple outline extruded to a closed, outward-facing
// prism. Oracles: checkSolidMesh (closed, consistently oriented), the signed volume against the
// shoelace area times the height, the cap triangles' areas summing to the outline's area (no overlap,
// no gap), and a generalized winding number of 1 inside and 0 outside at sample points decided by a
// point-in-polygon count written here.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/geometry/solid_mesh.h"
#include "core/geometry/triangle_mesh.h"

using namespace cdlab;

namespace {

double shoelace(const std::vector<Vec2>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) a += p[i].x() * p[(i + 1) % p.size()].y() - p[(i + 1) % p.size()].x() * p[i].y();
    return 0.5 * a;
}

bool insideOutline(const std::vector<Vec2>& p, const Vec2& q) {  // even-odd, a ray toward +x
    bool in = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
        if ((p[i].y() > q.y()) != (p[j].y() > q.y()) &&
            q.x() < (p[j].x() - p[i].x()) * (q.y() - p[i].y()) / (p[j].y() - p[i].y()) + p[i].x())
            in = !in;
    return in;
}

}  // namespace

TEST_CASE("prism meshes of non-convex outlines are closed, outward, of the right volume") {
    const std::vector<std::vector<Vec2>> outlines = {
        {{0, 0}, {3, 0}, {3, 2.4}, {2.1, 2.4}, {2.1, 0.9}, {0.9, 0.9}, {0.9, 2.4}, {0, 2.4}},  // U
        {{0, 0}, {2.6, 0}, {2.6, 0.8}, {0.8, 0.8}, {0.8, 2.4}, {0, 2.4}},                      // L
        {{0, 2.4}, {0.8, 2.4}, {0.8, 0.8}, {2.6, 0.8}, {2.6, 0}, {0, 0}},                      // L, clockwise
        {{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}},                                              // a deep notch
    };
    for (const auto& outline : outlines) {
        const TriangleMesh m = prismMesh(outline, 1.5);
        REQUIRE_FALSE(m.triangles.empty());
        CHECK(checkSolidMesh(m).status == SolidMeshStatus::Closed);
        CHECK(signedVolume(m) == doctest::Approx(std::abs(shoelace(outline)) * 1.5).epsilon(1e-12));
        // The bottom cap's triangles (z = 0 everywhere) tile the outline: their areas sum to its area.
        double capArea = 0;
        for (int t = 0; t < m.triangleCount(); ++t) {
            const Triangle tri = m.triangle(t);
            if (tri.a.z() == 0 && tri.b.z() == 0 && tri.c.z() == 0) capArea += 0.5 * (tri.b - tri.a).cross(tri.c - tri.a).norm();
        }
        CHECK(capArea == doctest::Approx(std::abs(shoelace(outline))).epsilon(1e-12));
        for (double x = -0.25; x < 4.3; x += 0.37)
            for (double y = -0.25; y < 4.3; y += 0.41) {
                const double w = windingNumber(m, Vec3(x, y, 0.7));
                CHECK(std::abs(w - (insideOutline(outline, Vec2(x, y)) ? 1.0 : 0.0)) < 1e-9);
            }
    }
}

TEST_CASE("prism meshes: a crossing outline, too few corners, no height") {
    CHECK(prismMesh({{0, 0}, {2, 2}, {2, 0}, {0, 2}}, 1.0).triangles.empty());  // a bow tie: not simple
    CHECK(prismMesh({{0, 0}, {1, 0}}, 1.0).triangles.empty());
    CHECK(prismMesh({{0, 0}, {1, 0}, {0, 1}}, 0.0).triangles.empty());
    CHECK(prismMesh({{0, 0}, {1, 0}, {NAN, 1}}, 1.0).triangles.empty());
}

TEST_CASE("a prism outline from any starting corner") {
    // A chevron (a turn sharper than 90° at its first corner) and a notched square: every rotation
    // of the corner list is the same polygon and must give a closed prism of the same volume.
    const std::vector<std::vector<Vec2>> outlines = {{{0, 0}, {2, 1}, {4, 0}, {2, 3}},
                                                     {{0, 0}, {3, 0}, {3, 3}, {1.5, 1}, {0, 3}}};
    for (const std::vector<Vec2>& base : outlines) {
        double area = 0;
        for (std::size_t i = 0; i < base.size(); ++i)
            area += 0.5 * (base[i].x() * base[(i + 1) % base.size()].y() - base[(i + 1) % base.size()].x() * base[i].y());
        for (std::size_t r = 0; r < base.size(); ++r) {
            std::vector<Vec2> o(base.begin() + std::ptrdiff_t(r), base.end());
            o.insert(o.end(), base.begin(), base.begin() + std::ptrdiff_t(r));
            CAPTURE(r);
            const TriangleMesh m = prismMesh(o, 2.0);
            REQUIRE_FALSE(m.triangles.empty());
            double volume = 0;
            for (int t = 0; t < m.triangleCount(); ++t) {
                const Triangle tr = m.triangle(t);
                volume += tr.a.dot(tr.b.cross(tr.c)) / 6.0;
            }
            CHECK(volume == doctest::Approx(2.0 * std::abs(area)).epsilon(1e-12));
        }
    }
}
