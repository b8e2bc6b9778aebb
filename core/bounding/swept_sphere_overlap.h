// Overlap tests between swept-sphere volumes of the same type: two SSVs overlap iff the distance
// between their cores is <= the sum of their radii (Larsen et al., "Fast Distance Queries with
// Rectangular Swept Sphere Volumes", ICRA 2000 §3; Ericson, "Real-Time Collision Detection"
// §4.5). PSS: point-point; LSS: segment-segment (Ericson §5.1.9, core/closest/closest_point.h);
// RSS: rectangle-rectangle (below).
//
// World frame, any consistent length unit. Closed sets: touching counts as a hit. Non-finite
// input or a negative radius gives hit == false and NaN distances.
#pragma once

#include "core/base/primitives.h"
#include "core/bounding/swept_sphere.h"

namespace cdlab {

/// Which pair of features of two rectangles gave their distance.
enum class RectangleFeaturePair {
    EdgeEdge,      ///< an edge of A and an edge of B (segment-segment)
    VertexFace,    ///< a corner of A and the rectangle B
    FaceVertex,    ///< the rectangle A and a corner of B
    EdgeCrossesB,  ///< an edge of A pierces B (distance 0)
    EdgeCrossesA,  ///< an edge of B pierces A (distance 0)
    Invalid,       ///< non-finite input
};

/// "EdgeEdge", "VertexFace", "FaceVertex", "EdgeCrossesB", "EdgeCrossesA", "Invalid".
const char* nameOf(RectangleFeaturePair pair);

/// Closest points of two rectangles (the cores of two RSSs; radii ignored).
struct RectangleDistanceResult {
    double distance = 0.0;         ///< >= 0; 0 when the rectangles touch or cross
    Vec3 pointOnA = Vec3::Zero();  ///< on rectangle A
    Vec3 pointOnB = Vec3::Zero();  ///< on rectangle B
    RectangleFeaturePair features = RectangleFeaturePair::Invalid;
    int featureA = -1;  ///< edge or corner index of A (0..3), -1 for a face
    int featureB = -1;  ///< edge or corner index of B (0..3), -1 for a face
};

/// Distance between two (solid, closed) rectangles in 3D. Two convex polygons that do not cross
/// have a closest pair with a point on the boundary of one of them (if both were interior points
/// the rectangles would be parallel, and sliding both along the common direction keeps the
/// distance to a boundary), so the distance is the minimum over the 16 edge-edge pairs (Ericson
/// §5.1.9) and the 8 corner-rectangle pairs, unless an edge of one pierces the other (distance 0).
/// Corner c of a rectangle is center + axes (+-a, +-b, 0) with signs (-,-), (+,-), (+,+), (-,+);
/// edge i runs from corner i to corner (i + 1) % 4.
RectangleDistanceResult distanceRectangleRectangle(const Rss& a, const Rss& b);

/// Result of an SSV-SSV overlap test.
struct SweptSphereOverlapResult {
    bool hit = false;
    double coreDistance = 0.0;     ///< distance between the cores (NaN for invalid input)
    double separation = 0.0;       ///< coreDistance - ra - rb: the gap (> 0) or overlap depth (<= 0)
    Vec3 pointOnA = Vec3::Zero();  ///< closest point of A's core
    Vec3 pointOnB = Vec3::Zero();  ///< closest point of B's core
};

/// PSS-PSS (sphere-sphere): |cb - ca| <= ra + rb.
SweptSphereOverlapResult testPssPss(const Sphere& a, const Sphere& b);

/// LSS-LSS (capsule-capsule): segment-segment distance <= ra + rb.
SweptSphereOverlapResult testLssLss(const Capsule& a, const Capsule& b);

/// RSS-RSS: rectangle-rectangle distance <= ra + rb.
SweptSphereOverlapResult testRssRss(const Rss& a, const Rss& b);

}  // namespace cdlab
