// The contact-model ops of `cdlab query` (docs/query.md): "contact" (the manifold of two
// shapes, computed by core/query/contact.h) and "mass_properties" (volume, centre of mass, inertia
// tensor).
#pragma once

#include <string>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Reads the op's keys from the query object and answers `op` ("contact" or "mass_properties").
/// Throws InputError.
Json answerContactQuery(const std::string& op, ObjectReader& reader);

}  // namespace cdlab::demos
