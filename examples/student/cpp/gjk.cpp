// Assignment item: the distance of two convex polyhedra by GJK, with its trace. You write the
// support function and the simplex reduction (gjk.h); gjk_loop.cpp calls them. `cdlab check` names
// the first iteration that breaks a rule of GJK and which part broke it (docs/check.md, "GJK trace").
#include "gjk.h"

using kit::V3;

V3 support(const std::vector<V3>& vertices, V3 d) {
    // TODO: the vertex with the largest dot(v, d). As shipped it returns the first vertex:
    // `cdlab check` says "your a is not extreme in A" (or b in B) at the first iteration where that is wrong.
    (void)d;
    return vertices[0];
}

void reduce(std::vector<SimplexPoint>& simplex, std::vector<double>& weights) {
    // TODO: the closest point of a segment, triangle (triangle.cpp) and tetrahedron to the origin,
    // by Voronoi regions. As shipped it keeps the newest point alone: `cdlab check` says "wrong
    // sub-simplex kept: the origin is in the Voronoi region of ... keep ..." where that is wrong.
    simplex = {simplex.back()};
    weights = {1.0};
}
