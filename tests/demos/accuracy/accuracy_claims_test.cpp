// What the accuracy scenes' captions claim is checked against the trace they draw (issue 42: a
// caption said "median error 0" where Johnson's median at 1e-6 is 7.6e-17). error_vs_scale's
// caption: "within a few roundings (u) from 1e-6 to 1e6, both solvers" — every decade's max, both
// solvers, at most 8 u.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "app/catalog/catalog.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("accuracy/error_vs_scale: the caption's claim holds in its trace") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/accuracy/error_vs_scale.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    REQUIRE(t.contains("decades"));
    const double u = std::ldexp(1.0, -53);
    int decades = 0;
    for (const Json& d : t["decades"]) {
        if (d["pairs"].get<int>() == 0) continue;
        ++decades;
        for (const char* solver : {"signed_volumes", "johnson"}) {
            INFO("decade from " << d["from"].get<double>() << ", " << solver);
            CHECK(d[solver]["max"].get<double>() <= 8 * u);
        }
    }
    CHECK(decades == 12);  // 1e-6 .. 1e6
    const std::string caption = loadScene(file)->common().caption;
    CHECK(caption.find("few roundings") != std::string::npos);  // the claim this test stands behind
}
