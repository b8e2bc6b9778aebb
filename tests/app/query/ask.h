// Helpers shared by the cdlab query tests: one query object in, its answer out; an answer's keys;
// a vector as query text (17 significant digits: the double read back exactly).
#pragma once

#include <set>
#include <sstream>
#include <string>

#include "core/base/types.h"
#include "app/query/query.h"

namespace cdlab::test {

inline demos::Json ask(const demos::Json& q) { return demos::answerQuery(q.dump()); }

inline std::set<std::string> keysOf(const demos::Json& j) {
    std::set<std::string> k;
    for (auto it = j.begin(); it != j.end(); ++it) k.insert(it.key());
    return k;
}

inline std::string vecText(const Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << v.x() << "," << v.y() << "," << v.z() << "]";
    return s.str();
}

}  // namespace cdlab::test
