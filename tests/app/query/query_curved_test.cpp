// Cylinders and cones in `cdlab query` (intersect, distance, penetration), checked against
// certificates built here from the shapes' own closed forms, sharing no code with the query:
//   distance d with points p, q: p in A and q in B (membership), |p − q| = d, and the direction
//     n = (q − p)/d separates by d: min_B n·x − max_A n·x >= d (so no pair is nearer);
//   depth d with normal n: the overlap along n, max_A n·x − min_B n·x, is d (translating b by d·n
//     leaves them touching), and no direction overlaps by less (a search over 3000 directions
//     refined by a shrinking pattern search: the depth is the least overlap over all directions).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "app/query/query.h"
#include "app/scene/json_reader.h"
#include "tests/app/query/curved_solid.h"

using namespace cdlab::demos;
using cdlab::Vec3;
using cdlab::test::Solid;
using cdlab::test::randomSolid;
using cdlab::test::vecOf;

namespace {

// Least overlap max_A n·x − min_B n·x over unit n: the penetration depth of A and B.
double leastOverlap(const Solid& a, const Solid& b, const Vec3& hint) {
    const auto overlap = [&](const Vec3& n) { return a.supportValue(n) + b.supportValue(-n); };
    Vec3 best = hint.normalized();
    double bestValue = overlap(best);
    const int count = 3000;  // a Fibonacci sphere
    for (int i = 0; i < count; ++i) {
        const double z = 1 - (2 * i + 1.0) / count, phi = i * 2.399963229728653;
        const double s = std::sqrt(1 - z * z);
        const Vec3 n(s * std::cos(phi), s * std::sin(phi), z);
        if (const double v = overlap(n); v < bestValue) bestValue = v, best = n;
    }
    for (double step = 0.05; step > 1e-13; step *= 0.5) {
        bool improved = true;
        while (improved) {
            improved = false;
            const Vec3 t1 = best.unitOrthogonal(), t2 = best.cross(t1);
            for (const Vec3& t : {t1, Vec3(-t1), t2, Vec3(-t2), Vec3(t1 + t2), Vec3(-t1 - t2), Vec3(t1 - t2), Vec3(t2 - t1)}) {
                const Vec3 n = (best + step * t).normalized();
                if (const double v = overlap(n); v < bestValue) {
                    bestValue = v, best = n, improved = true;
                    break;
                }
            }
        }
    }
    return bestValue;
}

Json ask(const std::string& op, const Solid& a, const Solid& b) {
    const Json ans = answerQuery(R"({"op":")" + op + R"(","a":)" + a.json() + R"(,"b":)" + b.json() + "}");
    REQUIRE_MESSAGE(!ans.contains("error"), ans.dump());
    return ans;
}

}  // namespace

TEST_CASE("cylinder and cone: closed-form distances and depths") {
    const auto one = [](const std::string& line) {
        const Json a = answerQuery(line);
        REQUIRE_MESSAGE(!a.contains("error"), a.dump());
        return a;
    };
    // A point beside, above and diagonally off a unit cylinder (radius 1, half height 1).
    const std::string cyl = R"({"cylinder":{"radius":1,"half_height":1}})";
    CHECK(one(R"({"op":"distance","a":{"point":[3,0,0]},"b":)" + cyl + "}")["distance"].get<double>() ==
          doctest::Approx(2).epsilon(1e-14));
    CHECK(one(R"({"op":"distance","a":{"point":[0,-4,0.5]},"b":)" + cyl + "}")["distance"].get<double>() ==
          doctest::Approx(3).epsilon(1e-14));
    CHECK(one(R"({"op":"distance","a":{"point":[2,3,0]},"b":)" + cyl + "}")["distance"].get<double>() ==
          doctest::Approx(std::sqrt(5.0)).epsilon(1e-13));
    // A sphere inside the cylinder near its side: depth = r_cyl − radial + r_sphere, pushed radially.
    Json p = one(R"({"op":"penetration","a":{"sphere":{"center":[0.3,0.2,0.4],"radius":0.25}},"b":)" + cyl + "}");
    CHECK(p["depth"].get<double>() == doctest::Approx(1 - 0.5 + 0.25).epsilon(1e-13));
    CHECK((vecOf(p["normal"]) - Vec3(-0.6, 0, -0.8)).norm() < 1e-12);
    // The same cylinder given by its cap centres, and a cone's apex into a plane below it.
    CHECK(one(R"({"op":"distance","a":{"point":[3,0,0]},"b":{"cylinder":{"a":[0,-1,0],"b":[0,1,0],"radius":1}}})")
              ["distance"].get<double>() == doctest::Approx(2).epsilon(1e-14));
    p = one(R"({"op":"penetration","a":{"cone":{"radius":1,"half_height":1,"rotation":[0,1,0,0]}},)"
            R"("b":{"plane":{"normal":[0,1,0],"offset":-0.75}}})");  // upside down: apex at y = −1
    CHECK(p["depth"].get<double>() == doctest::Approx(0.25).epsilon(1e-14));
    CHECK(one(R"({"op":"intersect","a":{"cone":{"radius":1,"half_height":1}},"b":{"point":[0.5,0,0]}})")["intersect"] ==
          true);  // the cone's radius at y = 0 is 0.5: on its surface
    CHECK(one(R"({"op":"intersect","a":{"cone":{"radius":1,"half_height":1}},"b":{"point":[0.5,0.001,0]}})")["intersect"] ==
          false);
}

TEST_CASE("cylinder and cone: distances certified by separation on random pairs") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const Solid::Kind kinds[] = {Solid::Cylinder, Solid::Cone, Solid::Sphere, Solid::Box};
    double worst = 0;
    int separated = 0;
    for (int i = 0; i < 4000; ++i) {
        const Solid a = randomSolid(rng, kinds[i % 2], Vec3::Zero());
        const Solid b = randomSolid(rng, kinds[(i / 2) % 4], 3.5 * Vec3(u(rng), u(rng), u(rng)));
        const Json ans = ask("distance", a, b);
        if (ans["intersect"] == true) {
            // Overlapping: some point lies in both (the penetration's deepest points bound it).
            CHECK(leastOverlap(a, b, Vec3::UnitX()) >= -1e-12);
            continue;
        }
        ++separated;
        const double d = ans["distance"].get<double>();
        const Vec3 p = vecOf(ans["point_a"]), q = vecOf(ans["point_b"]);
        const Vec3 n = (q - p) / (q - p).norm();
        const double separation = -b.supportValue(-n) - a.supportValue(n);
        worst = std::max({worst, a.outside(p), b.outside(q), std::abs((q - p).norm() - d), d - separation});
        CHECK(a.outside(p) <= 1e-12);
        CHECK_MESSAGE(b.outside(q) <= 1e-12, a.json() << " " << b.json() << " d=" << d);
        CHECK(std::abs((q - p).norm() - d) <= 1e-12);
        CHECK_MESSAGE(d - separation <= 1e-11 * (1 + d), a.json() << " " << b.json() << " ans " << ans.dump());
    }
    CHECK(separated > 150);
    MESSAGE("distance: worst certificate gap " << worst << " over " << separated << " separated pairs");
}

TEST_CASE("cylinder and cone: depths are the least overlap over all directions") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    const Solid::Kind kinds[] = {Solid::Cylinder, Solid::Cone, Solid::Sphere, Solid::Box};
    double worst = 0;
    int overlapping = 0;
    for (int i = 0; i < 3000; ++i) {
        const Solid a = randomSolid(rng, kinds[i % 2], Vec3::Zero());
        const Solid b = randomSolid(rng, kinds[(i / 2) % 4], 1.2 * Vec3(u(rng), u(rng), u(rng)));
        const Json ans = ask("penetration", a, b);
        if (ans["intersect"] != true) continue;
        ++overlapping;
        const double d = ans["depth"].get<double>();
        const Vec3 n = vecOf(ans["normal"]);
        CHECK(std::abs(n.norm() - 1) < 1e-14);
        const double along = a.supportValue(n) + b.supportValue(-n);
        const double least = leastOverlap(a, b, n);
        worst = std::max({worst, std::abs(along - d), d - least});
        CHECK_MESSAGE(std::abs(along - d) <= 1e-9, a.json() << " " << b.json());  // b moved by d·n touches a
        CHECK_MESSAGE(d - least <= 1e-9, a.json() << " " << b.json() << " ans " << ans.dump());  // and no shorter move separates them
        const Vec3 pa = vecOf(ans["point_a"]), pb = vecOf(ans["point_b"]);
        CHECK((pa - pb - d * n).norm() <= 1e-9);
    }
    CHECK(overlapping > 100);
    MESSAGE("penetration: worst gap " << worst << " over " << overlapping << " overlapping pairs");
}

TEST_CASE("cylinder and cone: bad input and ops that do not take them") {
    const auto error = [](const std::string& line) {
        const Json a = answerQuery(line);
        REQUIRE(a.contains("error"));
        return a["error"].get<std::string>();
    };
    CHECK(error(R"({"op":"distance","a":{"cylinder":{"radius":-1,"half_height":1}},"b":{"point":[0,0,0]}})")
              .find("$.a.cylinder.radius") != std::string::npos);
    CHECK(error(R"({"op":"distance","a":{"cylinder":{"a":[1,1,1],"b":[1,1,1],"radius":1}},"b":{"point":[0,0,0]}})")
              .find("coincide") != std::string::npos);
    CHECK(error(R"({"op":"distance","a":{"cylinder":{"a":[0,0,0],"b":[1,1,1],"radius":1,"half_height":2}},"b":{"point":[0,0,0]}})")
              .find("half_height") != std::string::npos);
    CHECK(error(R"({"op":"distance","a":{"cone":{"radius":1}},"b":{"point":[0,0,0]}})").find("half_height") !=
          std::string::npos);
    CHECK(error(R"({"op":"mass_properties","a":{"cone":{"radius":1,"half_height":0}}})").find("no volume") !=
          std::string::npos);
    // In a compound, the nearest piece answers.
    const Json d = answerQuery(R"({"op":"distance","a":{"compound":[{"cone":{"radius":1,"half_height":1}},)"
                               R"({"box":{"half_extents":[1,1,1],"position":[5,0,0]}}]},"b":{"point":[0,3,0]}})");
    CHECK(d["distance"].get<double>() == doctest::Approx(2).epsilon(1e-14));
}

// A prism of n sides inscribed in the cylinder (or a pyramid in the cone) as a polytope query: the
// hull-based mass properties, independent of the closed forms, converge to them like 1 − O(1/n²).
std::string inscribed(bool cone, double r, double h, int n) {
    std::ostringstream s;
    s.precision(17);
    s << R"({"polytope":{"vertices":[)";
    for (int i = 0; i < n; ++i) {
        const double phi = 2 * M_PI * i / n;
        s << (i ? "," : "") << "[" << r * std::cos(phi) << "," << -h << "," << r * std::sin(phi) << "]";
        if (!cone) s << ",[" << r * std::cos(phi) << "," << h << "," << r * std::sin(phi) << "]";
    }
    if (cone) s << ",[0," << h << ",0]";
    s << R"(],"rotation":[0.9,0.1,0.3,0.2],"position":[1,2,3]}})";
    return s.str();
}

TEST_CASE("cylinder and cone: mass properties converge with inscribed polytopes") {
    for (const bool cone : {false, true}) {
        const std::string solid = std::string(cone ? R"({"cone":)" : R"({"cylinder":)") +
                                  R"({"radius":0.7,"half_height":1.3,"rotation":[0.9,0.1,0.3,0.2],"position":[1,2,3]}})";
        const Json exact = answerQuery(R"({"op":"mass_properties","a":)" + solid + R"(,"density":2.5})");
        const Json approx = answerQuery(R"({"op":"mass_properties","a":)" + inscribed(cone, 0.7, 1.3, 2048) + R"(,"density":2.5})");
        REQUIRE_MESSAGE(!exact.contains("error"), exact.dump());
        REQUIRE_MESSAGE(!approx.contains("error"), approx.dump());
        // A 2048-gon's area is (1 − 1.6e-6) of the circle's.
        CHECK(approx["volume"].get<double>() == doctest::Approx(exact["volume"].get<double>()).epsilon(3e-6));
        CHECK((vecOf(approx["center_of_mass"]) - vecOf(exact["center_of_mass"])).norm() < 1e-9);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(approx["inertia"][i][j].get<double>() ==
                      doctest::Approx(exact["inertia"][i][j].get<double>()).epsilon(5e-6).scale(1));
    }
}
