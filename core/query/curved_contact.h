// Contact points of a cylinder or cone (core/query/shape.h's CurvedSolid) on a reference face
// (issue 21 §2): the ground plane of a contact query (core/query/contact.h), or a face of a
// polytope whose normal is the contact normal. The points lie on the true circles of the solid's
// rims (not on a prism's corners):
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
// reduced to maxPoints by the manifold rules of every contact (core/contact/contact_manifold.h:
// deepest, farthest, largest triangle, largest quad, then the most added area).
//
// The feature of a curved solid holding contact points (curvedFeature): a cap of one end (three
// or more points on that end, or any inside its disc), the side (points on both ends, or the apex
// and the base rim), a rim of one end (one or two points on its circle), or a cone's apex. The
// ends: Top is the +halfHeight cap (a cone has none: its apex is there), Bottom the −halfHeight
// one (a cone's base).
//
// Tested through `cdlab query`'s contact op: tests/app/query/query_contact_curved_test.cpp (rims,
// lying and tilted solids, a cone on its apex, a cylinder on a box face, random planes: every
// point on the solid at its plane depth).
#pragma once

#include <vector>

#include "core/base/types.h"
#include "core/query/shape.h"

namespace cdlab {

/// The face the solid rests on: outward unit normal n (out of the other body, toward the solid),
/// the face's plane n·x = offset, and its corners counter-clockwise seen from outside (none: the
/// whole plane, the ground of a contact query).
struct ReferenceFace {
    Vec3 normal = Vec3::UnitY();
    double offset = 0.0;
    std::vector<Vec3> corners;
};

/// A contact point: on the solid, its projection on the face, and the depth below the face (>= 0).
struct CurvedContactPoint {
    Vec3 onSolid = Vec3::Zero(), onFace = Vec3::Zero();
    double depth = 0.0;
};

/// The solid's points on or below the face (depth >= −touch), reduced to maxPoints, the deepest
/// first. Empty when no point of the solid reaches the face (within touch).
std::vector<CurvedContactPoint> curvedOnFace(const CurvedSolid& s, const ReferenceFace& face, int maxPoints, double touch);

/// The feature of a curved solid that holds a set of surface points (see the file comment).
struct CurvedFeature {
    enum class Type { Cap, Side, Rim, Apex };
    enum class End { None, Top, Bottom };
    Type type = Type::Side;
    End end = End::None;  ///< Cap and Rim: which end; None for Side and Apex
};
/// "cap", "side", "rim", "apex".
const char* nameOf(CurvedFeature::Type type);
/// "top", "bottom" ("" for None).
const char* nameOf(CurvedFeature::End end);

/// The feature of the solid holding `points` (on its surface, to 1e-9 of its size), as described
/// in the file comment.
CurvedFeature curvedFeature(const CurvedSolid& s, const std::vector<Vec3>& points);

}  // namespace cdlab
