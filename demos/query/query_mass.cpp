#include "demos/query/query_mass.h"

#include <cfloat>
#include <cmath>
#include <string>

#include "core/geometry/convex_hull.h"
#include "core/geometry/mass_properties.h"
#include "demos/query/query_json.h"
#include "demos/query/query_limits.h"
#include "demos/query/query_shapes.h"

namespace cdlab::demos {

Json answerMassPropertiesQuery(ObjectReader& r) {
    const JsonNode a = r.get("a");
    const QueryShape shape = parseQueryShape(a);
    double density = 1.0;
    if (auto d = r.find("density")) density = d->asPositive();
    r.finish();
    if (shape.kind != QueryShape::Kind::Polytope)
        a.fail(std::string("mass_properties needs a polytope, got a ") + nameOf(shape.kind));

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
        a.fail(std::string("the polytope's hull is ") + nameOf(hull.status) + ": no volume");
    const MassProperties mp = computeMassProperties(hull.polyhedron, {.density = density});
    if (!mp.ok()) a.fail(std::string("mass properties: ") + nameOf(mp.status) + ": " + mp.message);

    const double volume = std::ldexp(mp.volume, 3 * k);
    const double mass = density * volume;
    const Vec3 c = scaled(mp.centerOfMass, k) + origin;
    const Mat3 I = mp.inertia.unaryExpr([k](double x) { return std::ldexp(x, 5 * k); });
    // The principal moments are about volume * size^2: when their scale leaves the normal range
    // the unscaled tensor has lost its digits (or overflowed) — an error, not zeros.
    const double trace = I.trace();
    const auto representable = [](double x) { return std::isfinite(x) && std::abs(x) >= DBL_MIN; };
    if (!representable(volume) || !representable(mass) || !representable(trace) || !I.allFinite())
        a.fail("volume, mass or inertia leaves the range of double precision at this scale (" +
               std::string(!representable(volume) || !representable(mass) ? "volume or mass" : "inertia") + ")");
    Json inertia = Json::array();
    for (int i = 0; i < 3; ++i)
        inertia.push_back(Json::array({cleanZero(I(i, 0)), cleanZero(I(i, 1)), cleanZero(I(i, 2))}));
    return {{"volume", volume}, {"mass", mass}, {"center_of_mass", vecJson(c)}, {"inertia", inertia}};
}

}  // namespace cdlab::demos
