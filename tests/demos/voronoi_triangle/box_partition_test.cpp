// golden/voronoi_triangle/box run numerically: the partition frame's 27 cells. Each cell's centre
// is taken into the box's frame with the trace's axes and classified by hand (outside the slab of
// an axis on the + or − side, or within it); that gives the cell's signs, its kind (vertex, edge,
// face or inside by the number of axes it is outside of) and its region name, which must be core's.
#include <doctest/doctest.h>

#include <set>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("box Voronoi partition: 27 cells, each classified by hand from its centre") {
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/voronoi_triangle/box.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    const auto v = [](const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); };
    const Vec3 c = v(t["center"]), e = v(t["half_extents"]);
    Mat3 axes;
    for (int i = 0; i < 3; ++i) axes.col(i) = v(t["axes"][i]);
    const Json& cells = t["partition"];
    REQUIRE(cells.size() == 27);
    std::set<std::array<int, 3>> seen;
    int count[4] = {0, 0, 0, 0};
    for (const Json& cell : cells) {
        const Vec3 u = axes.transpose() * (v(cell["centre"]) - c);
        std::array<int, 3> signs{};
        std::string name;
        int outside = 0;
        for (int i = 0; i < 3; ++i) {
            signs[std::size_t(i)] = u[i] > e[i] ? 1 : u[i] < -e[i] ? -1 : 0;
            if (signs[std::size_t(i)] != 0) {
                ++outside;
                name += std::string(signs[std::size_t(i)] > 0 ? "+" : "−") + "xyz"[i];
            }
            CHECK(cell["signs"][i].get<int>() == signs[std::size_t(i)]);
        }
        seen.insert(signs);
        static const char* kKind[4] = {"inside", "face ", "edge ", "vertex "};
        const std::string expected = outside == 0 ? "inside" : kKind[outside] + name;
        CHECK(cell["region"].get<std::string>() == expected);
        CHECK(cell["dimension"].get<int>() == 3 - outside);
        ++count[outside];
    }
    CHECK(seen.size() == 27);  // every cell of the grid once
    CHECK(count[0] == 1);
    CHECK(count[1] == 6);
    CHECK(count[2] == 12);
    CHECK(count[3] == 8);
}
