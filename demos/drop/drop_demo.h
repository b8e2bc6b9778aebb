// demo_drop: a rigid convex polyhedron (box, tetrahedron or icosahedron) dropped with spin onto a
// ground plane and simulated step by step by core/dynamics/simulation.h (mass properties, semi-implicit
// Euler, polyhedron–plane manifold, sequential impulses with restitution and friction). Frames
// every k steps with the contact points and normals of that step, the centre-of-mass trail and the
// shadow; a contact sheet; a plot of kinetic / potential / total energy and penetration vs time.
// Scene keys: docs/scenes.md, "drop".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& dropDemo();

}  // namespace cdlab::demos
