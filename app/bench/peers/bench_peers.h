// Peer libraries for `cdlab bench` (optional): libccd (GJK intersect, GJK+EPA, MPR) and Bullet in
// double precision (btGjkEpaSolver2 Distance / Penetration), run on the same inputs as cdlab.
// Implemented in app/bench/peers/bench_peers.cpp, compiled only when CMake finds the packages
// (pkg-config ccd / bullet-float64); the bench then defines CDLAB_BENCH_PEERS.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "core/geometry/shapes.h"

namespace cdlab::demos {

/// One polytope pair: world-frame vertices and cdlab's support mappings of both shapes.
/// The mean of a vertex set: a point inside its hull, where MPR starts (libccd's center callbacks
/// and cdlab's mprIntersect in the bench get the same one).
inline Vec3 vertexCentroid(const std::vector<Vec3>& v) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : v) c += x;
    return c / static_cast<double>(v.size());
}

struct PeerPair {
    const std::vector<Vec3>* va = nullptr;
    const std::vector<Vec3>* vb = nullptr;
    const PolytopeShape* a = nullptr;
    const PolytopeShape* b = nullptr;
};

/// One query answered by a peer: the value compared with the oracle (distance, depth, or 1 / 0
/// for intersect) and the iterations if the peer reports them (else 0).
struct PeerAnswer {
    double value = 0.0;
    int iterations = 0;
};

/// A peer method over the pairs given to makePeerRunners: run(i) answers pair i.
struct PeerRunner {
    std::string method;  ///< e.g. "libccd GJK+EPA", "Bullet GJK"
    std::function<PeerAnswer(int)> run;
};

/// Peer runners for `query` ("gjk_distance", "gjk_intersect", "epa_depth") on `pairs`, which must
/// outlive the runners. libccd calls cdlab's PolytopeShape::support (the same support function);
/// Bullet uses btConvexHullShape on the same vertices with margin 0 (its own vertex loop).
std::vector<PeerRunner> makePeerRunners(const std::vector<PeerPair>& pairs, const std::string& query);

/// One pair for the contact-manifold rows: boxes (half extents, world poses) or hulls (world-frame
/// vertices, identity poses).
struct ContactPeerPair {
    Vec3 halfA = Vec3::Zero(), halfB = Vec3::Zero();
    Transform ta, tb;
    const std::vector<Vec3>* hullA = nullptr;
    const std::vector<Vec3>* hullB = nullptr;
};

/// Peer runners for the contact rows: "box_box" (Bullet's btBoxBoxDetector, and its general hull
/// clipping btPolyhedralContactClipping on the same boxes) and "hull_hull" (the hull clipping).
/// Answer: the deepest reported penetration (0 when no contact), iterations = contact points.
std::vector<PeerRunner> makeContactPeerRunners(const std::vector<ContactPeerPair>& pairs, const std::string& query);

/// One box on a plane for the box–plane rows: the box (half extents, world pose) against the solid
/// half-space normal · x <= offset.
struct PlanePeerCase {
    Vec3 half = Vec3::Ones();
    Transform pose;
    Vec3 normal = Vec3::UnitZ();
    double offset = 0.0;
};

/// Bullet's box–static plane algorithm (btConvexPlaneCollisionAlgorithm, what its dispatcher runs
/// for a box on a btStaticPlaneShape), one persistent algorithm and manifold per case as in a
/// simulation, the manifold cleared before each call: with one point (Bullet's default) and with
/// its multipoint perturbation (setPlaneConvexMultipointIterations(3, 3)). Answer: the deepest
/// penetration (0 when none) and the manifold's point count. The count is not cdlab's: Bullet keeps
/// corners up to its contact breaking threshold above the plane (0.02 times the box's size), and
/// reports corners only, where cdlab reports submerged corners and edge crossings.
std::vector<PeerRunner> makePlanePeerRunners(const std::vector<PlanePeerCase>& cases);

/// A peer broad phase kept across frames: frame(boxes) gives every object its box for this frame
/// (object i = boxes[i]; the same count every frame) and updates the peer's pairs; returns the
/// pairs the peer holds after the frame (its own notion: Bullet's cache holds pairs of its fattened
/// boxes, some of which no longer overlap).
struct PeerBroadPhase {
    std::string method;
    std::function<std::int64_t(const std::vector<Aabb>&)> frame;
};

/// One body of the many-body world rows (app/bench/bench_world.cpp), as cdlab's world holds it:
/// body frame at the centre of mass, principal-axis-free inertia reduced to its diagonal (Bullet
/// takes principal moments only).
struct PeerWorldBody {
    enum class Kind { Box, Hull, Sphere, Capsule, Plane };
    Kind kind = Kind::Box;
    Vec3 half = Vec3::Zero();                 ///< Box
    const std::vector<Vec3>* hull = nullptr;  ///< Hull: vertices in the body frame
    double radius = 0.0, halfHeight = 0.0;    ///< Sphere, Capsule (segment along the body's y)
    Vec3 planeNormal = Vec3::UnitZ();         ///< Plane: n · x <= offset solid
    double planeOffset = 0.0;
    bool isStatic = false;
    double mass = 0.0;
    Vec3 inertiaDiagonal = Vec3::Zero();
    Transform pose;
    double friction = 0.5, restitution = 0.0;  ///< cdlab's per-body values (see makeBulletWorld)
};

/// A peer world kept across steps: step() advances it by one fixed step and returns the thread-CPU
/// milliseconds of the whole step; collideMs receives those of its collision detection (broad +
/// narrow phase); contactPoints() and pairs() count what the last step held, deepest() its deepest point.
struct PeerWorld {
    std::string method;
    std::function<double(double& collideMs)> step;
    std::function<int()> contactPoints;
    std::function<int()> pairs;
    std::function<double()> deepest;  ///< the deepest penetration among the last step's points (>= 0)
};

/// Bullet's btDiscreteDynamicsWorld (btDbvtBroadphase, btCollisionDispatcher with the default
/// configuration, btSequentialImpulseConstraintSolver) with the same bodies, time step, gravity and
/// velocity iterations, sleeping off. Shapes: btBoxShape, btSphereShape, btCapsuleShape (y axis),
/// btConvexHullShape with margin 0.001 and polyhedral features (so hull pairs go through its SAT
/// clipping, as cdlab's do), btStaticPlaneShape. Bullet multiplies two bodies' friction and
/// restitution where cdlab takes √(μ_a μ_b) and max(e_a, e_b): each body gets √μ (the products
/// then equal cdlab's friction) and its e. Nothing when Bullet is not installed.
std::unique_ptr<PeerWorld> makeBulletWorld(const std::vector<PeerWorldBody>& bodies, double timeStep, int iterations,
                                           const Vec3& gravity);

/// Bullet's btDbvtBroadphase (two dynamic AABB trees with fattened boxes, incremental
/// re-optimisation, a hashed pair cache), or nothing when Bullet is not installed.
std::unique_ptr<PeerBroadPhase> makeBulletDbvtBroadPhase();

}  // namespace cdlab::demos
