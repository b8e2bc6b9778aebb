// Closest features of two simplices — points, segments, triangles, tetrahedra (solid) — by trying
// every feature pair: each vertex, edge and face of one against each of the other (Ericson,
// Real-Time Collision Detection §5.1: the closest pair of two convex polytopes lies on a pair of
// boundary features; featureDistance computes each pair, core/closest/feature_distance.h). A
// tetrahedron that holds a vertex of the other simplex intersects it although no boundary pair meets
// (exact orientation tests). The pair reported is the one of least distance, and among pairs within
// rounding of it (1e-12 of the simplices' size) the one of least total dimension: the features whose
// relative interiors hold the closest points (a vertex–face pair, not the face's edge–face pair). A
// pair within that rounding of touching counts as intersecting (distance 0).
// Small and exhaustive on purpose: the reference GJK is checked against in the demos, not a fast path.
#pragma once

#include <span>
#include <vector>

#include "core/base/types.h"

namespace cdlab {

/// A feature of a simplex by its vertex indices (1: vertex, 2: edge, 3: face, 4: a tetrahedron's inside).
struct SimplexFeature {
    std::vector<int> vertices;
    int dimension() const { return int(vertices.size()) - 1; }
};

struct SimplexPairCandidate {
    SimplexFeature a, b;
    double distance = 0.0;
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
};

struct SimplexPairResult {
    bool valid = false;       ///< false: 0 or more than 4 vertices, NaN / inf
    bool intersect = false;   ///< the solid simplices share a point
    double distance = 0.0;
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    SimplexFeature featureA, featureB;
    int pairsTested = 0;
};

/// The closest features of conv(a) and conv(b) (1 to 4 points each). `candidates`, when given,
/// receives every feature pair tried with its distance, nearest first.
SimplexPairResult closestFeaturesOfSimplices(std::span<const Vec3> a, std::span<const Vec3> b,
                                             std::vector<SimplexPairCandidate>* candidates = nullptr);

}  // namespace cdlab
