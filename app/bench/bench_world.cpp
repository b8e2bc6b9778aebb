// cdlab's world beside Bullet's (see bench_world.h).
//
// Scene: n bodies — boxes, 12-point hulls, spheres, capsules in turn, sizes 0.3..0.66 (mass ratios
// within ~20:1: see core/world/world.h on mass ratios), random
// orientations, seed 45 — on a k × k lattice 1.2 apart (k = ⌈1.5 ∛n⌉), layer over layer from
// z = 1, dropped into a bin: the ground plane z = 0 and four static wall boxes around the lattice.
// Both worlds: time step 1/60 s, gravity 9.81 down z, 8 velocity iterations, friction 0.5 (Bullet's
// per-body √0.5, its product rule), no restitution, no sleeping. cdlab adds 3 position sweeps (NGS);
// Bullet corrects penetration with its split impulses (its default). Steps run interleaved — one
// cdlab step, one Bullet step — so load on the shared machine falls on both alike.
#include "app/bench/bench_world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/measure/statistics.h"
#include "core/world/world.h"
#ifdef CDLAB_BENCH_PEERS
#include "app/bench/peers/bench_peers.h"
#endif

namespace cdlab::demos {

namespace {

struct Pile {
    std::vector<WorldBodyDesc> bodies;
    std::vector<std::vector<Vec3>> hulls;  ///< body frame vertices of each hull body (index: body)
};

Pile pileOf(int n) {
    Pile pile;
    std::mt19937_64 rng(45);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int k = static_cast<int>(std::ceil(1.5 * std::cbrt(n)));
    const double spacing = 1.2, half = 0.5 * spacing * k;
    pile.bodies.push_back(worldBody(worldPlane(Vec3::UnitZ(), 0.0), Transform{}));
    const double wallHeight = 0.5 * spacing * (n / (k * k) + 2);
    const auto wall = [&](const Vec3& h, const Vec3& p) {
        pile.bodies.push_back(worldBody(worldBox(h), Transform{p, Quat::Identity()}, true));
    };
    wall(Vec3(0.25, half + 0.5, wallHeight), Vec3(-half - 0.25, 0, wallHeight));
    wall(Vec3(0.25, half + 0.5, wallHeight), Vec3(half + 0.25, 0, wallHeight));
    wall(Vec3(half + 0.5, 0.25, wallHeight), Vec3(0, -half - 0.25, wallHeight));
    wall(Vec3(half + 0.5, 0.25, wallHeight), Vec3(0, half + 0.25, wallHeight));
    for (int i = 0; i < n; ++i) {
        const int layer = i / (k * k), cell = i % (k * k);
        const Vec3 p(-half + spacing * (cell % k + 0.5), -half + spacing * (cell / k + 0.5), 1.0 + spacing * layer);
        const Vec3 axis(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        const Quat q(Eigen::AngleAxisd(3.0 * u(rng), axis.norm() > 1e-3 ? Vec3(axis.normalized()) : Vec3::UnitZ()));
        const auto size = [&] { return 0.15 + 0.18 * u(rng); };  // the largest box's corner (0.57) within half the spacing
        WorldShapeBuild shape;
        switch (i % 4) {
            case 0: shape = worldBox(Vec3(size(), size(), size())); break;
            case 1: {
                std::vector<Vec3> pts;
                const double r = size() + 0.1;
                for (int j = 0; j < 12; ++j) {
                    const Vec3 d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
                    pts.push_back(r * d.normalized());
                }
                shape = worldHull(pts);
                break;
            }
            case 2: shape = worldSphere(size()); break;
            default: {  // radius r, segment 1.6 r: the mass of a box of the same size class
                const double r = size();
                shape = worldCapsule(0.8 * r, r);
                break;
            }
        }
        if (!shape.ok()) shape = worldBox(Vec3(0.3, 0.3, 0.3));  // a degenerate random hull: never with this seed
        pile.bodies.push_back(worldBody(shape, Transform{p, q}));
    }
    pile.hulls.resize(pile.bodies.size());
    for (std::size_t i = 0; i < pile.bodies.size(); ++i)
        if (pile.bodies[i].shape.kind == WorldShape::Kind::Hull) pile.hulls[i] = pile.bodies[i].shape.hull.positions();
    return pile;
}

#ifdef CDLAB_BENCH_PEERS
std::vector<PeerWorldBody> peerBodies(const Pile& pile) {
    std::vector<PeerWorldBody> out;
    for (std::size_t i = 0; i < pile.bodies.size(); ++i) {
        const WorldBodyDesc& d = pile.bodies[i];
        PeerWorldBody b;
        using K = WorldShape::Kind;
        using P = PeerWorldBody::Kind;
        switch (d.shape.kind) {
            case K::Box: b.kind = P::Box; break;
            case K::Hull: b.kind = P::Hull; break;
            case K::Sphere: b.kind = P::Sphere; break;
            case K::Capsule: b.kind = P::Capsule; break;
            case K::Plane: b.kind = P::Plane; break;
        }
        b.half = d.shape.halfExtents;
        b.hull = &pile.hulls[i];
        b.radius = d.shape.radius;
        b.halfHeight = d.shape.halfHeight;
        b.planeNormal = d.shape.plane.normal;
        b.planeOffset = d.shape.plane.offset;
        b.isStatic = d.isStatic;
        b.mass = d.density * d.volume;
        b.inertiaDiagonal = d.density * d.unitInertia.diagonal();
        b.pose = d.pose;
        b.friction = d.friction;
        b.restitution = d.restitution;
        out.push_back(b);
    }
    return out;
}
#endif

struct WorldRow {
    int n = 0, steps = 0;
    double collideMs = 0, stepMs = 0, broadMs = 0, narrowMs = 0, solveMs = 0;  // cdlab means per step
    double bulletCollideMs = NAN, bulletStepMs = NAN;
    double pairs = 0, points = 0, bulletPairs = NAN, bulletPoints = NAN, deepest = 0, bulletDeepest = NAN;
    int narrowKinds[6] = {0, 0, 0, 0, 0, 0};  // manifolds per NarrowMethod in the last step
};

bool measure(int n, int steps, WorldRow& r) {
    const Pile pile = pileOf(n);
    WorldOptions o;  // the defaults: 1/60 s, 8 + 3 iterations, SAP
    World world(pile.bodies, o);
    if (!world.ok()) {
        std::cerr << "cdlab bench: world refused: " << world.message() << "\n";
        return false;
    }
#ifdef CDLAB_BENCH_PEERS
    std::unique_ptr<PeerWorld> bullet = makeBulletWorld(peerBodies(pile), o.timeStep, o.velocityIterations, o.gravity);
#endif
    r.n = n;
    r.steps = steps;
    double bulletCollide = 0, bulletStep = 0, bulletPairs = 0, bulletPoints = 0;
    for (int s = 0; s < steps; ++s) {
        const double t0 = threadMilliseconds();
        world.collideBroad();
        const double t1 = threadMilliseconds();
        world.collideNarrow();
        const double t2 = threadMilliseconds();
        const WorldStepStats st = world.solve();
        const double t3 = threadMilliseconds();
        r.broadMs += t1 - t0;
        r.narrowMs += t2 - t1;
        r.solveMs += t3 - t2;
        r.pairs += st.narrowTests;
        r.points += st.contactPoints;
        if (s >= steps / 2) r.deepest = std::max(r.deepest, st.deepestPenetration);  // exact, at the step start
#ifdef CDLAB_BENCH_PEERS
        if (bullet) {
            double c = 0;
            bulletStep += bullet->step(c);
            bulletCollide += c;
            bulletPairs += bullet->pairs();
            bulletPoints += bullet->contactPoints();
            if (s >= steps / 2) r.bulletDeepest = std::max(std::isnan(r.bulletDeepest) ? 0.0 : r.bulletDeepest, bullet->deepest());
        }
#endif
    }
    for (const WorldManifold& m : world.manifolds()) ++r.narrowKinds[static_cast<int>(m.method)];
    r.broadMs /= steps, r.narrowMs /= steps, r.solveMs /= steps, r.pairs /= steps, r.points /= steps;
    r.collideMs = r.broadMs + r.narrowMs;
    r.stepMs = r.collideMs + r.solveMs;
#ifdef CDLAB_BENCH_PEERS
    if (bullet) {
        r.bulletCollideMs = bulletCollide / steps;
        r.bulletStepMs = bulletStep / steps;
        r.bulletPairs = bulletPairs / steps;
        r.bulletPoints = bulletPoints / steps;
    }
#endif
    return true;
}

std::string num(const char* f, double x) {
    if (std::isnan(x)) return "-";
    char b[64];
    std::snprintf(b, sizeof b, f, x);
    return b;
}

}  // namespace

int runWorldBench(bool quick, std::ostream& table) {
    std::vector<int> sizes = quick ? std::vector<int>{100, 1000} : std::vector<int>{100, 1000, 10000};
    table << "Mixed pile (boxes, 12-point hulls, spheres, capsules) dropped into a bin; thread-CPU ms per step,\n"
          << "mean over the steps (the pile falls, lands and settles: contacts grow through the run);\n"
          << "collide = broad + narrow phase (Bullet: performDiscreteCollisionDetection); x: Bullet / cdlab.\n";
    char line[512];
    std::snprintf(line, sizeof line, "%6s %5s | %9s %9s | %9s %9s | %6s %6s | %7s %7s %7s %7s | %7s %7s\n", "n",
                  "steps", "collide", "Bullet", "step", "Bullet", "x coll", "x step", "pairs", "Bul", "points", "Bul",
                  "deepest", "Bul");
    table << line;
    std::ostringstream where;
    for (int n : sizes) {
        const int steps = quick ? 60 : (n >= 10000 ? 120 : 240);
        std::cerr << "cdlab bench: world, " << n << " bodies, " << steps << " steps\n";
        WorldRow r;
        if (!measure(n, steps, r)) return 1;
        std::snprintf(line, sizeof line, "%6d %5d | %9s %9s | %9s %9s | %6s %6s | %7s %7s %7s %7s | %7s %7s\n", r.n, r.steps,
                      num("%.3f", r.collideMs).c_str(), num("%.3f", r.bulletCollideMs).c_str(),
                      num("%.3f", r.stepMs).c_str(), num("%.3f", r.bulletStepMs).c_str(),
                      num("%.2f", r.bulletCollideMs / r.collideMs).c_str(), num("%.2f", r.bulletStepMs / r.stepMs).c_str(),
                      num("%.0f", r.pairs).c_str(), num("%.0f", r.bulletPairs).c_str(), num("%.0f", r.points).c_str(),
                      num("%.0f", r.bulletPoints).c_str(), num("%.4f", r.deepest).c_str(),
                      num("%.4f", r.bulletDeepest).c_str());
        table << line;
        std::snprintf(line, sizeof line,
                      "%6d: broad %.3f ms, narrow %.3f ms, solve %.3f ms (%.0f %% / %.0f %% / %.0f %%); last step's manifolds: "
                      "box-box %d, box-plane %d, hull-hull %d, hull-plane %d, rounded %d\n",
                      r.n, r.broadMs, r.narrowMs, r.solveMs, 100 * r.broadMs / r.stepMs, 100 * r.narrowMs / r.stepMs,
                      100 * r.solveMs / r.stepMs, r.narrowKinds[1], r.narrowKinds[2], r.narrowKinds[3], r.narrowKinds[4],
                      r.narrowKinds[5]);
        where << line;
    }
    table << "pairs: narrow-phase pairs per step (cdlab: grown-box pairs + body-plane pairs; Bullet: its pair cache of\n"
          << "fattened boxes); points: contact points held; deepest: the deepest penetration of any contact point over\n"
          << "the second half of the run (cdlab: found by its narrow phase at a step's start; Bullet: its manifold\n"
          << "points' distances), landing impacts included.\n"
          << "Where cdlab's step goes:\n"
          << where.str();
    return 0;
}

}  // namespace cdlab::demos
