// Indexed triangle meshes (triangle soups) for the bounding-volume hierarchies of core/bvh/bvh.h and
// mesh-mesh collision (core/bvh/mesh_collision.h), with a few deterministic generators.
//
// A TriangleMesh is a soup: no manifoldness, orientation or connectivity is assumed. Vertices
// are in the mesh's body frame; a Transform (core/base/types.h) places the mesh in the world.
// Zero-area and duplicated triangles are allowed (the triangle-triangle test reports no hit for
// a zero-area triangle); indices out of range and non-finite vertices are not (validateMesh).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// Indexed triangle soup: triangle i has the vertices vertices[triangles[i][0..2]] (body frame).
struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;

    int triangleCount() const { return static_cast<int>(triangles.size()); }
    /// Triangle i in the body frame. Requires a valid mesh (validateMesh) and 0 <= i < count.
    Triangle triangle(int i) const {
        const std::array<int, 3>& t = triangles[i];
        return Triangle{vertices[t[0]], vertices[t[1]], vertices[t[2]]};
    }
    /// Triangle i in the world frame: each vertex through pose.apply (the same rounding as any
    /// other code that transforms the vertices with Transform::apply, e.g. a brute-force oracle).
    Triangle triangle(int i, const Transform& pose) const {
        const std::array<int, 3>& t = triangles[i];
        return Triangle{pose.apply(vertices[t[0]]), pose.apply(vertices[t[1]]), pose.apply(vertices[t[2]])};
    }
};

/// Outcome of validateMesh. Only Valid meshes may be given to the BVH builders.
enum class MeshStatus {
    Valid,            ///< every index in range, every vertex finite
    IndexOutOfRange,  ///< a triangle refers to a vertex < 0 or >= vertices.size()
    NonFiniteVertex,  ///< a vertex used by some triangle has a NaN or inf coordinate
};

/// Result of validateMesh: the status, the first offending triangle / vertex (-1 when Valid),
/// and counts of the allowed degeneracies.
struct MeshValidation {
    MeshStatus status = MeshStatus::Valid;
    int triangle = -1;          ///< first triangle with a bad index or a non-finite vertex
    int vertex = -1;            ///< the offending vertex index (out of range, or non-finite)
    int zeroAreaTriangles = 0;  ///< triangles with exactly zero cross product (b - a) x (c - a)
};

/// Checks every index and every vertex used by a triangle (unused vertices are not checked).
MeshValidation validateMesh(const TriangleMesh& mesh);

/// Human-readable name of a status ("valid", "index out of range", "non-finite vertex").
const char* nameOf(MeshStatus status);

/// Torus around the body z axis, centred at the origin: tube centre circle of radius
/// majorRadius in the xy plane, tube radius minorRadius. majorSegments x minorSegments quads,
/// each split into two triangles (2 * majorSegments * minorSegments triangles, counterclockwise
/// seen from outside). Segment counts below 3 are raised to 3.
TriangleMesh torusMesh(double majorRadius, double minorRadius, int majorSegments, int minorSegments);

/// Ellipsoid x²/rx² + y²/ry² + z²/rz² = 1 (radii = (rx, ry, rz)) as a latitude-longitude mesh
/// with `slices` meridians and `stacks` parallels bands (poles on the z axis, fan triangles at
/// the poles): 2 * slices * (stacks - 1) triangles, counterclockwise seen from outside. Counts
/// below 3 (slices) / 2 (stacks) are raised. A sphere is radii = (r, r, r).
TriangleMesh ellipsoidMesh(const Vec3& radii, int slices, int stacks);

/// Deterministic "noisy blob": ellipsoidMesh(radius * (1,1,1), slices, stacks) with each vertex
/// moved radially by a smooth random bump field of relative amplitude `noise` (0..~0.5), a sum
/// of 8 random cosine waves seeded by `seed` (same output on every platform: no std
/// distributions). The surface stays star-shaped around the origin for noise < 1.
TriangleMesh noisyBlobMesh(double radius, double noise, int slices, int stacks, std::uint64_t seed);

/// A closed prism: the simple polygon `outline` (either turn; non-convex allowed) in the plane z = 0
/// extruded to z = height, outward-facing. Its caps are triangulated by ear clipping (Eberly,
/// "Triangulation by Ear Clipping", 2002; Ericson §12.5.1), each ear decided by exact orientation
/// tests. Empty when the outline is not simple (two edges that are not neighbours meet — exact
/// orientations — or it has no area), has fewer than 3 corners, or height <= 0.
TriangleMesh prismMesh(const std::vector<Vec2>& outline, double height);

/// Deterministic random triangle soup: `count` triangles whose vertices are a random centre in
/// the cube [-halfSize, halfSize]^3 plus offsets of length <= triangleSize (3 vertices per
/// triangle, none shared). Seeded by `seed`, platform independent.
TriangleMesh randomSoupMesh(int count, double halfSize, double triangleSize, std::uint64_t seed);

}  // namespace cdlab
