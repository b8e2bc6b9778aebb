// Internal to core/geometry's convex hull: the construction's triangles (convex_hull.cpp) and the
// steps that turn the finished triangulation into polygon faces (convex_hull_faces.cpp).
#pragma once

#include <array>
#include <vector>

#include "core/base/types.h"
#include "core/geometry/convex_hull.h"

namespace cdlab::hull_internal {

// A hull triangle during construction. Edge k runs v[k] -> v[(k+1)%3]; adj[k] is the triangle on
// the other side of edge k. Vertices counter-clockwise seen from outside.
struct Tri {
    std::array<int, 3> v{};
    std::array<int, 3> adj{{-1, -1, -1}};
    Vec3 n = Vec3::Zero();  // unit outward normal
    double d = 0.0;         // plane offset: n · x = d
    bool alive = true;
    std::vector<int> conflicts;  // points (not yet inserted) that see this triangle by more than eps
};

// The alive triangles of the finished triangulation, numbered 0..count-1 ("compact" indices).
struct AliveTriangles {
    const std::vector<Tri>& tris;
    std::vector<int> compact;  // triangle id -> compact index, -1 when dead
    std::vector<int> alive;    // compact index -> triangle id
};

// Triangles grouped into would-be polygon faces: group[t] of each compact triangle, members of each group.
struct FaceGroups {
    std::vector<int> group;
    std::vector<std::vector<int>> members;
};

// The polygons of the hull: each group becomes one polygon if its boundary is one simple loop,
// convex within mergeTol; otherwise its triangles stay.
struct FacePolygons {
    std::vector<std::vector<int>> loops;
    int mergedGroups = 0;
    int rejected = 0;
};

AliveTriangles aliveTriangles(const std::vector<Tri>& tris);

// Nearly coplanar neighbours grouped around seed triangles, largest area first (every member's
// vertices within mergeTol of the seed plane); one group per triangle unless options.mergeCoplanarFaces.
FaceGroups groupCoplanar(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol,
                         const HullOptions& options);

// Merges groups across non-convex edges until every edge is convex (convex_hull_faces.cpp).
void mergeFolds(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol, FaceGroups& fg);

// The polygon loops of the groups (see FacePolygons).
FacePolygons facePolygons(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol, const FaceGroups& fg);

// Removes boundary vertices within tol of the segment joining their neighbours; returns the count
// removed (convex_hull_faces.cpp).
int removeCollinear(std::vector<std::vector<int>>& loops, const std::vector<Vec3>& P, double tol);

}  // namespace cdlab::hull_internal
