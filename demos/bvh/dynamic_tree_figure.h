// Internal to the BVH demo (BvhScene::runDynamicTree in bvh_scene.h): the dynamic AABB tree
// figure — boxes inserted one at a time into core's DynamicAabbTree (core/broadphase/dynamic_tree.h)
// with fat margins, then moved: per step the node boxes by depth, the fat boxes, the new leaf and
// the sibling the SAH branch and bound chose, the rotations on the way up, and the tree diagram.
// Every number comes from the tree's insertion traces; this file names nodes by the boxes under
// them and draws.
#pragma once

#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "app/scene/demo.h"
#include "render/gl_context.h"

namespace cdlab::demos::bvhdemo {

struct DynamicTreeSpec {
    struct Move {
        int box = 0;
        Vec3 by = Vec3::Zero();
    };
    std::vector<Aabb> boxes;  ///< inserted in order, named A, B, C, ...
    double margin = 0.2;      ///< fat box = box grown by this on every side
    std::vector<Move> moves;  ///< after the insertions, one frame each
    Vec3 view{0.35, -1.0, 1.1};
};

/// What the figure needs of its scene to draw.
struct DynamicTreeDrawing {
    render::GlContext* gl = nullptr;  ///< null: trace only
    int width = 1024, height = 768, scale = 1;
    std::string title, caption;
    bool labels = true, treePanel = true;
};

/// Runs the steps; returns the trace (steps with their siblings, costs, rotations and the tree
/// after each) and appends one frame per step when drawing.gl is set.
Json runDynamicTreeFigure(const DynamicTreeSpec& spec, const DynamicTreeDrawing& drawing, std::vector<Frame>& frames);

}  // namespace cdlab::demos::bvhdemo
