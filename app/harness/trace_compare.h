// Numeric comparison of JSON traces against their goldens: same structure, same strings,
// numbers within |a - e| <= absolute + relative * |e|.
#pragma once

#include <string>
#include <vector>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

struct TraceMismatch {
    std::string path;  // "$.queries[2].point[1]"
    std::string what;  // "expected 0.5, got 0.5000001 (|diff| 1e-07 > tolerance 1.5e-09)"
};

struct TraceComparison {
    std::vector<TraceMismatch> mismatches;  // the first few only
    std::size_t mismatchCount = 0;
    double maxNumberDiff = 0;  // largest |a - e| among numbers
    std::string maxNumberDiffPath;
    bool passed() const { return mismatchCount == 0; }
    std::string summary() const;  // one line
};

TraceComparison compareTraces(const Json& actual, const Json& expected, double absolute, double relative);

}  // namespace cdlab::demos
