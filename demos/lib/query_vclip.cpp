#include "demos/lib/query_vclip.h"

namespace cdlab::demos {

Json answerFeatureWalkQuery(const std::string& op, const std::string& method, const QueryShape&, const QueryShape&,
                            const JsonNode& aNode, const JsonNode&, bool) {
    aNode.fail("method '" + method + "' for op '" + op + "' is not available in this build");
}

}  // namespace cdlab::demos
