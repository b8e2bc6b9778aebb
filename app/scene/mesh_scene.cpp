#include "app/scene/mesh_scene.h"

#include <cstdint>

#include "app/scene/scene_limits.h"

namespace cdlab::demos {

bool readMeshGenerator(const std::string& kind, const JsonNode& body, ObjectReader& r, const MeshTessellation& defaults,
                       TriangleMesh& mesh) {
    if (kind == "torus") {
        const double R = r.find("major_radius") ? sceneSize(r.get("major_radius")) : 1.0;
        const double rr = r.find("minor_radius") ? sceneSize(r.get("minor_radius")) : 0.35;
        int nu = defaults.torusMajorSegments, nv = defaults.torusMinorSegments;
        if (auto n = r.find("major_segments")) nu = n->asInt(3, 256);
        if (auto n = r.find("minor_segments")) nv = n->asInt(3, 256);
        if (!(R > 0 && rr > 0 && rr < R)) body.fail("need 0 < minor_radius < major_radius");
        mesh = torusMesh(R, rr, nu, nv);
        return true;
    }
    if (kind == "ellipsoid") {
        Vec3 radii(1, 1, 1);
        if (auto v = r.find("radii")) radii = sceneSizes(*v);
        int sl = defaults.slices, st = defaults.stacks;
        if (auto n = r.find("slices")) sl = n->asInt(3, 256);
        if (auto n = r.find("stacks")) st = n->asInt(2, 256);
        if (!(radii.minCoeff() > 0)) body.fail("radii must be positive");
        mesh = ellipsoidMesh(radii, sl, st);
        return true;
    }
    if (kind == "blob") {
        const double radius = r.find("radius") ? sceneSize(r.get("radius")) : 1.0, noise = r.numberOr("noise", 0.2);
        int sl = defaults.slices, st = defaults.stacks, seed = 1;
        if (auto n = r.find("slices")) sl = n->asInt(3, 256);
        if (auto n = r.find("stacks")) st = n->asInt(2, 256);
        if (auto n = r.find("seed")) seed = n->asInt(0, 1 << 30);
        if (!(radius > 0) || !(noise >= 0 && noise < 1)) body.fail("need radius > 0 and 0 <= noise < 1");
        mesh = noisyBlobMesh(radius, noise, sl, st, std::uint64_t(seed));
        return true;
    }
    return false;
}

}  // namespace cdlab::demos
