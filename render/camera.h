// Cameras: orthographic and perspective look-at, and a 2D mode (x right, y up, no depth).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace cdlab::render {

struct Camera {
    enum class Projection { Orthographic, Perspective, TwoD };
    Projection projection = Projection::Perspective;
    Eigen::Vector3d eye{3, 2.5, 4};
    Eigen::Vector3d target{0, 0, 0};
    Eigen::Vector3d up{0, 1, 0};
    double fovYDegrees = 35.0;  // Perspective
    double viewHeight = 4.0;    // Orthographic and TwoD: world units visible vertically
    double nearPlane = 0.01, farPlane = 1000.0;

    /// 2D view centred on (cx, cy) showing `height` world units vertically.
    static Camera twoD(double cx, double cy, double height);
    /// 2D view of a width x height canvas in which one world unit is one output pixel, origin at the
    /// bottom left, y up: for plots, diagrams and lists laid out in pixels.
    static Camera pixels(double width, double height);
    /// Projection * view for the given aspect ratio (width / height), column-major like GL.
    Eigen::Matrix4d viewProjection(double aspect) const;
    /// Unit vector from target towards the eye (for lighting and sorting).
    Eigen::Vector3d viewDirection() const;
    /// Unit vector from a world point towards the eye: to the eye point in perspective, the view
    /// direction otherwise.
    Eigen::Vector3d directionToEye(const Eigen::Vector3d& p) const;
};

/// How a view sees a feature given by its points (one: a vertex, two: an edge, more: a face) and
/// the outward normals of the faces holding it, from `toEye` (unit): `facing`, the largest cosine
/// of a normal to the view (below 0: every face holding it turned away; 1 without normals), and
/// `foreshortening`, a face's |cos| to the view, an edge's |sin|, 1 for a vertex (near 0: edge-on).
/// What Canvas::noteFeature records (render/legibility.h) and the demos choose views by.
struct FeatureView {
    double facing = 1, foreshortening = 1;
};
FeatureView featureView(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                        const Eigen::Vector3d& toEye);

}  // namespace cdlab::render
