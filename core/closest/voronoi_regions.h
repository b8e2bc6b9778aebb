// Geometry of the Voronoi regions of a triangle's and a tetrahedron's features, for drawing.
// Demos draw these; they must not recompute the math.
//
// The Voronoi region of a feature F of a convex polytope is the set of points whose closest
// point lies in F's relative interior (Ericson, Real-Time Collision Detection §5.1.5 Fig. 5.6,
// §5.1.6). Each is an intersection of half-spaces through the feature:
//   vertex x:  (p - x)·(y - x) <= 0 for every neighbour y;
//   edge xy:   between the two planes through x and y perpendicular to xy, and on the outer side
//              of every face at the edge (measured in that face's plane);
//   face:      on the outer side of its plane, within the prism over the face.
// closest_point.h decides these regions exactly; this file only draws them (double, not exact).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "core/base/types.h"
#include "core/closest/closest_point.h"

namespace cdlab {

/// Closed half-space {x : normal · (x - point) <= 0}. normal need not be unit.
struct HalfSpace {
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
};

/// Sutherland–Hodgman clip of a planar convex polygon (any orientation) against one half-space.
/// Returns the part with normal·(x - point) <= 0; empty when nothing is left.
std::vector<Vec3> clipConvexPolygon(const std::vector<Vec3>& polygon, const HalfSpace& halfSpace);

// ---------------------------------------------------------------------------------------------
// Triangle

struct TriangleVoronoiInput {
    Triangle triangle;
    double margin = 1.0;  ///< the clip rectangle is the triangle's in-plane bounding box grown by this (units)
    double height = 1.0;  ///< half-height of the boundary slabs along the triangle normal (units)
};

/// One in-plane Voronoi region: a convex polygon in the triangle's plane (3D points),
/// counterclockwise seen from the side `normal` points to, clipped to the rectangle.
struct TriangleRegionPolygon {
    TriangleRegion region = TriangleRegion::ABC;
    std::vector<Vec3> vertices;
};

/// A plane separating two 3D Voronoi regions of the triangle. The points x with
/// normal·(x - point) > 0 lie on the `front` side. Only part of the plane is boundary: `quad`
/// is that part (the in-plane boundary segment, clipped to the rectangle, extruded by
/// ±height along the triangle normal), corners in order.
struct VoronoiBoundaryPlane {
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitX();  ///< unit
    TriangleRegion behind = TriangleRegion::A;
    TriangleRegion front = TriangleRegion::AB;
    std::array<Vec3, 4> quad{};
};

struct TriangleVoronoiDiagram {
    bool valid = false;           ///< false for a (exactly) collinear triangle or non-finite input: nothing else is set
    Vec3 normal = Vec3::UnitZ();  ///< unit normal (b-a)×(c-a) / |...|
    Vec3 axisU = Vec3::UnitX();   ///< in-plane unit axis along b - a
    Vec3 axisV = Vec3::UnitY();   ///< normal × axisU
    std::array<Vec3, 4> rectangle{};  ///< clip rectangle corners, counterclockwise about normal
    /// Indexed by TriangleRegion (A, B, C, AB, BC, CA, ABC); together they tile the rectangle.
    std::array<TriangleRegionPolygon, 7> regions{};
    /// A|AB, A|CA, B|AB, B|BC, C|BC, C|CA (planes through a vertex, perpendicular to an edge),
    /// then ABC|AB, ABC|BC, ABC|CA (planes containing an edge, perpendicular to the triangle).
    std::array<VoronoiBoundaryPlane, 9> boundaries{};
};

/// In-plane Voronoi regions of the triangle's 7 features and the 9 planes bounding their 3D
/// regions (world frame, same units as the triangle).
TriangleVoronoiDiagram triangleVoronoiRegions(const TriangleVoronoiInput& input);

// ---------------------------------------------------------------------------------------------
// Tetrahedron

struct TetrahedronVoronoiInput {
    Tetrahedron tetrahedron;
    double margin = 1.0;  ///< the clip box is the tetrahedron's bounding box grown by this (units)
};

/// One 3D Voronoi region of a tetrahedron feature: its bounding half-spaces (the region is their
/// intersection) and, for drawing, each bounding plane's part on the region clipped to the box.
struct TetrahedronRegionGeometry {
    TetrahedronRegion region = TetrahedronRegion::ABCD;
    std::vector<HalfSpace> halfSpaces;     ///< normals unit length
    std::vector<std::vector<Vec3>> faces;  ///< faces[i] lies on halfSpaces[i]'s plane (may be empty)
};

struct TetrahedronVoronoiDiagram {
    bool valid = false;  ///< false for a (exactly) flat tetrahedron or non-finite input
    Eigen::AlignedBox3d box;
    /// Indexed by TetrahedronRegion (A..D, AB..CD, ABC..BCD, ABCD).
    std::array<TetrahedronRegionGeometry, 15> regions{};
};

/// Bounding half-spaces and clipped boundary faces of the 15 Voronoi regions of a tetrahedron
/// (world frame, same units as the tetrahedron).
TetrahedronVoronoiDiagram tetrahedronVoronoiRegions(const TetrahedronVoronoiInput& input);

}  // namespace cdlab
