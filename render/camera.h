// Cameras: orthographic and perspective look-at, and a 2D mode (x right, y up, no depth).
#pragma once

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
};

}  // namespace cdlab::render
