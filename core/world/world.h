// A world of rigid convex bodies — boxes, hulls, spheres, capsules — and static ones (ground
// planes, boxes as walls, ramps or a bin), stepped with a fixed time step. One step, in order:
//
//   1. Broad phase: each bounded body's box at its pose, grown by its speculative margin
//      (marginOf: the slop-based speculative distance plus how far the body can move in the
//      step), into sweep and prune, the dynamic tree or the uniform grid (options.broadPhase;
//      core/broadphase); pairs of two static bodies dropped; every dynamic body against every plane
//      whose half-space its grown box reaches.
//   2. Narrow phase: each pair's manifold through core/world/narrow_phase.h with the pair's margin
//      (the sum of both bodies'), at most 4 points, each with its separation (> 0 speculative).
//   3. Persistent manifolds: a pair's manifold of the previous step with the same feature key
//      hands its accumulated impulses to the points of the new one with the same id (warm start;
//      Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005, §6).
//   4. Velocities: v += g dt.
//   5. Sequential impulses (Catto GDC 2005; Box2D v2.4 b2ContactSolver, whose 2D rules these are
//      in 3D): per point the normal impulse then two friction impulses, ACCUMULATED impulses
//      clamped (λ_n >= 0, |λ_t| <= μ λ_n as a disc), velocityIterations sweeps in a fixed order;
//      warm started with the matched impulses. Each point's normal velocity target (v_n >= bias):
//        speculative  s > 0: bias = −s / dt (it may close the gap in this step, not more);
//        bounce       v_n < −restitutionThreshold before the solve and s + v_n dt <= 0:
//                     bias = −e v_n (Newton's law; e = max of the two bodies', μ = √(μ_a μ_b));
//        otherwise 0. No Baumgarte term: penetration is not a velocity, so it adds no energy.
//   6. Positions: x += v dt, q = exp(ω dt / 2) q (core/dynamics/rigid_body.h).
//   7. Position correction by non-linear Gauss–Seidel (Box2D v2.4 b2ContactSolver::
//      SolvePositionConstraints, in 3D): positionIterations sweeps; per point the separation
//      s = (p_B − p_A) · n at the CURRENT poses from the anchors fixed at step 2 (n turning with A),
//      C = clamp(β (s + slop), −maxCorrection, 0), a pseudo-impulse −C / K along n moves and turns
//      both bodies directly. Velocities are untouched (no energy from it but the lift m g Δh).
//
// Conservative advancement of fast bodies is not done: a body faster than its size per step is
// caught by its speculative margin (it grows with |v| dt), as Box2D v3 does for non-bullets.
// Deterministic: fixed iteration counts, sorted pairs, no threads, no unordered containers, no
// clock: the same input gives bit-identical states (tests/core/world/world_test.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "core/dynamics/rigid_body.h"
#include "core/world/narrow_phase.h"
#include "core/world/world_shape.h"

namespace cdlab {

enum class BroadPhaseKind { SweepAndPrune, DynamicTree, Grid };
/// "sap", "tree", "grid".
const char* nameOf(BroadPhaseKind kind);

struct WorldOptions {
    double timeStep = 1.0 / 60.0;  ///< s
    int velocityIterations = 8;
    int positionIterations = 3;
    Vec3 gravity = Vec3(0.0, 0.0, -9.81);
    double slop = 0.005;  ///< penetration left alone (world units): resting contacts stay in the manifold
    double baumgarte = 0.2;       ///< β of step 7, in (0, 1]
    double maxCorrection = 0.2;   ///< the most step 7 moves a point per sweep (world units)
    double restitutionThreshold = 1.0;  ///< approach speeds below this do not bounce (world units / s)
    /// The speculative distance every body's margin starts from (world units; it also absorbs the
    /// slop): contacts this close are in the manifold before they touch.
    double speculativeDistance = 0.02;
    bool warmStart = true;
    BroadPhaseKind broadPhase = BroadPhaseKind::SweepAndPrune;
    double gridCellSize = 0.0;  ///< Grid: cell edge (world units); <= 0: twice the median body diameter
};

/// One body as the world is given it.
struct WorldBodyDesc {
    WorldShape shape;
    Mat3 unitInertia = Mat3::Zero();  ///< inertia for density 1 (WorldShapeBuild::unitInertia)
    double volume = 0.0;              ///< WorldShapeBuild::volume
    bool isStatic = false;            ///< planes are always static
    double density = 1.0;
    Transform pose;  ///< of the body frame (centre of mass); a plane's is ignored
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    double friction = 0.5;     ///< μ >= 0
    double restitution = 0.0;  ///< e in [0, 1]
};

/// A body description from a built shape (its volume and unit inertia copied).
WorldBodyDesc worldBody(const WorldShapeBuild& shape, const Transform& pose, bool isStatic = false,
                        double density = 1.0);

/// A contact point as solved in one step, world frame (anchors where the narrow phase found them).
struct WorldContact {
    WorldContactPoint point;
    double normalImpulse = 0.0;          ///< λ_n accumulated (N·s)
    Vec3 tangentImpulse = Vec3::Zero();  ///< λ_t as a world vector
    bool warmStarted = false;            ///< matched a point of the previous step (same key and id)
    // Solver data (fixed at step 5's start): anchors in the bodies' frames, lever arms, masses.
    Vec3 localA = Vec3::Zero(), localB = Vec3::Zero();
    Vec3 rA = Vec3::Zero(), rB = Vec3::Zero();
    Vec3 tangent1 = Vec3::Zero(), tangent2 = Vec3::Zero();
    double normalMass = 0.0, tangentMass1 = 0.0, tangentMass2 = 0.0, bias = 0.0;
};

struct WorldManifold {
    int a = -1, b = -1;  ///< body indices, a < b
    NarrowMethod method = NarrowMethod::None;
    Vec3 normal = Vec3::UnitZ();       ///< A → B, world, at the narrow phase
    Vec3 localNormal = Vec3::UnitZ();  ///< the normal in A's frame (step 7 turns it with A)
    std::uint64_t featureKey = 0;
    double friction = 0.0, restitution = 0.0;
    std::vector<WorldContact> points;
    std::uint64_t pairKey() const {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
    }
};

/// What one step did (all counts of that step; energies and penetration after it).
struct WorldStepStats {
    int step = 0;
    double time = 0.0;              ///< s, after the step
    int broadPairs = 0;             ///< pairs of grown boxes overlapping (static–static excluded)
    int planePairs = 0;             ///< dynamic body × plane pairs tested
    int narrowTests = 0;            ///< broadPairs + planePairs: pairs the narrow phase ran on
    int manifolds = 0;              ///< pairs with at least one point
    int contactPoints = 0;
    int warmStartedPoints = 0;      ///< points matched to the previous step
    double kinetic = 0.0, potential = 0.0;  ///< J, potential −m g · x summed over dynamic bodies
    double deepestPenetration = 0.0;        ///< max(0, −s) over all points at the poses after step 7
    double deepestBeforeCorrection = 0.0;   ///< the same after step 6
    double energy() const { return kinetic + potential; }
};

/// Why a world refuses its input (message names the body).
enum class WorldStatus { Ok, InvalidOptions, InvalidBody, TooManyBodies };

class World {
public:
    /// Bodies a world takes (the bench's 10 000 and room to spare; memory ~1 kB a body plus its pairs).
    static constexpr int kMaxBodies = 50000;

    /// The world is checked here: status() says whether it runs (step() does nothing otherwise).
    World(std::vector<WorldBodyDesc> bodies, const WorldOptions& options);
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    WorldStatus status() const { return status_; }
    const std::string& message() const { return message_; }
    bool ok() const { return status_ == WorldStatus::Ok; }

    /// Steps 1–7 of the file comment.
    WorldStepStats step();
    /// Steps 1–3 alone (the bench times it apart), then solve() runs 4–7 on their result.
    void collide();
    WorldStepStats solve();

    int bodyCount() const { return static_cast<int>(bodies_.size()); }
    const RigidBody& body(int i) const { return bodies_[i]; }
    const WorldShape& shape(int i) const { return descs_[i].shape; }
    const WorldBodyDesc& desc(int i) const { return descs_[i]; }
    /// The manifolds of the last step, sorted by (a, b).
    const std::vector<WorldManifold>& manifolds() const { return manifolds_; }
    /// The broad phase's pairs of the last step (a < b, sorted), planes excluded.
    const std::vector<std::pair<int, int>>& broadPairs() const { return broadPairs_; }
    /// The grown boxes the broad phase was given in the last step (planes: empty boxes).
    const std::vector<Aabb>& grownBoxes() const { return boxes_; }
    /// Body i's speculative margin at the current velocities (world units).
    double marginOf(int i) const;
    const WorldOptions& options() const { return options_; }
    int stepCount() const { return steps_; }

private:
    struct BroadPhase;
    void broadPhase(WorldStepStats& stats);
    void narrowPhase(WorldStepStats& stats);
    void prepareContacts(double dt);
    void warmStart();
    void solveVelocities();
    void correctPositions();
    double deepestPenetration() const;

    WorldStatus status_ = WorldStatus::Ok;
    std::string message_;
    WorldOptions options_;
    std::vector<WorldBodyDesc> descs_;
    std::vector<RigidBody> bodies_;
    std::vector<int> planes_;  ///< indices of the plane bodies
    std::vector<Aabb> boxes_;
    std::vector<std::pair<int, int>> broadPairs_;
    std::vector<WorldManifold> manifolds_, previous_;
    std::unique_ptr<BroadPhase> broad_;
    WorldStepStats pending_;  ///< collide()'s counts, completed by solve()
    int steps_ = 0;
};

}  // namespace cdlab
