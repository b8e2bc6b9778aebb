// Swept-sphere fits and volumes (core/bounding/swept_sphere.h). Oracles, sharing no code with core/:
// distances from the points to the stored core in long double (containment); shapes sampled
// from a known capsule / RSS, whose volume the fit must come close to; Monte Carlo volumes with
// long double membership.
#include <doctest/doctest.h>

#include <limits>
#include <numbers>

#include "core/base/tolerances.h"
#include "core/bounding/bounding_sphere.h"
#include "core/bounding/swept_sphere.h"
#include "verification/bounding_volume_oracle.h"

using namespace cdlab;
using bvoracle::LD;
using bvoracle::V;

namespace {

constexpr double kPi = std::numbers::pi;

// Distance from p to the RSS's rectangle in long double: coordinates along the stored axes.
LD rectDistance(const Rss& r, const Vec3& p) {
    const V d = V(p) - V(r.center);
    const LD x = bvoracle::dot(V(Vec3(r.axes.col(0))), d), y = bvoracle::dot(V(Vec3(r.axes.col(1))), d),
             z = bvoracle::dot(V(Vec3(r.axes.col(2))), d);
    const LD dx = std::max<LD>(std::abs(x) - r.halfLengths.x(), 0),
             dy = std::max<LD>(std::abs(y) - r.halfLengths.y(), 0);
    return std::sqrt(dx * dx + dy * dy + z * z);
}

LD capsuleDistance(const Capsule& c, const Vec3& p) { return bvoracle::distPointSegment(V(p), V(c.a), V(c.b)); }

// Containment tolerance: the fits pad the radius by 8 eps * (radius + magnitude) for the double
// evaluation; the long double evaluation differs from double by less than that, and the stored
// axes are orthonormal to ~1e-15 (an extra eps-level relative error on |p - center|).
// 4 eps * magnitude on top is a margin, still 1e-15 relative.
LD tol(const std::vector<Vec3>& pts) { return 4 * kMachineEpsilon * bvoracle::magnitude(pts); }

// Points on the surface of a capsule along x (half length h, radius r), rotated and offset:
// rings of 12 evenly spaced points across the axis (on the cylinder and on the caps) and the two
// tips. The symmetric rings make the covariance's major axis exactly the capsule's axis (up to
// rounding), so the fit must recover the capsule itself.
std::vector<Vec3> capsuleSurface(double h, double r, const Eigen::Quaterniond& q, const Vec3& offset) {
    std::vector<Vec3> pts;
    auto ring = [&](double x, double rho) {
        for (int k = 0; k < 12; ++k) {
            const double phi = k * kPi / 6.0;
            pts.push_back(offset + q * Vec3(x, rho * std::cos(phi), rho * std::sin(phi)));
        }
    };
    for (int i = 0; i <= 8; ++i) ring(-h + 2.0 * h * i / 8.0, r);
    for (int i = 1; i < 6; ++i) {
        const double a = i * kPi / 12.0;  // latitude on the caps
        ring(h + r * std::sin(a), r * std::cos(a));
        ring(-h - r * std::sin(a), r * std::cos(a));
    }
    pts.push_back(offset + q * Vec3(h + r, 0, 0));
    pts.push_back(offset + q * Vec3(-h - r, 0, 0));
    return pts;
}

}  // namespace

TEST_SUITE("swept_sphere") {
    TEST_CASE("LSS and RSS contain every point (long double), at scales and offsets") {
        std::mt19937 rng(50);
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                for (const Vec3& stretch : {Vec3(4, 1, 0.3), Vec3(1, 1, 1), Vec3(3, 2, 0)}) {
                    const auto pts = bvoracle::randomCloud(rng, 60, stretch, scale, Vec3(offset, 2 * offset, -offset));
                    const Capsule c = fitLss(pts);
                    const Rss r = fitRss(pts);
                    for (const Vec3& p : pts) {
                        CHECK(capsuleDistance(c, p) <= LD(c.radius) + tol(pts));
                        CHECK(rectDistance(r, p) <= LD(r.radius) + tol(pts));
                        CHECK(coreDistance(c, p) <= c.radius);
                        CHECK(coreDistance(r, p) <= r.radius);
                    }
                    // The RSS's axes are a rotation.
                    CHECK((r.axes.transpose() * r.axes - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-14);
                    CHECK(r.axes.determinant() == doctest::Approx(1.0).epsilon(1e-14));
                }
            }
        }
    }

    TEST_CASE("LSS recovers a sampled capsule, RSS recovers a sampled plate") {
        std::mt19937 rng(51);
        for (double offset : {0.0, 1e5}) {
            const auto q = bvoracle::randomRotation(rng);
            const auto pts = capsuleSurface(3.0, 0.5, q, Vec3::Constant(offset));
            const Capsule c = fitLss(pts);
            const double truth = kPi * 0.25 * 6.0 + 4.0 / 3.0 * kPi * 0.125;
            // Exact up to rounding of the rotated points (1e-16 relative, 1e-11 at offset 1e5 on
            // the unit-sized capsule) and the radius pad.
            CHECK(volume(c) / truth == doctest::Approx(1.0).epsilon(1e-9));
            CHECK(std::abs((c.b - c.a).normalized().dot(q * Vec3::UnitX())) == doctest::Approx(1.0).epsilon(1e-12));
            // The capsule is much tighter than the minimum sphere on this shape.
            CHECK(volume(c) < volume(fitSphereWelzl(pts)) * 0.3);
        }
        // A plate 4 x 2 x 0.2 sampled on a symmetric grid (both faces): RSS of radius 0.1 over the
        // 4 x 2 rectangle (the points at the rim lie on the rectangle's edges, slack 0 there).
        const auto q = bvoracle::randomRotation(rng);
        std::vector<Vec3> plate;
        for (int i = -10; i <= 10; ++i)
            for (int j = -5; j <= 5; ++j)
                for (double z : {-0.1, 0.1}) plate.push_back(Vec3(1, 2, 3) + q * Vec3(0.2 * i, 0.2 * j, z));
        SweptSphereFitTrace trace;
        const Rss r = fitRss(plate, &trace);
        CHECK(r.radius == doctest::Approx(0.1).epsilon(1e-9));
        CHECK(r.halfLengths.x() == doctest::Approx(2.0).epsilon(1e-9));
        CHECK(r.halfLengths.y() == doctest::Approx(1.0).epsilon(1e-9));
        CHECK(std::abs(r.axes.col(2).dot(q * Vec3::UnitZ())) == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(trace.coreRadius == doctest::Approx(0.1).epsilon(1e-9));
    }

    TEST_CASE("RSS corner fix: a point beyond a corner stays inside") {
        // Flat square cloud plus one point beyond the (+,+) corner at mid thickness: the side
        // pull-in alone would leave it outside; the corner pass must push an end out.
        std::vector<Vec3> pts;
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 5; ++j)
                for (double z : {-0.5, 0.5}) pts.push_back(Vec3(i * 0.8, j * 0.4, z));
        pts.push_back(Vec3(8.0 + 0.4, 2.0 + 0.4, 0.0));
        SweptSphereFitTrace trace;
        const Rss r = fitRss(pts, &trace);
        for (const Vec3& p : pts) CHECK(rectDistance(r, p) <= LD(r.radius) + tol(pts));
        CHECK(r.radius == doctest::Approx(0.5).epsilon(1e-9));  // the fix keeps the radius
        CHECK(trace.cornerFixes >= 1);
    }

    TEST_CASE("volume formulas agree with Monte Carlo (long double membership)") {
        std::mt19937 rng(52);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const Capsule c{Vec3(1, 2, 3), Vec3(3, 1, 4), 0.7};
        Rss r;
        r.center = Vec3(-1, 0, 2);
        r.axes = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
        r.halfLengths = Vec2(1.5, 0.6);
        r.radius = 0.4;
        const int n = 400000;
        auto mc = [&](auto inside, const Vec3& lo, const Vec3& hi) {
            int in = 0;
            for (int i = 0; i < n; ++i) in += inside(lo + (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
            return (hi - lo).prod() * in / n;
        };
        const Vec3 clo = c.a.cwiseMin(c.b).array() - c.radius, chi = c.a.cwiseMax(c.b).array() + c.radius;
        // Relative standard error ~ sqrt((1 - f) / (f n)) < 0.3 % here; 1.5 % is > 5 sigma.
        CHECK(mc([&](const Vec3& p) { return capsuleDistance(c, p) <= c.radius; }, clo, chi) ==
              doctest::Approx(volume(c)).epsilon(0.015));
        const double ext = r.halfLengths.x() + r.halfLengths.y() + r.radius;
        CHECK(mc([&](const Vec3& p) { return rectDistance(r, p) <= r.radius; }, r.center.array() - ext,
                 r.center.array() + ext) == doctest::Approx(volume(r)).epsilon(0.015));
        CHECK(volume(Capsule{Vec3::Zero(), Vec3::Zero(), 1.0}) == doctest::Approx(4.0 / 3.0 * kPi));
        CHECK(volume(Capsule{Vec3::Zero(), Vec3::Zero(), -1.0}) == 0.0);
    }

    TEST_CASE("degenerate: single point, collinear, coplanar, NaN, empty") {
        const std::vector<Vec3> one{Vec3(1e6, 3, 4)};
        Capsule c = fitLss(one);
        CHECK((c.a == one[0]));
        CHECK((c.b == one[0]));
        CHECK(c.radius < 1e-8);  // pad only: 8 eps * 1e6
        Rss r = fitRss(one);
        CHECK(r.halfLengths.maxCoeff() == 0.0);
        CHECK(rectDistance(r, one[0]) <= LD(r.radius));
        // Collinear: the capsule is the segment (radius ~0), the RSS a zero-width rectangle.
        std::vector<Vec3> line;
        for (int i = 0; i <= 10; ++i) line.push_back(Vec3(1, 2, 3) + i * Vec3(0.3, -0.2, 0.1));
        c = fitLss(line);
        CHECK(c.radius < 1e-12);
        CHECK((c.b - c.a).norm() == doctest::Approx(10 * Vec3(0.3, -0.2, 0.1).norm()).epsilon(1e-12));
        r = fitRss(line);
        for (const Vec3& p : line) CHECK(rectDistance(r, p) <= LD(r.radius) + tol(line));
        CHECK(volume(r) < 1e-10);
        // Coplanar: RSS radius ~0.
        std::mt19937 rng(53);
        const auto flat = bvoracle::randomCloud(rng, 50, Vec3(2, 1, 0), 1.0, Vec3(0, 0, 5));
        r = fitRss(flat);
        CHECK(r.radius < 1e-12);
        for (const Vec3& p : flat) CHECK(rectDistance(r, p) <= LD(r.radius) + tol(flat));
        // Duplicates.
        const std::vector<Vec3> dup(7, Vec3(0.25, 0.5, 0.75));
        CHECK(fitLss(dup).radius < 1e-14);  // the pad only
        CHECK(fitRss(dup).radius < 1e-14);
        // NaN skipped; empty: radius -1, NaN core.
        const std::vector<Vec3> nan{Vec3(0, 0, 0), Vec3(kNaN, 1, 1), Vec3(2, 0, 0)};
        c = fitLss(nan);
        CHECK(c.radius < 1e-12);
        CHECK((c.b - c.a).norm() == doctest::Approx(2.0));
        CHECK(fitRss(nan).center.allFinite());
        c = fitLss(std::span<const Vec3>{});
        CHECK(c.radius < 0);
        CHECK_FALSE(c.a.allFinite());
        r = fitRss(std::span<const Vec3>{});
        CHECK(r.radius < 0);
        CHECK(volume(r) == 0.0);
        CHECK(fitPss(std::span<const Vec3>{}).radius < 0);
    }

}  // TEST_SUITE
