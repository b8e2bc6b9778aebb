#include "core/query/mass.h"

#include <cfloat>
#include <cmath>
#include <vector>

namespace cdlab {

namespace {

// The answer, or OutOfRange where it leaves the range of normal doubles (a 1e-100 body has inertia
// ~1e-500) — not zeros.
MassQueryResult answer(double volume, double density, const Vec3& center, const Mat3& inertia) {
    MassQueryResult out;
    const double mass = density * volume;
    const auto representable = [](double x) { return std::isfinite(x) && std::abs(x) >= DBL_MIN; };
    if (!representable(volume) || !representable(mass) || !representable(inertia.trace()) || !inertia.allFinite() ||
        !center.allFinite()) {
        out.status = MassQueryResult::Status::OutOfRange;
        out.volumeOrMass = !representable(volume) || !representable(mass);
        return out;
    }
    out.volume = volume;
    out.mass = mass;
    out.centerOfMass = center;
    out.inertia = inertia;
    return out;
}

MassQueryResult failure(MassQueryResult::Status status) {
    MassQueryResult out;
    out.status = status;
    return out;
}

// Spheres, cylinders and cones in closed form: moments about the centroid in the body axes (y the
// axis), turned into world axes, R I Rᵀ.
MassQueryResult roundMassProperties(const QueryShape& s, double density) {
    const double pi = 3.14159265358979323846;
    if (s.kind == QueryShape::Kind::Sphere) {
        const double r = s.radius, volume = 4.0 / 3.0 * pi * r * r * r;
        if (!(r > 0)) return failure(MassQueryResult::Status::NoVolume);
        return answer(volume, density, s.vertices[0], (0.4 * density * volume * r * r) * Mat3::Identity());
    }
    const CurvedSolid& c = s.curved;
    const double r = c.radius, h = c.halfHeight;
    if (!(r > 0) || !(h > 0)) return failure(MassQueryResult::Status::NoVolume);
    double volume, axial, across, centroid;
    if (!c.cone) {
        volume = 2 * pi * r * r * h;
        axial = 0.5 * r * r;                  // per unit mass
        across = r * r / 4 + h * h / 3;       // (3 r² + (2h)²) / 12
        centroid = 0.0;
    } else {
        const double height = 2 * h;
        volume = pi * r * r * height / 3;
        axial = 0.3 * r * r;
        across = 3 * r * r / 20 + 3 * height * height / 80;
        centroid = -h / 2;  // a quarter of the height above the base at −h
    }
    const double mass = density * volume;
    const Mat3 local = Vec3(mass * across, mass * axial, mass * across).asDiagonal();
    return answer(volume, density, Vec3(c.center + centroid * c.axis()), c.rotation * local * c.rotation.transpose());
}

}  // namespace

MassQueryResult massPropertiesQuery(const QueryShape& shape, double density) {
    using Kind = QueryShape::Kind;
    if (shape.kind == Kind::Sphere || shape.isCurved()) return roundMassProperties(shape, density);
    if (shape.kind != Kind::Polytope && shape.kind != Kind::Aabb && shape.kind != Kind::Obb)
        return failure(MassQueryResult::Status::UnsupportedKind);

    // A local frame: translated to the first vertex (the inertia about the centre of mass does not
    // depend on where the body is, and the hull then loses no digits to a far offset), and scaled
    // by a power of two (exact) so the largest local coordinate is in [0.5, 1): volume and inertia
    // neither underflow nor overflow inside the computation. The answer is scaled back exactly
    // (volume by 2^3k, centre by 2^k, inertia by 2^5k) — and refused where that leaves the range
    // of normal doubles (a 1e-100 cube has inertia ~1e-500).
    const Vec3 origin = shape.vertices.front();
    double m = 0.0;
    for (const Vec3& v : shape.vertices) m = std::max(m, (v - origin).cwiseAbs().maxCoeff());
    int k = 0;
    if (m > 0) std::frexp(m, &k);
    std::vector<Vec3> unit;
    for (const Vec3& v : shape.vertices) unit.push_back(scaled(v - origin, -k));

    const HullResult hull = convexHull(unit);
    if (hull.status != HullStatus::Ok) {
        MassQueryResult out = failure(MassQueryResult::Status::DegenerateHull);
        out.hullStatus = hull.status;
        return out;
    }
    const MassProperties mp = computeMassProperties(hull.polyhedron, {.density = density});
    if (!mp.ok()) {
        MassQueryResult out = failure(MassQueryResult::Status::MassFailed);
        out.massStatus = mp.status;
        out.message = mp.message;
        return out;
    }
    const double volume = std::ldexp(mp.volume, 3 * k);
    const Vec3 c = scaled(mp.centerOfMass, k) + origin;
    const Mat3 I = mp.inertia.unaryExpr([k](double x) { return std::ldexp(x, 5 * k); });
    return answer(volume, density, c, I);
}

}  // namespace cdlab
