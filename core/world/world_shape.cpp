#include "core/world/world_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "core/geometry/polyhedron_presets.h"

namespace cdlab {

const char* nameOf(WorldShape::Kind kind) {
    switch (kind) {
        case WorldShape::Kind::Box: return "box";
        case WorldShape::Kind::Hull: return "hull";
        case WorldShape::Kind::Sphere: return "sphere";
        case WorldShape::Kind::Capsule: return "capsule";
        case WorldShape::Kind::Plane: return "plane";
    }
    return "?";
}

namespace {

bool positiveFinite(double x) { return x > 0 && std::isfinite(x); }

WorldShapeBuild refused(std::string message) {
    WorldShapeBuild b;
    b.message = std::move(message);
    return b;
}

double farthestVertex(const ConvexPolyhedron& p) {
    double r = 0.0;
    for (const auto& v : p.vertices()) r = std::max(r, v.position.norm());
    return r;
}

}  // namespace

WorldShapeBuild worldBox(const Vec3& h) {
    if (!positiveFinite(h.x()) || !positiveFinite(h.y()) || !positiveFinite(h.z()))
        return refused("a box's half extents must be finite and > 0");
    WorldShapeBuild b;
    b.shape.kind = WorldShape::Kind::Box;
    b.shape.halfExtents = h;
    b.shape.hull = presets::box(h);
    b.shape.boundingRadius = h.norm();
    b.volume = 8.0 * h.x() * h.y() * h.z();
    const Vec3 s = h.cwiseProduct(h);
    b.unitInertia = Mat3::Zero();
    b.unitInertia(0, 0) = b.volume * (s.y() + s.z()) / 3.0;
    b.unitInertia(1, 1) = b.volume * (s.x() + s.z()) / 3.0;
    b.unitInertia(2, 2) = b.volume * (s.x() + s.y()) / 3.0;
    return b;
}

WorldShapeBuild worldHull(const std::vector<Vec3>& points) {
    if (points.size() < 4) return refused("a hull needs at least 4 points");
    for (const Vec3& p : points)
        if (!p.allFinite()) return refused("a hull's points must be finite");
    const HullResult hull = convexHull(points);
    if (!hull.ok()) return refused("convex hull failed: " + hull.message);
    const MassProperties mass = computeMassProperties(hull.polyhedron);
    if (!mass.ok()) return refused("mass properties failed: " + mass.message);
    PolyhedronBuild recentred = hull.polyhedron.translated(-mass.centerOfMass);
    if (!recentred.ok()) return refused("recentred hull failed: " + recentred.check.message);
    WorldShapeBuild b;
    b.shape.kind = WorldShape::Kind::Hull;
    b.shape.hull = std::move(recentred.polyhedron);
    b.shape.boundingRadius = farthestVertex(b.shape.hull);
    b.volume = mass.mass;
    b.unitInertia = mass.inertia;
    b.inputOrigin = -mass.centerOfMass;
    return b;
}

WorldShapeBuild worldSphere(double radius) {
    if (!positiveFinite(radius)) return refused("a sphere's radius must be finite and > 0");
    WorldShapeBuild b;
    b.shape.kind = WorldShape::Kind::Sphere;
    b.shape.radius = radius;
    b.shape.boundingRadius = radius;
    b.volume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    b.unitInertia = Mat3::Identity() * (0.4 * b.volume * radius * radius);
    return b;
}

WorldShapeBuild worldCapsule(double halfHeight, double radius) {
    if (!positiveFinite(radius) || !(halfHeight >= 0) || !std::isfinite(halfHeight))
        return refused("a capsule's radius must be finite and > 0, its half height finite and >= 0");
    const double r = radius, h = halfHeight, pi = std::numbers::pi;
    const double mc = pi * r * r * 2.0 * h, ms = 4.0 / 3.0 * pi * r * r * r;
    WorldShapeBuild b;
    b.shape.kind = WorldShape::Kind::Capsule;
    b.shape.radius = r;
    b.shape.halfHeight = h;
    b.shape.boundingRadius = h + r;
    b.volume = mc + ms;
    const double axial = mc * r * r / 2.0 + ms * 2.0 * r * r / 5.0;
    const double across = mc * (r * r / 4.0 + h * h / 3.0) + ms * (2.0 * r * r / 5.0 + h * h + 0.75 * h * r);
    b.unitInertia = Mat3::Zero();
    b.unitInertia(0, 0) = across;
    b.unitInertia(1, 1) = axial;
    b.unitInertia(2, 2) = across;
    return b;
}

WorldShapeBuild worldPlane(const Vec3& normal, double offset) {
    const double n = normal.norm();
    if (!(n > 0) || !std::isfinite(n) || !std::isfinite(offset))
        return refused("a plane's normal must be non-zero and finite, its offset finite");
    WorldShapeBuild b;
    b.shape.kind = WorldShape::Kind::Plane;
    b.shape.plane = Plane{normal / n, offset / n};
    return b;
}

Aabb worldBounds(const WorldShape& shape, const Transform& pose) {
    switch (shape.kind) {
        case WorldShape::Kind::Box: {
            // |R| h: the extent of a rotated box (Ericson, Real-Time Collision Detection §4.2.6).
            const Mat3 r = pose.rotation.toRotationMatrix().cwiseAbs();
            const Vec3 e = r * shape.halfExtents;
            return Aabb{pose.position - e, pose.position + e};
        }
        case WorldShape::Kind::Hull: {
            Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
            const Mat3 r = pose.rotation.toRotationMatrix();
            for (const auto& v : shape.hull.vertices()) {
                const Vec3 p = r * v.position;
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
            return Aabb{lo + pose.position, hi + pose.position};
        }
        case WorldShape::Kind::Sphere: {
            const Vec3 e = Vec3::Constant(shape.radius);
            return Aabb{pose.position - e, pose.position + e};
        }
        case WorldShape::Kind::Capsule: {
            const Vec3 axis = pose.rotation * Vec3(0.0, shape.halfHeight, 0.0);
            const Vec3 e = axis.cwiseAbs() + Vec3::Constant(shape.radius);
            return Aabb{pose.position - e, pose.position + e};
        }
        case WorldShape::Kind::Plane: break;
    }
    return Aabb{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
}

}  // namespace cdlab
