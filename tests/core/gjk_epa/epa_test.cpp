// EPA penetration depth tests: analytic boxes / spheres, touching and degenerate contacts, and
// random polytope pairs against a long double facet-enumeration oracle (verification/minkowski_facet_oracle.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <sstream>

#include "core/base/tolerances.h"
#include "core/gjk_epa/epa.h"
#include "core/geometry/polyhedron.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/core/gjk_epa/gjk_epa_test_support.h"

using namespace cdlab;
using namespace cdlab::test;

namespace {

void checkFinite(const EpaResult& r) {
    CHECK(std::isfinite(r.depth));
    CHECK(r.normal.allFinite());
    CHECK(r.pointA.allFinite());
    CHECK(r.pointB.allFinite());
    CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-14);
}

// The depth of the origin inside conv(P) (it must be inside): facets enumerated exactly
// (forEachFacet), each plane's distance from an error-free cross product (a few ulps whatever the
// facet's width).
double exactFacetDepth(const std::vector<Vec3>& P) {
    double best = INFINITY;
    forEachFacet(P, [&](int i, int j, int k, bool) {
        best = std::min(best, std::abs(accurateCross(P[i], P[j], P[k]).normalized().dot(P[i])));
    });
    return best;
}

}  // namespace

TEST_SUITE("epa") {
    TEST_CASE("axis-aligned boxes: depth is the smallest overlap, normal the exact axis") {
        // Support ties on every axis-aligned direction put coplanar faces on the polytope.
        struct Case {
            Vec3 center;  // of B; A is [-1,1] x [-2,2] x [-3,3]
            double depth;
            Vec3 normal;
        } cases[] = {
            {Vec3(1.5, 0.0, 0.0), 0.5, Vec3(1, 0, 0)}, {Vec3(-1.75, 0.5, 0.5), 0.25, Vec3(-1, 0, 0)},
            {Vec3(0.2, 2.9, 0.1), 0.1, Vec3(0, 1, 0)}, {Vec3(0.0, 0.0, -3.5), 0.5, Vec3(0, 0, -1)},
            {Vec3(0.0, 0.0, 0.0), 2.0, Vec3(1, 0, 0)},  // concentric: x and -x tie at depth 2
        };
        for (const Case& c : cases) {
            for (double scale : {1e-3, 1.0, 1e3}) {
                for (double offset : {0.0, 1e6}) {
                    const Vec3 o = Vec3(offset, 2 * offset, -offset);
                    SupportBox a{o, scale * Vec3(1, 2, 3)};
                    SupportBox b{o + scale * c.center, scale * Vec3(1, 1, 1)};
                    const EpaResult r = penetration(a, b);
                    CAPTURE(c.center.transpose());
                    CAPTURE(scale);
                    CAPTURE(offset);
                    checkFinite(r);
                    CHECK(r.status == EpaStatus::Penetrating);
                    const double expected = c.depth * scale;
                    // exact up to the rounding of the box corners at the offset
                    const double slack = 1e-13 * expected + 8 * kMachineEpsilon * offset;
                    CHECK(std::abs(r.depth - expected) <= slack);
                    if (c.center.norm() > 0) CHECK((r.normal - c.normal).norm() <= 1e-12 + slack / scale);
                    // translating B by depth * normal separates to touching
                    const double h = static_cast<double>(supportValueL(a.corners(), b.corners(), r.normal));
                    CHECK(std::abs(h - r.depth) <= slack);
                }
            }
        }
    }

    TEST_CASE("touching boxes and flat contacts: depth 0, valid unit normal, never NaN") {
        SupportBox a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        for (const Vec3& c : {Vec3(2, 0.3, 0.1), Vec3(2, 2, 0), Vec3(2, 2, 2), Vec3(0, -2, 0.5)}) {
            SupportBox b{c, Vec3(1, 1, 1)};
            const EpaResult r = penetration(a, b);
            CAPTURE(c.transpose());
            checkFinite(r);
            CHECK(r.status == EpaStatus::Touching);
            CHECK(r.depth == 0.0);
            // the normal must be a contact normal: h_{A-B}(n) = 0 (A - B lies behind the plane)
            const double h = static_cast<double>(supportValueL(a.corners(), b.corners(), r.normal));
            CHECK(std::abs(h) <= 1e-14);
        }
        // Two coplanar squares overlapping: A - B is flat, the origin is on its boundary.
        SupportPolytope s1{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
        SupportPolytope s2{{Vec3(0.5, 0.5, 0), Vec3(1.5, 0.5, 0), Vec3(1.5, 1.5, 0), Vec3(0.5, 1.5, 0)}};
        EpaResult r = penetration(s1, s2);
        checkFinite(r);
        CHECK(r.status == EpaStatus::Touching);
        CHECK(std::abs(std::abs(r.normal.z()) - 1.0) <= 1e-14);
        // Coincident points, point on a segment, segment crossing a segment (all flat A - B).
        SupportPoint p{Vec3(1, 2, 3)};
        r = penetration(p, p);
        checkFinite(r);
        CHECK(r.status == EpaStatus::Touching);
        SupportSegment seg{Vec3(0, 0, 0), Vec3(2, 0, 0)};
        SupportPoint mid{Vec3(0.5, 0, 0)};
        r = penetration(seg, mid);
        checkFinite(r);
        CHECK(r.status == EpaStatus::Touching);
        SupportSegment cross{Vec3(1, -1, 0), Vec3(1, 1, 0)};
        r = penetration(seg, cross);
        checkFinite(r);
        CHECK(r.status == EpaStatus::Touching);
        CHECK(std::abs(r.normal.z()) == doctest::Approx(1.0));
    }

    TEST_CASE("degenerate start simplices are blown up: point, segment, triangle") {
        SupportBox a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
        SupportPoint inside{Vec3(0.25, 0.5, -0.125)};  // nearest face +y at 0.5
        SupportPolytope pa{a.corners()};
        const std::vector<Vec3> pb{inside.p};
        // Start from a 1-point simplex holding the origin exactly: w = a - b with a = b.
        GjkSimplex start;
        start.count = 1;
        start.vertex[0].a = inside.p;
        start.vertex[0].b = inside.p;
        start.vertex[0].w = Vec3::Zero();
        start.lambda[0] = 1;
        EpaTrace trace;
        EpaResult r = epaPenetration(a, inside, start, {}, &trace);
        checkFinite(r);
        CHECK(trace.start == "point blown up");
        CHECK(r.depth == doctest::Approx(0.5).epsilon(1e-14));
        CHECK((r.normal - Vec3(0, 1, 0)).norm() <= 1e-14);
        // Segment simplex with the origin inside it.
        start.count = 2;
        start.vertex[0] = {Vec3(-0.1, 0, 0), inside.p + Vec3(-0.1, 0, 0), inside.p, Vec3(-1, 0, 0)};
        start.vertex[1] = {Vec3(0.3, 0, 0), inside.p + Vec3(0.3, 0, 0), inside.p, Vec3(1, 0, 0)};
        r = epaPenetration(a, inside, start, {}, &trace);
        checkFinite(r);
        CHECK(r.depth == doctest::Approx(0.5).epsilon(1e-14));
        // Triangle simplex.
        start.count = 3;
        start.vertex[2] = {Vec3(0, 0.2, 0), inside.p + Vec3(0, 0.2, 0), inside.p, Vec3(0, 1, 0)};
        r = epaPenetration(a, inside, start, {}, &trace);
        checkFinite(r);
        CHECK(r.depth == doctest::Approx(0.5).epsilon(1e-14));
        const double h = static_cast<double>(supportValueL(pa.vertices, pb, r.normal));
        CHECK(std::abs(h - r.depth) <= 1e-14);
        // Empty simplex: defined error.
        GjkSimplex empty;
        r = epaPenetration(a, inside, empty);
        CHECK(r.status == EpaStatus::InvalidInput);
        CHECK(r.termination == EpaTermination::InvalidInput);
    }

    TEST_CASE("spheres: analytic depth (EPA on smooth shapes converges slowly)") {
        for (double size : {1e-3, 1.0, 1e3}) {
            SupportSphere a{Vec3(0, 0, 0), size};
            const Vec3 dir = Vec3(0.3, -0.2, 0.9).normalized();
            SupportSphere b{1.5 * size * dir, size};
            const EpaResult r = penetration(a, b);
            checkFinite(r);
            CHECK(r.status == EpaStatus::Penetrating);
            CHECK(r.depth == doctest::Approx(0.5 * size).epsilon(1e-6));
            CHECK((r.normal - dir).norm() <= 1e-3);
            CHECK(r.lowerBound <= 0.5 * size * (1 + 1e-12));
            CHECK(r.upperBound >= 0.5 * size * (1 - 1e-12));
        }
    }

    TEST_CASE("flat, elongated and deeply penetrating boxes") {
        SupportBox plank{Vec3(0, 0, 0), Vec3(1000, 1, 1e-3)};
        SupportBox needle{Vec3(3, 0.2, 0), Vec3(1e-3, 1e-3, 500)};  // pierces the plank along z
        EpaResult r = penetration(plank, needle);
        checkFinite(r);
        // cheapest exit: move the needle along +-y by 1 - 0.2 + 1e-3 or along z by 500 + 1e-3
        CHECK(r.depth == doctest::Approx(0.801).epsilon(1e-13));
        CHECK((r.normal - Vec3(0, 1, 0)).norm() <= 1e-12);
        SupportBox same{Vec3(0, 0, 0), Vec3(1000, 1, 1e-3)};
        r = penetration(plank, same);  // identical: depth = full thickness along z
        checkFinite(r);
        CHECK(r.depth == doctest::Approx(2e-3).epsilon(1e-13));
        CHECK(std::abs(std::abs(r.normal.z()) - 1) <= 1e-12);
    }

    TEST_CASE("random polytope pairs vs long double facet-enumeration oracle") {
        std::mt19937_64 rng(4321);
        std::uniform_int_distribution<int> count(8, 10);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        double maxDepthErr = 0, maxNormalErr = 0, maxWitnessErr = 0;
        int tested = 0, wrong = 0;
        for (int trial = 0; trial < 90; ++trial) {
            const auto [size, offset, o] = sweepTrial(trial, rng);
            const Vec3 sep = size * 1.2 * unit(rng) * randomUnit(rng);  // mostly overlapping
            SupportPolytope a{randomPolytope(rng, count(rng), size, o)};
            SupportPolytope b{randomPolytope(rng, count(rng), size, o + sep)};
            const HullOracle oracle = hullOracle(a.vertices, b.vertices);
            EpaTrace trace;
            GjkResult g;
            const EpaResult r = penetration(a, b, {}, &trace, &g);
            checkFinite(r);
            if (!oracle.inside || oracle.depth < 1e-9 * size) continue;
            ++tested;
            if (r.status != EpaStatus::Penetrating) {
                ++wrong;
                continue;
            }
            const double d = static_cast<double>(oracle.depth);
            maxDepthErr = std::max(maxDepthErr, std::abs(r.depth - d) / d);
            const double h = static_cast<double>(supportValueL(a.vertices, b.vertices, r.normal));
            maxNormalErr = std::max(maxNormalErr, std::abs(h - r.depth) / r.depth);
            const Vec3 diff = r.pointA - r.pointB - r.depth * r.normal;
            maxWitnessErr = std::max(maxWitnessErr, diff.norm() / (1e-12 * d + 16 * kMachineEpsilon * (offset + size)));
        }
        std::ostringstream msg;
        msg << "EPA: " << tested << " penetrating pairs, max rel depth error " << maxDepthErr
            << ", max |h(n) - depth| / depth " << maxNormalErr;
        MESSAGE(msg.str());
        CHECK(tested > 40);
        CHECK(wrong == 0);
        CHECK(maxDepthErr <= 1e-12);
        CHECK(maxNormalErr <= 1e-12);
        CHECK(maxWitnessErr <= 1.0);
    }

    // Sliver faces of A − B (tests/core/gjk_epa/gjk_epa_test_support.h) with the origin inside:
    // EPA's face planes from rounded cross products were off by ~u |w| / sine (depths up to 12%
    // wrong: 10 of 709 beyond 1e-10 of the size, the worst 7e-8), and a flat start's fallback
    // normal too (a touching origin given depth 4e-9 of the size). Now to a few u of the size.
    TEST_CASE("sliver faces: the depth is the nearest facet's, against an exact facet enumeration") {
        SliverConfigurations slivers(4417);
        const SupportPolytope origin{std::vector<Vec3>{Vec3::Zero()}};
        int inside = 0;
        double worst = 0.0;  // |depth - exact| / scale
        for (int trial = 0; trial < 1500; ++trial) {
            const std::vector<Vec3> P = slivers.next(trial);
            if (exactOriginSide(P) != 1) continue;
            ++inside;
            const SupportPolytope a{P};
            const EpaResult e = penetration(a, origin);
            const double depth = e.status == EpaStatus::Separated ? 0.0 : e.depth;
            worst = std::max(worst, std::abs(depth - exactFacetDepth(P)) / slivers.scale());
        }
        CHECK(inside > 600);
        CHECK(worst < 1e-12);  // measured 4.5e-14
    }

    TEST_CASE("trace: polytope stays a closed convex surface, horizon is one loop") {
        const auto [a, b] = randomPolytopePair(99, 24, Vec3(0.4, 0.1, 0.0));
        EpaTrace trace;
        const EpaResult r = penetration(a, b, {}, &trace);
        checkTraceEndsLikeResult(trace, r);
        for (const EpaTraceStep& s : trace.steps) {
            // Euler: a closed triangulated sphere has F = 2V' - 4 (V' = vertices in use)
            std::vector<int> used(s.vertices.size(), 0);
            for (const auto& f : s.faces)
                for (int v : f) used[v] = 1;
            int v = 0;
            for (int u : used) v += u;
            CHECK(static_cast<int>(s.faces.size()) == 2 * v - 4);
            // every face is a supporting plane of the polytope (convexity, up to rounding)
            for (const auto& f : s.faces) {
                const Vec3 n =
                    (s.vertices[f[1]] - s.vertices[f[0]]).cross(s.vertices[f[2]] - s.vertices[f[0]]).normalized();
                for (int k = 0; k < static_cast<int>(s.vertices.size()); ++k)
                    if (used[k]) CHECK(n.dot(s.vertices[k] - s.vertices[f[0]]) <= 1e-12);
            }
            CHECK(s.lowerBound <= r.depth * (1 + 1e-13));
            CHECK(s.upperBound >= r.depth * (1 - 1e-13));
            if (s.terminated) continue;
            REQUIRE(s.horizon.size() >= 3);
            CHECK(!s.removedFaces.empty());
            for (size_t k = 0; k < s.horizon.size(); ++k)  // consecutive edges share a vertex
                CHECK(s.horizon[k][1] == s.horizon[(k + 1) % s.horizon.size()][0]);
        }
    }
}

TEST_CASE("the EPA face graph stays consistent through expansion, and the check catches a broken link") {
    // The invariant the sanitizer build asserts after every expansion: build a tetrahedron around
    // the origin, expand it by points outside each face in turn, check after each step.
    detail::EpaPolytope poly;
    const Vec3 corners[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (const Vec3& c : corners) poly.addVertex({c, c, Vec3::Zero()});
    REQUIRE(poly.buildTetrahedron());
    CHECK(poly.adjacencyConsistent());
    for (int step = 0; step < 6; ++step) {
        const int f = poly.closestFace();
        REQUIRE(f >= 0);
        const Vec3 w = 3.0 * poly.face[f].normal + 0.1 * Vec3(step, -step, 0.5 * step);
        const int vi = poly.addVertex({w, w, Vec3::Zero()});
        REQUIRE(vi >= 0);
        REQUIRE(poly.expand(f, vi, 1e-14, nullptr) == detail::EpaExpand::Ok);
        CHECK(poly.adjacencyConsistent());
    }
    // A neighbour that does not name the face back is caught.
    const int f = poly.closestFace();
    poly.face[f].adjEdge[0] = (poly.face[f].adjEdge[0] + 1) % 3;
    CHECK_FALSE(poly.adjacencyConsistent());
}

TEST_CASE("EPA: a degenerate start gives a unit normal and a depth that separates, never touching for overlap") {
    // Two boxes overlapping by 0.25 along x, started from a segment through the origin 2e-150 .. 2e-161
    // long: the blow-up direction perpendicular to it is computed from squared norms near underflow
    // (|n|² − 1 up to 2.4e-4 at 1e-161) and the start polytope has no volume. It came back as
    // "touching" with depth 0 and that non-unit normal.
    const SupportBox a{Vec3(0, 0, 0), Vec3(1, 1, 1)}, b{Vec3(1.75, 0.5, 0), Vec3(1, 1, 1)};
    for (double e : {1e-150, 1e-155, 1e-158, 1e-160, 1e-161}) {
        CAPTURE(e);
        GjkSimplex start;
        start.count = 2;
        const Vec3 p = a.support(Vec3(1, 1, 1));  // the origin lies inside the segment w0 w1
        start.vertex[0] = {Vec3(-e, 0, 0), p, p + Vec3(e, 0, 0), Vec3::UnitX()};
        start.vertex[1] = {Vec3(e, 0, 0), p, p - Vec3(e, 0, 0), Vec3::UnitX()};
        const EpaResult r = epaPenetration(a, b, start);
        REQUIRE(r.status != EpaStatus::InvalidInput);
        CHECK(r.normal.squaredNorm() == doctest::Approx(1.0).epsilon(1e-15));
        // The answer separates: translating b by depth * normal leaves the supports touching.
        const double gap = r.normal.dot(b.support(Vec3(-r.normal))) + r.depth - r.normal.dot(a.support(r.normal));
        CHECK(std::abs(gap) < 1e-12);
        CHECK(r.depth == doctest::Approx(0.25));  // x is the direction of least overlap
        CHECK(r.status == EpaStatus::Penetrating);
        CHECK((r.pointA - r.pointB - r.depth * r.normal).norm() < 1e-12);
    }
}
