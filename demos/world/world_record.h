// What the world demo keeps of a run for its frames (demos/world/world_demo.cpp runs the world,
// demos/world/world_frames.cpp draws): every step's counts, and at the chosen steps the bodies'
// poses and the contacts with their impulses.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/scene/demo.h"
#include "app/scene/scene.h"
#include "core/world/world.h"
#include "render/gl_context.h"

namespace cdlab::demos {

/// One contact point of a snapshot: where the narrow phase found it (the middle of its two surface
/// points), the normal A → B, and the normal impulse the step's solver gave it.
struct ContactSnapshot {
    int a = -1, b = -1;
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
    double separation = 0.0;
    double impulse = 0.0;  ///< λ_n (N·s) of the step; 0: speculative, not pushing
};

/// The world at one step's start (the poses its narrow phase saw) and what the step did.
struct StepSnapshot {
    int step = 0;         ///< 1-based: the step about to run
    double time = 0.0;    ///< s, at its start
    WorldStepStats stats;
    std::vector<Transform> poses;
    std::vector<char> touching;  ///< body has a point with λ_n > 0 in this step
    std::vector<ContactSnapshot> contacts;
    std::vector<Aabb> grownBoxes;              ///< the broad phase's boxes (pipeline frame only)
    std::vector<std::pair<int, int>> pairs;    ///< its pairs (pipeline frame only)
    std::vector<int> manifoldPairs;            ///< per contact, which manifold (pipeline frame only)
};

/// Triangles and edges of a body in its own frame, for drawing (spheres and capsules as
/// tessellated solids; their outlines are drawn from the exact radius).
struct BodyMesh {
    std::vector<Vec3> vertices;
    std::vector<Eigen::Vector3i> triangles;
    std::vector<std::pair<int, int>> edges;  ///< polytopes only
};

struct WorldRun {
    WorldOptions options;
    std::vector<WorldShape> shapes;
    std::vector<char> isStatic;
    std::vector<BodyMesh> meshes;
    std::vector<WorldStepStats> stats;  ///< every step, in order
    std::vector<StepSnapshot> frames;   ///< the chosen steps
    bool hasPipeline = false;
    StepSnapshot pipeline;
    double maxImpulse = 0.0;  ///< the largest λ_n over the drawn snapshots (one arrow scale)
};

/// The mesh drawn for a shape (a plane has none).
BodyMesh bodyMesh(const WorldShape& shape);

/// frame_NN: the side view and the top view of a snapshot.
Frame drawWorldFrame(render::GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run,
                     const StepSnapshot& s, int index);
/// "pipeline": one step as broad phase → narrow phase → solver, three side views.
Frame drawPipelineFrame(render::GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run);
/// "counts", "energy", "penetration": per-step plots.
std::vector<Frame> drawWorldPlots(render::GlContext& gl, int scale, const SceneCommon& common, const WorldRun& run);

}  // namespace cdlab::demos
