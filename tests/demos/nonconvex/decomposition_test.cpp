// golden/nonconvex/*: the decomposition frame's walk checked by volumes. The kept pieces' volumes
// add up to the prism's (its outline's shoelace area times its height: no piece missing, none
// overlapping), every cut cell's volume is its two children's, and the counts the panels print
// per depth follow from the steps.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("convex decomposition walk: kept volumes add up to the prism, every cut conserves volume") {
    for (const char* name : {"u_and_l", "apart"}) {
        CAPTURE(name);
        const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/nonconvex/" + name + ".json";
        const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
        const Json& prism = s["a"]["prism"];
        double area = 0;
        const Json& o = prism["outline"];
        for (std::size_t i = 0; i < o.size(); ++i) {
            const Json &p = o[i], &q = o[(i + 1) % o.size()];
            area += p[0].get<double>() * q[1].get<double>() - q[0].get<double>() * p[1].get<double>();
        }
        const double volume = 0.5 * std::abs(area) * prism["height"].get<double>();
        const Json& steps = t["decomposition_a"];
        double kept = 0;
        int pieces = 0;
        std::map<int, double> childVolume;
        for (const Json& st : steps) {
            if (st["kind"] == "solid" && st["piece"].get<int>() >= 0) kept += st["volume"].get<double>(), ++pieces;
            if (st["parent"].get<int>() >= 0) childVolume[st["parent"].get<int>()] += st["volume"].get<double>();
        }
        CHECK(pieces == t["pieces_a"].get<int>());
        CHECK(kept == doctest::Approx(volume).epsilon(1e-9));
        for (const Json& st : steps)
            if (st["kind"] == "inner")
                CHECK(childVolume[st["node"].get<int>()] == doctest::Approx(st["volume"].get<double>()).epsilon(1e-9));
    }
}
