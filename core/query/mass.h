// Mass properties of a query shape (`cdlab query`'s "mass_properties"): a polytope or box through its
// convex hull (core/geometry/mass_properties.h) in a local frame scaled by a power of two; a sphere,
// cylinder or cone in closed form (solid, uniform density; the cone's centroid a quarter of its
// height above the base). Tests: tests/app/query/*mass*_test.cpp.
#pragma once

#include <string>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "core/query/shape.h"

namespace cdlab {

struct MassQueryResult {
    enum class Status {
        Ok,
        UnsupportedKind,  ///< not a polytope, box, sphere, cylinder or cone
        NoVolume,         ///< a sphere of radius 0, a cylinder or cone of radius or half height 0
        DegenerateHull,   ///< the hull of the vertices is flat or a point (hullStatus)
        MassFailed,       ///< computeMassProperties refused (massStatus, message)
        OutOfRange,       ///< volume, mass or inertia leaves the range of normal doubles (volumeOrMass says which)
    };
    Status status = Status::Ok;
    HullStatus hullStatus = HullStatus::Ok;
    MassStatus massStatus = MassStatus::Ok;
    std::string message;
    bool volumeOrMass = false;  ///< OutOfRange: the volume or the mass (else the inertia)
    double volume = 0.0, mass = 0.0;
    Vec3 centerOfMass = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();  ///< about the centre of mass, world axes
};

/// The shape's volume, mass (density > 0), centre of mass and inertia about it in world axes.
MassQueryResult massPropertiesQuery(const QueryShape& shape, double density);

}  // namespace cdlab
