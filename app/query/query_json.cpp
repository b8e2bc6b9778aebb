#include "app/query/query_json.h"

#include <cmath>

namespace cdlab::demos {

void requireFiniteAnswer(const Json& answer) {
    if (answer.is_number_float() && !std::isfinite(answer.get<double>()))
        throw InputError("query: the answer overflows double precision (coordinates too large)");
    if (answer.is_array() || answer.is_object())
        for (const Json& x : answer) requireFiniteAnswer(x);
}

}  // namespace cdlab::demos
