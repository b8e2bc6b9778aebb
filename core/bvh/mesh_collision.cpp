// Mesh-mesh collision through BVHs (see mesh_collision.h).
#include "core/bvh/mesh_collision.h"

#include "core/overlap/triangle_triangle.h"

namespace cdlab {

MeshCollisionResult collideMeshes(const TriangleMesh& meshA, const Bvh& bvhA, const Transform& poseA,
                                  const TriangleMesh& meshB, const Bvh& bvhB, const Transform& poseB,
                                  const MeshCollisionOptions& options, BvhTraversalTrace* trace) {
    MeshCollisionResult result;
    if (bvhA.status != BvhStatus::Ok || bvhB.status != BvhStatus::Ok) {
        result.status = MeshCollisionStatus::InvalidTree;
        return result;
    }
    if (bvhA.triangleCount() != meshA.triangleCount() || bvhB.triangleCount() != meshB.triangleCount()) {
        result.status = MeshCollisionStatus::TreeMeshMismatch;
        return result;
    }
    long long triangleTests = 0;
    auto leafPair = [&](int leafA, int leafB) {
        const BvhNode& na = bvhA.nodes[leafA];
        const BvhNode& nb = bvhB.nodes[leafB];
        for (int p = na.first; p < na.first + na.count; ++p) {
            const int ta = bvhA.triangleOrder[p];
            const Triangle worldA = meshA.triangle(ta, poseA);
            for (int q = nb.first; q < nb.first + nb.count; ++q) {
                const int tb = bvhB.triangleOrder[q];
                ++triangleTests;
                const bool hit = intersectTriangleTriangle(worldA, meshB.triangle(tb, poseB)).hit;
                if (trace) {
                    BvhTraversalStep step;
                    step.nodeA = leafA;
                    step.nodeB = leafB;
                    step.action = BvhTraversalAction::TriangleTest;
                    step.triangleA = ta;
                    step.triangleB = tb;
                    step.triangleHit = hit;
                    trace->steps.push_back(step);
                }
                if (!hit) continue;
                result.hit = true;
                result.pairs.push_back({ta, tb});
                if (options.firstHitOnly) return true;  // stop the traversal
            }
        }
        return false;
    };
    result.stats = traverseBvhPair(bvhA, poseA, bvhB, poseB, leafPair, trace);
    result.stats.triangleTests = triangleTests;
    return result;
}

MeshCollisionResult collideMeshesBruteForce(const TriangleMesh& meshA, const Transform& poseA,
                                            const TriangleMesh& meshB, const Transform& poseB,
                                            const MeshCollisionOptions& options) {
    MeshCollisionResult result;
    std::vector<Triangle> worldB(meshB.triangles.size());
    for (int j = 0; j < meshB.triangleCount(); ++j) worldB[j] = meshB.triangle(j, poseB);
    for (int i = 0; i < meshA.triangleCount(); ++i) {
        const Triangle worldA = meshA.triangle(i, poseA);
        for (int j = 0; j < meshB.triangleCount(); ++j) {
            ++result.stats.triangleTests;
            if (!intersectTriangleTriangle(worldA, worldB[j]).hit) continue;
            result.hit = true;
            result.pairs.push_back({i, j});
            if (options.firstHitOnly) return result;
        }
    }
    return result;
}

}  // namespace cdlab
