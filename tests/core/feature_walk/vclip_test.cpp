// V-Clip tests: Voronoi planes, answers against a long double brute-force oracle
// (verification/feature_walk_oracle.h) and GJK, and the walk's invariants checked on every trace step
// (Mirtich, "V-Clip", ACM TOG 1998: distance never increases, dimension-raising updates
// decrease it, dimension-lowering ones keep it; no pair repeats; steps <= number of pairs).
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <sstream>
#include <tuple>

#include "core/feature_walk/vclip.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "verification/feature_walk_oracle.h"
#include "tests/core/feature_walk/walk_test_bodies.h"

using namespace cdlab;
using namespace cdlab::test;

namespace {

struct CheckStats {
    int queries = 0, separated = 0, penetrating = 0, steps = 0, updates = 0, dimUp = 0, dimDown = 0, localMin = 0;
    int dimUpEqual = 0;  // dimension-raising updates that kept the distance (see the check below)
};

/// Runs V-Clip with a trace and checks every invariant. Returns the result. useOracle: compare
/// with the brute-force distance. generic: random configuration without exact ties (checks
/// which dimension-raising updates may keep the distance).
VClipResult checkQuery(const VClipPolyhedron& A, const Transform& pa, const VClipPolyhedron& B, const Transform& pb,
                       VClipCache* cache, CheckStats* stats = nullptr, bool useOracle = true, double tolScale = 1e-9,
                       bool generic = false) {
    VClipTrace trace;
    const VClipResult r = vclip(A, pa, B, pb, cache, {}, &trace);
    const double scale = std::max(extent(A.mesh()), extent(B.mesh()));
    const double tol = tolScale * scale;
    REQUIRE_MESSAGE((r.status == VClipStatus::Separated || r.status == VClipStatus::Penetrating), r.message);
    CHECK(trace.status == r.status);
    // Steps: bounded by the number of feature pairs, one trace step per update plus the final one.
    CHECK(r.steps <= A.featureCount() * B.featureCount());
    REQUIRE(static_cast<int>(trace.steps.size()) == r.steps + 1);
    // No feature pair repeats.
    std::set<std::tuple<int, int, int, int>> seen;
    for (const VClipTraceStep& s : trace.steps) {
        const auto key = std::make_tuple(static_cast<int>(s.featureA.type), s.featureA.index,
                                         static_cast<int>(s.featureB.type), s.featureB.index);
        CHECK_MESSAGE(seen.insert(key).second, "pair repeated at step ", s.step);
        CHECK((!(s.featureA.type == VClipFeatureType::Face && s.featureB.type == VClipFeatureType::Face)));
    }
    // Distance monotonicity with the oracle's feature distances (long double, independent code).
    const std::vector<WalkVec> wa = worldVertices(A.mesh(), pa), wb = worldVertices(B.mesh(), pb);
    auto pairDistance = [&](const VClipFeature& fa, const VClipFeature& fb) {
        return static_cast<double>(std::sqrt(featureDistance2(oracleFeature(A.mesh(), wa, fa.dimension(), fa.index),
                                                              oracleFeature(B.mesh(), wb, fb.dimension(), fb.index))));
    };
    for (size_t i = 0; i + 1 < trace.steps.size(); ++i) {
        const VClipTraceStep& s = trace.steps[i];
        REQUIRE((s.kind == VClipStepKind::Update));
        const VClipTraceStep& n = trace.steps[i + 1];
        CHECK((s.to == (s.updatedBody == 0 ? n.featureA : n.featureB)));
        if (stats) ++stats->updates;
        if (s.localMinimum) {
            if (stats) ++stats->localMin;
            continue;  // handleLocalMin jumps to another face: distance not monotone (paper §5.4)
        }
        const double before = pairDistance(s.featureA, s.featureB), after = pairDistance(n.featureA, n.featureB);
        const int dimChange = s.to.dimension() - s.from.dimension();
        CAPTURE(i);
        CAPTURE(s.rule);
        CAPTURE(before);
        CAPTURE(after);
        // The trace's own numbers agree with the oracle's.
        CHECK(std::abs(s.distanceBefore - before) <= tol);
        CHECK(std::abs(s.distanceAfter - after) <= tol);
        if (dimChange < 0) {
            if (stats) ++stats->dimDown;
            CHECK(std::abs(after - before) <= tol);  // lowering the dimension keeps the distance
            CHECK(s.distanceChange == 0);
        } else {
            if (stats) ++stats->dimUp;
            CHECK(after <= before + tol);  // raising it never increases it
            CHECK(s.distanceChange <= 0);
            // Strictly smaller, except E-E edge -> face when the edge's closest point to the other
            // edge is an endpoint (then the face's is the same point): the one non-strict case
            // the walk allows (the paper states strict decrease for every such update).
            if (after > before - tol && before > tol) {
                if (stats) ++stats->dimUpEqual;
            }
            if (generic && after > before - tol && before > tol) {
                CHECK((s.state == VClipState::EdgeEdge));
                CHECK((s.to.type == VClipFeatureType::Face));
            }
        }
    }
    const VClipTraceStep& last = trace.steps.back();
    CHECK((last.kind == (r.status == VClipStatus::Separated ? VClipStepKind::Done : VClipStepKind::Penetration)));
    if (useOracle) {
        const OracleDistance o = oracleDistance(A.mesh(), pa, B.mesh(), pb);
        CAPTURE(static_cast<double>(o.distance));
        CAPTURE(r.distance);
        if (o.intersect) {
            CHECK(r.status == VClipStatus::Penetrating);
        } else if (static_cast<double>(o.distance) > tol) {
            CHECK(r.status == VClipStatus::Separated);
            CHECK(std::abs(r.distance - static_cast<double>(o.distance)) <= tol);
        }
    }
    if (r.status == VClipStatus::Separated) {
        // Witnesses: their distance is the answer; each lies in the other's final feature region.
        CHECK(std::abs((r.pointB - r.pointA).norm() - r.distance) <= tol + 1e-15 * r.pointA.norm());
        CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
        const double dFinal = pairDistance(r.featureA, r.featureB);
        CHECK(std::abs(dFinal - r.distance) <= tol);
        for (int body = 0; body < 2; ++body) {
            const VClipPolyhedron& P = body == 0 ? A : B;
            const Transform& T = body == 0 ? pa : pb;
            const VClipFeature f = body == 0 ? r.featureA : r.featureB;
            const Vec3 x = T.applyInverse(body == 0 ? r.pointB : r.pointA);  // the OTHER body's witness
            std::vector<int> planes;
            if (f.type == VClipFeatureType::Vertex)
                planes.assign(P.vertexPlanes(f.index).begin(), P.vertexPlanes(f.index).end());
            if (f.type == VClipFeatureType::Face)
                planes.assign(P.facePlanes(f.index).begin(), P.facePlanes(f.index).end());
            if (f.type == VClipFeatureType::Edge)
                for (int k = 0; k < 4; ++k) planes.push_back(4 * f.index + k);
            for (int i : planes) CHECK(P.regionDistance(i, f, x) >= -tol);
            if (f.type == VClipFeatureType::Face) CHECK(P.mesh().planeDistance(f.index, x) >= -tol);
        }
        if (stats) ++stats->separated;
    } else if (stats) {
        ++stats->penetrating;
    }
    if (stats) {
        ++stats->queries;
        stats->steps += r.steps;
    }
    return r;
}

GjkResult gjkOf(const ConvexPolyhedron& a, const Transform& pa, const ConvexPolyhedron& b, const Transform& pb) {
    Transformed<PolytopeShape> sa{PolytopeShape(a), pa}, sb{PolytopeShape(b), pb};
    return gjkDistance(sa, sb);
}

std::vector<ConvexPolyhedron> smallShapes() {
    return {presets::tetrahedron(1.0),
            presets::box(Vec3(1.0, 0.7, 0.4)),
            presets::octahedron(0.9),
            presets::icosahedron(1.1),
            presets::dodecahedron(1.0),
            presets::prism(7, 0.8, 0.5),
            presets::disk(12, 1.0),
            presets::randomHull(24, 7),
            presets::randomHull(40, 11, presets::RandomHullKind::InBall)};
}

}  // namespace

TEST_SUITE("vclip") {
    TEST_CASE("Voronoi planes: oriented towards the edge, through their features, regions contain their features") {
        for (const ConvexPolyhedron& poly : smallShapes()) {
            const VClipPolyhedron P = build(poly);
            const ConvexPolyhedron& m = P.mesh();
            const double tol = 1e-12 * extent(m);
            REQUIRE(P.planes().size() == 4 * static_cast<size_t>(m.edgeCount()));
            for (int e = 0; e < m.edgeCount(); ++e) {
                const Vec3 t = m.position(P.edgeTail(e)), h = m.position(P.edgeHead(e));
                const Vec3 nl = m.face(P.edgeLeftFace(e)).normal, nr = m.face(P.edgeRightFace(e)).normal;
                const Vec3 mid = 0.5 * (t + h);
                // A point pushed out of the edge along the normals' sum is in VR(e): all 4 planes >= 0.
                const Vec3 out = mid + 0.1 * (nl + nr).normalized();
                for (int k = 0; k < 4; ++k) {
                    const VClipPlane& pl = P.plane(4 * e + k);
                    CHECK(std::abs(pl.normal.norm() - 1) <= 1e-14);
                    CHECK((pl.edge == VClipFeature::edge(e)));
                    CHECK(pl.signedDistance(out) > 0);
                    CHECK(std::abs(pl.signedDistance(k == 1 ? h : t)) <= tol);  // passes through its vertex / the edge
                    if (k >= 2) CHECK(std::abs(pl.signedDistance(h)) <= tol);
                }
                CHECK((P.plane(4 * e).other == VClipFeature::vertex(P.edgeTail(e))));
                CHECK((P.plane(4 * e + 1).other == VClipFeature::vertex(P.edgeHead(e))));
                CHECK((P.plane(4 * e + 2).other == VClipFeature::face(P.edgeLeftFace(e))));
                CHECK((P.plane(4 * e + 3).other == VClipFeature::face(P.edgeRightFace(e))));
            }
            for (int v = 0; v < m.vertexCount(); ++v) {
                Vec3 n = Vec3::Zero();
                for (int f : m.vertexFaces(v)) n += m.face(f).normal;
                const Vec3 x = m.position(v) + 0.1 * n.normalized();
                CHECK(P.vertexPlanes(v).size() == m.vertexEdges(v).size());
                for (int i : P.vertexPlanes(v)) CHECK(P.regionDistance(i, VClipFeature::vertex(v), x) > 0);
            }
            for (int f = 0; f < m.faceCount(); ++f) {
                Vec3 c = Vec3::Zero();
                for (int v : m.faceVertices(f)) c += m.position(v);
                c /= m.faceDegree(f);
                const Vec3 x = c + 0.1 * m.face(f).normal;
                CHECK(static_cast<int>(P.facePlanes(f).size()) == m.faceDegree(f));
                for (int i : P.facePlanes(f)) CHECK(P.regionDistance(i, VClipFeature::face(f), x) > 0);
            }
        }
    }

    TEST_CASE("build rejects empty, invalid and coplanar-face polyhedra with a message") {
        CHECK(buildVClipPolyhedron(ConvexPolyhedron{}).status == VClipBuildStatus::EmptyPolyhedron);
        // A cube with triangulated faces: adjacent coplanar triangles.
        std::vector<Vec3> v;
        for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        HullOptions o;
        o.mergeCoplanarFaces = false;
        const HullResult h = convexHull(v, o);
        REQUIRE(h.ok());
        const VClipBuild b = buildVClipPolyhedron(h.polyhedron);
        CHECK(b.status == VClipBuildStatus::CoplanarFaces);
        CHECK(b.message.find("coplanar") != std::string::npos);
        CHECK(b.polyhedron.empty());
        // Merged hull: accepted.
        CHECK(buildVClipPolyhedron(convexHull(v).polyhedron).ok());
    }

    TEST_CASE("invalid input: empty polyhedron, non-finite pose, out-of-range cache falls back to a cold start") {
        const VClipPolyhedron box = build(presets::box(Vec3(1, 1, 1)));
        CHECK(vclip(VClipPolyhedron{}, {}, box, {}).status == VClipStatus::InvalidInput);
        Transform bad = pose(Vec3(std::nan(""), 0, 0));
        CHECK(vclip(box, {}, box, bad).status == VClipStatus::InvalidInput);
        VClipCache cache{VClipFeature::face(99), VClipFeature::edge(-3)};
        const VClipResult r = vclip(box, {}, box, pose(Vec3(3, 0, 0)), &cache);
        CHECK(r.status == VClipStatus::Separated);
        CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-15));
        CHECK((cache.a == r.featureA));
    }

    TEST_CASE("boxes: face-face, edge-edge and vertex-vertex closest features, exact distances") {
        const VClipPolyhedron box = build(presets::box(Vec3(1, 1, 1)));
        // Face-face: any closest pair, distance 1.
        VClipResult r = checkQuery(box, {}, box, pose(Vec3(3, 0.3, -0.2)), nullptr);
        CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-14));
        // Edge-edge: B turned 45 degrees about z and x, offset along the diagonal.
        const Quat q = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()));
        r = checkQuery(box, {}, box, pose(Vec3(1 + std::sqrt(2.0) + 0.5, 0, 0), q), nullptr);
        CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-13));
        // Vertex-vertex along the main diagonal.
        r = checkQuery(box, {}, box, pose(Vec3(3, 3, 3)), nullptr);
        CHECK(r.distance == doctest::Approx(std::sqrt(3.0)).epsilon(1e-14));
        CHECK((r.featureA.type == VClipFeatureType::Vertex));
        CHECK((r.featureB.type == VClipFeatureType::Vertex));
    }

    TEST_CASE("random poses of many shapes: oracle, GJK and every invariant") {
        const std::vector<ConvexPolyhedron> shapes = smallShapes();
        std::vector<VClipPolyhedron> built;
        for (const ConvexPolyhedron& s : shapes) built.push_back(build(s));
        presets::SplitMix64 rng(12345);
        CheckStats stats;
        for (int q = 0; q < 400; ++q) {
            const int i = static_cast<int>(rng.next() % shapes.size()),
                      j = static_cast<int>(rng.next() % shapes.size());
            const Transform pa =
                pose(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)), randomRotation(rng));
            const Transform pb = pose(pa.position + 2.6 * rng.inUnitBall(), randomRotation(rng));
            CAPTURE(q);
            CAPTURE(i);
            CAPTURE(j);
            const VClipResult r = checkQuery(built[i], pa, built[j], pb, nullptr, &stats, true, 1e-9, true);
            const GjkResult g = gjkOf(shapes[i], pa, shapes[j], pb);
            if (g.status == GjkStatus::Separated && g.distance > 1e-9) {
                CHECK(r.status == VClipStatus::Separated);
                CHECK(std::abs(r.distance - g.distance) <= 1e-9);
            }
            if (g.status == GjkStatus::Intersecting) CHECK(r.intersect);
        }
        MESSAGE("random: ", stats.queries, " queries, ", stats.separated, " separated, ", stats.penetrating,
                " penetrating, ", stats.dimUp, " dimension-up (", stats.dimUpEqual,
                " of them E-E edge -> face at equal distance) and ", stats.dimDown, " dimension-down updates, ",
                stats.localMin, " local minima");
        CHECK(stats.separated > 50);
        CHECK(stats.penetrating > 50);
    }

    TEST_CASE("every seed pair gives the same answer") {
        const std::vector<std::pair<ConvexPolyhedron, ConvexPolyhedron>> pairs = {
            {presets::tetrahedron(1.0), presets::box(Vec3(1, 0.7, 0.4))},
            {presets::icosahedron(1.0), presets::prism(5, 0.7, 0.6)},
        };
        presets::SplitMix64 rng(99);
        for (const auto& [sa, sb] : pairs) {
            const VClipPolyhedron A = build(sa), B = build(sb);
            for (int trial = 0; trial < 3; ++trial) {
                const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
                const Transform pb = pose((trial == 2 ? 1.2 : 2.4) * rng.onUnitSphere(), randomRotation(rng));
                const OracleDistance o = oracleDistance(sa, pa, sb, pb);
                auto seedsOf = [](const VClipPolyhedron& P) {
                    std::vector<VClipFeature> s;
                    for (int i = 0; i < P.mesh().vertexCount(); ++i) s.push_back(VClipFeature::vertex(i));
                    for (int i = 0; i < P.mesh().edgeCount(); ++i) s.push_back(VClipFeature::edge(i));
                    for (int i = 0; i < P.mesh().faceCount(); ++i) s.push_back(VClipFeature::face(i));
                    return s;
                };
                int count = 0;
                for (const VClipFeature& fa : seedsOf(A))
                    for (const VClipFeature& fb : seedsOf(B)) {
                        VClipCache cache{fa, fb};
                        const VClipResult r = vclip(A, pa, B, pb, &cache);
                        CAPTURE(nameOf(fa));
                        CAPTURE(nameOf(fb));
                        REQUIRE_MESSAGE((r.status == VClipStatus::Separated || r.status == VClipStatus::Penetrating),
                                        r.message);
                        CHECK(r.intersect == o.intersect);
                        if (!o.intersect) CHECK(std::abs(r.distance - static_cast<double>(o.distance)) <= 1e-12);
                        ++count;
                    }
                CHECK(count == A.featureCount() * B.featureCount());
                // Traced invariants from a handful of seeds.
                for (int k = 0; k < 20; ++k) {
                    VClipCache cache{seedsOf(A)[rng.next() % A.featureCount()],
                                     seedsOf(B)[rng.next() % B.featureCount()]};
                    checkQuery(A, pa, B, pb, &cache);
                }
            }
        }
    }

    TEST_CASE("adversarial: near-parallel faces from 1e-12 to 1e-3 rad") {
        const ConvexPolyhedron sb = presets::box(Vec3(1, 1, 1));
        const VClipPolyhedron box = build(sb);
        for (double angle : {1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3}) {
            for (double gap : {0.1, 1e-6, -0.05}) {
                CAPTURE(angle);
                CAPTURE(gap);
                const Quat q(Eigen::AngleAxisd(angle, Vec3(1, 0.3, 0).normalized()));
                // B rests above A, its bottom face tilted by `angle`.
                const Transform pb = pose(Vec3(0.2, -0.1, 2 + gap + 1.5 * std::sin(angle)), q);
                VClipCache cache;
                const VClipResult r = checkQuery(box, {}, box, pb, &cache, nullptr, true, 1e-9);
                if (gap > 0) CHECK(r.status == VClipStatus::Separated);
                if (gap < 0) CHECK(r.status == VClipStatus::Penetrating);
                // Warm start from the answer: DONE at once.
                const VClipResult again = vclip(box, {}, box, pb, &cache);
                CHECK(again.steps == 0);
                CHECK(again.status == r.status);
            }
        }
    }

    TEST_CASE("adversarial: exact touching, coincident copies, scaled copy inside, one body through another") {
        const ConvexPolyhedron sb = presets::box(Vec3(1, 1, 1));
        const VClipPolyhedron box = build(sb);
        // Face on face at distance exactly 0, vertex on face, edge on edge (exactly representable).
        for (const Transform& pb : {pose(Vec3(2, 0.5, 0.25)), pose(Vec3(2, 2, 0)), pose(Vec3(2, 2, 2))}) {
            for (int seed = 0; seed < 6; ++seed) {
                VClipCache cache{VClipFeature::vertex(seed), VClipFeature::vertex(7 - seed)};
                const VClipResult r = checkQuery(box, {}, box, pb, &cache);
                CHECK(r.status == VClipStatus::Penetrating);
                CHECK(r.distance == 0.0);
            }
        }
        // Coincident identical polyhedra, and under many rotations of both.
        presets::SplitMix64 rng(5);
        for (int k = 0; k < 10; ++k) {
            const Transform p = pose(rng.inUnitBall(), randomRotation(rng));
            CHECK(checkQuery(box, p, box, p, nullptr).status == VClipStatus::Penetrating);
        }
        // A scaled copy strictly inside: no edge crosses a face, the local minimum finds it.
        const VClipPolyhedron ico = build(presets::icosahedron(1.0)), small = build(presets::icosahedron(0.3));
        for (int k = 0; k < 10; ++k) {
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng)),
                            pb = pose(0.2 * rng.inUnitBall(), randomRotation(rng));
            const VClipResult r = checkQuery(ico, pa, small, pb, nullptr);
            CHECK(r.status == VClipStatus::Penetrating);
            CHECK((r.penetration == VClipPenetration::LocalMinimum));
            const VClipResult r2 = checkQuery(small, pb, ico, pa, nullptr);
            CHECK(r2.status == VClipStatus::Penetrating);
        }
        // A long thin bar through a box: no vertex of either inside the other.
        const VClipPolyhedron bar = build(presets::box(Vec3(3, 0.1, 0.1)));
        for (int k = 0; k < 10; ++k) {
            const Transform pb = pose(Vec3(0, 0.3 * rng.uniform(-1, 1), 0.3 * rng.uniform(-1, 1)),
                                      Quat(Eigen::AngleAxisd(rng.uniform(-0.3, 0.3), Vec3::UnitZ())));
            const VClipResult r = checkQuery(box, {}, bar, pb, nullptr);
            CHECK(r.status == VClipStatus::Penetrating);
        }
    }

    TEST_CASE("adversarial: edges crossing exactly, a vertex exactly on a Voronoi plane") {
        const VClipPolyhedron box = build(presets::box(Vec3(1, 1, 1)));
        const VClipPolyhedron tet = build(presets::tetrahedron(1.0));
        // Edge of B (turned 90 degrees about the z axis... a 45-degree diamond) touching the top
        // edge of A exactly: crossing edges at distance 0, then lifted by 0.25.
        const Quat q(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()));
        for (double lift : {0.0, 0.25}) {
            const Transform pb = pose(Vec3(1 + std::sqrt(2.0) + lift, 0, 0), q);
            const VClipResult r = checkQuery(box, {}, box, pb, nullptr);
            if (lift == 0) CHECK(r.intersect);
            else CHECK(r.distance == doctest::Approx(lift).epsilon(1e-12));
        }
        // Tetrahedron vertex (1, 1, 1) placed exactly on the FE plane x = 1 of the box's top edge,
        // on the VE plane y = 1 of a corner, and on both.
        for (const Vec3& target : {Vec3(1, 0, 2.5), Vec3(0.5, 1, 2.5), Vec3(1, 1, 2.5)}) {
            const Vec3 apex = presets::tetrahedron(1.0).position(0);
            const Quat flip(Eigen::AngleAxisd(M_PI, Vec3(1, 1, 0).normalized()));  // puts a vertex below
            Transform pb = pose(Vec3::Zero(), flip);
            int lowest = 0;
            for (int v = 0; v < tet.mesh().vertexCount(); ++v)
                if (pb.apply(tet.mesh().position(v)).z() < pb.apply(tet.mesh().position(lowest)).z()) lowest = v;
            pb.position = target - pb.rotate(tet.mesh().position(lowest));
            (void)apex;
            for (int seed = 0; seed < tet.featureCount(); ++seed) {
                VClipCache cache{VClipFeature::vertex(seed % 8), VClipFeature::vertex(seed % 4)};
                checkQuery(box, {}, tet, pb, &cache);
            }
        }
    }

    TEST_CASE("adversarial: 1e4 and 1e6 world offsets, 1e-3 and 1e3 scales") {
        presets::SplitMix64 rng(77);
        for (double scale : {1e-3, 1.0, 1e3}) {
            const ConvexPolyhedron sa = presets::dodecahedron(scale),
                                   sb = presets::randomHull(30, 3, presets::RandomHullKind::OnSphere, scale);
            const VClipPolyhedron A = build(sa), B = build(sb);
            for (double offset : {0.0, 1e4, 1e6}) {
                for (int k = 0; k < 6; ++k) {
                    const Vec3 o(offset, -offset, 0.5 * offset);
                    const Transform pa = pose(o, randomRotation(rng)),
                                    pb = pose(o + 2.3 * scale * rng.onUnitSphere(), randomRotation(rng));
                    CAPTURE(scale);
                    CAPTURE(offset);
                    // Pose rounding at the offset is ~ulp(offset): the tolerance follows it.
                    const double tolScale = 1e-9 + 1e-13 * offset / scale;
                    const VClipResult r = checkQuery(A, pa, B, pb, nullptr, nullptr, true, tolScale);
                    // Same relative configuration at the origin gives the same distance.
                    Transform pa0 = pa, pb0 = pb;
                    pa0.position -= o;
                    pb0.position -= o;
                    const VClipResult r0 = vclip(A, pa0, B, pb0);
                    CHECK(r.status == r0.status);
                    CHECK(std::abs(r.distance - r0.distance) <= tolScale * scale * 10);
                }
            }
        }
    }

    TEST_CASE("642-vertex geodesic sphere with large rotations per call, warm-started") {
        const ConvexPolyhedron sg = presets::geodesicSphere(3, 1.0);
        REQUIRE(sg.vertexCount() == 642);
        const VClipPolyhedron G = build(sg), D = build(presets::disk(60, 1.0)),
                              C = build(presets::box(Vec3(0.5, 0.5, 0.5)));
        presets::SplitMix64 rng(2024);
        VClipCache cacheG, cacheD, cacheC;
        CheckStats stats;
        for (int k = 0; k < 60; ++k) {
            const Transform pa = pose(Vec3::Zero(), randomRotation(rng));
            const Transform pb = pose((k % 3 == 0 ? 1.3 : 2.4) * rng.onUnitSphere(), randomRotation(rng));
            CAPTURE(k);
            // The oracle is O(E^2) on the sphere: a few queries against it, GJK for the rest.
            checkQuery(G, pa, G, pb, &cacheG, &stats, k < 2);
            for (auto [P, cache, shape] : {std::tuple{&D, &cacheD, presets::disk(60, 1.0)},
                                           std::tuple{&C, &cacheC, presets::box(Vec3(0.5, 0.5, 0.5))}}) {
                const VClipResult r = checkQuery(G, pa, *P, pb, cache, &stats, k < 6);
                const GjkResult g = gjkOf(sg, pa, shape, pb);
                if (g.status == GjkStatus::Separated && g.distance > 1e-9)
                    CHECK(std::abs(r.distance - g.distance) <= 1e-9);
                if (g.status == GjkStatus::Intersecting) CHECK(r.intersect);
            }
            const VClipResult r = vclip(G, pa, G, pb, &cacheG);
            const GjkResult g = gjkOf(sg, pa, sg, pb);
            if (g.status == GjkStatus::Separated && g.distance > 1e-9) CHECK(std::abs(r.distance - g.distance) <= 1e-9);
        }
        MESSAGE("geodesic: ", stats.queries, " queries, mean ", double(stats.steps) / stats.queries, " steps, ",
                stats.dimUpEqual, " of ", stats.dimUp, " dimension-up updates at equal distance");
    }

    TEST_CASE("coherence: small relative motions finish in a few steps from the cached pair") {
        const VClipPolyhedron ico = build(presets::icosahedron(1.0)), box = build(presets::box(Vec3(0.6, 0.6, 0.6)));
        VClipCache cache;
        int total = 0, maxSteps = 0;
        for (int k = 0; k < 360; ++k) {
            const double a = k * M_PI / 180;
            const Transform pa = pose(Vec3::Zero(), Quat(Eigen::AngleAxisd(a, Vec3(0.2, 1, 0.1).normalized())));
            const Transform pb = pose(Vec3(2.2 * std::cos(0.5 * a), 0.3, 2.2 * std::sin(0.5 * a)),
                                      Quat(Eigen::AngleAxisd(-a, Vec3::UnitX())));
            const VClipResult r = checkQuery(ico, pa, box, pb, &cache, nullptr, k % 30 == 0);
            if (k > 0) {
                total += r.steps;
                maxSteps = std::max(maxSteps, r.steps);
            }
        }
        MESSAGE("coherent 1 degree per call: mean ", total / 359.0, " steps, max ", maxSteps);
        CHECK(total / 359.0 < 2.0);
        CHECK(maxSteps <= 6);
    }
}
