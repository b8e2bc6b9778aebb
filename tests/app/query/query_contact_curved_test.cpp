// `contact` with cylinders and cones (issue 21 §2): points on the true rim circles, the manifold
// rules (more max_points never fewer, full-depth ends kept), clipping to a polytope face, and on
// random poses every point on the solid at the depth the plane gives it — against closed forms and
// the solids' own membership tests (tests/app/query/curved_solid.h), not the query's code.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "app/query/query.h"
#include "tests/app/query/curved_solid.h"

using namespace cdlab::demos;
using cdlab::Vec3;
using cdlab::test::Solid;
using cdlab::test::randomSolid;
using cdlab::test::vecOf;

namespace {

Json contact(const std::string& a, const std::string& b, int maxPoints = 4) {
    const Json ans = answerQuery(R"({"op":"contact","a":)" + a + R"(,"b":)" + b + R"(,"max_points":)" +
                                 std::to_string(maxPoints) + "}");
    REQUIRE_MESSAGE(!ans.contains("error"), ans.dump());
    return ans;
}

// Every point: point_a − point_b = depth·normal.
void checkConvention(const Json& ans) {
    const Vec3 n = vecOf(ans["normal"]);
    for (const Json& p : ans["points"])
        CHECK((vecOf(p["point_a"]) - vecOf(p["point_b"]) - p["depth"].get<double>() * n).norm() <= 1e-12);
}

const std::string kGround = R"({"plane":{"normal":[0,1,0],"offset":-0.9}})";  // y <= −0.9

}  // namespace

TEST_CASE("contact: a cylinder standing on the ground, points on its rim circle") {
    const std::string cyl = R"({"cylinder":{"radius":1,"half_height":1}})";  // bottom cap at y = −1
    std::size_t previous = 0;
    for (int maxPoints : {1, 2, 3, 4, 6, 8, 16, 32}) {
        const Json ans = contact(cyl, kGround, maxPoints);
        CHECK(ans["colliding"] == true);
        CHECK(ans["depth"].get<double>() == doctest::Approx(0.1).epsilon(1e-14));
        CHECK(ans["feature_a"]["type"] == (maxPoints >= 3 ? "cap" : "rim"));
        checkConvention(ans);
        const Json& pts = ans["points"];
        CHECK(int(pts.size()) == maxPoints);  // a circle has more corners than any max_points
        CHECK(pts.size() >= previous);        // more points asked, never fewer given
        previous = pts.size();
        for (const Json& p : pts) {
            const Vec3 a = vecOf(p["point_a"]);
            CHECK(std::hypot(a.x(), a.z()) == doctest::Approx(1).epsilon(1e-15));  // on the circle, not a chord
            CHECK(a.y() == doctest::Approx(-1).epsilon(1e-15));
        }
        if (maxPoints == 4) {  // the largest quad in a circle: a square of area 2
            const Vec3 p0 = vecOf(pts[0]["point_a"]), p1 = vecOf(pts[1]["point_a"]);
            CHECK((p0 - p1).norm() == doctest::Approx(2).epsilon(1e-14));  // the farthest: a diameter
        }
    }
}

TEST_CASE("contact: lying, tilted, a cone on its apex, a cylinder on a box face") {
    // Lying on its side (axis x), sunk 0.001: both ends of the bottom line at full depth.
    Json ans = contact(R"({"cylinder":{"a":[-1,0,0],"b":[1,0,0],"radius":1}})",
                       R"({"plane":{"normal":[0,1,0],"offset":-0.999}})");
    CHECK(ans["feature_a"]["type"] == "side");
    int fullDepth = 0;
    for (const Json& p : ans["points"])
        if (std::abs(p["depth"].get<double>() - 0.001) < 1e-12) {
            ++fullDepth;
            CHECK(std::abs(std::abs(vecOf(p["point_a"]).x()) - 1) < 1e-12);
        }
    CHECK(fullDepth == 2);
    // Tilted 30° about z: the lowest rim point is at y = −(cos 30° + sin 30°).
    ans = contact(R"({"cylinder":{"radius":1,"half_height":1,"rotation":[0.9659258262890683,0,0,0.25881904510252074]}})",
                  R"({"plane":{"normal":[0,1,0],"offset":-1.2}})");
    CHECK(ans["depth"].get<double>() == doctest::Approx(std::sqrt(3.0) / 2 + 0.5 - 1.2).epsilon(1e-14));
    checkConvention(ans);
    // A cone on its apex: the apex alone (no zero-depth rim points around it).
    ans = contact(R"({"cone":{"radius":1,"half_height":1,"rotation":[0,1,0,0]}})", kGround);
    CHECK(ans["points"].size() == 1);
    CHECK(ans["feature_a"]["type"] == "apex");
    // Standing on a box's top face (x, z in [−1, 1]) with its axis at x = 0.5: the disc clipped at
    // x = 1, every point on the circle or on that edge, inside the face.
    ans = contact(R"({"cylinder":{"radius":1,"half_height":1,"position":[0.5,0,0]}})",
                  R"({"box":{"half_extents":[1,0.5,1],"position":[0,-1.4,0]}})", 8);
    CHECK(ans["points"].size() == 8);
    checkConvention(ans);
    for (const Json& p : ans["points"]) {
        const Vec3 a = vecOf(p["point_a"]);
        CHECK(a.x() <= 1 + 1e-12);
        const bool onCircle = std::abs(std::hypot(a.x() - 0.5, a.z()) - 1) < 1e-12, onEdge = std::abs(a.x() - 1) < 1e-12;
        CHECK((onCircle || onEdge));
        CHECK(p["depth"].get<double>() == doctest::Approx(0.1).epsilon(1e-13));
    }
    CHECK(ans["feature_b"]["type"] == "face");
    // Lying across the box's edge x = −0.5 (its side from x = −1 to 1), sunk 0.001: the contact line
    // clipped to the face, x in [−0.5, 1], both ends at full depth — not the far end alone (which a
    // solver would tip about). And a cone lying across it: its lowest generator, base rim to apex.
    for (int maxPoints : {2, 4, 8}) {
        ans = contact(R"({"cylinder":{"a":[-1,0,0],"b":[1,0,0],"radius":0.5}})",
                      R"({"aabb":{"min":[-0.5,-2,-3],"max":[3,-0.499,3]}})", maxPoints);
        checkConvention(ans);
        CHECK(ans["feature_a"]["type"] == "side");
        std::vector<double> ends;
        for (const Json& p : ans["points"])
            if (std::abs(p["depth"].get<double>() - 0.001) < 1e-12) ends.push_back(vecOf(p["point_a"]).x());
        std::sort(ends.begin(), ends.end());
        REQUIRE(ends.size() == 2);
        CHECK(ends[0] == doctest::Approx(-0.5).epsilon(1e-12));
        CHECK(ends[1] == doctest::Approx(1.0).epsilon(1e-12));
    }
    // The same with the box first: the normal flips (from the box toward the cylinder), the points
    // keep point_a − point_b = depth·n, both ends of the line still come back.
    ans = contact(R"({"aabb":{"min":[-0.5,-2,-3],"max":[3,-0.499,3]}})", R"({"cylinder":{"a":[-1,0,0],"b":[1,0,0],"radius":0.5}})", 4);
    checkConvention(ans);
    CHECK(vecOf(ans["normal"]) == Vec3(0, 1, 0));
    CHECK(ans["feature_b"]["type"] == "side");
    {
        std::vector<double> ends;
        for (const Json& p : ans["points"])
            if (std::abs(p["depth"].get<double>() - 0.001) < 1e-12) ends.push_back(vecOf(p["point_b"]).x());
        std::sort(ends.begin(), ends.end());
        REQUIRE(ends.size() == 2);
        CHECK(ends[0] == doctest::Approx(-0.5).epsilon(1e-12));
        CHECK(ends[1] == doctest::Approx(1.0).epsilon(1e-12));
    }
    // A cone lying on a generator (its axis tilted by the half-angle α = atan(0.5 / 2) from the
    // face), across the box's edge x = 0: the line runs from the base rim (x < 0, off the face) to the
    // apex; clipped to the face, its ends are the edge point x = 0 and the apex, both at full depth.
    const double alpha = std::atan(0.25), theta = -M_PI / 2 - alpha;  // about z: +y (apex) to +x, then down by α
    const Vec3 axis(std::cos(theta + M_PI / 2), std::sin(theta + M_PI / 2), 0);
    const Vec3 apex = axis;  // the centre is the origin, the apex one half height along the axis
    const double lineY = apex.y();  // the lowest generator is level: every point of it at the apex's height
    char cone[200];
    std::snprintf(cone, sizeof cone, R"({"cone":{"radius":0.5,"half_height":1,"rotation":[%.17g,0,0,%.17g]}})",
                  std::cos(theta / 2), std::sin(theta / 2));
    char box[160];
    std::snprintf(box, sizeof box, R"({"aabb":{"min":[0,-3,-3],"max":[3,%.17g,3]}})", lineY + 0.001);
    ans = contact(cone, box, 4);
    checkConvention(ans);
    CHECK(ans["depth"].get<double>() == doctest::Approx(0.001).epsilon(1e-4));
    std::vector<double> lineEnds;
    for (const Json& p : ans["points"]) {
        CHECK(vecOf(p["point_a"]).x() >= -1e-9);
        if (std::abs(p["depth"].get<double>() - ans["depth"].get<double>()) < 1e-6) lineEnds.push_back(vecOf(p["point_a"]).x());
    }
    std::sort(lineEnds.begin(), lineEnds.end());
    REQUIRE(lineEnds.size() >= 2);
    CHECK(std::abs(lineEnds.front()) < 1e-6);                 // where the line leaves the face
    CHECK(lineEnds.back() == doctest::Approx(apex.x()).epsilon(1e-6));  // the apex
    // The rotation rounded to 6 digits tilts the line by ~2e-7: the points still come from the face,
    // so the normal is the face's own — exactly (0, −1, 0) from the cone toward the box — and every
    // point keeps point_a − point_b = depth·n (EPA's normal, 2e-7 off, broke it by 2e-10).
    ans = contact(R"({"cone":{"radius":0.5,"half_height":1,"rotation":[0.615412,0,0,-0.788205]}})", box, 4);
    CHECK(ans["feature_b"]["type"] == "face");
    CHECK(vecOf(ans["normal"]) == Vec3(0, -1, 0));
    checkConvention(ans);
    // A sphere resting on the middle of the top cap: one point, inside the disc: the cap, not the rim.
    ans = contact(R"({"sphere":{"center":[0.2,1.9,0.1],"radius":1}})", R"({"cylinder":{"radius":1,"half_height":1}})");
    CHECK(ans["feature_b"]["type"] == "cap");
    // A box resting flat on the cylinder's top cap: the box's four corners over the disc.
    ans = contact(R"({"box":{"half_extents":[0.5,0.5,0.5],"position":[0,1.4,0]}})",
                  R"({"cylinder":{"radius":1,"half_height":1}})");
    CHECK(ans["points"].size() == 4);
    for (const Json& p : ans["points"]) CHECK(std::abs(std::abs(vecOf(p["point_a"]).x()) - 0.5) < 1e-12);
}

TEST_CASE("contact: cylinders and cones on random planes, every point on the solid at its plane depth") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    int colliding = 0;
    for (int i = 0; i < 400; ++i) {
        const Solid s = randomSolid(rng, i % 2 ? Solid::Cone : Solid::Cylinder, Vec3(u(rng), u(rng), u(rng)));
        const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
        const double offset = n.dot(s.c) + 0.8 * u(rng);
        std::ostringstream plane;
        plane.precision(17);
        plane << R"({"plane":{"normal":[)" << n.x() << "," << n.y() << "," << n.z() << R"(],"offset":)" << offset << "}}";
        const int maxPoints = 1 + i % 8;
        const Json ans = contact(s.json(), plane.str(), maxPoints);
        const double lowest = -s.supportValue(-n) - offset;  // the solid's lowest signed height
        if (ans["colliding"] != true) {
            CHECK(ans["distance"].get<double>() == doctest::Approx(lowest).epsilon(1e-12));
            continue;
        }
        ++colliding;
        CHECK(ans["depth"].get<double>() == doctest::Approx(-lowest).epsilon(1e-12).scale(1));
        CHECK(int(ans["points"].size()) <= maxPoints);
        checkConvention(ans);
        for (const Json& p : ans["points"]) {
            const Vec3 a = vecOf(p["point_a"]);
            CHECK(s.outside(a) <= 1e-12);                                                // on the solid
            CHECK(p["depth"].get<double>() == doctest::Approx(offset - n.dot(a)).epsilon(1e-12).scale(1));  // below the plane
            CHECK(p["depth"].get<double>() <= -lowest + 1e-12);
        }
    }
    CHECK(colliding > 100);
}
