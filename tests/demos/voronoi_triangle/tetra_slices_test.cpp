// golden/voronoi_triangle/tetrahedron run numerically: the regions frame's four slices. Each cell's
// centroid is classified by brute force — the nearest of the tetrahedron's vertices, edge interiors,
// face interiors, or the inside — which must name the cell's region; the cells of a slice tile its
// square window (areas add up).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace tetra_slices_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

/// The feature of tetrahedron t whose relative interior holds the point of t nearest p, by name.
std::string nearestFeature(const std::vector<Vec3>& t, const Vec3& p) {
    static const char* kName = "ABCD";
    // Inside: on the inner side of every face.
    bool inside = true;
    for (int i = 0; i < 4; ++i) {
        const Vec3 &a = t[(i + 1) % 4], &b = t[(i + 2) % 4], &c = t[(i + 3) % 4];
        const Vec3 n = (b - a).cross(c - a);
        if (n.dot(p - a) * n.dot(t[i] - a) < 0) inside = false;
    }
    if (inside) return "ABCD";
    double best = INFINITY;
    std::string name;
    const auto offer = [&](const Vec3& q, const std::string& n) {
        if ((q - p).norm() < best) best = (q - p).norm(), name = n;
    };
    for (int i = 0; i < 4; ++i) offer(t[i], std::string(1, kName[i]));
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const Vec3 e = t[j] - t[i];
            const double s = (p - t[i]).dot(e) / e.squaredNorm();
            if (s > 0 && s < 1) offer(t[i] + s * e, std::string(1, kName[i]) + kName[j]);
        }
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            for (int k = j + 1; k < 4; ++k) {
                const Vec3 n = (t[j] - t[i]).cross(t[k] - t[i]).normalized();
                const Vec3 q = p - n.dot(p - t[i]) * n;
                const auto side = [&](const Vec3& a, const Vec3& b) { return n.dot((b - a).cross(q - a)); };
                const double s0 = side(t[i], t[j]), s1 = side(t[j], t[k]), s2 = side(t[k], t[i]);
                if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0))
                    offer(q, std::string(1, kName[i]) + kName[j] + kName[k]);
            }
    return name;
}

}  // namespace tetra_slices_test

TEST_CASE("tetrahedron region slices: each cell's centroid is nearest its region's feature, cells tile the window") {
    using namespace tetra_slices_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/voronoi_triangle/tetrahedron.json";
    const Json t = loadScene(file)->run(RunContext{}).trace;
    std::vector<Vec3> tet;
    for (const Json& v : t["vertices"]) tet.push_back(vec(v));
    std::set<std::string> all;
    for (const Json& slice : t["slices"]) {
        const double half = slice["half_width"].get<double>();
        double area = 0;
        for (const Json& cell : slice["cells"]) {
            std::vector<Vec3> poly;
            for (const Json& p : cell["polygon"]) poly.push_back(vec(p));
            Vec3 c = Vec3::Zero();
            for (const Vec3& p : poly) c += p;
            c /= double(poly.size());
            for (std::size_t i = 1; i + 1 < poly.size(); ++i) area += 0.5 * (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]).norm();
            CAPTURE(cell["region"].get<std::string>());
            CHECK(nearestFeature(tet, c) == cell["region"].get<std::string>());
            all.insert(cell["region"].get<std::string>());
        }
        CHECK(area == doctest::Approx(4 * half * half).epsilon(1e-9));
    }
    CHECK(all.size() == 15);
}
