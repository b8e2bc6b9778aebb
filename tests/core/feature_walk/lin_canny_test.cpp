// Lin–Canny tests: distances against the long double brute-force oracle (verification/feature_walk_oracle.h,
// independent code) and V-Clip on separated pairs; penetrating pairs never get a distance; the
// degenerate families (exact touching, parallel faces, points on Voronoi planes) end in a defined
// status; warm starts; the trace agrees with the result.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/feature_walk/lin_canny.h"
#include "core/feature_walk/vclip.h"
#include "core/geometry/polyhedron_presets.h"
#include "verification/feature_walk_oracle.h"
#include "tests/core/feature_walk/walk_test_bodies.h"

using namespace cdlab;
using namespace cdlab::test;

namespace {

/// The shapes every test loops over (all VClip-buildable).
std::vector<VClipPolyhedron> shapes() {
    return {
        build(presets::box(Vec3(0.5, 0.5, 0.5))), build(presets::tetrahedron(1.0)), build(presets::icosahedron(1.0)),
        build(presets::dodecahedron(0.8)),        build(presets::disk(60, 1.0)),    build(presets::prism(7, 0.6, 1.2)),
        build(presets::randomHull(40, 7))};
}

struct Tally {
    int separated = 0, penetrating = 0, cycles = 0;
};

/// One query, checked: Separated must equal the oracle (and V-Clip); an intersecting oracle must
/// never get Separated; a cycle is allowed only when the oracle says the bodies intersect or
/// `allowCycle` (degenerate families).
void checkPair(const VClipPolyhedron& A, const Transform& pa, const VClipPolyhedron& B, const Transform& pb,
               LinCannyCache* cache, Tally& tally, bool allowCycle = false, double tolScale = 1e-9) {
    LinCannyTrace trace;
    const LinCannyResult r = linCanny(A, pa, B, pb, cache, {}, &trace);
    const OracleDistance o = oracleDistance(A.mesh(), pa, B.mesh(), pb);
    const double od = static_cast<double>(o.distance);
    const double scale = std::max(extent(A.mesh()), extent(B.mesh()));
    const double tol = tolScale * (scale + pa.position.norm() + pb.position.norm());
    CAPTURE(nameOf(r.status));
    CAPTURE(r.message);
    CAPTURE(od);
    CAPTURE(r.distance);
    CHECK(r.status != LinCannyStatus::InvalidInput);
    CHECK(r.status != LinCannyStatus::StepLimit);
    CHECK(trace.status == r.status);
    REQUIRE(!trace.steps.empty());
    CHECK(r.steps <= A.featureCount() * B.featureCount());
    // One trace step per update plus the final decision.
    CHECK(static_cast<int>(trace.steps.size()) == (r.status == LinCannyStatus::CycleDetected ? r.steps : r.steps + 1));
    if (r.status == LinCannyStatus::Separated) {
        ++tally.separated;
        CHECK(!o.intersect);
        CHECK(std::abs(r.distance - od) <= tol);
        CHECK(std::abs((r.pointB - r.pointA).norm() - r.distance) <= tol);
        CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
        CHECK((trace.steps.back().kind == VClipStepKind::Done));
        // The final features are at the answer's distance (oracle's feature distance).
        const std::vector<WalkVec> wa = worldVertices(A.mesh(), pa), wb = worldVertices(B.mesh(), pb);
        const double fd = static_cast<double>(
            std::sqrt(featureDistance2(oracleFeature(A.mesh(), wa, r.featureA.dimension(), r.featureA.index),
                                       oracleFeature(B.mesh(), wb, r.featureB.dimension(), r.featureB.index))));
        CHECK(std::abs(fd - od) <= tol);
        // V-Clip agrees.
        const VClipResult v = vclip(A, pa, B, pb);
        if (v.status == VClipStatus::Separated) CHECK(std::abs(v.distance - r.distance) <= tol);
    } else if (r.status == LinCannyStatus::Penetrating) {
        ++tally.penetrating;
        CHECK(r.intersect);
        CHECK(r.distance == 0.0);
        // Reported contact: the oracle intersects or the gap is at rounding level.
        CHECK(od <= tol);
    } else {
        ++tally.cycles;
        CHECK(r.status == LinCannyStatus::CycleDetected);
        CHECK(r.cycleLength >= 2);
        CHECK(trace.cycleLength == r.cycleLength);
        CHECK((trace.steps.back().kind == VClipStepKind::Aborted));
        CHECK((o.intersect || od <= tol || allowCycle));
    }
}

}  // namespace

TEST_SUITE("lin_canny") {
    TEST_CASE("separated random pairs: distance equals the brute-force oracle and V-Clip (cold start)") {
        const std::vector<VClipPolyhedron> s = shapes();
        presets::SplitMix64 rng(11);
        Tally t;
        for (size_t i = 0; i < s.size(); ++i)
            for (size_t j = 0; j < s.size(); ++j)
                for (int k = 0; k < 8; ++k) {
                    const Transform pa =
                        pose(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)), randomRotation(rng));
                    // 2.6 exceeds the sum of any two circumradii (<= 1.3 each): always separated.
                    const Transform pb =
                        pose(pa.position + rng.onUnitSphere() * rng.uniform(2.6, 4.0), randomRotation(rng));
                    checkPair(s[i], pa, s[j], pb, nullptr, t);
                }
        CHECK(t.separated == static_cast<int>(s.size() * s.size() * 8));
    }

    TEST_CASE("near pairs (gaps 1e-6 .. 0.3) and mixed: never a wrong distance") {
        const std::vector<VClipPolyhedron> s = shapes();
        presets::SplitMix64 rng(12);
        Tally t;
        for (int n = 0; n < 300; ++n) {
            const VClipPolyhedron& A = s[n % s.size()];
            const VClipPolyhedron& B = s[(n / s.size()) % s.size()];
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
            const Transform pb = pose(rng.onUnitSphere() * rng.uniform(0.2, 2.4), randomRotation(rng));
            checkPair(A, pa, B, pb, nullptr, t);
        }
        MESSAGE("separated ", t.separated, ", penetrating ", t.penetrating, ", cycles ", t.cycles);
        CHECK(t.separated > 50);
        CHECK(t.penetrating > 20);
    }

    TEST_CASE("warm start over a coherent motion: same answers, few steps") {
        const VClipPolyhedron A = build(presets::icosahedron(1.0)), B = build(presets::disk(60, 1.0));
        LinCannyCache cache;
        Tally t;
        long long steps = 0;
        const int n = 200;
        for (int i = 0; i < n; ++i) {
            const double a = 0.05 * i;
            const Transform pa = pose(Vec3::Zero(), Quat(Eigen::AngleAxisd(a, Vec3::UnitZ())));
            const Transform pb = pose(Vec3(3.0 * std::cos(0.3 * a), 3.0 * std::sin(0.3 * a), 0.5),
                                      Quat(Eigen::AngleAxisd(0.7 * a, Vec3(1, 1, 0).normalized())));
            LinCannyCache before = cache;
            checkPair(A, pa, B, pb, &cache, t);
            const LinCannyResult r = linCanny(A, pa, B, pb, &before);
            steps += r.steps;
        }
        CHECK(t.separated == n);
        MESSAGE("mean warm steps ", static_cast<double>(steps) / n);
        CHECK(static_cast<double>(steps) / n < 3.0);
    }

    TEST_CASE("large offsets and scales") {
        presets::SplitMix64 rng(13);
        Tally t;
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e4, 1e6}) {
                const VClipPolyhedron A = build(presets::icosahedron(scale)),
                                      B = build(presets::box(Vec3(scale, 0.5 * scale, 0.7 * scale)));
                for (int k = 0; k < 10; ++k) {
                    const Vec3 base = Vec3(offset, -offset, 0.5 * offset);
                    const Transform pa = pose(base, randomRotation(rng));
                    const Transform pb =
                        pose(base + rng.onUnitSphere() * scale * rng.uniform(2.4, 4.0), randomRotation(rng));
                    CAPTURE(scale);
                    CAPTURE(offset);
                    // Coordinates of 1e6 carry ~1e-10 absolute rounding: the tolerance scales with them.
                    checkPair(A, pa, B, pb, nullptr, t, false, 1e-9);
                }
            }
        CHECK(t.separated == 90);
    }

    TEST_CASE("penetrating pairs: Penetrating or CycleDetected, never a distance") {
        const std::vector<VClipPolyhedron> s = shapes();
        presets::SplitMix64 rng(14);
        Tally t;
        for (int n = 0; n < 400; ++n) {
            const VClipPolyhedron& A = s[n % s.size()];
            const VClipPolyhedron& B = s[(n / 3) % s.size()];
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
            const Transform pb = pose(rng.onUnitSphere() * rng.uniform(0.0, 0.3), randomRotation(rng));
            LinCannyCache cache{VClipFeature::face(0), VClipFeature::vertex(0)};  // an arbitrary seed too
            checkPair(A, pa, B, pb, n % 2 ? &cache : nullptr, t);
            CHECK(t.separated == 0);
            // With cdlab's inside test the verdict is the same (or found earlier).
            LinCannyOptions inside;
            inside.insideTest = true;
            const LinCannyResult ri = linCanny(A, pa, B, pb, nullptr, inside);
            CHECK((ri.status == LinCannyStatus::Penetrating || ri.status == LinCannyStatus::CycleDetected));
        }
        MESSAGE("penetrating ", t.penetrating, ", cycles ", t.cycles);
    }

    TEST_CASE("degenerate families never hang and never give a wrong distance") {
        const VClipPolyhedron cube = build(presets::box(Vec3(0.5, 0.5, 0.5)));
        Tally t;
        // Exact touching / parallel faces / vertices and edges on Voronoi planes: B's offsets are
        // multiples of 0.25 (faces coplanar with A's, edges aligned, vertices on VE / FE planes).
        for (int ix = -6; ix <= 6; ++ix)
            for (int iy = -6; iy <= 6; ++iy)
                for (double gap : {0.0, 0.25, 1.0}) {
                    const Transform pa = pose(Vec3::Zero());
                    const Transform pb = pose(Vec3(0.25 * ix, 0.25 * iy, 1.0 + gap));
                    for (int seed = 0; seed < 3; ++seed) {
                        LinCannyCache cache{VClipFeature::vertex(seed), VClipFeature::face(seed)};
                        checkPair(cube, pa, cube, pb, &cache, t, true);
                    }
                }
        MESSAGE("separated ", t.separated, ", touching ", t.penetrating, ", cycles ", t.cycles);
        CHECK(t.separated > 0);
    }

    TEST_CASE("cycles are detected, and without detection the step limit ends the walk") {
        // A negative applicability tolerance makes a point ON a region boundary violate the regions on
        // both sides: the mechanism of Lin–Canny's cycles (rounding puts a boundary point outside both
        // regions), forced. The walk then bounces between neighbours for ever.
        const VClipPolyhedron A = build(presets::box(Vec3(0.5, 0.5, 0.5))), B = build(presets::icosahedron(1.0));
        presets::SplitMix64 rng(15);
        int cycles = 0;
        for (int n = 0; n < 50; ++n) {
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
            const Transform pb = pose(rng.onUnitSphere() * 3.0, randomRotation(rng));
            LinCannyOptions forced;
            forced.applicability = -0.05;
            LinCannyTrace trace;
            const LinCannyResult r = linCanny(A, pa, B, pb, nullptr, forced, &trace);
            CHECK(r.status != LinCannyStatus::StepLimit);
            if (r.status != LinCannyStatus::CycleDetected) continue;
            ++cycles;
            CHECK(r.cycleLength >= 2);
            CHECK(r.distance == 0.0);
            CHECK(!r.intersect);
            CHECK(trace.cycleLength == r.cycleLength);
            CHECK(static_cast<int>(trace.steps.size()) == r.steps);
            // The last cycleLength updates return to the pair they started from.
            const LinCannyTraceStep& first = trace.steps[trace.steps.size() - r.cycleLength];
            CHECK((first.featureA == r.featureA));
            CHECK((first.featureB == r.featureB));
            // Brent: found within 2 x (tail + cycle) updates.
            CHECK(r.steps <= 2 * (r.steps - r.cycleLength + 1) + 2 * r.cycleLength);
            // Detection off: the step limit stops the same walk.
            forced.detectCycles = false;
            forced.maxSteps = 300;
            const LinCannyResult s = linCanny(A, pa, B, pb, nullptr, forced);
            CHECK(s.status == LinCannyStatus::StepLimit);
            CHECK(s.steps == 300);
            CHECK(s.distance == 0.0);
        }
        MESSAGE("forced cycles: ", cycles, " of 50");
        CHECK(cycles > 20);
    }

    TEST_CASE("natural cycles on penetrating pairs (count only)") {
        // cdlab's Lin–Canny computes exact feature-pair closest points (an edge piercing a face gives
        // distance 0: FeaturesMeet) and searches all faces at a local minimum, so penetrating pairs are
        // mostly reported as such; any cycle must still be on an intersecting pair.
        const VClipPolyhedron A = build(presets::icosahedron(1.0)), B = build(presets::box(Vec3(0.6, 0.4, 0.5)));
        presets::SplitMix64 rng(16);
        int cycles = 0;
        for (int n = 0; n < 1000; ++n) {
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
            const Transform pb = pose(rng.onUnitSphere() * rng.uniform(0.0, 0.6), randomRotation(rng));
            LinCannyCache seed{VClipFeature::vertex(static_cast<int>(rng.next() % 12)),
                               VClipFeature::face(static_cast<int>(rng.next() % 6))};
            const LinCannyResult r = linCanny(A, pa, B, pb, &seed);
            CHECK(r.status != LinCannyStatus::Separated);
            if (r.status == LinCannyStatus::CycleDetected) {
                ++cycles;
                CHECK(oracleDistance(A.mesh(), pa, B.mesh(), pb).intersect);
            }
        }
        MESSAGE("natural cycles: ", cycles, " of 1000");
    }

    TEST_CASE("invalid input") {
        const VClipPolyhedron A = build(presets::box(Vec3(1, 1, 1)));
        const VClipPolyhedron empty;
        CHECK(linCanny(A, Transform{}, empty, Transform{}).status == LinCannyStatus::InvalidInput);
        Transform bad;
        bad.position = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
        CHECK(linCanny(A, bad, A, pose(Vec3(5, 0, 0))).status == LinCannyStatus::InvalidInput);
        // An out-of-range seed falls back to a cold start.
        LinCannyCache cache{VClipFeature::face(99), VClipFeature::edge(-3)};
        const LinCannyResult r = linCanny(A, Transform{}, A, pose(Vec3(5, 0, 0)), &cache);
        CHECK(r.status == LinCannyStatus::Separated);
        CHECK(r.distance == doctest::Approx(3.0));
    }

    TEST_CASE("exact cases: face-face parallel, vertex-face, edge-edge") {
        const VClipPolyhedron cube = build(presets::box(Vec3(0.5, 0.5, 0.5)));
        // Parallel faces, gap 0.5: distance 0.5 whatever the seed.
        for (int v = 0; v < 8; ++v) {
            LinCannyCache c{VClipFeature::vertex(v), VClipFeature::vertex(7 - v)};
            const LinCannyResult r = linCanny(cube, Transform{}, cube, pose(Vec3(0.3, -0.2, 1.5)), &c);
            REQUIRE(r.status == LinCannyStatus::Separated);
            CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-14));
            CHECK(r.normal.z() == doctest::Approx(1.0));
        }
        // Vertex of a rotated cube above a face: the corner points down (rotation that maps (1,1,1) to -z).
        const Quat q = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), -Vec3::UnitZ());
        const LinCannyResult r =
            linCanny(cube, Transform{}, cube, pose(Vec3(0.1, 0.1, 0.5 + std::sqrt(0.75) + 0.25), q));
        REQUIRE(r.status == LinCannyStatus::Separated);
        CHECK(r.distance == doctest::Approx(0.25).epsilon(1e-12));
        CHECK((r.featureB.type == VClipFeatureType::Vertex));
        CHECK((r.featureA.type == VClipFeatureType::Face));
        // Crossed edges: two cubes rotated 45 degrees about x and y, edge above edge.
        const Quat qx(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())), qy(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()));
        const double h = std::sqrt(0.5);
        const LinCannyResult e = linCanny(cube, pose(Vec3::Zero(), qy), cube, pose(Vec3(0, 0, 2 * h + 0.1), qx));
        REQUIRE(e.status == LinCannyStatus::Separated);
        CHECK(e.distance == doctest::Approx(0.1).epsilon(1e-12));
        CHECK((e.featureA.type == VClipFeatureType::Edge));
        CHECK((e.featureB.type == VClipFeatureType::Edge));
    }

}  // TEST_SUITE
