// demo_bvh: bounding-volume hierarchies over triangle meshes (Ericson, Real-Time Collision
// Detection ch. 6; Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996; van den Bergen, JGT 1997):
// the hierarchy level by level with its tree, AABB tree vs OBB tree on a torus, a dual traversal
// step by step, and refitting a deforming mesh. Scene keys: docs/scenes.md, "bvh".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& bvhDemo();

}  // namespace cdlab::demos
