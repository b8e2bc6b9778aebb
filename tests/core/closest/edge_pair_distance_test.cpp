// Accurate edge-pair distance (core/closest/edge_pair_distance.h) and GJK's use of it on nearly
// parallel edges. Oracles: distances known by construction (two edges perpendicular to n whose
// projections along n cross: their distance is the gap along n; rounding the constructed end
// points moves it by at most their rounding, 1-Lipschitz), and a long double segment-segment
// minimisation over the boundary cases for well-conditioned random pairs.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/tolerances.h"
#include "core/closest/edge_pair_distance.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "verification/closest_oracle.h"
#include "verification/minkowski_facet_oracle.h"

using namespace cdlab;

namespace {

double logUniform(std::mt19937_64& rng, double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

Vec3 perpendicularUnit(const Vec3& e) {
    const Vec3 t = std::abs(e.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    return e.cross(t).normalized();
}

/// Two ridges of length 2 crossing at `angle`, |gap| apart along n, centred at `at`.
struct CrossedEdges {
    Vec3 a0, a1, b0, b1, n, e, m;
    double gap;
};

CrossedEdges crossedEdges(std::mt19937_64& rng, double angle, double gap, const Vec3& at) {
    CrossedEdges c;
    c.e = test::randomUnit(rng);
    c.n = perpendicularUnit(c.e);
    c.m = c.e.cross(c.n);
    const Vec3 e2 = Eigen::AngleAxisd(angle, c.n) * c.e;
    const double shift = std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
    c.a0 = at - c.e;
    c.a1 = at + c.e;
    c.b0 = at + shift * c.e - e2 + gap * c.n;
    c.b1 = at + shift * c.e + e2 + gap * c.n;
    c.gap = gap;
    return c;
}

// Long double segment-segment distance by the boundary cases plus the interior critical point
// found by exact-in-long-double 2x2 solve; only used on well-conditioned (angle > 0.1) pairs.
long double pointSegmentLd(const Vec3& x, const Vec3& p, const Vec3& q) {
    long double d[3], w[3], dd = 0, wd = 0;
    for (int i = 0; i < 3; ++i) {
        d[i] = static_cast<long double>(q[i]) - p[i];
        w[i] = static_cast<long double>(x[i]) - p[i];
        dd += d[i] * d[i];
        wd += w[i] * d[i];
    }
    long double t = dd > 0 ? wd / dd : 0;
    t = std::clamp<long double>(t, 0, 1);
    long double s = 0;
    for (int i = 0; i < 3; ++i) s += (w[i] - t * d[i]) * (w[i] - t * d[i]);
    return std::sqrt(s);
}

long double segmentSegmentLd(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
    long double best = std::min({pointSegmentLd(a0, b0, b1), pointSegmentLd(a1, b0, b1), pointSegmentLd(b0, a0, a1),
                                 pointSegmentLd(b1, a0, a1)});
    long double d1[3], d2[3], r[3];
    for (int i = 0; i < 3; ++i) {
        d1[i] = static_cast<long double>(a1[i]) - a0[i];
        d2[i] = static_cast<long double>(b1[i]) - b0[i];
        r[i] = static_cast<long double>(a0[i]) - b0[i];
    }
    long double a = 0, b = 0, c = 0, d = 0, e = 0;
    for (int i = 0; i < 3; ++i) {
        a += d1[i] * d1[i];
        b += d1[i] * d2[i];
        c += d1[i] * r[i];
        e += d2[i] * d2[i];
        d += d2[i] * r[i];
    }
    const long double den = a * e - b * b;
    if (den > 0) {
        const long double s = (b * d - c * e) / den, t = (a * d - b * c) / den;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            long double q = 0;
            for (int i = 0; i < 3; ++i) {
                const long double x = r[i] + s * d1[i] - t * d2[i];
                q += x * x;
            }
            best = std::min(best, std::sqrt(q));
        }
    }
    return best;
}

/// Rounding of the constructed points moves the distance by at most their displacement: b0 and
/// b1 take four rounded operations per coordinate (at + shift e - e2 + gap n), a0 and a1 one;
/// 8 u of the largest coordinate per point covers both (sqrt 3 for the three coordinates).
double constructionSlack(const CrossedEdges& c) {
    double m = 0;
    for (const Vec3* p : {&c.a0, &c.a1, &c.b0, &c.b1}) m = std::max(m, p->cwiseAbs().maxCoeff());
    return 8 * kMachineEpsilon * m * std::sqrt(3.0) * 2;  // two points per edge may move apart
}

}  // namespace

TEST_SUITE("edge pair distance") {
    TEST_CASE("crossed edges: the gap along n at every angle, offset and scale") {
        std::mt19937_64 rng(7);
        for (int i = 0; i < 2000; ++i) {
            const double angle = logUniform(rng, 1e-12, 1.5);
            const double scale = logUniform(rng, 1e-3, 1e3);
            const double offset = i % 3 == 0 ? 0.0 : logUniform(rng, 1.0, 1e6);
            const double gap = logUniform(rng, 1e-12, 1e-1) * (i % 2 ? 1 : -1);
            const CrossedEdges c = crossedEdges(rng, angle, gap, offset * test::randomUnit(rng));
            const double k = scale;
            const EdgePairDistance r = edgePairDistance(k * c.a0, k * c.a1, k * c.b0, k * c.b1);
            CAPTURE(angle);
            CAPTURE(gap);
            CAPTURE(offset);
            REQUIRE(r.ok);
            const double slack = k * constructionSlack(c) + 4 * kMachineEpsilon * k * std::abs(gap);
            CHECK(std::abs(r.distance - k * std::abs(gap)) <= slack);
            // Witnesses: on their segments and distance apart.
            CHECK(std::abs((r.pointB - r.pointA).norm() - r.distance) <= slack + 8 * kMachineEpsilon * k * (offset + 2));
            // The axis of the ROUNDED edges differs from n by ~ulp(coordinates) / angle.
            const double axisSlack = 1e-12 + 16 * kMachineEpsilon * (offset + 2) / angle;
            if (r.distance > 1e3 * slack) CHECK(std::abs(r.axis.dot(c.n) * (gap > 0 ? 1 : -1) - 1) <= axisSlack);
        }
    }

    TEST_CASE("well-conditioned random pairs and end point cases: long double oracle") {
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> u(-1, 1);
        for (int i = 0; i < 5000; ++i) {
            const Vec3 a0(u(rng), u(rng), u(rng)), a1(u(rng), u(rng), u(rng));
            Vec3 b0(u(rng), u(rng), u(rng)), b1(u(rng), u(rng), u(rng));
            if (i % 10 == 0) b1 = b0;                    // a point
            if (i % 10 == 1) b0 = a1;                    // shared end point
            if (i % 10 == 2) b1 = a0 + 0.5 * (a1 - a0);  // touching at an interior point
            const EdgePairDistance r = edgePairDistance(a0, a1, b0, b1);
            REQUIRE(r.ok);
            const double expected = static_cast<double>(segmentSegmentLd(a0, a1, b0, b1));
            CAPTURE(i);
            CHECK(std::abs(r.distance - expected) <= 1e-14);
        }
    }

    TEST_CASE("degenerate input: NaN refused, coincident points give zero") {
        const Vec3 z = Vec3::Zero(), x = Vec3::UnitX();
        CHECK_FALSE(edgePairDistance(Vec3(NAN, 0, 0), x, z, x).ok);
        CHECK_FALSE(edgePairDistance(z, x, Vec3(INFINITY, 0, 0), x).ok);
        const EdgePairDistance same = edgePairDistance(z, z, z, z);
        REQUIRE(same.ok);
        CHECK(same.distance == 0.0);
        const EdgePairDistance parallel = edgePairDistance(z, x, Vec3(0.5, 1, 0), Vec3(3, 1, 0));
        REQUIRE(parallel.ok);
        CHECK(parallel.distance == doctest::Approx(1.0).epsilon(1e-15));
        CHECK_FALSE(linePairSeparation(z, x, Vec3(0.5, 1, 0), Vec3(3, 1, 0)).ok);  // parallel lines
        const EdgePairDistance tiny =
            edgePairDistance(1e-300 * x, 2e-300 * x, Vec3(0, 1e-300, 0), Vec3(0, 1e-300, 1e-300));
        REQUIRE(tiny.ok);
        CHECK(tiny.distance == doctest::Approx(std::sqrt(2.0) * 1e-300).epsilon(1e-14));
    }

    TEST_CASE("point vs triangle: long double oracle, and slivers with the height known by construction") {
        std::mt19937_64 rng(13);
        std::uniform_real_distribution<double> u(-1, 1);
        for (int i = 0; i < 5000; ++i) {
            const Vec3 p(u(rng), u(rng), u(rng)), t0(u(rng), u(rng), u(rng)), t1(u(rng), u(rng), u(rng)),
                t2(u(rng), u(rng), u(rng));
            const EdgePairDistance r = pointTriangleDistance(p, t0, t1, t2);
            REQUIRE(r.ok);
            const double expected = static_cast<double>(std::sqrt(oracle::triangleDistance2(p, t0, t1, t2)));
            CAPTURE(i);
            CHECK(std::abs(r.distance - expected) <= 1e-14);
            CHECK(std::abs((r.pointB - r.pointA).norm() - r.distance) <= 1e-14);
        }
        // A needle triangle (width 1e-3..1e-12 of its length) in the plane through `at` spanned by
        // e and m, and a point h above its interior along n = e x m: the distance is h.
        for (int i = 0; i < 2000; ++i) {
            const double width = logUniform(rng, 1e-12, 1e-3), h = logUniform(rng, 1e-9, 1.0);
            const Vec3 e = test::randomUnit(rng), n = perpendicularUnit(e), m = n.cross(e);
            const Vec3 at = i % 2 ? Vec3::Zero() : Vec3(3e3, 1e3, -2e3);
            const Vec3 t0 = at - e, t1 = at + e + width * m, t2 = at + e - width * m;
            const Vec3 p = at + 0.5 * e + h * n;
            const EdgePairDistance r = pointTriangleDistance(p, t0, t1, t2);
            REQUIRE(r.ok);
            double c = 0;
            for (const Vec3* x : {&p, &t0, &t1, &t2}) c = std::max(c, x->cwiseAbs().maxCoeff());
            // Rounding of the constructed points (<= 4 operations each) moves the distance by at
            // most their displacement.
            CAPTURE(width);
            CAPTURE(h);
            CHECK(std::abs(r.distance - h) <= 32 * kMachineEpsilon * c + 4 * kMachineEpsilon * h);
        }
    }

    TEST_CASE("GJK on wedges with nearly parallel ridges: distance = gap to rounding") {
        // The stress family "nearly parallel edges": two thin wedges whose ridges cross at
        // 1e-10..1e-1 rad, `gap` apart along n. With edge-pair refinement the distance is the gap to
        // rounding of the input (GJK's own answer is up to ~5e-9 off here).
        std::mt19937_64 rng(3);
        int refined = 0;
        for (int i = 0; i < 2000; ++i) {
            const double angle = logUniform(rng, 1e-10, 1e-1);
            const double gap = logUniform(rng, 1e-9, 1e-2);
            const Vec3 at = i % 2 ? Vec3::Zero() : Vec3(1e4, -3e3, 2e3);
            const CrossedEdges c = crossedEdges(rng, angle, gap, at);
            const Vec3 m2 = (Eigen::AngleAxisd(angle, c.n) * c.e).cross(c.n);
            const Vec3 mid = 0.5 * (c.b0 + c.b1);
            const PolytopeShape a(std::vector<Vec3>{c.a0, c.a1, at + 0.2 * (-c.n + c.m), at + 0.2 * (-c.n - c.m)});
            const PolytopeShape b(std::vector<Vec3>{c.b0, c.b1, mid + 0.2 * (c.n + m2), mid + 0.2 * (c.n - m2)});
            // Signed volumes only: Johnson's sub-determinants misjudge these slivers' sides (it
            // may even report an intersection; `cdlab stress` keeps it as information only).
            const GjkResult r = gjkDistance(a, b);
            CAPTURE(angle);
            CAPTURE(gap);
            CAPTURE(i);
            REQUIRE(r.status == GjkStatus::Separated);
            CHECK(std::abs(r.distance - gap) <= 2 * constructionSlack(c) + 1e-13 * gap);  // slack per shape
            refined += r.edgePairRefined;
        }
        CHECK(refined > 1000);  // the edge-edge case is the common final simplex here
    }
}
