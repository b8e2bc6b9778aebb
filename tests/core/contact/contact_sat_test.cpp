// SAT contact of two polyhedra: depth against a long double Minkowski-difference facet oracle
// (verification/minkowski_facet_oracle.h) and EPA, brute-force SAT over all edge pairs (no Gauss-map pruning),
// stacked boxes (4 points), crossed edges (1 point), manifold points inside both bodies, offsets,
// scales, invalid input.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/contact/contact_sat.h"
#include "core/geometry/polyhedron_presets.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/core/contact/random_pose.h"

using namespace cdlab;

namespace {

std::vector<Vec3> world(const ConvexPolyhedron& m, const Transform& t) {
    std::vector<Vec3> v;
    for (const auto& x : m.vertices()) v.push_back(t.apply(x.position));
    return v;
}

using cdlab::test::insideBody;

// Brute-force SAT: every face normal of both and every edge cross product (no pruning), both
// orientations, separation = gap of the projection intervals. Long double, relative to a_0.
long double bruteSatSeparation(const ConvexPolyhedron& ma, const Transform& ta, const ConvexPolyhedron& mb,
                               const Transform& tb) {
    const std::vector<Vec3> a = world(ma, ta), b = world(mb, tb);
    std::vector<Vec3> axes;
    for (int f = 0; f < ma.faceCount(); ++f) axes.push_back(ta.rotate(ma.face(f).normal));
    for (int f = 0; f < mb.faceCount(); ++f) axes.push_back(tb.rotate(mb.face(f).normal));
    for (int i = 0; i < ma.edgeCount(); ++i)
        for (int j = 0; j < mb.edgeCount(); ++j) {
            const auto [a0, a1] = ma.edgeVertices(i);
            const auto [b0, b1] = mb.edgeVertices(j);
            const Vec3 c = (a[a1] - a[a0]).cross(b[b1] - b[b0]);
            if (c.norm() > 1e-6 * (a[a1] - a[a0]).norm() * (b[b1] - b[b0]).norm()) axes.push_back(c.normalized());
        }
    long double best = -INFINITY;
    for (const Vec3& u : axes)
        for (const Vec3& s : {u, Vec3(-u)}) best = std::max(best, -test::supportValueL(a, b, s));
    return best;
}

}  // namespace

TEST_SUITE("contact_sat") {
    TEST_CASE("stacked boxes: face contact, 4 points of equal depth, touching") {
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                const ConvexPolyhedron ground = presets::box(Vec3(2, 2, 0.5) * scale);
                const ConvexPolyhedron cube = presets::box(Vec3(0.5, 0.5, 0.5) * scale);
                Transform tg, tc;
                tg.position = Vec3(offset, offset, -offset);
                tc.position = tg.position + Vec3(0.1, -0.2, 0.99) * scale;  // 1% of the cube sunk
                tc.rotation = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
                SatContactTrace tr;
                const SatContactResult r = contactPolyhedra(ground, tg, cube, tc, {}, &tr);
                CAPTURE(scale);
                CAPTURE(offset);
                REQUIRE(r.status == SatContactStatus::Penetrating);
                CHECK(r.normal.isApprox(Vec3(0, 0, 1), 1e-12));
                CHECK(r.depth == doctest::Approx(0.01 * scale).epsilon(1e-6));
                CHECK(r.axisKind == SatAxisKind::FaceA);
                REQUIRE(r.manifold.size() == 4);
                for (const ContactPoint& c : r.manifold) {
                    CHECK(c.depth == doctest::Approx(0.01 * scale).epsilon(1e-6));
                    CHECK((c.pointA - c.pointB - c.depth * r.normal).norm() <= 1e-9 * (scale + offset));
                }
                CHECK(tr.edgePairsPruned + tr.edgePairsParallel + (int)tr.axes.size() - ground.faceCount() -
                          cube.faceCount() ==
                      tr.edgePairsTotal);
                tc.position.z() = tg.position.z() + 1.0 * scale;
                const SatContactResult t = contactPolyhedra(ground, tg, cube, tc);
                CHECK(t.status == SatContactStatus::Touching);
                CHECK(t.manifold.size() == 4);
            }
        }
    }

    TEST_CASE("crossed edges: edge-edge axis, one point") {
        const ConvexPolyhedron box = presets::box(Vec3(2, 0.5, 0.5));
        Transform ta, tb;
        ta.rotation = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()));
        tb.rotation =
            Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()));
        tb.position = Vec3(0, 0, std::sqrt(2.0) - 0.01);
        const SatContactResult r = contactPolyhedra(box, ta, box, tb);
        REQUIRE(r.status == SatContactStatus::Penetrating);
        CHECK(r.axisKind == SatAxisKind::EdgeEdge);
        CHECK(r.featureA.type == FeatureType::Edge);
        REQUIRE(r.manifold.size() == 1);
        CHECK(r.depth == doctest::Approx(0.01).epsilon(1e-9));
        CHECK(r.normal.isApprox(Vec3(0, 0, 1), 1e-12));
        CHECK(r.manifold[0].pointA.isApprox(Vec3(0, 0, std::sqrt(0.5)), 1e-12));
    }

    TEST_CASE("random pairs: SAT depth = Minkowski facet oracle = EPA, pruning loses nothing") {
        std::mt19937_64 rng(5);
        const ConvexPolyhedron bodies[] = {presets::box(Vec3(0.6, 0.4, 0.3)), presets::tetrahedron(0.7),
                                           presets::octahedron(0.6), presets::prism(5, 0.5, 0.3),
                                           presets::randomHull(9, 21)};
        int penetrating = 0, separated = 0;
        for (double offset : {0.0, 1e5}) {
            for (const ConvexPolyhedron& a : bodies) {
                for (const ConvexPolyhedron& b : bodies) {
                    for (int k = 0; k < 8; ++k) {
                        const Vec3 c = Vec3::Constant(offset);
                        const Transform ta = test::randomPose(rng, c, 0.0), tb = test::randomPose(rng, c, 0.45);
                        SatContactTrace tr;
                        const SatContactResult r = contactPolyhedra(a, ta, b, tb, {}, &tr);
                        const std::vector<Vec3> wa = world(a, ta), wb = world(b, tb);
                        const test::HullOracle o = test::hullOracle(wa, wb);
                        const long double brute = bruteSatSeparation(a, ta, b, tb);
                        const double tol = 1e-11 * (1 + offset);
                        if (o.inside) {
                            ++penetrating;
                            CHECK(r.colliding());
                            CHECK(-r.separation == doctest::Approx((double)o.depth).epsilon(1e-9).scale(tol));
                            CHECK(std::abs(r.separation - (double)brute) <= tol);
                            CHECK(r.depth >= -r.separation - tol);
                            CHECK(r.depth <= -r.separation * 1.02 + 3 * r.tolerance + tol);
                            const EpaResult e = penetration(PolytopeShape(wa), PolytopeShape(wb));
                            if (e.status == EpaStatus::Penetrating)
                                CHECK(std::abs(e.depth + r.separation) <= 1e-9 + tol);
                            REQUIRE(!r.manifold.empty());
                            CHECK(r.manifold.size() <= 4);
                            for (const ContactPoint& p : r.manifold) {
                                CHECK(insideBody(a, ta, p.pointA, 1e-9 + tol));
                                CHECK(insideBody(b, tb, p.pointB, 1e-9 + tol));
                                CHECK(p.depth <= r.depth + 1e-12 + tol);
                            }
                        } else if (o.distance > 1e-9) {
                            ++separated;
                            CHECK(r.status == SatContactStatus::Separated);
                            CHECK(r.separation <= (double)o.distance + tol);  // a lower bound of the distance
                            CHECK(r.manifold.empty());
                        }
                    }
                }
            }
        }
        CHECK(penetrating > 60);
        CHECK(separated > 60);
    }

    // The untraced call finds its supports by descent and its edge pairs by walking each arc of A
    // over B's Gauss map, skipping the arcs whose pairs are bounded below what the axis choice can
    // use (SatContactOptions::pruneEdgeArcs) and the faces bounded below their family's best
    // (pruneFaceAxes); the traced call tests every vertex and every edge pair in index order.
    // Generic poses: the same axis, separation, features and manifold, bit for bit. Degenerate
    // poses (parallel faces and edges, B at A's pose: axes tied in exact arithmetic, their rounded
    // values apart by ulps): the same status and separation and depth to rounding, whichever of
    // the tied axes each picks.
    TEST_CASE("untraced query (descent, Gauss-map walk) = traced query (every vertex, every edge pair)") {
        std::mt19937_64 rng(11);
        std::vector<ConvexPolyhedron> bodies = {presets::box(Vec3(0.6, 0.4, 0.3)), presets::box(Vec3(0.5, 0.5, 0.5)),
                                                presets::tetrahedron(0.7), presets::octahedron(0.6),
                                                presets::prism(5, 0.5, 0.3), presets::prism(24, 0.5, 0.2)};
        for (int n : {8, 16, 64, 200}) bodies.push_back(presets::randomHull(n, 100 + n));
        int generic = 0, degenerate = 0, edgeAxes = 0, faceAxes = 0, pruned = 0, facesPruned = 0;
        const auto compare = [&](const ConvexPolyhedron& a, const Transform& ta, const ConvexPolyhedron& b,
                                 const Transform& tb, bool isGeneric) {
            SatContactTrace tr;
            const SatContactResult all = contactPolyhedra(a, ta, b, tb, {}, &tr);
            const SatContactResult walk = contactPolyhedra(a, ta, b, tb);  // edges pruned by the bound
            SatContactOptions unpruned;
            unpruned.pruneEdgeArcs = unpruned.pruneFaceAxes = false;
            const SatContactResult walkAll = contactPolyhedra(a, ta, b, tb, unpruned);
            SatContactOptions facesOnly;  // face axes pruned, every crossing edge pair tested
            facesOnly.pruneEdgeArcs = false;
            const SatContactResult walkFaces = contactPolyhedra(a, ta, b, tb, facesOnly);
            REQUIRE(walk.status == all.status);
            if (!isGeneric) {
                ++degenerate;
                const double ulps = 1e-14 * (1.0 + ta.position.cwiseAbs().maxCoeff());
                CHECK(std::abs(walk.separation - all.separation) <= ulps);
                CHECK(std::abs(walk.depth - all.depth) <= std::abs(all.depth) * 0.021 + ulps);  // within the face bias
                return;
            }
            ++generic;
            // The same pairs tested without the pruning: a walk that missed crossings tests fewer,
            // one that fell back to the all-pairs test for an edge tests its pairs twice. With it,
            // fewer pairs and (below) the same answer bit for bit.
            CHECK(walkAll.axesTested == all.axesTested);
            CHECK(walk.axesTested <= all.axesTested);
            pruned += walk.axesTested < all.axesTested;
            CHECK(walkFaces.axesTested <= all.axesTested);
            facesPruned += walkFaces.axesTested < all.axesTested;
            CHECK(walkFaces.separation == all.separation);
            CHECK(walkFaces.depth == all.depth);
            CHECK(walkFaces.normal == all.normal);
            CHECK(walkFaces.featureA.index == all.featureA.index);
            CHECK(walkFaces.featureB.index == all.featureB.index);
            CHECK(walk.separation == all.separation);
            CHECK(walk.depth == all.depth);
            REQUIRE(walk.axisKind == all.axisKind);
            CHECK(walk.featureA.index == all.featureA.index);
            CHECK(walk.featureB.index == all.featureB.index);
            CHECK(walk.normal == all.normal);
            REQUIRE(walk.manifold.size() == all.manifold.size());
            for (size_t i = 0; i < all.manifold.size(); ++i) {
                CHECK(walk.manifold[i].pointA == all.manifold[i].pointA);
                CHECK(walk.manifold[i].pointB == all.manifold[i].pointB);
            }
            (all.axisKind == SatAxisKind::EdgeEdge ? edgeAxes : faceAxes) += all.colliding();
        };
        for (const ConvexPolyhedron& a : bodies)
            for (const ConvexPolyhedron& b : bodies)
                for (int k = 0; k < 12; ++k) {
                    // Random poses (generic), then poses sharing a rotation, axis-aligned on a grid,
                    // and B at A's own pose (degenerate).
                    const Vec3 c = Vec3::Constant(k % 4 == 3 ? 1e5 : 0.0);
                    Transform ta = test::randomPose(rng, c, 0.0), tb = test::randomPose(rng, c, 0.4);
                    bool isGeneric = true;
                    if (k % 3 == 1) tb.rotation = ta.rotation, isGeneric = false;
                    if (k % 6 == 2) {
                        ta.rotation = tb.rotation = Quat::Identity();
                        tb.position = c + Vec3(0.5 * (k % 4), 0.25, 0.0);
                        isGeneric = false;
                    }
                    if (k == 11) tb = ta, isGeneric = false;
                    compare(a, ta, b, tb, isGeneric);
                }
        // Far from the origin, B's offset from A rounded to ulps of 1e7: still the same pairs.
        for (int k = 0; k < 40; ++k) {
            const Vec3 c(1e7, -3e6, 2e6);
            compare(bodies[6 + k % 4], test::randomPose(rng, c, 0.0), bodies[7 + k % 3], test::randomPose(rng, c, 0.3), true);
        }
        CHECK(generic == 5 * int(bodies.size() * bodies.size()) + 40);
        CHECK(degenerate == 7 * int(bodies.size() * bodies.size()));
        CHECK(edgeAxes > 50);  // both kinds of contact are compared, not only faces
        CHECK(pruned > generic / 4);  // the bound skips edges on a good share of the poses
        CHECK(facesPruned > generic / 2);  // and faces on most
        CHECK(faceAxes > 200);
    }

    // The prunings bound a face's separation by the ball about the other body's vertex mean inside
    // its face planes; a valid mesh's faces are planar only within its scale tolerance, relative to
    // its own body-frame coordinates. A reviewer's body: a box whose roof is two faces sloped by 1e-4,
    // their vertices 0.8 of that tolerance off plane, the mesh 2^20 from its body origin and posed near
    // the world's. With a margin measured in the posed coordinates the pruned query chose face A 0 at
    // depth 0.20010206 where the unpruned and traced ones choose face A 5 at 0.20010007.
    TEST_CASE("a ridge far from its body origin: pruned = unpruned = traced") {
        const Vec3 o = Vec3::Constant(1048576.0);
        const double slope = 1e-4, offPlane = 0x1.99999ap-17;
        const double xs[5] = {-1, -0.5, 0, 0.5, 1};
        const double zs[5] = {1, 1 + slope / 2 + offPlane, 1 + slope, 1 + slope / 2 + offPlane, 1};
        std::vector<Vec3> p = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
        for (int side = 0; side < 2; ++side)
            for (int i = 0; i < 5; ++i) p.push_back(Vec3(xs[i], side ? 1 : -1, zs[i]));
        for (Vec3& x : p) x += o;
        const std::vector<std::vector<int>> faces = {{0, 3, 2, 1},          {4, 5, 6, 11, 10, 9},
                                                     {6, 7, 8, 13, 12, 11}, {0, 1, 8, 7, 6, 5, 4},
                                                     {3, 9, 10, 11, 12, 13, 2}, {0, 4, 9, 3},
                                                     {1, 2, 13, 8}};
        const auto built = ConvexPolyhedron::fromFaces(p, faces);
        REQUIRE(built.ok());
        const ConvexPolyhedron& b = built.polyhedron;
        REQUIRE(b.validate().ok());
        const ConvexPolyhedron a = presets::box(Vec3(1, 1, 1));
        const Transform tb{-o, Quat::Identity()};
        const Transform ta{Vec3(-0x1.ccc61d853c5c2p+0, -0x1.31e83898695ep-4, 0x1.ccccccccccccdp+0),
                           Quat(0x1.ffffffffffff5p-1, 0x1.75c1df2c02536p-25, -0x1.570d5c0aa9152p-29,
                                -0x1.a50398739de82p-26)};
        SatContactOptions unprunedOptions;
        unprunedOptions.pruneFaceAxes = unprunedOptions.pruneEdgeArcs = false;
        SatContactTrace trace;
        const SatContactResult pruned = contactPolyhedra(a, ta, b, tb);
        const SatContactResult unpruned = contactPolyhedra(a, ta, b, tb, unprunedOptions);
        const SatContactResult traced = contactPolyhedra(a, ta, b, tb, {}, &trace);
        for (const SatContactResult* r : {&pruned, &traced}) {
            CHECK(r->featureA.index == unpruned.featureA.index);
            CHECK(r->featureB.index == unpruned.featureB.index);
            CHECK(r->depth == unpruned.depth);
            CHECK(r->normal == unpruned.normal);
        }
        CHECK(unpruned.featureA.index == 5);  // the face the traced query tests every axis to find
        CHECK(unpruned.depth == doctest::Approx(0.20010007155414211).epsilon(1e-12));
    }

    // A negative faceBiasRelative lets an edge axis win below the face axes' best, where the edge
    // pruning's bound would skip it: the pruning is off then (a reviewer's pose, where it picked
    // face A at depth 0.027 instead of the edge pair at 0.051).
    TEST_CASE("negative face bias: the pruned walk answers as the unpruned one") {
        const ConvexPolyhedron a = presets::randomHull(20, 10, presets::RandomHullKind::InBall);
        const ConvexPolyhedron b = presets::octahedron(0.6);
        const Quat q(0x1.1843c16f2e8c1p-3, -0x1.c912c94f0356fp-1, 0x1.1e91dbed9c44cp-2, 0x1.4d652e6d22e75p-2);
        const Transform ta{Vec3(-0x1.29a021e73b885p+0, -0x1.52f17b850a0fp-2, -0x1.307152a396a73p-3), q};
        const Transform tb{Vec3(-0x1.d1d15a743debp+0, -0x1.95531242ee908p-2, -0x1.5acfd43724a9cp-1), q};
        for (const double bias : {-0.5, -0.02, 0.0, 0.02}) {
            SatContactOptions pruned, unpruned;
            pruned.faceBiasRelative = unpruned.faceBiasRelative = bias;
            pruned.maxPoints = unpruned.maxPoints = 1;
            unpruned.pruneEdgeArcs = false;
            const SatContactResult p = contactPolyhedra(a, ta, b, tb, pruned), u = contactPolyhedra(a, ta, b, tb, unpruned);
            CAPTURE(bias);
            CHECK(p.axisKind == u.axisKind);
            CHECK(p.depth == u.depth);
            CHECK(p.normal == u.normal);
            CHECK(p.featureA.index == u.featureA.index);
            CHECK(p.featureB.index == u.featureB.index);
        }
        SatContactOptions negative;
        negative.faceBiasRelative = -0.5;
        CHECK(contactPolyhedra(a, ta, b, tb, negative).axisKind == SatAxisKind::EdgeEdge);  // the pose still tests it
    }

    // A body without volume (a square as two faces back to back) is accepted by fromFaces; its
    // folded edges have no Gauss arc to walk, so both queries test every pair and agree.
    TEST_CASE("flat body: untraced = traced") {
        const std::vector<Vec3> square = {Vec3(-0.3, -0.3, 0), Vec3(0.3, -0.3, 0), Vec3(0.3, 0.3, 0), Vec3(-0.3, 0.3, 0)};
        const PolyhedronBuild flat = ConvexPolyhedron::fromFaces(square, {{0, 1, 2}, {0, 2, 3}, {1, 0, 3}, {1, 3, 2}});
        REQUIRE(flat.ok());
        const ConvexPolyhedron box = presets::box(Vec3(0.5, 0.5, 0.5));
        std::mt19937_64 rng(4);
        for (int k = 0; k < 50; ++k) {
            const Transform tf = test::randomPose(rng, Vec3::Zero(), k < 10 ? 0.0 : 0.5), tb = test::randomPose(rng, Vec3::Zero(), 0.2);
            for (const bool flatFirst : {true, false}) {
                const ConvexPolyhedron& a = flatFirst ? flat.polyhedron : box;
                const ConvexPolyhedron& b = flatFirst ? box : flat.polyhedron;
                const Transform& ta = flatFirst ? tf : tb;
                const Transform& tb2 = flatFirst ? tb : tf;
                SatContactTrace tr;
                const SatContactResult all = contactPolyhedra(a, ta, b, tb2, {}, &tr);
                const SatContactResult walk = contactPolyhedra(a, ta, b, tb2);
                CHECK(walk.status == all.status);
                CHECK(walk.separation == all.separation);
                CHECK(walk.axesTested == all.axesTested);
            }
        }
        // A square at the centre of a larger box is inside it.
        CHECK(contactPolyhedra(flat.polyhedron, {}, box, {}).colliding());
    }

    TEST_CASE("invalid input") {
        const ConvexPolyhedron box = presets::box(Vec3(1, 1, 1));
        Transform t, bad;
        bad.position.y() = NAN;
        CHECK(contactPolyhedra(box, t, box, bad).status == SatContactStatus::InvalidInput);
        CHECK(contactPolyhedra(ConvexPolyhedron{}, t, box, t).status == SatContactStatus::InvalidInput);
        // A mesh with a NaN vertex never reaches the contact: fromFaces refuses it (empty polyhedron).
        std::vector<Vec3> corners = box.positions();
        corners[3].x() = NAN;
        std::vector<std::vector<int>> faces;
        for (int f = 0; f < box.faceCount(); ++f) faces.push_back(box.faceVertices(f));
        const PolyhedronBuild broken = ConvexPolyhedron::fromFaces(corners, faces);
        CHECK_FALSE(broken.ok());
        CHECK(contactPolyhedra(broken.polyhedron, t, box, t).status == SatContactStatus::InvalidInput);
        bad = Transform{};
        bad.rotation = Quat(0, 0, 0, 0);
        CHECK(contactPolyhedra(box, bad, box, t).status == SatContactStatus::InvalidInput);
    }
}
