// Many-body world benchmark (`cdlab bench --only world`): cdlab's world (core/world/world.h) beside
// Bullet's btDiscreteDynamicsWorld on the same pile of boxes, hulls, spheres and capsules falling
// into a bin, at 100, 1000 and 10 000 bodies.
#pragma once

#include <ostream>

namespace cdlab::demos {

/// Runs the benchmark and prints its table to `table`: per body count, thread-CPU ms per step of
/// collision detection (broad + narrow phase) and of the whole step for cdlab and Bullet, their
/// ratios, the pairs and contact points each held, cdlab's deepest penetration, and where cdlab's
/// step time goes (broad phase, narrow phase by pair kind, solver). quick: 100 and 1000 bodies, fewer
/// steps. Returns 0, or 1 when cdlab's world refused its input.
int runWorldBench(bool quick, std::ostream& table);

}  // namespace cdlab::demos
