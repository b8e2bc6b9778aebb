// ConvexPolyhedron (half-edge mesh) and presets. Oracles: closed-form counts, volumes and
// centroids; orientation checked with independent cross products; broken meshes built by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "core/geometry/polyhedron.h"
#include "core/geometry/polyhedron_presets.h"

using namespace cdlab;

namespace {

// The topology flattened at construction (edgeEnds, neighbors, faceVertexIds, faceAcross) against
// the half-edge walks: the same vertices, edges and faces, the steps exact position differences.
void checkFlatTopology(const ConvexPolyhedron& P) {
    REQUIRE(P.edgeEnds().size() == size_t(P.edgeCount()));
    for (int e = 0; e < P.edgeCount(); ++e) {
        const ConvexPolyhedron::EdgeEnds& ends = P.edgeEnds()[e];
        CHECK(std::pair(ends.v0, ends.v1) == P.edgeVertices(e));
        CHECK(std::pair(ends.f1, ends.f2) == P.edgeFaces(e));
    }
    REQUIRE(P.neighborStart().size() == size_t(P.vertexCount() + 1));
    REQUIRE(P.neighborStart().back() == P.halfEdgeCount());
    // Slot j of vertex v holds the j-th half-edge leaving v in index order (the descents and walks
    // break ties by it): its destination, its edge, the step between the two positions.
    std::vector<int> seen(P.vertexCount(), 0);
    for (int h = 0; h < P.halfEdgeCount(); ++h) {
        const int v = P.halfEdge(h).origin;
        const ConvexPolyhedron::Neighbor& n = P.neighbors()[P.neighborStart()[v] + seen[v]++];
        CHECK(n.vertex == P.halfEdgeDestination(h));
        CHECK(n.edge == P.halfEdge(h).edge);
        CHECK(n.step == P.position(n.vertex) - P.position(v));
    }
    for (int v = 0; v < P.vertexCount(); ++v) {
        CHECK(P.neighborStart()[v + 1] - P.neighborStart()[v] == seen[v]);
        CHECK(seen[v] == static_cast<int>(P.vertexNeighbors(v).size()));
    }
    REQUIRE(P.faceVertexStart().size() == size_t(P.faceCount() + 1));
    for (int f = 0; f < P.faceCount(); ++f) {
        const int begin = P.faceVertexStart()[f], end = P.faceVertexStart()[f + 1];
        const std::vector<int> loop = P.faceVertices(f);
        CHECK(std::vector<int>(P.faceVertexIds().begin() + begin, P.faceVertexIds().begin() + end) == loop);
        for (int k = begin; k < end; ++k) {  // the other face of the edge from this vertex to the next
            const int a = loop[k - begin], b = loop[(k - begin + 1) % loop.size()];
            int across = -1;
            for (int e = 0; e < P.edgeCount(); ++e) {
                const auto [u, w] = P.edgeVertices(e);
                const auto [f1, f2] = P.edgeFaces(e);
                if ((u == a && w == b) || (u == b && w == a)) across = f1 == f ? f2 : f1;
            }
            CHECK(P.faceAcross()[k] == across);
        }
    }
}

void checkMesh(const ConvexPolyhedron& P, int V, int E, int F) {
    REQUIRE(!P.empty());
    const PolyhedronCheck c = P.validate();
    INFO(c.message);
    CHECK(c.ok());
    CHECK(P.eulerCharacteristic() == 2);
    if (V >= 0) CHECK(P.vertexCount() == V);
    if (E >= 0) CHECK(P.edgeCount() == E);
    if (F >= 0) CHECK(P.faceCount() == F);
    CHECK(P.halfEdgeCount() == 2 * P.edgeCount());
    // Faces counter-clockwise from outside: every corner turns left about the outward normal.
    for (int f = 0; f < P.faceCount(); ++f) {
        const auto l = P.faceVertices(f);
        const size_t k = l.size();
        for (size_t i = 0; i < k; ++i) {
            const Vec3 e0 = P.position(l[(i + 1) % k]) - P.position(l[i]);
            const Vec3 e1 = P.position(l[(i + 2) % k]) - P.position(l[(i + 1) % k]);
            CHECK(e0.cross(e1).dot(P.face(f).normal) > 0.0);
        }
    }
    // Vertex rings counter-clockwise from outside; face i lies between outgoing edges i and i+1.
    for (int v = 0; v < P.vertexCount(); ++v) {
        const auto hs = P.vertexHalfEdges(v);
        const auto fs = P.vertexFaces(v);
        const auto ns = P.vertexNeighbors(v);
        REQUIRE(hs.size() >= 3);
        REQUIRE(fs.size() == hs.size());
        for (size_t i = 0; i < hs.size(); ++i) {
            CHECK(P.halfEdge(hs[i]).origin == v);
            const Vec3 a = P.position(ns[i]) - P.position(v);
            const Vec3 b = P.position(ns[(i + 1) % ns.size()]) - P.position(v);
            CHECK(a.cross(b).dot(P.face(fs[i]).normal) > 0.0);
        }
    }
    for (int e = 0; e < P.edgeCount(); ++e) {
        const auto [a, b] = P.edgeVertices(e);
        const auto [f, g] = P.edgeFaces(e);
        CHECK(a != b);
        CHECK(f != g);
    }
    checkFlatTopology(P);
}

}  // namespace

TEST_SUITE("polyhedron") {
    TEST_CASE("platonic solids: counts, Euler, validity, volume") {
        const double r = 1.7;
        const ConvexPolyhedron tet = presets::tetrahedron(r);
        checkMesh(tet, 4, 6, 4);
        // Regular tetrahedron of circumradius r: edge a = r * sqrt(8/3), volume a^3 / (6 sqrt 2).
        const double a = r * std::sqrt(8.0 / 3.0);
        CHECK(tet.volume() == doctest::Approx(a * a * a / (6 * std::sqrt(2.0))).epsilon(1e-12));
        const ConvexPolyhedron oct = presets::octahedron(r);
        checkMesh(oct, 6, 12, 8);
        CHECK(oct.volume() == doctest::Approx(4.0 / 3.0 * r * r * r).epsilon(1e-12));
        const ConvexPolyhedron ico = presets::icosahedron(r);
        checkMesh(ico, 12, 30, 20);
        // Icosahedron: edge a = r / sin(2 pi / 5), volume 5/12 (3 + sqrt 5) a^3.
        const double ai = r / std::sin(2 * std::numbers::pi / 5);
        CHECK(ico.volume() == doctest::Approx(5.0 / 12.0 * (3 + std::sqrt(5.0)) * ai * ai * ai).epsilon(1e-12));
        const ConvexPolyhedron dod = presets::dodecahedron(r);
        checkMesh(dod, 20, 30, 12);
        for (int f = 0; f < dod.faceCount(); ++f) CHECK(dod.faceDegree(f) == 5);
        // Dodecahedron: edge a = r * 4 / (sqrt 3 (1 + sqrt 5)), volume (15 + 7 sqrt 5) / 4 a^3.
        const double ad = r * 4 / (std::sqrt(3.0) * (1 + std::sqrt(5.0)));
        CHECK(dod.volume() == doctest::Approx((15 + 7 * std::sqrt(5.0)) / 4 * ad * ad * ad).epsilon(1e-12));
        for (const ConvexPolyhedron* p : {&tet, &oct, &ico, &dod}) {
            CHECK(p->centroid().norm() < 1e-12);
            for (int v = 0; v < p->vertexCount(); ++v)
                CHECK(p->position(v).norm() == doctest::Approx(r).epsilon(1e-14));
        }
    }

    TEST_CASE("box: counts, quads, volume, area, centroid") {
        const Vec3 h(0.5, 2.0, 3.0);
        const ConvexPolyhedron b = presets::box(h);
        checkMesh(b, 8, 12, 6);
        for (int f = 0; f < 6; ++f) CHECK(b.faceDegree(f) == 4);
        CHECK(b.volume() == doctest::Approx(8 * h.x() * h.y() * h.z()));
        CHECK(b.surfaceArea() == doctest::Approx(8 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x())));
        CHECK(b.boundsMax() == h);
        CHECK(b.boundsMin() == -h);
        for (int f = 0; f < 6; ++f) CHECK(b.face(f).normal.cwiseAbs().maxCoeff() == 1.0);
    }

    TEST_CASE("prism and disk") {
        for (int n : {3, 4, 7, 64}) {
            CAPTURE(n);
            const ConvexPolyhedron p = presets::prism(n, 2.0, 0.75);
            checkMesh(p, 2 * n, 3 * n, n + 2);
            const double area = 0.5 * n * 4.0 * std::sin(2 * std::numbers::pi / n);
            CHECK(p.volume() == doctest::Approx(area * 1.5).epsilon(1e-12));
        }
        const ConvexPolyhedron d = presets::disk(32, 1.0);
        checkMesh(d, 64, 96, 34);
        CHECK(d.boundsMax().y() == doctest::Approx(1e-4));
        const auto poly = presets::regularPolygon(5, 2.0);
        REQUIRE(poly.size() == 5);
        // Counter-clockwise seen from +y.
        CHECK((poly[1] - poly[0]).cross(poly[2] - poly[1]).y() > 0);
    }

    TEST_CASE("geodesic spheres") {
        for (int level = 0; level <= 3; ++level) {
            CAPTURE(level);
            const ConvexPolyhedron g = presets::geodesicSphere(level, 2.0);
            const int V = 10 * (1 << (2 * level)) + 2;
            checkMesh(g, V, -1, -1);
            CHECK(g.volume() < 4.0 / 3.0 * std::numbers::pi * 8.0);
            if (level == 3) CHECK(g.volume() > 0.97 * 4.0 / 3.0 * std::numbers::pi * 8.0);
        }
    }

    TEST_CASE("random hulls: valid and deterministic for a seed") {
        for (auto kind : {presets::RandomHullKind::OnSphere, presets::RandomHullKind::InBall}) {
            for (std::uint64_t seed : {1ull, 42ull, 1234567ull}) {
                const ConvexPolyhedron a = presets::randomHull(300, seed, kind, 3.0);
                checkMesh(a, -1, -1, -1);
                const ConvexPolyhedron b = presets::randomHull(300, seed, kind, 3.0);
                CHECK(a.positions() == b.positions());
                CHECK(a.faceCount() == b.faceCount());
                if (kind == presets::RandomHullKind::OnSphere) CHECK(a.vertexCount() == 300);
            }
        }
        CHECK(presets::randomHull(50, 1).positions() != presets::randomHull(50, 2).positions());
        // Pin the generator: splitmix64 from seed 0 (reference values of the published algorithm).
        presets::SplitMix64 rng(0);
        CHECK(rng.next() == 0xE220A8397B1DCDAFull);
        CHECK(rng.next() == 0x6E789E6AA1B965F4ull);
    }

    TEST_CASE("volume and centroid far from the origin") {
        const Vec3 h(1.0, 2.0, 0.5);
        const Vec3 offset(1e6, -2e6, 3e6);
        const ConvexPolyhedron b = presets::box(h);
        std::vector<Vec3> pos = b.positions();
        for (Vec3& p : pos) p += offset;
        std::vector<std::vector<int>> faces;
        for (int f = 0; f < b.faceCount(); ++f) faces.push_back(b.faceVertices(f));
        const PolyhedronBuild moved = ConvexPolyhedron::fromFaces(pos, faces);
        REQUIRE(moved.ok());
        CHECK(moved.polyhedron.validate().ok());
        CHECK(moved.polyhedron.volume() == doctest::Approx(8.0).epsilon(1e-9));
        CHECK((moved.polyhedron.centroid() - offset).norm() < 1e-9);
        for (int f = 0; f < 6; ++f) CHECK(moved.polyhedron.face(f).normal.isApprox(b.face(f).normal, 1e-12));
    }

    TEST_CASE("fromFaces rejects broken meshes") {
        const ConvexPolyhedron b = presets::box(Vec3(1, 1, 1));
        const std::vector<Vec3> pos = b.positions();
        std::vector<std::vector<int>> faces;
        for (int f = 0; f < 6; ++f) faces.push_back(b.faceVertices(f));
        REQUIRE(ConvexPolyhedron::fromFaces(pos, faces).ok());
        {
            auto open = faces;
            open.pop_back();
            const auto r = ConvexPolyhedron::fromFaces(pos, open);
            CHECK(r.check.defect == PolyhedronDefect::OpenEdge);
            CHECK(r.polyhedron.empty());
        }
        {
            auto flipped = faces;
            std::reverse(flipped[2].begin(), flipped[2].end());
            CHECK(ConvexPolyhedron::fromFaces(pos, flipped).check.defect == PolyhedronDefect::NonManifoldEdge);
        }
        {
            auto bad = faces;
            bad[0][1] = 8;
            CHECK(ConvexPolyhedron::fromFaces(pos, bad).check.defect == PolyhedronDefect::BadVertexIndex);
            bad = faces;
            bad[0] = {bad[0][0], bad[0][1]};
            CHECK(ConvexPolyhedron::fromFaces(pos, bad).check.defect == PolyhedronDefect::FaceTooSmall);
            bad = faces;
            bad[0][2] = bad[0][0];
            CHECK(ConvexPolyhedron::fromFaces(pos, bad).check.defect == PolyhedronDefect::RepeatedVertexInFace);
        }
        {
            auto extra = pos;
            extra.push_back(Vec3(5, 5, 5));
            CHECK(ConvexPolyhedron::fromFaces(extra, faces).check.defect == PolyhedronDefect::IsolatedVertex);
            extra = pos;
            extra[3].x() = std::nan("");
            CHECK(ConvexPolyhedron::fromFaces(extra, faces).check.defect == PolyhedronDefect::NonFinite);
        }
        CHECK(ConvexPolyhedron::fromFaces({}, {}).check.defect == PolyhedronDefect::NoFaces);
        CHECK(ConvexPolyhedron().validate().defect == PolyhedronDefect::NoFaces);
    }

    TEST_CASE("validate catches non-planar, non-convex and dented meshes") {
        const ConvexPolyhedron b = presets::box(Vec3(1, 1, 1));
        std::vector<std::vector<int>> faces;
        for (int f = 0; f < 6; ++f) faces.push_back(b.faceVertices(f));
        {
            auto pos = b.positions();
            pos[7] += Vec3(0.1, 0.05, 0.0);  // lift a corner: three quads become non-planar
            const auto r = ConvexPolyhedron::fromFaces(pos, faces);
            REQUIRE(r.ok());  // topology is fine
            CHECK(r.polyhedron.validate().defect == PolyhedronDefect::NonPlanarFace);
            CHECK(r.polyhedron.validate(0.2).ok());  // within a loose tolerance it is acceptable
        }
        {
            // Octahedron with its top vertex pushed inside: vertices lie in front of face planes.
            const ConvexPolyhedron o = presets::octahedron(1.0);
            auto pos = o.positions();
            std::vector<std::vector<int>> of;
            for (int f = 0; f < o.faceCount(); ++f) of.push_back(o.faceVertices(f));
            for (Vec3& p : pos)
                if (p.y() > 0.5) p.y() = -0.5;
            const auto r = ConvexPolyhedron::fromFaces(pos, of);
            REQUIRE(r.ok());
            const PolyhedronCheck c = r.polyhedron.validate();
            CHECK(!c.ok());
            CHECK(!c.message.empty());
        }
    }

}  // TEST_SUITE
