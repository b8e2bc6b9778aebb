// AABB and covariance-OBB fits (core/bounding/bounding_volume_fit.h). Oracles, sharing no code with the
// fits: containment recomputed in long double from the stored box; min / max of coordinates by
// a plain loop; boxes of known pose (a rotated box mesh) whose volume the fit must recover.
#include <doctest/doctest.h>

#include <limits>

#include "core/base/tolerances.h"
#include "core/bounding/bounding_volume_fit.h"
#include "core/overlap/sat_tests.h"
#include "verification/bounding_volume_oracle.h"

using namespace cdlab;
using bvoracle::LD;
using bvoracle::V;

namespace {

// Max over points of how far (in long double) a point lies outside the box, measured along the
// stored axes: max_i (|a_i . (p - c)| - h_i), <= 0 when inside.
LD maxOutside(const Obb& box, const std::vector<Vec3>& pts) {
    LD worst = -1e30L;
    const V c(box.center);
    for (const Vec3& p : pts) {
        const V d = V(p) - c;
        for (int i = 0; i < 3; ++i) {
            const LD u = std::abs(bvoracle::dot(V(Vec3(box.axes.col(i))), d)) - LD(box.halfExtents[i]);
            worst = std::max(worst, u);
        }
    }
    return worst;
}

// |A^T A - I| (max entry) and det A, in long double.
LD orthoError(const Mat3& a) {
    LD worst = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            LD s = 0;
            for (int k = 0; k < 3; ++k) s += LD(a(k, i)) * LD(a(k, j));
            worst = std::max(worst, std::abs(s - (i == j ? 1.0L : 0.0L)));
        }
    return worst;
}
LD det(const Mat3& a) {
    return bvoracle::dot(V(Vec3(a.col(0))), bvoracle::cross(V(Vec3(a.col(1))), V(Vec3(a.col(2)))));
}

// Tolerance of the containment check: the fit pads its extents by 16 eps * magnitude, and the
// axes are orthonormal to ~1e-15 (checked separately), so a point may sit outside the LONG
// DOUBLE box by at most a few eps * magnitude. 64 eps * magnitude is a margin over that and
// still ~1e-13 relative: a real containment bug (a wrong extent, a missed point) is far larger.
double containTol(const std::vector<Vec3>& pts) {
    return 64.0 * kMachineEpsilon * bvoracle::magnitude(pts);
}

void checkAxes(const Obb& box) {
    CHECK(orthoError(box.axes) < 1e-14L);
    CHECK(std::abs(det(box.axes) - 1.0L) < 1e-14L);  // right-handed rotation
}

}  // namespace

TEST_SUITE("bounding_volume_fit") {
    TEST_CASE("fitAabb is the coordinate min / max of the finite points") {
        std::mt19937 rng(1);
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                const auto pts = bvoracle::randomCloud(rng, 50, Vec3(1, 2, 3), scale, Vec3::Constant(offset));
                const Aabb box = fitAabb(pts);
                for (int i = 0; i < 3; ++i) {
                    double lo = pts[0][i], hi = pts[0][i];
                    for (const Vec3& p : pts) {
                        lo = p[i] < lo ? p[i] : lo;
                        hi = p[i] > hi ? p[i] : hi;
                    }
                    CHECK(box.min[i] == lo);
                    CHECK(box.max[i] == hi);
                }
                // Triangles version: same box over the same vertices.
                std::vector<Triangle> tris;
                for (size_t i = 0; i + 2 < pts.size(); i += 3) tris.push_back({pts[i], pts[i + 1], pts[i + 2]});
                const Aabb tb = fitAabb(tris);
                CHECK((tb.min == fitAabb(bvoracle::vertices(tris)).min));
                CHECK((tb.max == fitAabb(bvoracle::vertices(tris)).max));
            }
        }
    }

    TEST_CASE("fitAabb: empty input is the empty box (no hit), NaN points are skipped") {
        const Aabb empty = fitAabb(std::span<const Vec3>{});
        CHECK(empty.min.x() > empty.max.x());
        CHECK_FALSE(testAabbAabb(empty, Aabb{Vec3::Constant(-1e300), Vec3::Constant(1e300)}).hit);
        CHECK(volume(empty) == 0.0);
        const std::vector<Vec3> pts{Vec3(1, 2, 3), Vec3(kNaN, 0, 0), Vec3(-1, 0, 5)};
        const Aabb box = fitAabb(pts);
        CHECK((box.min == Vec3(-1, 0, 3)));
        CHECK((box.max == Vec3(1, 2, 5)));
        const std::vector<Triangle> tris{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, kNaN, 0)}};
        CHECK(fitAabb(tris).min.x() > fitAabb(tris).max.x());
    }

    TEST_CASE("covariance OBB: orthonormal right-handed axes, contains every point") {
        std::mt19937 rng(2);
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                for (const Vec3& stretch : {Vec3(1, 1, 1), Vec3(5, 1, 0.2), Vec3(1, 1, 0)}) {
                    const auto pts =
                        bvoracle::randomCloud(rng, 40, stretch, scale, Vec3(offset, -offset, 0.5 * offset));
                    ObbFitTrace trace;
                    const Obb box = fitObbCovariance(pts, &trace);
                    CHECK((trace.method == ObbFitMethod::PointCovariance));
                    CHECK(trace.eigenvalues[0] >= trace.eigenvalues[1]);
                    CHECK(trace.eigenvalues[1] >= trace.eigenvalues[2]);
                    checkAxes(box);
                    CHECK(maxOutside(box, pts) <= containTol(pts));
                    // double contains() agrees with no slack (the fit pads for the double test).
                    for (const Vec3& p : pts) CHECK(contains(box, p));
                }
            }
        }
    }

    TEST_CASE("triangle-covariance OBB recovers a rotated box mesh (volume ratio 1)") {
        std::mt19937 rng(3);
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                const Vec3 h = scale * Vec3(3.0, 1.0, 0.4);
                const auto q = bvoracle::randomRotation(rng);
                const Vec3 off = Vec3(offset, 0.3 * offset, -offset);
                // k = 6: the +x face is split into 72 triangles. Area weighting makes the fit
                // independent of that; a vertex covariance would tilt toward the dense face.
                for (int k : {1, 6}) {
                    const auto tris = bvoracle::boxMesh(h, q, off, k);
                    ObbFitTrace trace;
                    const Obb box = fitObbTriangles(tris, &trace);
                    CHECK((trace.method == ObbFitMethod::TriangleCovariance));
                    checkAxes(box);
                    const auto pts = bvoracle::vertices(tris);
                    CHECK(maxOutside(box, pts) <= containTol(pts));
                    const double truth = 8.0 * h.x() * h.y() * h.z();
                    // The fit pads each half extent by 16 eps * magnitude (for containment in
                    // double); at offset 1e6 and scale 1e-3 that is 3.6e-9 on a 4e-4 half extent,
                    // a relative 1e-5. Allow twice the three pads' relative sum, plus 1e-9 for
                    // the eigenvector rounding.
                    const double pad = 16.0 * kMachineEpsilon * bvoracle::magnitude(pts);
                    const double volTol = 1e-9 + 2.0 * (pad / h.x() + pad / h.y() + pad / h.z());
                    CHECK(volume(box) / truth == doctest::Approx(1.0).epsilon(volTol));
                    // Major axis along the box's long side (up to sign).
                    CHECK(std::abs(box.axes.col(0).dot(q * Vec3::UnitX())) == doctest::Approx(1.0).epsilon(1e-9));
                    CHECK((box.center - off).norm() <=
                          1e-9 * scale + 64.0 * kMachineEpsilon * offset);
                }
            }
        }
    }

    TEST_CASE("vertex covariance is tessellation dependent, triangle covariance is not") {
        // The test that the area weighting is really there: with the +x face split into many
        // triangles, a 3:2:1 box's vertices crowd at +x; rotated 30 degrees about z the vertex
        // covariance tilts, the box it gives is measurably larger.
        const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5, Vec3(0.3, 0.2, 1.0).normalized()));
        const auto tris = bvoracle::boxMesh(Vec3(3, 2, 1), q, Vec3::Zero(), 12);
        const double truth = 48.0;
        CHECK(volume(fitObbTriangles(tris)) / truth == doctest::Approx(1.0).epsilon(1e-9));
        CHECK(volume(fitObbCovariance(bvoracle::vertices(tris))) / truth > 1.01);
    }

    TEST_CASE("repeated eigenvalues still give a rotation matrix") {
        // A cube (triple eigenvalue) and a square slab (double eigenvalue), in several poses.
        std::mt19937 rng(4);
        for (int i = 0; i < 20; ++i) {
            const auto q = bvoracle::randomRotation(rng);
            for (const Vec3& h : {Vec3(1, 1, 1), Vec3(2, 2, 0.5), Vec3(1, 3, 3)}) {
                const auto tris = bvoracle::boxMesh(h, q, Vec3(1e4, 0, 0));
                const Obb box = fitObbTriangles(tris);
                checkAxes(box);
                const auto pts = bvoracle::vertices(tris);
                CHECK(maxOutside(box, pts) <= containTol(pts));
                const Obb pbox = fitObbCovariance(pts);
                checkAxes(pbox);
                CHECK(maxOutside(pbox, pts) <= containTol(pts));
            }
        }
        // The regular octahedron's vertices: isotropic covariance.
        const std::vector<Vec3> oct{Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                    Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
        checkAxes(fitObbCovariance(oct));
    }

    TEST_CASE("degenerate inputs: zero area, collinear, coincident, single point, NaN, empty") {
        ObbFitTrace trace;
        // Zero-area triangles spanning a plane (every triangle collinear): point covariance.
        const std::vector<Triangle> flat{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},
                                         {Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(0, 3, 0)}};
        Obb box = fitObbTriangles(flat, &trace);
        CHECK((trace.method == ObbFitMethod::PointCovariance));
        checkAxes(box);
        CHECK(maxOutside(box, bvoracle::vertices(flat)) <= 1e-14L);
        // Collinear points: a segment-shaped box (two zero extents up to the pad).
        const std::vector<Vec3> line{Vec3(1e4, 1e4, 1e4), Vec3(1e4 + 1, 1e4 + 2, 1e4 + 3),
                                     Vec3(1e4 + 2, 1e4 + 4, 1e4 + 6)};
        box = fitObbCovariance(line, &trace);
        checkAxes(box);
        CHECK(box.halfExtents[0] == doctest::Approx(std::sqrt(14.0)));
        CHECK(box.halfExtents[1] < 1e-9);
        CHECK(box.halfExtents[2] < 1e-9);
        CHECK(maxOutside(box, line) <= containTol(line));
        // Coincident points and degenerate triangles: identity axes around the point.
        const std::vector<Triangle> dot{{Vec3(0.1, 0.2, 0.3), Vec3(0.1, 0.2, 0.3), Vec3(0.1, 0.2, 0.3)}};
        box = fitObbTriangles(dot, &trace);
        CHECK((trace.method == ObbFitMethod::AxisAligned));
        CHECK((box.axes == Mat3::Identity()));
        CHECK((box.center == Vec3(0.1, 0.2, 0.3)));
        CHECK(box.halfExtents.maxCoeff() < 1e-14);  // the pad only
        const std::vector<Vec3> single{Vec3(-5, 6, 7)};
        box = fitObbCovariance(single, &trace);
        CHECK((trace.method == ObbFitMethod::AxisAligned));
        CHECK(contains(box, single[0]));
        // NaN: skipped and counted.
        const std::vector<Vec3> withNaN{Vec3(0, 0, 0), Vec3(kNaN, 1, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        box = fitObbCovariance(withNaN, &trace);
        CHECK(trace.skippedNonFinite == 1);
        CHECK(box.center.allFinite());
        checkAxes(box);
        // Empty and all-NaN: NaN center, no overlap with anything.
        const std::vector<Vec3> allNaN{Vec3(kNaN, 0, 0)};
        box = fitObbCovariance(allNaN, &trace);
        CHECK((trace.method == ObbFitMethod::Empty));
        CHECK_FALSE(box.center.allFinite());
        CHECK_FALSE(testObbObb(box, Obb{Vec3::Zero(), Vec3::Constant(1e300), Mat3::Identity()}).hit);
        box = fitObbTriangles(std::span<const Triangle>{}, &trace);
        CHECK((trace.method == ObbFitMethod::Empty));
        CHECK_FALSE(box.center.allFinite());
    }

    TEST_CASE("OBB never looser than needed on its own axes: every face touches a point") {
        // Tightness oracle: for each axis, some point projects onto each end of the extent
        // (to within the pad), i.e. the box is the smallest one with these axes.
        std::mt19937 rng(5);
        const auto pts = bvoracle::randomCloud(rng, 30, Vec3(4, 2, 1), 1.0, Vec3(3, 4, 5));
        const Obb box = fitObbCovariance(pts);
        for (int i = 0; i < 3; ++i) {
            LD lo = 1e30L, hi = -1e30L;
            for (const Vec3& p : pts) {
                const LD u = bvoracle::dot(V(Vec3(box.axes.col(i))), V(p) - V(box.center));
                lo = std::min(lo, u);
                hi = std::max(hi, u);
            }
            CHECK(std::abs(hi - LD(box.halfExtents[i])) < 1e-12L);
            CHECK(std::abs(lo + LD(box.halfExtents[i])) < 1e-12L);
        }
    }

}  // TEST_SUITE

TEST_CASE("transformAabb: the AABB of the box's eight moved corners, holding every moved point") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 500; ++trial) {
        Aabb box{Vec3(u(rng), u(rng), u(rng)), Vec3::Zero()};
        box.max = box.min + Vec3(std::abs(u(rng)), std::abs(u(rng)), std::abs(u(rng)));
        const Quat q = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
        const Transform pose{Vec3(u(rng), u(rng), u(rng)), q};
        const Aabb got = transformAabb(box, pose);
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (int k = 0; k < 8; ++k) {
            const Vec3 c = pose.apply(Vec3(k & 1 ? box.max.x() : box.min.x(), k & 2 ? box.max.y() : box.min.y(),
                                           k & 4 ? box.max.z() : box.min.z()));
            lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
        }
        CHECK((got.min - lo).norm() <= 1e-12);
        CHECK((got.max - hi).norm() <= 1e-12);
        // Any point of the box, moved, lies inside (up to rounding).
        const Vec3 t(std::abs(u(rng)) / 3, std::abs(u(rng)) / 3, std::abs(u(rng)) / 3);
        const Vec3 inside = pose.apply(box.min + t.cwiseProduct(box.max - box.min));
        CHECK(contains(got, inside, 1e-12));
    }
    const Aabb empty{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
    CHECK(transformAabb(empty, Transform{}).min.x() == INFINITY);
}
