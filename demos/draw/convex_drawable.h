// Convex bodies as drawn in figures: hulls of vertices (polytopes) or of support samples (curved
// shapes), the Minkowski difference A − B as a hull, and the drawing of bodies, the origin and
// labels pushed away from a centre. Only geometry for drawing: every answer comes from core.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/base/primitives.h"
#include "core/base/types.h"
#include "app/scene/pair_scene.h"
#include "render/canvas.h"

namespace cdlab::demos {

/// Convex hull of points in the xy plane (z ignored, kept from the input), counter-clockwise,
/// duplicates and collinear points dropped (Andrew's monotone chain). For 2D outlines in figures.
std::vector<Vec3> hull2d(std::vector<Vec3> points);

/// A drawable convex body: triangles (3D) or a CCW outline (2D), plus feature edges worth drawing.
struct ConvexDrawable {
    bool planar = false;
    std::vector<Vec3> vertices;
    std::vector<Eigen::Vector3i> triangles;  // 3D
    std::vector<std::pair<int, int>> edges;  // 3D polytopes: hull edges; 2D: the outline loop
    std::vector<Vec3> outline;               // 2D: CCW polygon
    Vec3 center = Vec3::Zero();
    double radius = 0.0;  // bounding sphere about center
    bool valid = false;
};

/// The shape as drawn: hull of its vertices (polytopes) or of support samples (curved shapes).
ConvexDrawable shapeDrawable(const SceneShape& shape);
/// An oriented box as a drawable body (a degenerate box draws nothing).
ConvexDrawable boxDrawable(const Obb& box);
/// A - B: hull of {a_i - b_j} when both are polytopes (exact), else of s_A(d) - s_B(-d) over
/// evenly spread directions d (inscribed in the true set).
ConvexDrawable minkowskiDrawable(const SceneShape& a, const SceneShape& b, bool* exact = nullptr);

/// Bounding sphere of points (centre of the bounding box, max distance).
void boundingSphere(const std::vector<Vec3>& points, Vec3& center, double& radius);

/// Draws a body translucent with its edges (3D) or a filled outline (2D); the edges behind it
/// (edgeStyleSeen) dashed, or left out when not `hiddenEdges` (a background body such as A − B
/// behind an algorithm's own simplex or polytope: its far side would only crowd their labels).
void drawBody(render::Canvas& canvas, const ConvexDrawable& body, const render::Color& fill, float alpha,
              const render::Color& edge, float edgeWidth, bool hiddenEdges = true);

/// True when the face through `point` with outward `normal` is turned towards the camera.
bool facesCamera(const render::Camera& camera, const Vec3& point, const Vec3& normal);
/// How an edge of a convex body is drawn: `visible` on the side the camera sees, dashed and faded
/// when both faces meeting at it (outward normals n1, n2) are turned away, i.e. behind the body, so
/// a translucent body reads in depth instead of flipping like a Necker cube.
render::LineStyle edgeStyleSeen(const render::Camera& camera, const Vec3& midpoint, const Vec3& n1, const Vec3& n2,
                                render::LineStyle visible);
/// The four faces of a tetrahedron over vertex ids 0..3 (a GJK or EPA simplex drawn as a mesh).
inline const std::vector<Eigen::Vector3i> kTetrahedronFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

/// Each edge of a closed convex triangle mesh (an EPA polytope, a GJK tetrahedron) once, in the
/// order of its vertex ids, styled by edgeStyleSeen with the outward normals (away from the
/// vertices' mean) of the faces meeting at it; an edge beside a flat face (normal under 1e-9 of
/// the edge's length squared) is drawn `visible`.
void drawConvexMeshEdges(render::Canvas& canvas, const std::vector<Vec3>& vertices,
                         const std::vector<Eigen::Vector3i>& faces, const render::LineStyle& visible);

/// True when `point` is seen through a convex body given by its face planes (unit outward normals,
/// world frame; n · x <= d inside): the ray from the point towards the camera runs inside the body
/// for longer than `tolerance` (a point on a face turned towards the camera or on the silhouette is
/// seen; one on the far side is behind the body).
bool behindBody(const render::Camera& camera, const Vec3& point, const std::vector<Plane>& faces, double tolerance);
/// The same along a given direction to the eye (an orthographic view being chosen): whether the
/// ray from `point` along `toEye` runs inside the body for longer than `tolerance`; no faces, no.
bool insideAlong(const Vec3& point, const Vec3& toEye, const std::vector<Plane>& faces, double tolerance);
/// A 3D drawable's face planes (unit outward normals, n · x <= d inside), one per triangle.
std::vector<Plane> facePlanes(const ConvexDrawable& body);

/// Draws the little "O" origin marker with a cross.
void drawOrigin(render::Canvas& canvas, double size, bool planar);

/// A body's name ("A", "B") at its centre, or beside it when a marker or label is there.
/// The name names the strokes drawn under bodyOwner(name) (Canvas::setStrokeOwner): it may cross
/// its own body's outline, no other stroke (render/legibility.h).
void drawBodyName(render::Canvas& canvas, const Vec3& at, const std::string& name, render::Role role);
/// The stroke owner id of the body named `name` (never 0): draw its outline under
/// canvas.setStrokeOwner(bodyOwner(name)), its name with drawBodyName or TextStyle::names.
int bodyOwner(const std::string& name);
/// Where the names of two bodies go: their centres, except that when the centres are close
/// (one body deep inside the other) the larger body's name moves away from the smaller one, onto
/// a part of it the other does not cover.
std::pair<Vec3, Vec3> bodyNamePoints(const ConvexDrawable& a, const ConvexDrawable& b);
/// Text next to `at`, pushed `px` output pixels away from `from` on screen (so labels fan out
/// from a centre instead of piling onto the point they name). A feature's label may name it at
/// any of `alsoAt` too (points of a face or an edge): it goes where its spot is cleanest
/// (Canvas::drawTextAtAnyOf).
void drawLabelAway(render::Canvas& canvas, const Vec3& at, const Vec3& from, const std::string& text,
                   render::TextStyle style, double px = 16.0, const std::vector<Vec3>& alsoAt = {});

}  // namespace cdlab::demos
