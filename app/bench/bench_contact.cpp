#include "app/bench/bench_contact.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "core/contact/contact_box.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "app/bench/bench_inputs.h"
#include "app/bench/peers/bench_peers.h"

namespace cdlab::demos {

namespace {

double deepest(const ContactManifold& m) {
    double d = 0.0;
    for (const ContactPoint& p : m) d = std::max(d, p.depth);
    return d;
}

Answer manifoldAnswer(const ContactManifold& m) { return Answer{deepest(m), static_cast<int>(m.size())}; }

// Peers on the same pairs, each row's ratio against rows[reference] (cdlab's fast path).
void contactPeerRows(const Settings& settings, std::vector<Row>& rows, const std::string& input,
                     const std::vector<ContactPeerPair>& pairs, const std::string& query, size_t reference,
                     const std::function<double(int, const Answer&)>& error) {
#ifdef CDLAB_BENCH_PEERS
    appendPeerRows(settings, rows, "contact_manifold", input, makeContactPeerRunners(pairs, query),
                   static_cast<int>(pairs.size()), reference, error);
#else
    (void)settings, (void)rows, (void)input, (void)pairs, (void)query, (void)reference, (void)error;
#endif
}

// Box–box on the penetrating oriented boxes of the query rows (same seed): depth against the
// Minkowski hull oracle.
void benchBoxBox(const Settings& settings, std::vector<Row>& rows) {
    const int n = settings.quick ? 200 : 1000;
    const std::vector<OrientedBoxPair> all = boxPairs(n, 0.5, false, 32);
    std::vector<const OrientedBoxPair*> pen;
    std::vector<ConvexPolyhedron> polyA, polyB;
    std::vector<ContactPeerPair> peers;
    for (const OrientedBoxPair& p : all) {
        if (!p.oracle.ok || !p.oracle.inside) continue;
        pen.push_back(&p);
        polyA.push_back(presets::box(p.a.shape.halfExtents));
        polyB.push_back(presets::box(p.b.shape.halfExtents));
        peers.push_back({p.a.shape.halfExtents, p.b.shape.halfExtents, p.a.transform, p.b.transform, nullptr, nullptr});
    }
    const int count = static_cast<int>(pen.size());
    const auto error = [&](int i, const Answer& a) { return relativeError(a.value, pen[i]->oracle.depth, 1.0); };
    const std::string input = "OBB penetrating";
    const size_t reference = rows.size();
    rows.push_back(measure(
        settings, "contact_manifold", input, "box-box fast path", count,
        [&](int i) {
            const OrientedBoxPair& p = *pen[i];
            return manifoldAnswer(
                contactBoxBox(p.a.shape.halfExtents, p.a.transform, p.b.shape.halfExtents, p.b.transform).manifold);
        },
        error));
    rows.push_back(measure(
        settings, "contact_manifold", input, "general SAT + clipping", count,
        [&](int i) {
            return manifoldAnswer(contactPolyhedra(polyA[i], pen[i]->a.transform, polyB[i], pen[i]->b.transform).manifold);
        },
        error));
    rows.back().ratio = rows.back().nsMin / rows[reference].nsMin;
    contactPeerRows(settings, rows, input, peers, "box_box", reference, error);
}

// A box against a plane, the depth against the lowest corner in long double. resting = false: a
// random rotation, the plane through a point near the centre with a random normal (cut corners:
// edge crossings, the full reduction); true: the ground z = 0 under a box lying on a face, tilted
// by up to 3°, its lowest face sunk by 1% of its height: two to four corners below (2 in ~72% of
// the poses, 3 in ~24%, 4 in ~3%) and the crossings of their edges, the box settling on the ground.
void benchBoxPlane(const Settings& settings, bool resting, std::vector<Row>& rows) {
    const int n = settings.quick ? 200 : 1000;
    std::mt19937_64 rng(resting ? 53 : 52);
    std::uniform_real_distribution<double> half(0.2, 1.0), shift(-0.3, 0.3), tilt(-0.05, 0.05);
    struct Case {
        Vec3 h;
        Transform pose;
        Plane plane;
        double depth = 0.0;  // oracle
    };
    std::vector<Case> cases;
    for (int i = 0; i < n; ++i) {
        Case c;
        c.h = Vec3(half(rng), half(rng), half(rng));
        Vec3 normal = Vec3::UnitZ();
        if (resting) {
            c.pose.rotation = Quat(Eigen::AngleAxisd(tilt(rng), Vec3::UnitX())) *
                              Quat(Eigen::AngleAxisd(tilt(rng), Vec3::UnitY())) *
                              Quat(Eigen::AngleAxisd(6.0 * shift(rng), Vec3::UnitZ()));
            c.pose.position = Vec3(shift(rng), shift(rng), 0.99 * c.h.z());
        } else {
            c.pose.rotation = randomRotation(rng);
            c.pose.position = Vec3(shift(rng), shift(rng), shift(rng));
            normal = randomUnit(rng);
        }
        c.plane = Plane{normal, 0.0};
        long double low = INFINITY;
        for (int k = 0; k < 8; ++k) {
            const Vec3 x = c.pose.apply(Vec3((k & 1) ? c.h.x() : -c.h.x(), (k & 2) ? c.h.y() : -c.h.y(),
                                             (k & 4) ? c.h.z() : -c.h.z()));
            long double s = 0;
            for (int j = 0; j < 3; ++j) s += (long double)normal[j] * x[j];
            low = std::min(low, s);
        }
        c.depth = double(std::max(0.0L, -low));
        cases.push_back(c);
    }
    std::vector<ConvexPolyhedron> poly;
    for (const Case& c : cases) poly.push_back(presets::box(c.h));
    const auto error = [&](int i, const Answer& a) { return relativeError(a.value, cases[i].depth, 1.0); };
    const std::string input = resting ? "box resting on plane" : "box cut by plane";
    const size_t reference = rows.size();
    rows.push_back(measure(
        settings, "contact_manifold", input, "box-plane fast path", n,
        [&](int i) { return manifoldAnswer(contactBoxPlane(cases[i].h, cases[i].pose, cases[i].plane).manifold); },
        error));
    rows.push_back(measure(
        settings, "contact_manifold", input, "general plane contact", n,
        [&](int i) {
            return manifoldAnswer(contactPolyhedronPlane(poly[i], cases[i].pose, cases[i].plane).manifold);
        },
        error));
    rows.back().ratio = rows.back().nsMin / rows[reference].nsMin;
    // The floor: the deepest corner alone (no manifold), a plain loop over the 8 corners with the
    // rotation as a matrix. (Rotating each corner by the quaternion measured 180 ns here, not 50:
    // in this folder's unity build GCC keeps Eigen's quaternion rotation out of line.)
    rows.push_back(measure(
        settings, "contact_manifold", input, "8-corner loop, deepest only", n,
        [&](int i) {
            const Case& c = cases[i];
            const Eigen::Matrix3d rotation = c.pose.rotation.toRotationMatrix();
            double low = INFINITY;
            for (int k = 0; k < 8; ++k) {
                const Vec3 x = c.pose.position + rotation * Vec3((k & 1) ? c.h.x() : -c.h.x(),
                                                                 (k & 2) ? c.h.y() : -c.h.y(),
                                                                 (k & 4) ? c.h.z() : -c.h.z());
                low = std::min(low, c.plane.normal.dot(x) - c.plane.offset);
            }
            return Answer{std::max(0.0, -low), 1};
        },
        error));
    rows.back().ratio = rows.back().nsMin / rows[reference].nsMin;
#ifdef CDLAB_BENCH_PEERS
    std::vector<PlanePeerCase> peerCases;
    for (const Case& c : cases) peerCases.push_back({c.h, c.pose, c.plane.normal, c.plane.offset});
    appendPeerRows(settings, rows, "contact_manifold", input, makePlanePeerRunners(peerCases), n, reference, error);
#endif
}

// Hull pairs (16 / 64 points on ellipsoids, centres 0.4 apart): the general SAT beside Bullet's
// hull clipping, depth against the Minkowski hull oracle.
void benchHullHull(const Settings& base, int nv, std::vector<Row>& rows) {
    const int n = base.quick ? 100 : (nv >= 64 ? 300 : 1000);
    // Three repetitions of the set: a 64-vertex hull pair costs Bullet's clipping ~15 ms (its
    // separating-axis search projects both hulls on every edge pair), 100k calls would take hours.
    Settings settings = base;
    settings.targetQueries = 3 * n;
    const std::vector<PolyPair> all = polyPairs(nv, n, 0.4, 60 + nv);
    std::vector<const PolyPair*> pen;
    std::vector<ConvexPolyhedron> hullA, hullB;
    std::vector<ContactPeerPair> peers;
    for (const PolyPair& p : all) {
        const HullResult ha = convexHull(p.va), hb = convexHull(p.vb);
        if (!p.oracle.ok || !p.oracle.inside || !ha.ok() || !hb.ok()) continue;
        pen.push_back(&p);
        hullA.push_back(ha.polyhedron);
        hullB.push_back(hb.polyhedron);
        peers.push_back({Vec3::Zero(), Vec3::Zero(), Transform{}, Transform{}, &p.va, &p.vb});
    }
    const int count = static_cast<int>(pen.size());
    const auto error = [&](int i, const Answer& a) { return relativeError(a.value, pen[i]->oracle.depth, 1.0); };
    const std::string input = "hull" + std::to_string(nv) + " penetrating";
    const size_t reference = rows.size();
    rows.push_back(measure(
        settings, "contact_manifold", input, "general SAT + clipping", count,
        [&](int i) { return manifoldAnswer(contactPolyhedra(hullA[i], Transform{}, hullB[i], Transform{}).manifold); },
        error));
    contactPeerRows(settings, rows, input, peers, "hull_hull", reference, error);
}

}  // namespace

void benchContacts(const Settings& settings, std::vector<Row>& rows) {
    std::cerr << "cdlab bench: contact manifolds\n";
    benchBoxBox(settings, rows);
    for (bool resting : {true, false}) benchBoxPlane(settings, resting, rows);
    for (int nv : {16, 64}) benchHullHull(settings, nv, rows);
}

}  // namespace cdlab::demos
