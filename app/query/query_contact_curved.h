// Contact points of a cylinder or cone on a reference face (issue 21 §2): the ground plane of the
// `contact` op, or a face of a polytope whose normal is the contact normal. The points lie on the
// true circles of the solid's rims (not on a prism's corners):
//   - each rim circle sampled at 32 azimuths starting at its deepest one (so the deepest point is
//     the exact support point), the submerged samples kept;
//   - where a rim circle crosses the face's plane, or (for a face) one of its side planes, the
//     crossing points, solved on the circle (a cos φ + b sin φ = c);
//   - the cone's apex when submerged;
//   - the side's deepest generator line (rim to rim, or base rim to apex) where it crosses the face's
//     side planes (at its depth there: a cylinder lying across a face's edge keeps both ends of its
//     contact line) or the face's plane;
//   - for a face, the samples outside it dropped, and when a cap lies flat on the face (its normal
//     the face's to 1e-9), the face's corners inside the cap disc;
// reduced to max_points by the manifold rules of every contact (core/contact/contact_manifold.h:
// deepest, farthest, largest triangle, largest quad, then the most added area). Features of a
// curved solid: {"type":"cap","end":E} (three or more points on one end, or any inside its disc),
// {"type":"side"} (points on both ends, or the apex and the base rim), {"type":"rim","end":E} (one or
// two points on one rim circle),
// {"type":"apex"}; E is "top" (the +half_height cap; for "a"/"b" cylinders, b's) or "bottom" (a
// cone's base).
#pragma once

#include <vector>

#include "core/base/types.h"
#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// The face the solid rests on: outward unit normal n (out of the other body, toward the solid),
/// the face's plane n·x = offset, and its corners counter-clockwise seen from outside (none: the
/// whole plane, the ground of the contact op).
struct ReferenceFace {
    Vec3 normal = Vec3::UnitY();
    double offset = 0.0;
    std::vector<Vec3> corners;
};

/// A contact point: on the solid, its projection on the face, and the depth below the face.
struct CurvedContactPoint {
    Vec3 onSolid = Vec3::Zero(), onFace = Vec3::Zero();
    double depth = 0.0;
};

/// The solid's points on or below the face (depth >= −touch), reduced to maxPoints, the deepest first.
std::vector<CurvedContactPoint> curvedOnFace(const CurvedSolid& s, const ReferenceFace& face, int maxPoints, double touch);

/// The feature of the solid holding `points` (on its surface), as described above.
Json curvedFeature(const CurvedSolid& s, const std::vector<Vec3>& points);

}  // namespace cdlab::demos
