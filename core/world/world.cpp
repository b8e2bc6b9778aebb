#include "core/world/world.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/broadphase/sweep_and_prune.h"
#include "core/broadphase/tree_broad_phase.h"
#include "core/broadphase/uniform_grid.h"

namespace cdlab {

const char* nameOf(BroadPhaseKind kind) {
    switch (kind) {
        case BroadPhaseKind::SweepAndPrune: return "sap";
        case BroadPhaseKind::DynamicTree: return "tree";
        case BroadPhaseKind::Grid: return "grid";
    }
    return "?";
}

WorldBodyDesc worldBody(const WorldShapeBuild& shape, const Transform& pose, bool isStatic, double density) {
    WorldBodyDesc d;
    d.shape = shape.shape;
    d.unitInertia = shape.unitInertia;
    d.volume = shape.volume;
    d.isStatic = isStatic || shape.shape.kind == WorldShape::Kind::Plane;
    d.density = density;
    d.pose = pose;
    return d;
}

struct World::BroadPhase {
    SweepAndPrune sap;
    bool sapBuilt = false;
    TreeBroadPhase tree;
    UniformGrid grid;
    std::vector<int> bounded;  ///< broad-phase object k is body bounded[k]
    std::vector<Aabb> boxes;   ///< their grown boxes
};

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

// Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017): t1, t2 ⟂ n, continuous in
// n away from n_z = −1, so a resting contact's friction directions do not turn from step to step.
void tangentBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
    const double sign = std::copysign(1.0, n.z());
    const double a = -1.0 / (sign + n.z());
    const double b = n.x() * n.y() * a;
    t1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
    t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

// 1 / (m_A⁻¹ + m_B⁻¹ + d·((I_A⁻¹(r_A×d))×r_A) + d·((I_B⁻¹(r_B×d))×r_B)): the effective mass along d.
double effectiveMass(double ma, const Mat3& ia, const Vec3& ra, double mb, const Mat3& ib, const Vec3& rb,
                     const Vec3& d) {
    const Vec3 ca = ra.cross(d), cb = rb.cross(d);
    const double k = ma + mb + ca.dot(ia * ca) + cb.dot(ib * cb);
    return k > 0 ? 1.0 / k : 0.0;
}

void rotateBy(Quat& q, const Vec3& theta) {
    const Quat dq(0.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z());
    Quat r = dq * q;
    q = Quat(q.w() + r.w(), q.x() + r.x(), q.y() + r.y(), q.z() + r.z()).normalized();
}

std::string checkOptions(const WorldOptions& o) {
    if (!(o.timeStep > 0) || !(o.timeStep <= 1)) return "timeStep must be in (0, 1] s";
    if (o.velocityIterations < 1 || o.velocityIterations > 1000) return "velocityIterations must be in [1, 1000]";
    if (o.substeps < 1 || o.substeps > 64) return "substeps must be in [1, 64]";
    if (o.positionIterations < 0 || o.positionIterations > 1000) return "positionIterations must be in [0, 1000]";
    if (!finite(o.gravity)) return "gravity must be finite";
    if (!(o.slop >= 0) || !std::isfinite(o.slop)) return "slop must be finite and >= 0";
    if (!(o.baumgarte > 0) || !(o.baumgarte <= 1)) return "baumgarte must be in (0, 1]";
    if (!(o.maxCorrection > 0) || !std::isfinite(o.maxCorrection)) return "maxCorrection must be finite and > 0";
    if (!(o.restitutionThreshold >= 0) || !std::isfinite(o.restitutionThreshold))
        return "restitutionThreshold must be finite and >= 0";
    if (!(o.speculativeDistance >= 0) || !std::isfinite(o.speculativeDistance))
        return "speculativeDistance must be finite and >= 0";
    if (!std::isfinite(o.gridCellSize)) return "gridCellSize must be finite";
    if (o.maxPairs < 0) return "maxPairs must be >= 0";
    return "";
}

std::string checkBody(const WorldBodyDesc& d) {
    if (!finite(d.pose.position) || !d.pose.rotation.coeffs().allFinite() || !(d.pose.rotation.norm() > 0.5))
        return "pose must be finite with a unit quaternion";
    if (!finite(d.linearVelocity) || !finite(d.angularVelocity)) return "velocities must be finite";
    if (!(d.friction >= 0) || !std::isfinite(d.friction)) return "friction must be finite and >= 0";
    if (!(d.restitution >= 0) || !(d.restitution <= 1)) return "restitution must be in [0, 1]";
    if (!d.isStatic && (!(d.density > 0) || !std::isfinite(d.density) || !(d.volume > 0)))
        return "a dynamic body needs density > 0 and a volume";
    return "";
}

}  // namespace

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::World(std::vector<WorldBodyDesc> bodies, const WorldOptions& options)
    : options_(options), descs_(std::move(bodies)), broad_(std::make_unique<BroadPhase>()) {
    const auto fail = [&](WorldStatus s, std::string m) {
        status_ = s;
        message_ = std::move(m);
    };
    if (std::string m = checkOptions(options_); !m.empty()) {
        fail(WorldStatus::InvalidOptions, m);
        return;
    }
    if (descs_.size() > static_cast<std::size_t>(kMaxBodies)) {
        fail(WorldStatus::TooManyBodies, "at most " + std::to_string(kMaxBodies) + " bodies");
        return;
    }
    bodies_.reserve(descs_.size());
    for (std::size_t i = 0; i < descs_.size(); ++i) {
        WorldBodyDesc& d = descs_[i];
        if (d.shape.kind == WorldShape::Kind::Plane) d.isStatic = true;
        if (std::string m = checkBody(d); !m.empty()) {
            fail(WorldStatus::InvalidBody, "body " + std::to_string(i) + ": " + m);
            return;
        }
        d.pose.rotation.normalize();
        if (d.isStatic || d.shape.kind == WorldShape::Kind::Plane) {
            bodies_.push_back(makeStaticBody(d.shape.kind == WorldShape::Kind::Plane ? Transform{} : d.pose));
            continue;
        }
        const RigidBodyBuild b = makeDynamicBody(d.density * d.volume, d.density * d.unitInertia, d.pose,
                                                 d.linearVelocity, d.angularVelocity);
        if (!b.ok()) {
            fail(WorldStatus::InvalidBody, "body " + std::to_string(i) + ": " + b.message);
            return;
        }
        bodies_.push_back(b.body);
    }
    for (int i = 0; i < bodyCount(); ++i)
        if (descs_[i].shape.kind == WorldShape::Kind::Plane) planes_.push_back(i);
        else broad_->bounded.push_back(i);
    if (options_.broadPhase == BroadPhaseKind::Grid && !(options_.gridCellSize > 0)) {
        std::vector<double> sizes;
        for (int i : broad_->bounded) sizes.push_back(2.0 * descs_[i].shape.boundingRadius);
        if (!sizes.empty()) {
            std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
            options_.gridCellSize = 2.0 * sizes[sizes.size() / 2];
        } else {
            options_.gridCellSize = 1.0;
        }
    }
    if (options_.broadPhase == BroadPhaseKind::Grid) {
        // Each body's box, grown by at most its size, must touch at most the grid's cell limit
        // (UniformGridOptions::maxCellsPerBox): a slab 120 wide on a 0.2 grid touched 360 000 cells
        // and the grid refused it every step (the hostile review: spheres fell through it).
        const double h = options_.gridCellSize;
        for (int i : broad_->bounded) {
            const Aabb b = worldBounds(descs_[i].shape, descs_[i].pose);
            const Vec3 e = (b.max - b.min).array() + 2.0 * descs_[i].shape.boundingRadius + 2.0 * options_.speculativeDistance;
            const double cells = (std::floor(e.x() / h) + 2) * (std::floor(e.y() / h) + 2) * (std::floor(e.z() / h) + 2);
            const auto limit = UniformGridOptions{}.maxCellsPerBox;
            if (!(cells <= double(limit))) {
                fail(WorldStatus::InvalidOptions, "body " + std::to_string(i) + " would cover " + std::to_string(cells) +
                                                      " grid cells of " + std::to_string(h) + " (at most " +
                                                      std::to_string(limit) + "): a larger gridCellSize, or sweep and prune");
                return;
            }
        }
    }
    boxes_.assign(bodies_.size(), Aabb{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)});
    margins_.assign(bodies_.size(), 0.5 * options_.speculativeDistance);  // planes keep this one
}

double World::marginOf(int i) const {
    const double half = 0.5 * options_.speculativeDistance;
    const RigidBody& b = bodies_[i];
    if (b.isStatic()) return half;
    const double dt = options_.timeStep;
    return half + dt * (b.linearVelocity.norm() + options_.gravity.norm() * dt +
                        b.angularVelocity.norm() * descs_[i].shape.boundingRadius);
}

void World::broadPhase(WorldStepStats& stats) {
    BroadPhase& bp = *broad_;
    bp.boxes.resize(bp.bounded.size());
    for (std::size_t k = 0; k < bp.bounded.size(); ++k) {
        const int i = bp.bounded[k];
        Aabb box = worldBounds(descs_[i].shape, bodies_[i].transform());
        margins_[i] = marginOf(i);
        const Vec3 m = Vec3::Constant(margins_[i]);
        box.min -= m;
        box.max += m;
        bp.boxes[k] = box;
        boxes_[i] = box;
    }
    const std::vector<BoxPair>* pairs = nullptr;
    switch (options_.broadPhase) {
        case BroadPhaseKind::SweepAndPrune:
            if (!bp.sapBuilt) {
                bp.sap.build(bp.boxes);
                bp.sapBuilt = true;
            } else {
                bp.sap.update(bp.boxes);
            }
            pairs = &bp.sap.pairs();
            break;
        case BroadPhaseKind::DynamicTree:
            bp.tree.update(bp.boxes);
            pairs = &bp.tree.pairs();
            break;
        case BroadPhaseKind::Grid: {
            UniformGridOptions o;
            o.cellSize = options_.gridCellSize;
            if (bp.grid.build(bp.boxes, o).status == GridStatus::Ok) {
                pairs = &bp.grid.pairs();
                break;
            }
            // A box grew past the cell limit in flight (the constructor checked the start): this
            // step's pairs from sweep and prune, which has no such limit.
            if (!bp.sapBuilt) bp.sap.build(bp.boxes), bp.sapBuilt = true;
            else bp.sap.update(bp.boxes);
            pairs = &bp.sap.pairs();
            break;
        }
    }
    broadPairs_.clear();
    if (std::int64_t(pairs->size()) > options_.maxPairs) {
        status_ = WorldStatus::TooManyPairs;
        message_ = "step " + std::to_string(steps_ + 1) + ": the broad phase found " + std::to_string(pairs->size()) +
                   " pairs, more than " + std::to_string(options_.maxPairs) + " (bodies heaped on one another)";
        return;
    }
    for (const BoxPair& p : *pairs) {
        const int a = bp.bounded[p.a], b = bp.bounded[p.b];
        if (bodies_[a].isStatic() && bodies_[b].isStatic()) continue;
        broadPairs_.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(broadPairs_.begin(), broadPairs_.end());
    stats.broadPairs = static_cast<int>(broadPairs_.size());
}

void World::narrowPhase(WorldStepStats& stats) {
    std::swap(previous_, manifolds_);
    manifolds_.clear();
    // Every pair in (a, b) order: the broad phase's, and each dynamic body with each plane it may reach.
    std::vector<std::pair<int, int>> pairs = broadPairs_;
    for (int p : planes_) {
        const Plane& plane = descs_[p].shape.plane;
        for (int i : broad_->bounded) {
            if (bodies_[i].isStatic()) continue;
            // The grown box's corner deepest along the plane normal: n·x <= d reached?
            const Aabb& box = boxes_[i];
            const Vec3 low(plane.normal.x() > 0 ? box.min.x() : box.max.x(),
                           plane.normal.y() > 0 ? box.min.y() : box.max.y(),
                           plane.normal.z() > 0 ? box.min.z() : box.max.z());
            if (plane.normal.dot(low) - plane.offset > 0.5 * options_.speculativeDistance) continue;
            pairs.emplace_back(std::min(i, p), std::max(i, p));
            ++stats.planePairs;
        }
    }
    if (std::int64_t(pairs.size()) > options_.maxPairs) {  // planes count too: each reaches every body
        status_ = WorldStatus::TooManyPairs;
        message_ = "step " + std::to_string(steps_ + 1) + ": " + std::to_string(pairs.size()) +
                   " pairs with the planes counted, more than " + std::to_string(options_.maxPairs);
        return;
    }
    // The broad phase's pairs are sorted; the plane pairs, appended after them, are merged in.
    const auto planeStart = pairs.begin() + std::ptrdiff_t(broadPairs_.size());
    std::sort(planeStart, pairs.end());
    std::inplace_merge(pairs.begin(), planeStart, pairs.end());
    stats.narrowTests = static_cast<int>(pairs.size());
    PairManifold pm;
    std::size_t cursor = 0;  // previous_ is sorted by pair: one merge walk finds each pair's old manifold
    std::size_t axisCursor = 0;  // likewise axes_, the separating axes of the last step's apart pairs
    std::vector<std::pair<std::uint64_t, Vec3>> nextAxes;
    for (const auto& [a, b] : pairs) {
        const double margin = margins_[a] + margins_[b];  // this step's, from the broad phase
        const Transform ta = bodies_[a].transform(), tb = bodies_[b].transform();
        const std::uint64_t pairKey = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
        // A pair apart last step: its separating axis, tested first, usually still separates it
        // (the separating-axis cache of Bullet's and Box2D's pair caches).
        while (axisCursor < axes_.size() && axes_[axisCursor].first < pairKey) ++axisCursor;
        if (axisCursor < axes_.size() && axes_[axisCursor].first == pairKey &&
            separationAlong(descs_[a].shape, ta, descs_[b].shape, tb, axes_[axisCursor].second) > margin) {
            nextAxes.push_back(axes_[axisCursor]);
            ++stats.cachedAxisSkips;
            continue;
        }
        if (!collideShapes(descs_[a].shape, ta, descs_[b].shape, tb, margin, pm)) {
            if (pm.separatingAxis.squaredNorm() > 0) nextAxes.emplace_back(pairKey, pm.separatingAxis);
            continue;
        }
        WorldManifold m;
        m.a = a;
        m.b = b;
        m.method = pm.method;
        m.normal = pm.normal;
        m.normalBody = pm.normalBody;
        m.localNormal = bodies_[pm.normalBody == 1 ? b : a].orientation.conjugate() * pm.normal;
        m.radiusA = descs_[a].shape.rounded() ? descs_[a].shape.radius : 0.0;
        m.radiusB = descs_[b].shape.rounded() ? descs_[b].shape.radius : 0.0;
        m.featureKey = pm.featureKey;
        m.friction = std::sqrt(descs_[a].friction * descs_[b].friction);
        m.restitution = std::max(descs_[a].restitution, descs_[b].restitution);
        const std::uint64_t key = m.pairKey();
        while (cursor < previous_.size() && previous_[cursor].pairKey() < key) ++cursor;
        const WorldManifold* old =
            cursor < previous_.size() && previous_[cursor].pairKey() == key && previous_[cursor].featureKey == m.featureKey
                ? &previous_[cursor]
                : nullptr;
        for (const WorldContactPoint& p : pm.points) {
            WorldContact c;
            c.point = p;
            stats.deepestPenetration = std::max(stats.deepestPenetration, -p.separation);
            if (old && options_.warmStart)
                for (const WorldContact& o : old->points)
                    if (o.point.id == p.id) {
                        c.normalImpulse = o.normalImpulse;
                        c.tangentImpulse = o.tangentImpulse;
                        c.approach = o.approach;
                        c.warmStarted = true;
                        ++stats.warmStartedPoints;
                        break;
                    }
            m.points.push_back(c);
        }
        // Points in id order: the solver visits a resting manifold's points in the same order every
        // step (the generators list them deepest first, an order that flips as the body rocks).
        std::sort(m.points.begin(), m.points.end(),
                  [](const WorldContact& x, const WorldContact& y) { return x.point.id < y.point.id; });
        stats.contactPoints += static_cast<int>(m.points.size());
        manifolds_.push_back(std::move(m));
    }
    stats.manifolds = static_cast<int>(manifolds_.size());
    axes_ = std::move(nextAxes);
}

void World::collide() {
    collideBroad();
    collideNarrow();
}

void World::collideBroad() {
    pending_ = WorldStepStats{};
    if (ok()) broadPhase(pending_);
}

void World::collideNarrow() {
    if (ok()) narrowPhase(pending_);
    else manifolds_.clear();
}

void World::anchorContacts() {
    for (WorldManifold& m : manifolds_) {
        const RigidBody& A = bodies_[m.a];
        const RigidBody& B = bodies_[m.b];
        for (WorldContact& c : m.points) {
            c.localA = A.orientation.conjugate() * (c.point.pointA - m.radiusA * m.normal - A.position);
            c.localB = B.orientation.conjugate() * (c.point.pointB + m.radiusB * m.normal - B.position);
        }
    }
}

Vec3 World::normalNow(const WorldManifold& m) const {
    const RigidBody& A = bodies_[m.a];
    const RigidBody& B = bodies_[m.b];
    if (m.normalBody == 1) return B.orientation * m.localNormal;
    if (m.normalBody == 2 && !m.points.empty()) {
        const WorldContact& c = m.points.front();
        const Vec3 d = B.position + B.orientation * c.localB - A.position - A.orientation * c.localA;
        const double len = d.norm();
        if (len > 1e-9 * (m.radiusA + m.radiusB)) return d / len;
    }
    return A.orientation * m.localNormal;
}

void World::pointsNow(const WorldManifold& m, const WorldContact& c, const Vec3& n, Vec3& pa, Vec3& pb) const {
    const RigidBody& A = bodies_[m.a];
    const RigidBody& B = bodies_[m.b];
    pa = A.position + A.orientation * c.localA + m.radiusA * n;
    pb = B.position + B.orientation * c.localB - m.radiusB * n;
}

void World::prepareContacts(double h, bool first) {
    for (WorldManifold& m : manifolds_) {
        const RigidBody& A = bodies_[m.a];
        const RigidBody& B = bodies_[m.b];
        const Mat3 ia = A.inverseInertiaWorld(), ib = B.inverseInertiaWorld();
        m.normal = normalNow(m);  // turned with its body since the narrow phase
        const Vec3& n = m.normal;
        for (WorldContact& c : m.points) {
            Vec3 pa, pb;
            pointsNow(m, c, n, pa, pb);
            // Both bodies take the impulse at one point, the middle of the two surface points: an
            // impulse and its reaction on one line of action carry no spurious torque (a friction
            // impulse at pointA and its reaction at pointB would turn the pair by λ_t × depth n).
            const Vec3 mid = 0.5 * (pa + pb);
            c.rA = mid - A.position;
            c.rB = mid - B.position;
            tangentBasis(n, c.tangent1, c.tangent2);
            c.normalMass = effectiveMass(A.inverseMass, ia, c.rA, B.inverseMass, ib, c.rB, n);
            c.tangentMass1 = effectiveMass(A.inverseMass, ia, c.rA, B.inverseMass, ib, c.rB, c.tangent1);
            c.tangentMass2 = effectiveMass(A.inverseMass, ia, c.rA, B.inverseMass, ib, c.rB, c.tangent2);
            c.angularAn = ia * c.rA.cross(n), c.angularBn = ib * c.rB.cross(n);
            c.angularA1 = ia * c.rA.cross(c.tangent1), c.angularB1 = ib * c.rB.cross(c.tangent1);
            c.angularA2 = ia * c.rA.cross(c.tangent2), c.angularB2 = ib * c.rB.cross(c.tangent2);
            const double vn = (B.velocityAt(mid) - A.velocityAt(mid)).dot(n);
            const double s = (pb - pa).dot(n);  // the separation now, from the anchors
            c.bias = s > 0 ? -s / h : 0.0;
            if (first) {
                // Restitution at the approach speed the point had: now, or when it was last
                // speculative and pushed (the step that closed a gap left only the gap's speed,
                // s / dt). It applies to a point that reaches contact in this step from within the
                // speculative distance; one farther apart only closes its gap (bouncing it there
                // turned a ball at 100 m/s around 1 m above the ground: the hostile review) and
                // bounces the next step, touching. tests/core/world/world_test.cpp, "fast bodies".
                c.approach = std::min(vn, c.approach);
                c.bounce = s <= options_.speculativeDistance && c.approach < -options_.restitutionThreshold &&
                           s + c.approach * options_.timeStep <= 0;
                if (c.bounce) c.bias = std::max(c.bias, -m.restitution * c.approach);
            }
            // The warm-start impulse turned with the normal: its tangent part kept in the tangent plane.
            c.tangentImpulse -= c.tangentImpulse.dot(n) * n;
        }
    }
}

void World::warmStart(bool first) {
    for (WorldManifold& m : manifolds_) {
        RigidBody& A = bodies_[m.a];
        RigidBody& B = bodies_[m.b];
        for (WorldContact& c : m.points) {
            if (!first && (c.point.separation > 0 || c.bounce)) {
                c.normalImpulse = 0;
                c.tangentImpulse = Vec3::Zero();
                continue;
            }
            const Vec3 p = c.normalImpulse * m.normal + c.tangentImpulse;
            if (p.squaredNorm() == 0) continue;
            if (!A.isStatic()) A.applyImpulse(-p, A.position + c.rA);
            if (!B.isStatic()) B.applyImpulse(p, B.position + c.rB);
        }
    }
}

void World::solveVelocities() {
    // Per point the angular responses I⁻¹(r × d) for d = n, t1, t2 were computed once in
    // prepareContacts: an impulse λ d changes ω_A by −λ I_A⁻¹(r_A × d), ω_B by +λ I_B⁻¹(r_B × d).
    const auto solvePoint = [&](WorldManifold& m, WorldContact& c) {
        RigidBody& A = bodies_[m.a];
        RigidBody& B = bodies_[m.b];
        const double ma = A.inverseMass, mb = B.inverseMass;
        const Vec3& n = m.normal;
        // Friction first, inside the cone of the current normal impulse (Box2D's order).
        Vec3 dv = B.linearVelocity + B.angularVelocity.cross(c.rB) - A.linearVelocity - A.angularVelocity.cross(c.rA);
        const double old1 = c.tangentImpulse.dot(c.tangent1), old2 = c.tangentImpulse.dot(c.tangent2);
        double l1 = old1 - c.tangentMass1 * dv.dot(c.tangent1);
        double l2 = old2 - c.tangentMass2 * dv.dot(c.tangent2);
        const double limit = m.friction * c.normalImpulse;
        const double len = std::sqrt(l1 * l1 + l2 * l2);
        if (len > limit) {
            const double k = len > 0 ? limit / len : 0.0;
            l1 *= k, l2 *= k;
        }
        const double d1 = l1 - old1, d2 = l2 - old2;
        c.tangentImpulse = l1 * c.tangent1 + l2 * c.tangent2;
        const Vec3 pt = d1 * c.tangent1 + d2 * c.tangent2;
        A.linearVelocity -= ma * pt;
        A.angularVelocity -= d1 * c.angularA1 + d2 * c.angularA2;
        B.linearVelocity += mb * pt;
        B.angularVelocity += d1 * c.angularB1 + d2 * c.angularB2;
        // Then the normal impulse, accumulated and clamped at zero.
        dv = B.linearVelocity + B.angularVelocity.cross(c.rB) - A.linearVelocity - A.angularVelocity.cross(c.rA);
        const double old = c.normalImpulse;
        c.normalImpulse = std::max(0.0, old + c.normalMass * (c.bias - dv.dot(n)));
        const double dn = c.normalImpulse - old;
        A.linearVelocity -= (ma * dn) * n;
        A.angularVelocity -= dn * c.angularAn;
        B.linearVelocity += (mb * dn) * n;
        B.angularVelocity += dn * c.angularBn;
    };
    // Symmetric Gauss–Seidel: even sweeps visit the points in order, odd ones in reverse, so no
    // point is always first (a fixed order leans a stack toward its first-solved corner:
    // tests/core/world/world_test.cpp, the 10-box stack).
    for (int it = 0; it < options_.velocityIterations; ++it) {
        if (it % 2 == 0) {
            for (WorldManifold& m : manifolds_)
                for (WorldContact& c : m.points) solvePoint(m, c);
        } else {
            for (auto m = manifolds_.rbegin(); m != manifolds_.rend(); ++m)
                for (auto c = m->points.rbegin(); c != m->points.rend(); ++c) solvePoint(*m, *c);
        }
    }
}

void World::correctPositions() {
    std::vector<Mat3> inverseInertia(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) inverseInertia[i] = bodies_[i].inverseInertiaWorld();
    for (int it = 0; it < options_.positionIterations; ++it) {
        for (WorldManifold& m : manifolds_) {
            RigidBody& A = bodies_[m.a];
            RigidBody& B = bodies_[m.b];
            const Mat3& ia = inverseInertia[m.a];
            const Mat3& ib = inverseInertia[m.b];
            for (const WorldContact& c : m.points) {
                const Vec3 n = normalNow(m);
                Vec3 pa, pb;
                pointsNow(m, c, n, pa, pb);
                const double s = (pb - pa).dot(n);
                const double C =
                    std::clamp(options_.baumgarte * (s + options_.slop), -options_.maxCorrection, 0.0);
                if (C == 0) continue;
                const Vec3 ra = pa - A.position, rb = pb - B.position;
                const double k = effectiveMass(A.inverseMass, ia, ra, B.inverseMass, ib, rb, n);
                const Vec3 p = (-C * k) * n;
                if (!A.isStatic()) {
                    A.position -= A.inverseMass * p;
                    rotateBy(A.orientation, -(ia * ra.cross(p)));
                }
                if (!B.isStatic()) {
                    B.position += B.inverseMass * p;
                    rotateBy(B.orientation, ib * rb.cross(p));
                }
            }
        }
    }
}

double World::deepestPenetration() const {
    double deepest = 0.0;
    for (const WorldManifold& m : manifolds_) {
        const Vec3 n = normalNow(m);
        for (const WorldContact& c : m.points) {
            Vec3 pa, pb;
            pointsNow(m, c, n, pa, pb);
            const double s = (pb - pa).dot(n);
            deepest = std::max(deepest, -s);
        }
    }
    return deepest;
}

WorldStepStats World::solve() {
    WorldStepStats stats = pending_;
    if (!ok()) return stats;
    const int substeps = options_.substeps;
    const double h = options_.timeStep / substeps;
    anchorContacts();
    for (int sub = 0; sub < substeps; ++sub) {
        for (RigidBody& b : bodies_) integrateVelocity(b, options_.gravity, h);
        prepareContacts(h, sub == 0);
        if (options_.warmStart) {
            warmStart(sub == 0);
        } else {
            for (WorldManifold& m : manifolds_)
                for (WorldContact& c : m.points) {
                    c.normalImpulse = 0;
                    c.tangentImpulse = Vec3::Zero();
                }
        }
        solveVelocities();
        for (RigidBody& b : bodies_) integratePosition(b, h);
    }
    // A speculative point the solver pushed (its gap closes in this step) keeps its approach
    // speed for the restitution of the next step, when the bodies touch; any other point forgets it.
    for (WorldManifold& m : manifolds_)
        for (WorldContact& c : m.points)
            c.approach = c.point.separation > options_.speculativeDistance && c.normalImpulse > 0 ? c.approach : 0.0;
    stats.estimateBeforeCorrection = deepestPenetration();
    correctPositions();
    stats.estimateAfterCorrection = deepestPenetration();
    for (const RigidBody& b : bodies_) {
        stats.kinetic += b.kineticEnergy();
        stats.potential += b.potentialEnergy(options_.gravity);
        if (!b.isStatic()) stats.momentum += b.linearVelocity / b.inverseMass;
    }
    ++steps_;
    stats.step = steps_;
    stats.time = steps_ * options_.timeStep;
    return stats;
}

WorldStepStats World::step() {
    collide();
    return solve();
}

}  // namespace cdlab
