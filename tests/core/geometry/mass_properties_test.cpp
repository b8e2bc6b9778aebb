// Polyhedral mass properties. Oracles: closed forms (box m(b²+c²)/12, regular tetrahedron m L²/20,
// icosahedron φ² m s²/10, a corner of a box by hand), an L-shaped (non-convex) solid composed from two
// boxes with the parallel-axis theorem, and for random hulls the degree-2-exact 4-point quadrature
// rule on a tetrahedron decomposition in long double (Keast 1986; a different formula from the code's).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/polyhedron_presets.h"

using namespace cdlab;

namespace {

// Box [lo, hi] with faces counter-clockwise from outside, explicit (no preset).
void boxMesh(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& p, std::vector<std::vector<int>>& f) {
    p.clear();
    for (int i = 0; i < 8; ++i)
        p.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
    f = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
}

Mat3 boxInertia(double m, const Vec3& size) {
    const Vec3 s2 = size.cwiseProduct(size);
    return Vec3(m * (s2.y() + s2.z()) / 12, m * (s2.x() + s2.z()) / 12, m * (s2.x() + s2.y()) / 12).asDiagonal();
}

double relErr(const Mat3& a, const Mat3& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

Quat someRotation() { return Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())); }

// Oracle for a convex polyhedron: tetrahedra (interior point, face fan triangle), each integrated with
// the 4-point rule exact for polynomials of degree 2 (points α, β, β, β barycentric; weights V/4),
// accumulated in long double.
struct LongMass {
    long double V = 0;
    std::array<long double, 3> first{};
    std::array<std::array<long double, 3>, 3> second{};
    Vec3 origin = Vec3::Zero();  ///< the point the moments are taken about
};
LongMass quadratureOracle(const ConvexPolyhedron& P) {
    using L = long double;
    const L alpha = 0.5854101966249685L, beta = 0.1381966011250105L;  // (5 + 3√5)/20, (5 − √5)/20
    Vec3 o = P.centroid();
    // Integrate relative to the apex o (long double: 11 more bits than the inputs).
    LongMass M;
    for (int f = 0; f < P.faceCount(); ++f) {
        const auto vs = P.faceVertices(f);
        for (size_t k = 1; k + 1 < vs.size(); ++k) {
            std::array<std::array<L, 3>, 4> t;
            const Vec3* pts[4] = {&o, &P.position(vs[0]), &P.position(vs[k]), &P.position(vs[k + 1])};
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 3; ++j) t[i][j] = static_cast<L>((*pts[i])[j]) - static_cast<L>(o[j]);
            L e[3][3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) e[i][j] = t[i + 1][j] - t[0][j];
            const L vol =
                (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                 e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
                6;
            M.V += vol;
            for (int q = 0; q < 4; ++q) {
                std::array<L, 3> x{};
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 3; ++j) x[j] += (i == q ? alpha : beta) * t[i][j];
                for (int j = 0; j < 3; ++j) {
                    M.first[j] += vol / 4 * x[j];
                    for (int l = 0; l < 3; ++l) M.second[j][l] += vol / 4 * x[j] * x[l];
                }
            }
        }
    }
    M.origin = o;  // moments are about o: no cancellation at large offsets
    return M;
}

}  // namespace

TEST_SUITE("mass_properties") {
    TEST_CASE("box: volume, centre and m(b²+c²)/12 at scales 1e-3..1e3 and offsets up to 1e6") {
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e4, 1e6}) {
                const Vec3 lo = Vec3(offset, -offset, 0.5 * offset);
                std::vector<Vec3> p;
                std::vector<std::vector<int>> f;
                boxMesh(lo, lo + scale * Vec3(1.0, 2.0, 3.0), p, f);
                // The box the coordinates describe: lo + size rounds at 1e6 (ulp 1.2e-10), so the oracle
                // takes the exact difference of the stored corners (Sterbenz: exact) as the size.
                const Vec3 size = p[7] - p[0];
                const MassProperties m = computeMassProperties(p, f, {.density = 2.5});
                INFO("scale " << scale << " offset " << offset << " " << m.message);
                REQUIRE(m.ok());
                const double V = size.prod();
                CHECK(std::abs(m.volume - V) <= 1e-14 * V);
                CHECK(std::abs(m.mass - 2.5 * V) <= 1e-14 * 2.5 * V);
                // The centre is rounded to the coordinates' ulp (2.2e-16 x offset).
                CHECK((m.centerOfMass - (p[0] + 0.5 * size)).norm() <= 1e-14 * scale + 4e-16 * offset);
                CHECK(relErr(m.inertia, boxInertia(2.5 * V, size)) <= 1e-14);
            }
    }

    TEST_CASE("preset box, every starting vertex of every face, rotated and translated: R I Rᵀ") {
        const ConvexPolyhedron B = presets::box(Vec3(0.5, 1.0, 1.5));
        const Quat q = someRotation();
        const Vec3 t(3, -4, 5);
        std::vector<Vec3> p;
        for (const Vec3& v : B.positions()) p.push_back(q * v + t);
        std::vector<std::vector<int>> faces;
        for (int f = 0; f < B.faceCount(); ++f) faces.push_back(B.faceVertices(f));
        for (int shift = 0; shift < 4; ++shift) {
            auto g = faces;
            for (auto& face : g) std::rotate(face.begin(), face.begin() + shift % face.size(), face.end());
            const MassProperties m = computeMassProperties(p, g);
            REQUIRE(m.ok());
            CHECK(m.volume == doctest::Approx(6.0).epsilon(1e-14));
            CHECK((m.centerOfMass - t).norm() < 1e-14 * 10);
            const Mat3 R = q.toRotationMatrix();
            CHECK(relErr(m.inertia, R * boxInertia(6.0, Vec3(1, 2, 3)) * R.transpose()) < 1e-14);
        }
    }

    TEST_CASE("regular tetrahedron: V = L³/(6√2), I = m L²/20 about every axis") {
        for (double R : {1e-3, 1.0, 1e3}) {
            const ConvexPolyhedron T = presets::tetrahedron(R);
            const MassProperties m = computeMassProperties(T);
            REQUIRE(m.ok());
            const double L = R * std::sqrt(8.0 / 3.0);  // edge of a tetrahedron with circumradius R
            const double V = L * L * L / (6 * std::sqrt(2.0));
            CHECK(m.volume == doctest::Approx(V).epsilon(1e-13));
            CHECK(m.centerOfMass.norm() < 1e-15 * R * 10);
            CHECK(relErr(m.inertia, (m.mass * L * L / 20) * Mat3::Identity()) < 1e-13);
        }
    }

    TEST_CASE("icosahedron: V = 5(3+√5)s³/12, I = φ² m s²/10") {
        const ConvexPolyhedron I = presets::icosahedron(1.0);
        const MassProperties m = computeMassProperties(I);
        REQUIRE(m.ok());
        const double phi = std::numbers::phi;
        // Edge length measured directly from the mesh: the shortest vertex distance.
        double edge = 1e300;
        for (int e = 0; e < I.edgeCount(); ++e) {
            const auto [a, b] = I.edgeVertices(e);
            edge = std::min(edge, (I.position(a) - I.position(b)).norm());
        }
        CHECK(m.volume == doctest::Approx(5 * (3 + std::sqrt(5.0)) / 12 * edge * edge * edge).epsilon(1e-13));
        CHECK(relErr(m.inertia, (phi * phi * m.mass * edge * edge / 10) * Mat3::Identity()) < 1e-13);
    }

    TEST_CASE("non-convex L-shaped prism equals two boxes composed with the parallel-axis theorem") {
        // Cross-section (x, y): [0,2]x[0,1] ∪ [0,1]x[1,2], extruded z in [0, 1]. 6-gon caps, 6 side quads.
        const std::vector<Vec2> ring = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counter-clockwise from +z
        std::vector<Vec3> p;
        for (double z : {0.0, 1.0})
            for (const Vec2& v : ring) p.emplace_back(v.x(), v.y(), z);
        std::vector<std::vector<int>> f = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
        for (int i = 0; i < 6; ++i) f.push_back({i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i});
        const MassProperties m = computeMassProperties(p, f);
        REQUIRE(m.ok());
        CHECK(m.volume == doctest::Approx(3.0));
        const Vec3 c1(1, 0.5, 0.5), c2(0.5, 1.5, 0.5);
        const Vec3 c = (2 * c1 + 1 * c2) / 3;
        CHECK((m.centerOfMass - c).norm() < 1e-15 * 10);
        const Mat3 I = inertiaAboutPoint(boxInertia(2, Vec3(2, 1, 1)), 2, c1, c) +
                       inertiaAboutPoint(boxInertia(1, Vec3(1, 1, 1)), 1, c2, c);
        CHECK(relErr(m.inertia, I) < 1e-14);
    }

    TEST_CASE("parallel-axis by hand: a box about its corner") {
        // About the corner (0,0,0) of [0,a]x[0,b]x[0,c]: I_xx = m(b²+c²)/3, I_xy = −m a b / 4.
        const double a = 1, b = 2, c = 3, mass = 6;
        const Mat3 I = inertiaAboutPoint(boxInertia(mass, Vec3(a, b, c)), mass, Vec3(a, b, c) / 2, Vec3::Zero());
        Mat3 hand;
        hand << mass * (b * b + c * c) / 3, -mass * a * b / 4, -mass * a * c / 4,  //
            -mass * a * b / 4, mass * (a * a + c * c) / 3, -mass * b * c / 4,      //
            -mass * a * c / 4, -mass * b * c / 4, mass * (a * a + b * b) / 3;
        CHECK(relErr(I, hand) < 1e-15);
    }

    TEST_CASE("random hulls against a long-double quadrature oracle, translated and rotated") {
        const Quat q = someRotation();
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            const HullResult h = convexHull(presets::randomHull(40, seed, presets::RandomHullKind::InBall).positions());
            REQUIRE(h.status == HullStatus::Ok);
            for (double offset : {0.0, 1e5}) {
                std::vector<Vec3> moved;
                for (const Vec3& v : h.polyhedron.positions())
                    moved.push_back(q * v + Vec3(offset, 2 * offset, -offset));
                const PolyhedronBuild pb = ConvexPolyhedron::fromFaces(moved, [&] {
                    std::vector<std::vector<int>> f;
                    for (int i = 0; i < h.polyhedron.faceCount(); ++i) f.push_back(h.polyhedron.faceVertices(i));
                    return f;
                }());
                REQUIRE(pb.ok());
                const MassProperties m = computeMassProperties(pb.polyhedron);
                REQUIRE(m.ok());
                const LongMass o = quadratureOracle(pb.polyhedron);
                Vec3 c;
                for (int j = 0; j < 3; ++j)
                    c[j] = static_cast<double>(o.first[j] / o.V + static_cast<long double>(o.origin[j]));
                Mat3 I;
                for (int j = 0; j < 3; ++j)
                    for (int l = 0; l < 3; ++l) {
                        const long double cov = o.second[j][l] - o.V * (o.first[j] / o.V) * (o.first[l] / o.V);
                        I(j, l) = static_cast<double>(-cov);
                    }
                const double tr = -(I.trace());
                I += tr * Mat3::Identity();
                INFO("seed " << seed << " offset " << offset);
                // At 1e5 offset both see the same (rounded) vertices; the code's fan sums lose ~1e-11.
                const double tol = offset == 0 ? 1e-12 : 1e-9;
                CHECK(m.volume == doctest::Approx(static_cast<double>(o.V)).epsilon(1e-12));
                CHECK((m.centerOfMass - c).norm() <= 1e-12 * (1 + offset));
                CHECK(relErr(m.inertia, I) < tol);
                // Rotating back gives the tensor of the unrotated hull: R I Rᵀ.
                if (offset == 0) {
                    const MassProperties m0 = computeMassProperties(h.polyhedron);
                    const Mat3 R = q.toRotationMatrix();
                    CHECK(relErr(m.inertia, R * m0.inertia * R.transpose()) < 1e-12);
                }
            }
        }
    }

    TEST_CASE("errors: NaN, density, open surface, inside-out, flat, non-planar face, bad index") {
        std::vector<Vec3> p;
        std::vector<std::vector<int>> f;
        boxMesh(Vec3::Zero(), Vec3::Ones(), p, f);
        REQUIRE(computeMassProperties(p, f).ok());

        auto nan = p;
        nan[3].y() = std::numeric_limits<double>::quiet_NaN();
        CHECK(computeMassProperties(nan, f).status == MassStatus::NonFinite);
        CHECK(computeMassProperties(nan, f).index == 3);
        auto inf = p;
        inf[0].x() = std::numeric_limits<double>::infinity();
        CHECK(computeMassProperties(inf, f).status == MassStatus::NonFinite);
        CHECK(computeMassProperties(p, f, {.density = 0.0}).status == MassStatus::NonPositiveDensity);
        CHECK(computeMassProperties(p, f, {.density = -1.0}).status == MassStatus::NonPositiveDensity);
        CHECK(computeMassProperties(p, f, {.density = std::numeric_limits<double>::quiet_NaN()}).status ==
              MassStatus::NonFinite);

        auto open = f;
        open.pop_back();
        CHECK(computeMassProperties(p, open).status == MassStatus::OpenSurface);
        auto flipped = f;
        std::reverse(flipped[2].begin(), flipped[2].end());  // one face against the others
        CHECK(computeMassProperties(p, flipped).status == MassStatus::OpenSurface);
        auto inside = f;
        for (auto& face : inside) std::reverse(face.begin(), face.end());
        CHECK(computeMassProperties(p, inside).status == MassStatus::Degenerate);

        auto flat = p;  // squash z to 0: a closed surface with no volume
        for (Vec3& v : flat) v.z() = 0;
        CHECK(computeMassProperties(flat, f).status == MassStatus::Degenerate);
        const std::vector<Vec3> tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};  // coplanar tetrahedron
        CHECK(computeMassProperties(tet, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}).status ==
              MassStatus::Degenerate);

        auto bent = p;
        bent[7] += Vec3(0.0, 0.0, 1e-3);  // the top face's corner lifts off its plane
        const MassProperties nb = computeMassProperties(bent, f);
        CHECK(nb.status == MassStatus::NonPlanarFace);
        CHECK(!nb.message.empty());
        auto slight = p;
        slight[7] += Vec3(0.0, 0.0, 1e-13);  // within tolerance (1e-9 of the size)
        CHECK(computeMassProperties(slight, f).ok());

        auto bad = f;
        bad[0][1] = 99;
        CHECK(computeMassProperties(p, bad).status == MassStatus::BadFace);
        bad = f;
        bad[1] = {1, 3};
        CHECK(computeMassProperties(p, bad).status == MassStatus::BadFace);
        CHECK(computeMassProperties(ConvexPolyhedron{}).status == MassStatus::Degenerate);
    }
}
