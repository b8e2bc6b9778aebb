// Box–box and box–plane fast paths (core/contact/contact_box.h): the same answers as the general
// contactPolyhedra / contactPolyhedronPlane on presets::box (features included, which checks the
// corner, edge and face numbering), depths against the long double Minkowski facet oracle, signed
// distances against long double corners, manifold points inside both bodies, invalid input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/contact/contact_box.h"
#include "core/geometry/polyhedron_presets.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/core/contact/random_pose.h"

using namespace cdlab;

namespace {

Vec3 randomExtents(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.1, 1.0);
    return Vec3(u(rng), u(rng), u(rng));
}

std::vector<Vec3> corners(const Vec3& h, const Transform& t) {
    std::vector<Vec3> c;
    for (int k = 0; k < 8; ++k) c.push_back(t.apply(Vec3((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(), (k & 4) ? h.z() : -h.z())));
    return c;
}

bool insideBox(const Vec3& h, const Transform& t, const Vec3& x, double tol) {
    return (t.applyInverse(x).cwiseAbs() - h).maxCoeff() <= tol;
}

// Twice the area of the convex hull of the points' pointB, in the plane ⟂ normal (monotone chain).
double hullArea(const ContactManifold& m, const Vec3& normal) {
    const Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
    std::vector<Vec2> p;
    for (const ContactPoint& c : m) p.emplace_back(u.dot(c.pointB), w.dot(c.pointB));
    std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    if (p.size() < 3) return 0.0;
    const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
        return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
    };
    std::vector<Vec2> h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    double area = 0.0;
    for (size_t i = 0; i + 1 < k; ++i) area += h[i].x() * h[i + 1].y() - h[i + 1].x() * h[i].y();
    return area;
}

// The same manifold up to exact ties: the same deepest point first, as many points, and the same
// area spanned. The reduction's picks tie exactly where a clipped rectangle has parallel sides (two
// points make the same triangle with the first two), and rounding then decides which is taken;
// both answers are equally good reductions, so the points may differ but never the area.
void checkSameManifold(const ContactManifold& fast, const ContactManifold& general, const Vec3& normal, double tol) {
    REQUIRE(fast.size() == general.size());
    if (fast.empty()) return;
    CHECK((fast[0].pointA - general[0].pointA).norm() <= tol);
    CHECK((fast[0].pointB - general[0].pointB).norm() <= tol);
    CHECK(std::abs(fast[0].depth - general[0].depth) <= tol);
    CHECK(std::abs(hullArea(fast, normal) - hullArea(general, normal)) <= tol);
}

}  // namespace

TEST_SUITE("contact_box") {
    TEST_CASE("box-box: the general SAT's answer on 3000 random pairs, features and manifold included") {
        std::mt19937_64 rng(11);
        int counts[3] = {0, 0, 0};  // separated, face contact, edge contact
        for (double offset : {0.0, 1e4}) {
            for (int k = 0; k < 1500; ++k) {
                const Vec3 ha = randomExtents(rng), hb = randomExtents(rng);
                const Vec3 c = Vec3::Constant(offset);
                const Transform ta = test::randomPose(rng, c, 0.0), tb = test::randomPose(rng, c, 0.8);
                const SatContactResult f = contactBoxBox(ha, ta, hb, tb);
                const SatContactResult g = contactPolyhedra(presets::box(ha), ta, presets::box(hb), tb);
                const double tol = 1e-11 * (1.0 + offset);
                CAPTURE(k);
                CAPTURE(offset);
                REQUIRE(f.status == g.status);
                REQUIRE(f.axisKind == g.axisKind);
                CHECK(f.featureA.type == g.featureA.type);
                CHECK(f.featureA.index == g.featureA.index);
                CHECK(f.featureB.type == g.featureB.type);
                CHECK(f.featureB.index == g.featureB.index);
                CHECK((f.normal - g.normal).norm() <= 1e-12);
                CHECK(std::abs(f.separation - g.separation) <= tol);
                CHECK(std::abs(f.depth - g.depth) <= tol);
                CHECK(f.tolerance == doctest::Approx(g.tolerance).epsilon(1e-12));
                checkSameManifold(f.manifold, g.manifold, g.normal, tol);
                ++counts[f.status == SatContactStatus::Separated ? 0 : f.axisKind == SatAxisKind::EdgeEdge ? 2 : 1];
            }
        }
        CHECK(counts[0] > 300);  // every branch exercised
        CHECK(counts[1] > 300);
        CHECK(counts[2] > 30);
    }

    TEST_CASE("box-box: depth = the Minkowski facet oracle's, points inside both boxes") {
        std::mt19937_64 rng(12);
        int penetrating = 0;
        for (int k = 0; k < 300; ++k) {
            const Vec3 ha = randomExtents(rng), hb = randomExtents(rng);
            const Transform ta = test::randomPose(rng, Vec3::Zero(), 0.0), tb = test::randomPose(rng, Vec3::Zero(), 0.6);
            const SatContactResult r = contactBoxBox(ha, ta, hb, tb);
            const test::HullOracle o = test::hullOracle(corners(ha, ta), corners(hb, tb));
            if (o.inside) {
                ++penetrating;
                REQUIRE(r.colliding());
                CHECK(-r.separation == doctest::Approx(double(o.depth)).epsilon(1e-10));
                // The face preference: a face is kept over a better axis by at most 2% (+ tol).
                CHECK(0.98 * r.depth <= -r.separation + r.tolerance);
                REQUIRE(!r.manifold.empty());
                CHECK(r.manifold.size() <= 4);
                for (const ContactPoint& p : r.manifold) {
                    CHECK(insideBox(ha, ta, p.pointA, 1e-9));
                    CHECK(insideBox(hb, tb, p.pointB, 1e-9));
                    CHECK((p.pointA - p.pointB - p.depth * r.normal).norm() <= 1e-9);
                    CHECK(p.depth <= r.depth + 1e-12);
                }
            } else if (o.distance > 1e-9) {
                CHECK(r.status == SatContactStatus::Separated);
                CHECK(r.separation > 0.0);
                CHECK(r.separation <= double(o.distance) + 1e-12);  // a lower bound of the distance
            }
        }
        CHECK(penetrating > 100);
    }

    TEST_CASE("box-box: boxes of half-size 1e78 and 1e-120 give the unit answer scaled") {
        // A scene scaled by a power of two has the same contact scaled. Half-sizes ~1e78 gave NaN
        // edge-edge points (squared edge lengths overflow in the closest points of the two edges).
        std::mt19937_64 rng(15);
        int edgeContacts = 0;
        for (int k = 0; k < 600; ++k) {
            const Vec3 ha = randomExtents(rng), hb = randomExtents(rng);
            const Transform ta = test::randomPose(rng, Vec3::Zero(), 0.0), tb = test::randomPose(rng, Vec3::Zero(), 0.8);
            const SatContactResult unit = contactBoxBox(ha, ta, hb, tb);
            if (!unit.colliding()) continue;
            edgeContacts += unit.axisKind == SatAxisKind::EdgeEdge;
            for (const double scale : {0x1p+260, 0x1p-400}) {
                Transform sa = ta, sb = tb;
                sa.position *= scale;
                sb.position *= scale;
                const SatContactResult r = contactBoxBox(scale * ha, sa, scale * hb, sb);
                CAPTURE(k);
                CAPTURE(scale);
                REQUIRE(r.status == unit.status);
                REQUIRE(r.axisKind == unit.axisKind);
                REQUIRE(r.manifold.size() == unit.manifold.size());
                CHECK(std::abs(r.depth - scale * unit.depth) <= 1e-12 * scale);
                for (size_t i = 0; i < r.manifold.size(); ++i) {
                    CHECK((r.manifold[i].pointA - scale * unit.manifold[i].pointA).norm() <= 1e-12 * scale);
                    CHECK((r.manifold[i].pointB - scale * unit.manifold[i].pointB).norm() <= 1e-12 * scale);
                }
            }
        }
        CHECK(edgeContacts > 10);
    }

    TEST_CASE("box-box: resting box, 4 points of the sunk depth, invalid input named") {
        const Vec3 ground(2, 2, 0.5), cube(0.5, 0.5, 0.5);
        Transform tg, tc;
        tc.position = Vec3(0.1, -0.2, 0.99);
        tc.rotation = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
        const SatContactResult r = contactBoxBox(ground, tg, cube, tc);
        REQUIRE(r.status == SatContactStatus::Penetrating);
        CHECK(r.normal.isApprox(Vec3::UnitZ(), 1e-12));
        REQUIRE(r.manifold.size() == 4);
        for (const ContactPoint& p : r.manifold) CHECK(p.depth == doctest::Approx(0.01).epsilon(1e-9));
        CHECK(contactBoxBox(Vec3(1, 0, 1), tg, cube, tc).message == "A: box half extents must be finite, > 0 and at most 1e150");
        CHECK(contactBoxBox(ground, tg, Vec3(1, NAN, 1), tc).message == "B: box half extents must be finite, > 0 and at most 1e150");
        // Beyond double precision's range: an error, never an out-of-range face index.
        CHECK(contactBoxBox(Vec3::Constant(1e200), tg, cube, tc).status == SatContactStatus::InvalidInput);
        Transform west = tg, east = tc;  // centres 3.4e308 apart: the difference overflows
        west.position = Vec3(-1.7e308, 0, 0);
        east.position = Vec3(1.7e308, 0, 0);
        const SatContactResult huge = contactBoxBox(Vec3::Constant(1e150), west, Vec3::Constant(1e150), east);
        CHECK(huge.status == SatContactStatus::InvalidInput);
        CHECK(huge.message == "the boxes' coordinates overflow double precision");
        Transform corner = tc;  // n · x = 0.6 x + 0.8 y = 2.4e308 overflows
        corner.position = Vec3(1.7e308, 1.7e308, 0);
        CHECK(contactBoxPlane(Vec3::Constant(1e150), corner, Plane{Vec3(0.6, 0.8, 0), 0.0}).status ==
              PlaneContactStatus::InvalidInput);
        tc.rotation.coeffs() *= 2.0;
        const SatContactResult bad = contactBoxBox(ground, tg, cube, tc);
        CHECK(bad.status == SatContactStatus::InvalidInput);
        CHECK(bad.message == "B: pose rotation is not a unit quaternion");
    }

    // The simulation case the fast path takes a shortcut on: a box on a face or an edge, tilted by a
    // few degrees and sunk a little (2 to 4 corners below, steep edges whose crossings are the rim
    // of a corner, shallow ones that are not), at the default tolerance, at tolerance 0 (the
    // surface band then exceeds tol: a corner just below the plane is not "submerged") and keeping
    // every candidate (maxPoints 0: no rule 0).
    TEST_CASE("box-plane: resting and tilted boxes, the general plane contact's manifold") {
        std::mt19937_64 rng(14);
        std::uniform_real_distribution<double> u(-1.0, 1.0), half(0.1, 1.0);
        int reduced = 0, shortcut = 0;
        for (int k = 0; k < 3000; ++k) {
            const Vec3 h(half(rng), half(rng), half(rng));
            const double tilt = (k % 3 == 0 ? 0.7 : 0.06);  // up to ~40° or ~3.4°
            Transform t;
            t.rotation = Quat(Eigen::AngleAxisd(tilt * u(rng), Vec3::UnitX())) *
                         Quat(Eigen::AngleAxisd(tilt * u(rng), Vec3::UnitY())) *
                         Quat(Eigen::AngleAxisd(3.0 * u(rng), Vec3::UnitZ()));
            if (k % 2) t.rotation = t.rotation * Quat(Eigen::AngleAxisd(0.785398, Vec3::UnitX()));  // on an edge
            t.position = Vec3(u(rng), u(rng), (k % 2 ? 1.3 : 0.97) * h.z() + 0.05 * u(rng));
            const Plane plane{Vec3::UnitZ(), 0.0};
            PlaneContactOptions options;
            options.maxPoints = k % 7;  // 0 .. 6
            if (k % 5 == 0) options.tolerance = 0.0;
            const BoxPlaneContact f = contactBoxPlane(h, t, plane, options);
            PlaneContactTrace trace;
            const PlaneContactResult g = contactPolyhedronPlane(presets::box(h), t, plane, options, &trace);
            CAPTURE(k);
            REQUIRE(f.status == g.status);
            CHECK(f.deepestVertex == g.deepestVertex);
            if (options.maxPoints > 0) {
                checkSameManifold(f.manifold, g.manifold, g.normal, 1e-13);
            } else if (g.colliding()) {  // every candidate, the deepest first (the general function: its polygon)
                REQUIRE(f.manifold.size() == trace.candidates.size());
                CHECK(f.manifold[0].depth == doctest::Approx(g.depth).epsilon(1e-13));
            }
            if (g.colliding()) (g.manifold.size() < g.polygon.size() ? reduced : shortcut) += 1;
        }
        CHECK(reduced > 300);  // both outcomes of the reduction exercised
        CHECK(shortcut > 300);
    }

    // Box-plane's fast path gives the general manifold for boxes of 1e-100 .. 1e140 (squared lengths
    // in its rim bound overflow at 1e80 and underflow at 1e-100, which would drop every crossing next
    // to a submerged corner) and with a negative relativeTolerance (a corner below the plane that it
    // leaves out of the candidates is not taken as submerged).
    TEST_CASE("box-plane: huge and tiny boxes, negative relative tolerance: the general manifold") {
        for (double size : {1.0, 1e-100, 1e-80, 1e80, 1e100, 1e140}) {
            const Vec3 h = Vec3::Constant(size);
            Transform t;
            t.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
            t.position = Vec3(0, 0, size * (std::cos(0.3) + std::sin(0.3)) - 0.5 * size);
            const Plane plane{Vec3::UnitZ(), 0.0};
            const BoxPlaneContact f = contactBoxPlane(h, t, plane);
            const PlaneContactResult g = contactPolyhedronPlane(presets::box(h), t, plane);
            CAPTURE(size);
            REQUIRE(g.manifold.size() == 4);
            REQUIRE(f.manifold.size() == 4);
            CHECK((f.manifold[0].pointA - g.manifold[0].pointA).norm() <= 1e-13 * size);
            CHECK(std::abs(hullArea(f.manifold, g.normal) / hullArea(g.manifold, g.normal) - 1.0) <= 1e-12);
        }
        int compared = 0;
        for (double rx : {0.3, 0.5})
            for (double z : {0.5, 1.0, 1.3})
                for (double relative : {-0.1, -0.2, -0.3})
                    for (int maxPoints : {3, 4}) {
                        Transform t;
                        t.rotation = Quat(Eigen::AngleAxisd(rx, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(0.2, Vec3::UnitY()));
                        t.position = Vec3(0, 0, z);
                        PlaneContactOptions options;
                        options.maxPoints = maxPoints;
                        options.relativeTolerance = relative;
                        const Plane plane{Vec3::UnitZ(), 0.0};
                        const BoxPlaneContact f = contactBoxPlane(Vec3(1, 1, 1), t, plane, options);
                        const PlaneContactResult g = contactPolyhedronPlane(presets::box(Vec3(1, 1, 1)), t, plane, options);
                        CAPTURE(rx);
                        CAPTURE(z);
                        CAPTURE(relative);
                        REQUIRE(f.status == g.status);
                        checkSameManifold(f.manifold, g.manifold, g.normal, 1e-13);
                        compared += g.colliding();
                    }
        CHECK(compared >= 10);
    }

    TEST_CASE("box-plane: the general plane contact's answer, signed distance = long double corners") {
        std::mt19937_64 rng(13);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        int colliding = 0;
        for (int k = 0; k < 3000; ++k) {
            const Vec3 h = randomExtents(rng);
            const Transform t = test::randomPose(rng, Vec3::Zero(), 0.5);
            const Plane plane{test::randomUnit(rng) * (0.5 + u(rng) * u(rng)), 0.3 * u(rng)};
            PlaneContactOptions options;
            options.maxPoints = 1 + k % 6;
            const BoxPlaneContact f = contactBoxPlane(h, t, plane, options);
            const PlaneContactResult g = contactPolyhedronPlane(presets::box(h), t, plane, options);
            CAPTURE(k);
            REQUIRE(f.status == g.status);
            CHECK(f.deepestVertex == g.deepestVertex);
            CHECK(std::abs(f.signedDistance - g.signedDistance) <= 1e-14);
            CHECK(f.normal.isApprox(g.normal, 1e-15));
            CHECK(f.tolerance == doctest::Approx(g.tolerance).epsilon(1e-12));
            checkSameManifold(f.manifold, g.manifold, g.normal, 1e-13);
            long double low = INFINITY;  // independent: corners and the plane in long double
            const long double len = std::sqrt((long double)plane.normal.squaredNorm());
            for (const Vec3& c : corners(h, t)) {
                long double s = -plane.offset;
                for (int i = 0; i < 3; ++i) s += (long double)plane.normal[i] * c[i];
                low = std::min(low, s / len);
            }
            CHECK(std::abs(f.signedDistance - double(low)) <= 1e-14);
            colliding += f.colliding();
        }
        CHECK(colliding > 500);
        CHECK(std::string(contactBoxPlane(Vec3(1, 1, 1), Transform{}, Plane{Vec3::Zero(), 0.0}).message) ==
              "plane normal is zero");
        CHECK(std::string(contactBoxPlane(Vec3(1, -1, 1), Transform{}, Plane{Vec3::UnitZ(), 0.0}).message) ==
              "box half extents must be finite, > 0 and at most 1e150");
    }
}
