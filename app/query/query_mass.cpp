#include "app/query/query_mass.h"

#include <cfloat>
#include <cmath>
#include <string>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

namespace {

// Volume, mass, centre of mass and world-axis inertia about it as JSON; an error where they leave
// the range of normal doubles (a 1e-100 body has inertia ~1e-500) — not zeros.
Json massJson(double volume, double density, const Vec3& center, const Mat3& inertia, const JsonNode& a) {
    const double mass = density * volume;
    const auto representable = [](double x) { return std::isfinite(x) && std::abs(x) >= DBL_MIN; };
    if (!representable(volume) || !representable(mass) || !representable(inertia.trace()) || !inertia.allFinite() ||
        !center.allFinite())
        a.fail("volume, mass or inertia leaves the range of double precision at this scale (" +
               std::string(!representable(volume) || !representable(mass) ? "volume or mass" : "inertia") + ")");
    Json rows = Json::array();
    for (int i = 0; i < 3; ++i)
        rows.push_back(Json::array({cleanZero(inertia(i, 0)), cleanZero(inertia(i, 1)), cleanZero(inertia(i, 2))}));
    return {{"volume", volume}, {"mass", mass}, {"center_of_mass", vecJson(center)}, {"inertia", rows}};
}

// Spheres, cylinders and cones in closed form (solid, uniform density; the cone's centroid is a
// quarter of its height above the base): moments about the centroid in the body axes (y the axis),
// turned into world axes, R I Rᵀ.
Json roundMassProperties(const QueryShape& s, double density, const JsonNode& a) {
    const double pi = 3.14159265358979323846;
    if (s.kind == QueryShape::Kind::Sphere) {
        const double r = s.radius, volume = 4.0 / 3.0 * pi * r * r * r;
        if (!(r > 0)) a.fail("a sphere of radius 0 has no volume");
        return massJson(volume, density, s.vertices[0], (0.4 * density * volume * r * r) * Mat3::Identity(), a);
    }
    const CurvedSolid& c = s.curved;
    const double r = c.radius, h = c.halfHeight;
    if (!(r > 0) || !(h > 0)) a.fail(std::string("a flat ") + nameOf(s.kind) + " (radius or half_height 0) has no volume");
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
    return massJson(volume, density, Vec3(c.center + centroid * c.axis()), c.rotation * local * c.rotation.transpose(), a);
}

}  // namespace

Json answerMassPropertiesQuery(ObjectReader& r) {
    const JsonNode a = r.get("a");
    const QueryShape shape = parseQueryShape(a);
    double density = 1.0;
    if (auto d = r.find("density")) density = d->asPositive();
    r.finish();
    using Kind = QueryShape::Kind;
    if (shape.kind == Kind::Sphere || shape.isCurved()) return roundMassProperties(shape, density, a);
    if (shape.kind != Kind::Polytope && shape.kind != Kind::Aabb && shape.kind != Kind::Obb)
        a.fail(std::string("mass_properties needs a polytope, box, sphere, cylinder or cone, got a ") + nameOf(shape.kind));

    requireHullVerticesWithinLimit(shape.vertices.size(), "mass_properties", a);

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
    if (hull.status != HullStatus::Ok)
        a.fail(std::string("the ") + nameOf(shape.kind) + "'s hull is " + nameOf(hull.status) + ": no volume");
    const MassProperties mp = computeMassProperties(hull.polyhedron, {.density = density});
    if (!mp.ok()) a.fail(std::string("mass properties: ") + nameOf(mp.status) + ": " + mp.message);

    const double volume = std::ldexp(mp.volume, 3 * k);
    const Vec3 c = scaled(mp.centerOfMass, k) + origin;
    const Mat3 I = mp.inertia.unaryExpr([k](double x) { return std::ldexp(x, 5 * k); });
    return massJson(volume, density, c, I, a);
}

}  // namespace cdlab::demos
