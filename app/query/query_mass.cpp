// `mass_properties` (docs/query.md): the query's JSON read into core's mass properties of a
// query shape (core/query/mass.h), the answer and its refusals written back as JSON.
#include "app/query/query_mass.h"

#include <string>

#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_shapes.h"
#include "core/query/mass.h"

namespace cdlab::demos {

Json answerMassPropertiesQuery(ObjectReader& r) {
    const JsonNode a = r.get("a");
    const QueryShape shape = parseQueryShape(a);
    double density = 1.0;
    if (auto d = r.find("density")) density = d->asPositive();
    r.finish();
    using Kind = QueryShape::Kind;
    const bool round = shape.kind == Kind::Sphere || shape.isCurved();
    if (!round && shape.kind != Kind::Polytope && shape.kind != Kind::Aabb && shape.kind != Kind::Obb)
        a.fail(std::string("mass_properties needs a polytope, box, sphere, cylinder or cone, got a ") + nameOf(shape.kind));
    if (!round) requireHullVerticesWithinLimit(shape.vertices.size(), "mass_properties", a);

    const MassQueryResult m = massPropertiesQuery(shape, density);
    using Status = MassQueryResult::Status;
    switch (m.status) {
        case Status::Ok: break;
        case Status::UnsupportedKind: a.fail("mass_properties: unsupported shape");
        case Status::NoVolume:
            if (shape.kind == Kind::Sphere) a.fail("a sphere of radius 0 has no volume");
            a.fail(std::string("a flat ") + nameOf(shape.kind) + " (radius or half_height 0) has no volume");
        case Status::DegenerateHull:
            a.fail(std::string("the ") + nameOf(shape.kind) + "'s hull is " + nameOf(m.hullStatus) + ": no volume");
        case Status::MassFailed: a.fail(std::string("mass properties: ") + nameOf(m.massStatus) + ": " + m.message);
        case Status::OutOfRange:
            a.fail("volume, mass or inertia leaves the range of double precision at this scale (" +
                   std::string(m.volumeOrMass ? "volume or mass" : "inertia") + ")");
    }
    Json rows = Json::array();
    for (int i = 0; i < 3; ++i)
        rows.push_back(Json::array({cleanZero(m.inertia(i, 0)), cleanZero(m.inertia(i, 1)), cleanZero(m.inertia(i, 2))}));
    return {{"volume", m.volume}, {"mass", m.mass}, {"center_of_mass", vecJson(m.centerOfMass)}, {"inertia", rows}};
}

}  // namespace cdlab::demos
