#include "demos/lib/query_mass.h"

#include <cmath>
#include <string>

#include "core/convex_hull.h"
#include "core/mass_properties.h"
#include "demos/lib/query_shapes.h"

namespace cdlab::demos {

Json answerMassPropertiesQuery(ObjectReader& r) {
    const JsonNode a = r.get("a");
    const QueryShape shape = parseQueryShape(a);
    double density = 1.0;
    if (auto d = r.find("density")) density = d->asPositive();
    r.finish();
    if (shape.kind != QueryShape::Kind::Polytope)
        a.fail(std::string("mass_properties needs a polytope, got a ") + toString(shape.kind));

    // Scale by a power of two (exact) so the largest coordinate is in [0.5, 1): volume and inertia
    // then neither underflow nor overflow inside the computation; the answer is scaled back exactly
    // (volume by 2^3k, centre by 2^k, inertia by 2^5k).
    double m = 0.0;
    for (const Vec3& v : shape.vertices) m = std::max(m, v.cwiseAbs().maxCoeff());
    int k = 0;
    if (m > 0) std::frexp(m, &k);
    std::vector<Vec3> unit;
    for (const Vec3& v : shape.vertices) unit.push_back(v.unaryExpr([k](double c) { return std::ldexp(c, -k); }));

    const HullResult hull = convexHull(unit);
    if (hull.status != HullStatus::Ok) a.fail(std::string("the polytope's hull is ") + statusName(hull.status) + ": no volume");
    const MassProperties mp = computeMassProperties(hull.polyhedron, {.density = density});
    if (!mp.ok()) a.fail(std::string("mass properties: ") + statusName(mp.status) + ": " + mp.message);

    const double volume = std::ldexp(mp.volume, 3 * k);
    const double mass = density * volume;
    const Vec3 c = mp.centerOfMass.unaryExpr([k](double x) { return std::ldexp(x, k); });
    const Mat3 I = mp.inertia.unaryExpr([k](double x) { return std::ldexp(x, 5 * k); });
    if (!std::isfinite(volume) || !std::isfinite(mass) || !I.allFinite() || volume == 0.0)
        a.fail("volume or inertia overflows / underflows double at this scale");
    Json inertia = Json::array();
    for (int i = 0; i < 3; ++i) inertia.push_back(Json::array({I(i, 0), I(i, 1), I(i, 2)}));
    return {{"volume", volume},
            {"mass", mass},
            {"center_of_mass", Json::array({c.x(), c.y(), c.z()})},
            {"inertia", inertia}};
}

}  // namespace cdlab::demos
