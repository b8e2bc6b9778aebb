// Mesh generators named in scene files ("torus", "ellipsoid", "blob": docs/scenes.md), shared by
// the demos that draw triangle meshes (bounding_volumes, bvh).
#pragma once

#include <string>

#include "core/geometry/triangle_mesh.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Tessellation used when a scene does not give one (each demo picks its own density).
struct MeshTessellation {
    int torusMajorSegments = 24, torusMinorSegments = 12;
    int slices = 16, stacks = 8;  // ellipsoid and blob
};

/// Reads generator `kind`'s keys from `r`, the reader of its object `body`, into `mesh`.
/// Returns false when `kind` is none of torus / ellipsoid / blob (the caller parses its own
/// kinds). Bad values throw InputError naming the JSON path. The caller calls r.finish().
bool readMeshGenerator(const std::string& kind, const JsonNode& body, ObjectReader& r, const MeshTessellation& defaults,
                       TriangleMesh& mesh);

}  // namespace cdlab::demos
