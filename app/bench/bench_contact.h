// Contact manifolds in `cdlab bench` (section "contact"): box–box, box–plane and hull–hull, cdlab's
// allocation-free box paths (core/contact/contact_box.h) beside its general SAT and plane contact,
// and Bullet's box–box detector and general hull clipping on the same poses when Bullet is
// installed. The value scored against the oracle is the deepest manifold point's depth; the
// iterations column holds the mean number of manifold points.
#pragma once

#include <vector>

#include "app/bench/bench_measure.h"

namespace cdlab::demos {

/// Appends the contact rows to `rows`.
void benchContacts(const Settings& settings, std::vector<Row>& rows);

}  // namespace cdlab::demos
