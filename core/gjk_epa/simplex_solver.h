// Closest point of a simplex (1..4 points) to the origin: the sub-algorithm inside GJK.
//
// Two interchangeable solvers:
//  - Johnson's distance sub-algorithm (Gilbert, Johnson, Keerthi 1988; van den Bergen,
//    "Collision Detection in Interactive 3D Environments" §4.3.3): cofactor recursion over every
//    sub-simplex, the one whose cofactors are all positive and whose extensions are all
//    non-positive wins; if rounding leaves no such sub-simplex, the backup procedure keeps the
//    sub-simplex with positive cofactors whose closest point is nearest the origin.
//  - Signed volumes (Montanari, Petrinic, Barbieri, "Improving the GJK algorithm for faster and
//    more reliable distance queries between convex objects", ACM TOG 36(3), 2017): signed
//    volumes / projected areas decide the Voronoi region, descending only into the facets whose
//    sign says the origin lies beyond them. More accurate than Johnson near degenerate simplices.
#pragma once

#include "core/base/types.h"

namespace cdlab {

/// Which simplex sub-algorithm GJK uses.
enum class SimplexSolver { Johnson, SignedVolumes };

/// The closest point of conv{w[0..n-1]} to the origin, as a sub-simplex plus barycentric weights.
struct SimplexClosest {
    Vec3 v = Vec3::Zero();  ///< closest point, v = sum lambda[k] * w[index[k]]
    double lambda[4] = {};  ///< barycentric weights of the kept vertices, each > 0, sum 1
    int index[4] = {};      ///< input indices of the kept vertices, ascending
    int count = 0;          ///< number of kept vertices (1..4); 4 means the origin is inside
};

/// Closest point of the simplex w[0..n-1] (1 <= n <= 4, any frame, any units) to the origin by
/// the signed-volumes method. Degenerate simplices (repeated, collinear, coplanar points) fall back
/// to their faces / edges; the answer is always a valid sub-simplex.
SimplexClosest closestSignedVolumes(const Vec3* w, int n);

/// Same query by Johnson's distance sub-algorithm with the backup procedure.
SimplexClosest closestJohnson(const Vec3* w, int n);

/// Dispatch on the solver.
inline SimplexClosest closestOnSimplex(const Vec3* w, int n, SimplexSolver solver) {
    return solver == SimplexSolver::Johnson ? closestJohnson(w, n) : closestSignedVolumes(w, n);
}

/// Display name of the solver ("Johnson", "SignedVolumes").
const char* nameOf(SimplexSolver solver);

}  // namespace cdlab
