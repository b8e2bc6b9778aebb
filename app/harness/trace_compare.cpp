#include "app/harness/trace_compare.h"

#include <cmath>
#include <sstream>

namespace cdlab::demos {

namespace {

constexpr std::size_t kMaxReported = 8;

struct Comparer {
    double absolute, relative;
    TraceComparison result;

    void mismatch(const std::string& path, const std::string& what) {
        if (result.mismatches.size() < kMaxReported) result.mismatches.push_back({path, what});
        ++result.mismatchCount;
    }

    void compare(const Json& a, const Json& e, const std::string& path) {
        if (a.is_number() && e.is_number()) {
            double x = a.get<double>(), y = e.get<double>();
            double diff = std::fabs(x - y);
            if (diff > result.maxNumberDiff) {
                result.maxNumberDiff = diff;
                result.maxNumberDiffPath = path;
            }
            double tol = absolute + relative * std::fabs(y);
            if (!(diff <= tol)) {
                std::ostringstream s;
                s.precision(17);
                s << "expected " << y << ", got " << x << " (|diff| " << diff << " > tolerance " << tol << ")";
                mismatch(path, s.str());
            }
            return;
        }
        if (a.type() != e.type()) {
            mismatch(path, "expected " + JsonNode::describe(e) + ", got " + JsonNode::describe(a));
            return;
        }
        if (a.is_array()) {
            if (a.size() != e.size()) {
                mismatch(path, "expected " + std::to_string(e.size()) + " elements, got " + std::to_string(a.size()));
                return;
            }
            for (std::size_t i = 0; i < a.size(); ++i) compare(a[i], e[i], path + "[" + std::to_string(i) + "]");
        } else if (a.is_object()) {
            for (auto it = e.begin(); it != e.end(); ++it) {
                auto found = a.find(it.key());
                if (found == a.end()) mismatch(path + "." + it.key(), "missing in actual trace");
                else compare(*found, it.value(), path + "." + it.key());
            }
            for (auto it = a.begin(); it != a.end(); ++it)
                if (!e.contains(it.key())) mismatch(path + "." + it.key(), "not in golden trace");
        } else if (a != e) {
            mismatch(path, "expected " + e.dump() + ", got " + a.dump());
        }
    }
};

}  // namespace

std::string TraceComparison::summary() const {
    std::ostringstream s;
    s.precision(3);
    if (passed()) {
        s << "trace matches (max |diff| " << maxNumberDiff;
        if (!maxNumberDiffPath.empty()) s << " at " << maxNumberDiffPath;
        s << ")";
    } else {
        s << mismatchCount << " trace mismatch(es); first: " << mismatches.front().path << ": "
          << mismatches.front().what;
    }
    return s.str();
}

TraceComparison compareTraces(const Json& actual, const Json& expected, double absolute, double relative) {
    Comparer c{absolute, relative, {}};
    c.compare(actual, expected, "$");
    return c.result;
}

}  // namespace cdlab::demos
