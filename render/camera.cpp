#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace cdlab::render {

Camera Camera::twoD(double cx, double cy, double height) {
    Camera c;
    c.projection = Projection::TwoD;
    c.target = {cx, cy, 0};
    c.eye = {cx, cy, 1};
    c.up = {0, 1, 0};
    c.viewHeight = height;
    return c;
}

Camera Camera::pixels(double width, double height) { return twoD(width / 2.0, height / 2.0, height); }

Eigen::Vector3d Camera::viewDirection() const {
    if (projection == Projection::TwoD) return {0, 0, 1};
    const Eigen::Vector3d d = eye - target;
    const double n = d.norm();
    return n > 0 ? Eigen::Vector3d(d / n) : Eigen::Vector3d(0, 0, 1);  // eye == target: look down -z
}

Eigen::Vector3d Camera::directionToEye(const Eigen::Vector3d& p) const {
    if (projection != Projection::Perspective) return viewDirection();
    const Eigen::Vector3d d = eye - p;
    return d.norm() > 0 ? Eigen::Vector3d(d.normalized()) : viewDirection();
}

FeatureView featureView(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                        const Eigen::Vector3d& toEye) {
    FeatureView v{normals.empty() ? 1.0 : -1.0, 1.0};
    for (const Eigen::Vector3d& n : normals)
        if (n.norm() > 0) v.facing = std::max(v.facing, n.normalized().dot(toEye));
    if (points.size() > 2 && !normals.empty()) v.foreshortening = std::abs(v.facing);
    if (points.size() == 2 && (points[1] - points[0]).norm() > 0)
        v.foreshortening = (points[1] - points[0]).normalized().cross(toEye).norm();
    return v;
}

Eigen::Matrix4d Camera::viewProjection(double aspect) const {
    // View: gluLookAt (right-handed, camera looks down -z). A degenerate `up` (parallel to the
    // view direction or zero) is replaced by the world axis least aligned with the view.
    const Eigen::Vector3d f = -viewDirection();
    Eigen::Vector3d u = up;
    Eigen::Vector3d s = f.cross(u);
    if (!(s.norm() > 1e-12 * std::max(1.0, u.norm()))) {  // also catches NaN
        const Eigen::Vector3d a = f.cwiseAbs();
        u = a.x() <= a.y() && a.x() <= a.z() ? Eigen::Vector3d::UnitX()
            : a.y() <= a.z()                 ? Eigen::Vector3d::UnitY()
                                             : Eigen::Vector3d::UnitZ();
        s = f.cross(u);
    }
    s.normalize();
    u = s.cross(f);
    const Eigen::Vector3d e = projection == Projection::TwoD ? Eigen::Vector3d(target.x(), target.y(), 0) : eye;
    Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
    view.block<1, 3>(0, 0) = s.transpose();
    view.block<1, 3>(1, 0) = u.transpose();
    view.block<1, 3>(2, 0) = -f.transpose();
    view(0, 3) = -s.dot(e);
    view(1, 3) = -u.dot(e);
    view(2, 3) = f.dot(e);

    if (!(aspect > 0) || !std::isfinite(aspect)) aspect = 1.0;
    Eigen::Matrix4d proj = Eigen::Matrix4d::Zero();
    if (projection == Projection::Perspective) {
        // gluPerspective.
        const double t = 1.0 / std::tan(0.5 * fovYDegrees * M_PI / 180.0);
        const double n = nearPlane, fr = farPlane;
        proj(0, 0) = t / aspect;
        proj(1, 1) = t;
        proj(2, 2) = (fr + n) / (n - fr);
        proj(2, 3) = 2.0 * fr * n / (n - fr);
        proj(3, 2) = -1.0;
    } else {
        // glOrtho. 2D: depth range [-far, far] around the z = 0 plane (depth is unused there).
        const double top = 0.5 * viewHeight, right = top * aspect;
        const double n = projection == Projection::TwoD ? -farPlane : nearPlane, fr = farPlane;
        proj(0, 0) = 1.0 / right;
        proj(1, 1) = 1.0 / top;
        proj(2, 2) = -2.0 / (fr - n);
        proj(2, 3) = -(fr + n) / (fr - n);
        proj(3, 3) = 1.0;
    }
    return proj * view;
}

}  // namespace cdlab::render
