#include "demos/lib/query_contact.h"

namespace cdlab::demos {

Json answerContactQuery(const std::string& op, ObjectReader& reader) {
    reader.node().fail("op '" + op + "' is not available in this build");
}

}  // namespace cdlab::demos
