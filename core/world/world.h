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
//      A pair apart last step is first tested on the axis that separated it then (the gap of the
//      two shapes' supports along it): still more than the margin, the narrow phase is skipped.
//   3. Persistent manifolds: a pair's manifold of the previous step with the same feature key
//      hands its accumulated impulses to the points of the new one with the same id (warm start;
//      Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005, §6).
//   4. Velocities: v += g dt.
//   5. Sequential impulses (Catto GDC 2005; Box2D v2.4 b2ContactSolver, whose 2D rules these are
//      in 3D): per point two friction impulses (inside the cone of its current normal impulse)
//      then the normal impulse, ACCUMULATED impulses
//      clamped (λ_n >= 0, |λ_t| <= μ λ_n as a disc), velocityIterations sweeps, even ones in
//      order and odd ones in reverse (symmetric Gauss–Seidel: a fixed order leans a stack toward
//      the corner solved first); warm started with the matched impulses. Both bodies take a point's
//      impulse at the middle of its two surface points. Each point's normal velocity target (v_n >= bias):
//        speculative  s > 0: bias = −s / dt (it may close the gap in this step, not more);
//        bounce       s <= speculativeDistance, approaching faster than restitutionThreshold and
//                     reaching contact in the step (s + v dt <= 0): bias = −e v (Newton's law;
//                     e = max of the two bodies', μ = √(μ_a μ_b)), v the approach speed now or,
//                     if the point closed a wider gap last step, then (a wider gap only closes);
//        otherwise 0. No Baumgarte term: penetration is not a velocity, so it adds no energy.
//   6. Positions: x += v dt, q = exp(ω dt / 2) q (core/dynamics/rigid_body.h).
//   7. Position correction by non-linear Gauss–Seidel (Box2D v2.4 b2ContactSolver::
//      SolvePositionConstraints, in 3D): positionIterations sweeps; per point the separation
//      s = (p_B − p_A) · n at the CURRENT poses from the anchors fixed at step 2 (n turning with
//      the body of the face it came from; a sphere's or capsule's anchor is its core point, its
//      surface point that ± radius · n, so a rolling ball's contact stays under it),
//      C = clamp(β (s + slop), −maxCorrection, 0), a pseudo-impulse −C / K along n moves and turns
//      both bodies directly. Velocities are untouched (no energy from it but the lift m g Δh).
//
// Steps 4–6 may run in substeps (options.substeps). Mass ratios: sequential impulses converge
// slowly when a heavy body rests on a light one (Catto, GDC 2005): a 0.51 kg box on a 0.023 kg
// capsule sinks it 5 cm into the ground with 8 sweeps (30 sweeps: 6 mm); keep ratios within ~10:1,
// as the scenes do.
// Conservative advancement of fast bodies is not done: a body faster than its size per step is
// caught by its speculative margin, which grows with |v| dt (tests: "fast bodies").
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
    /// Steps 4–6 run this many times per step with dt / substeps on the one manifold of step 2,
    /// each substep's separations from the anchors at its poses (Box2D v3's substepping). Resting
    /// contacts carry their impulse from substep to substep; contacts found apart or bouncing do
    /// not (an impact's impulse applied again would push the bodies apart). Measured
    /// (tests/core/world/world_test.cpp): 4 substeps × 2 sweeps hold the 10-box stack within 7 mm
    /// where 1 × 8 lets it sway 30 mm, but a striker hitting a row of 8 touching spheres with
    /// e = 0 comes back at 0.25 m/s (1 × 8: the row moves on as one block).
    int substeps = 1;
    int velocityIterations = 8;  ///< sweeps per substep (8 per step: Box2D's default; Bullet's is 10)
    int positionIterations = 6;  ///< NGS sweeps (3 left a 1000-body pile 5.7 cm deep after 5 s, 6: 8 mm)
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
    /// The most pairs a step's narrow phase may test: the work and the manifolds' memory grow with
    /// them (2000 spheres on one point make 2·10⁶). Past it the world stops with TooManyPairs
    /// before the narrow phase. A settled pile has ~2.5 a body.
    std::int64_t maxPairs = 10'000'000;
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
    bool bounce = false;  ///< restitution applies (decided at the first substep)
    /// The normal velocity (< 0: approaching) restitution uses: the point's before this step's solve,
    /// or, lower, the one it had the step before when it was speculative and pushed (matched by id).
    double approach = 0.0;
    /// I⁻¹(r × d) of each body for d = n, t1, t2: the angular velocity a unit impulse along d gives.
    Vec3 angularAn = Vec3::Zero(), angularBn = Vec3::Zero(), angularA1 = Vec3::Zero(), angularB1 = Vec3::Zero(),
         angularA2 = Vec3::Zero(), angularB2 = Vec3::Zero();
};

struct WorldManifold {
    int a = -1, b = -1;  ///< body indices, a < b
    NarrowMethod method = NarrowMethod::None;
    Vec3 normal = Vec3::UnitZ();       ///< A → B, world, at the narrow phase
    /// The normal in the frame of body normalBody (0: A, 1: B), which it turns with as the bodies
    /// move in steps 5–7; normalBody 2: two rounded shapes, the normal is the line between their
    /// cores' anchors (localNormal in A's frame is the fallback when they meet).
    Vec3 localNormal = Vec3::UnitZ();
    int normalBody = 0;
    /// Each side's rounding radius (a sphere's or capsule's, else 0): the anchors are core points,
    /// the surface point is the anchor ± radius · normal, so a rolling ball's contact stays under it.
    double radiusA = 0.0, radiusB = 0.0;
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
    int cachedAxisSkips = 0;        ///< pairs still separated by the axis that separated them last step
    int contactPoints = 0;
    int warmStartedPoints = 0;      ///< points matched to the previous step
    double kinetic = 0.0, potential = 0.0;  ///< J, potential −m g · x summed over dynamic bodies
    Vec3 momentum = Vec3::Zero();           ///< Σ m v over dynamic bodies (N·s)
    /// max(0, −s) over the points the narrow phase found at this step's start: the exact depth of
    /// the poses the previous step left (what the figures plot against the slop).
    double deepestPenetration = 0.0;
    /// The solver's own estimate from its anchors after step 6 and after step 7 (the anchors and
    /// the normal turn with the bodies: good for small rotations in a step, not for a spinning body).
    double estimateBeforeCorrection = 0.0, estimateAfterCorrection = 0.0;
    double energy() const { return kinetic + potential; }
};

/// Why a world refuses its input (message names the body).
enum class WorldStatus {
    Ok,
    InvalidOptions,
    InvalidBody,
    TooManyBodies,
    TooManyPairs,  ///< a step's broad phase found more than options.maxPairs pairs: the world stops there
};

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
    /// collide() in its two parts, for timing them apart: step 1, then steps 2–3.
    void collideBroad();
    void collideNarrow();
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
    void anchorContacts();
    void prepareContacts(double h, bool first);
    void warmStart(bool first);
    void solveVelocities();
    void correctPositions();
    double deepestPenetration() const;
    /// The manifold's normal and a point's two surface points at the bodies' current poses.
    Vec3 normalNow(const WorldManifold& m) const;
    void pointsNow(const WorldManifold& m, const WorldContact& c, const Vec3& n, Vec3& pa, Vec3& pb) const;

    WorldStatus status_ = WorldStatus::Ok;
    std::string message_;
    WorldOptions options_;
    std::vector<WorldBodyDesc> descs_;
    std::vector<RigidBody> bodies_;
    std::vector<int> planes_;  ///< indices of the plane bodies
    std::vector<Aabb> boxes_;
    std::vector<double> margins_;  ///< marginOf each body at this step's broad phase
    std::vector<std::pair<int, int>> broadPairs_;
    std::vector<WorldManifold> manifolds_, previous_;
    std::vector<std::pair<std::uint64_t, Vec3>> axes_;  ///< apart pairs' separating axes (world), by pair key
    std::unique_ptr<BroadPhase> broad_;
    WorldStepStats pending_;  ///< collide()'s counts, completed by solve()
    int steps_ = 0;
};

}  // namespace cdlab
