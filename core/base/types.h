// Basic geometric types shared by every core algorithm (double precision, Eigen).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <initializer_list>
#include <limits>
#include <span>

namespace cdlab {

/// The quiet NaN that invalid or undefined results carry.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// No NaN or infinite coordinate in any of the points (true for none): the one spelling of "all
/// coordinates finite" for point sets in core (a single vector asks Eigen: v.allFinite()).
inline bool allFinite(std::span<const Vec3> points) {
    for (const Vec3& p : points)
        if (!p.allFinite()) return false;
    return true;
}
inline bool allFinite(std::span<const Vec2> points) {
    for (const Vec2& p : points)
        if (!p.allFinite()) return false;
    return true;
}
inline bool allFinite(std::initializer_list<Vec3> points) {
    return allFinite(std::span<const Vec3>(points.begin(), points.size()));
}

/// Line segment from a to b (a == b is a point and is allowed).
struct Segment {
    Vec3 a, b;
};

/// Triangle with vertices a, b, c in this order (zero area is allowed).
struct Triangle {
    Vec3 a, b, c;
    /// No NaN or infinite coordinate.
    bool allFinite() const { return a.allFinite() && b.allFinite() && c.allFinite(); }
};

/// Tetrahedron with vertices a, b, c, d (zero volume is allowed).
struct Tetrahedron {
    Vec3 a, b, c, d;
};

/// Plane: the points x with normal · x = offset. normal need not be unit.
struct Plane {
    Vec3 normal;
    double offset = 0.0;
};

/// Rigid transform: x_world = rotation * x_body + position. rotation is a unit quaternion.
struct Transform {
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();

    Vec3 apply(const Vec3& body) const { return rotation * body + position; }
    Vec3 applyInverse(const Vec3& world) const { return rotation.conjugate() * (world - position); }
    Vec3 rotate(const Vec3& v) const { return rotation * v; }
    Vec3 rotateInverse(const Vec3& v) const { return rotation.conjugate() * v; }
};

}  // namespace cdlab
