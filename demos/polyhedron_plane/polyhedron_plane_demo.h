// demo_polyhedron_plane: the contact model. Three scene modes:
//   "plane"    a convex polyhedron above, touching and penetrating a plane (core/contact/contact_plane.h):
//              body highlighted when colliding, vertex depths, contact polygon, reduced manifold
//              with per-point depth and normals, or the closest feature when separated;
//   "features" the six contact types V–V … F–F (core/closest/feature_distance.h): the two features, their
//              closest points and the contact normal with its rule;
//   "sat"      two polyhedra (core/contact/contact_sat.h): SAT axis, reference and incident faces, the
//              Sutherland–Hodgman clip seen along the reference normal, the clipped manifold.
// Scene keys: docs/scenes.md, "polyhedron_plane".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& polyhedronPlaneDemo();

}  // namespace cdlab::demos
