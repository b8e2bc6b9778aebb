// One rigid body's shape in the scenes of the demos that need a half-edge polyhedron (drop,
// polyhedron_plane): the presets and any convex polytope the user gives, with the same keys in
// both demos (docs/scenes.md, "Bodies").
#pragma once

#include <optional>
#include <string>

#include "core/geometry/polyhedron.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// {"box": {"half_extents"}}, {"tetrahedron" | "icosahedron": {"circumradius"}},
/// {"prism": {"sides", "radius", "half_height"}} or {"polytope": {"vertices": [...]}} (the convex
/// hull of at most kMaxShapeVertices points spanning a volume, recentred at its centre of mass so
/// the body's pose places that centre, as for the presets). `name` gets the key. Errors name the
/// JSON path; a pose key inside the body says that it belongs beside "body".
ConvexPolyhedron readConvexBody(const JsonNode& body, std::string& name);

/// The scenes' one vocabulary takes either of two synonymous keys — a preset's "radius" or
/// "circumradius" (the same length), a prism's "sides" or "n", a hull's "polytope" or "hull" —
/// not both (an error at the second).
std::optional<JsonNode> findEither(ObjectReader& reader, const char* key, const char* synonym);
/// The same, required: an error naming both keys when neither is there.
JsonNode getEither(ObjectReader& reader, const char* key, const char* synonym);

}  // namespace cdlab::demos
