// demo_world: many rigid bodies together — the course's capstone. core/world/world.h steps boxes,
// hulls, spheres and capsules with a ground plane and static walls: broad phase, narrow phase,
// persistent manifolds, sequential impulses with friction and restitution, position correction.
// Frames every k steps from the side and from above (bodies in contact outlined, contact points,
// impulses to one scale), one step drawn as the pipeline (grown boxes and pairs → manifolds →
// impulses), and per-step plots of the pair and contact counts, the energy and the deepest
// penetration against the slop. Scene keys: docs/scenes.md, "world".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& worldDemo();

}  // namespace cdlab::demos
