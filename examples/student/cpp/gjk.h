// GJK's two parts you write (gjk.cpp) and the loop that calls them (gjk_loop.cpp, given).
#pragma once

#include "kit.h"

// A point of the simplex: w = a − b with the support points it came from.
struct SimplexPoint {
    kit::V3 w, a, b;
};

// The vertex of the polytope farthest along d.
kit::V3 support(const std::vector<kit::V3>& vertices, kit::V3 d);

// simplex: 1 to 4 points, the newest last. Keeps the smallest sub-simplex whose hull holds the
// point of the simplex nearest the origin (the feature whose Voronoi region holds the origin) and
// sets weights to that point's barycentric weights on the points kept (each > 0, summing to 1). A
// tetrahedron holding the origin is kept whole.
void reduce(std::vector<SimplexPoint>& simplex, std::vector<double>& weights);
