#include "demos/lib/query_mass.h"

namespace cdlab::demos {

Json answerMassPropertiesQuery(ObjectReader& r) {
    r.node().fail("op 'mass_properties' is not available in this build yet");
}

}  // namespace cdlab::demos
