// The "mass_properties" op of `cdlab query` (docs/query.md):
//   {"op": "mass_properties", "a": {"polytope": {...}}, "density": 1}
//   -> {"volume": V, "mass": m, "center_of_mass": [x, y, z], "inertia": [[...], [...], [...]]}
// The solid is the convex hull of the polytope's world-frame vertices (after its position and
// rotation). "density" is optional (default 1, must be > 0); mass = density * volume. "inertia" is
// the inertia tensor about the centre of mass, world axes, units density * length^5 (= mass * length^2).
#pragma once

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Reads "a" (a polytope) and the optional "density" from the query object and answers the
/// mass_properties op; calls r.finish() (the caller has read "op" and ignored "id"). Throws
/// InputError for a shape other than a polytope, a non-positive density and a flat / degenerate hull.
Json answerMassPropertiesQuery(ObjectReader& r);

}  // namespace cdlab::demos
