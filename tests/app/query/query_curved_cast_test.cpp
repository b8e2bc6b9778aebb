// `raycast` and `time_of_impact` with cylinders and cones, against oracles sharing no code with
// the query: ray casts against the faces one by one (caps and side quadric roots in long double,
// Ericson §5.3.7), and certificates for the time of impact (touching points at t, a separating
// direction just before t — the touching times of two translating convex shapes are one interval,
// so separated at t' means separated at every earlier time).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>

#include "app/query/query.h"
#include "tests/app/query/curved_solid.h"
#include "tests/app/query/ask.h"

using namespace cdlab::demos;
using cdlab::Vec3;
using cdlab::test::Solid;
using cdlab::test::randomSolid;
using cdlab::test::vecOf;

namespace {

using Real = long double;

struct OracleHit {
    Real t;
    Vec3 normal;  // outward, of the face entered
};

// First entry of o + t d into the solid (outside origin), face by face; nullopt: a miss.
std::optional<OracleHit> oracleCast(const Solid& s, const Vec3& o, const Vec3& d) {
    Real ol[3], dl[3];
    for (int i = 0; i < 3; ++i) {
        ol[i] = Real(s.axis(i).dot(o - s.c));
        dl[i] = Real(s.axis(i).dot(d));
    }
    const Real h = s.h, r = s.r, k = s.kind == Solid::Cone ? r / (2 * h) : 0;
    std::optional<OracleHit> best;
    const auto consider = [&](Real t, const Vec3& localNormal) {
        if (t < 0 || (best && best->t <= t)) return;
        Vec3 n = Vec3::Zero();
        for (int i = 0; i < 3; ++i) n += localNormal[i] * s.axis(i);
        best = OracleHit{t, n.normalized()};
    };
    const auto radialAt = [&](Real t) { return std::hypot(ol[0] + t * dl[0], ol[2] + t * dl[2]); };
    // Caps (the cone's base only).
    for (const Real y : {-h, h}) {
        if (s.kind == Solid::Cone && y > 0) continue;
        if (dl[1] == 0) continue;
        const Real t = (y - ol[1]) / dl[1];
        if (radialAt(t) <= r) consider(t, Vec3(0, y > 0 ? 1 : -1, 0));
    }
    // Side: x² + z² = r² (cylinder) or (k (h − y))² (cone, h − y >= 0), |y| <= h.
    Real A = dl[0] * dl[0] + dl[2] * dl[2], B = 2 * (ol[0] * dl[0] + ol[2] * dl[2]), C = ol[0] * ol[0] + ol[2] * ol[2];
    if (s.kind == Solid::Cylinder) C -= r * r;
    else {
        const Real u0 = h - ol[1];
        A -= k * k * dl[1] * dl[1];
        B += 2 * k * k * u0 * dl[1];
        C -= k * k * u0 * u0;
    }
    const Real disc = B * B - 4 * A * C;
    if (A != 0 && disc >= 0)
        for (const Real t : {(-B - std::sqrt(disc)) / (2 * A), (-B + std::sqrt(disc)) / (2 * A)}) {
            const Real y = ol[1] + t * dl[1];
            if (y < -h || y > h) continue;
            const Real x = ol[0] + t * dl[0], z = ol[2] + t * dl[2], rho = std::hypot(x, z);
            if (rho == 0) continue;  // the apex: a cap or another root names it
            consider(t, s.kind == Solid::Cylinder ? Vec3(double(x / rho), 0, double(z / rho))
                                                  : Vec3(double(x / rho), double(k), double(z / rho)));
        }
    return best;
}

Json askOk(const std::string& line) {
    const Json a = answerQuery(line);
    REQUIRE_MESSAGE(!a.contains("error"), a.dump() << " for " << line);
    return a;
}

using cdlab::test::vecText;

// The solid moved by `offset`.
Solid moved(Solid s, const Vec3& offset) {
    s.c += offset;
    return s;
}

}  // namespace

TEST_CASE("raycast: cylinders and cones against the face-by-face oracle") {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, misses = 0, checked = 0;
    double worstT = 0;
    for (int i = 0; i < 3000; ++i) {
        const Solid s = randomSolid(rng, i % 2 ? Solid::Cone : Solid::Cylinder, Vec3(u(rng), u(rng), u(rng)));
        const Vec3 o = 4 * Vec3(u(rng), u(rng), u(rng)).normalized();
        const Vec3 aim = s.c + 1.5 * Vec3(u(rng), u(rng), u(rng));
        const Vec3 d = (aim - o) * (0.5 + std::abs(u(rng)));  // not unit: t in units of d
        if (s.outside(o) == 0) continue;
        const Json a = askOk(R"({"op":"raycast","ray":{"origin":)" + vecText(o) + R"(,"direction":)" + vecText(d) +
                           R"(},"shape":)" + s.json() + "}");
        const std::optional<OracleHit> want = oracleCast(s, o, d);
        if (!want) {
            ++misses;
            CHECK_MESSAGE(a["hit"] == false, a.dump() << " " << s.json());
            continue;
        }
        ++hits;
        REQUIRE_MESSAGE(a["hit"] == true, a.dump() << " " << s.json() << " oracle t " << double(want->t));
        const double t = a["t"].get<double>();
        const Vec3 p = vecOf(a["point"]), n = vecOf(a["normal"]);
        CHECK((p - (o + t * d)).norm() <= 1e-12 * (1 + p.norm()));
        CHECK(s.outside(p) <= 1e-12);
        CHECK(std::abs(n.norm() - 1) <= 1e-14);
        CHECK(s.supportValue(n) - n.dot(p) <= 1e-12);  // outward: no point of the solid beyond p along n
        // t is well conditioned unless the ray meets the surface at a grazing angle.
        const double cosine = std::abs(want->normal.dot(d.normalized()));
        if (cosine < 1e-3) continue;
        ++checked;
        const double error = std::abs(t - double(want->t)) / (1 + std::abs(t));
        worstT = std::max(worstT, error);
        CHECK_MESSAGE(error <= 1e-12, s.json() << " t " << t << " oracle " << double(want->t));
    }
    CHECK(hits > 1000);
    CHECK(misses > 300);
    MESSAGE("raycast: " << hits << " hits (" << checked << " t compared, worst " << worstT << "), " << misses
                        << " misses");
}

TEST_CASE("raycast: grazing rays, rays inside and along the axis") {
    const std::string cyl = R"({"cylinder":{"radius":1,"half_height":1}})";
    const auto cast = [&](const std::string& ray, const std::string& shape) {
        return askOk(R"({"op":"raycast","ray":)" + ray + R"(,"shape":)" + shape + "}");
    };
    // Tangent to the side at x = 1: a hit at the tangent point, t exact.
    Json a = cast(R"({"origin":[1,0.5,-5],"direction":[0,0,1]})", cyl);
    CHECK(a["hit"] == true);
    CHECK(a["t"].get<double>() == doctest::Approx(5).epsilon(1e-15));
    // 1e-6 outside the side: a miss; along the top cap's plane: a hit where the ray meets the disc.
    CHECK(cast(R"({"origin":[1.000001,0.5,-5],"direction":[0,0,1]})", cyl)["hit"] == false);
    a = cast(R"({"origin":[-5,1,0.6],"direction":[1,0,0]})", cyl);
    CHECK(a["hit"] == true);
    CHECK(a["t"].get<double>() == doctest::Approx(5 - 0.8).epsilon(1e-14));
    // From inside: t = 0, inside; along the axis into the cap; a cone's apex from above.
    CHECK(cast(R"({"origin":[0.2,0,0],"direction":[1,0,0]})", cyl)["inside"] == true);
    a = cast(R"({"origin":[0,-7,0],"direction":[0,0.5,0]})", cyl);
    CHECK(a["t"].get<double>() == doctest::Approx(12).epsilon(1e-15));
    CHECK(vecOf(a["normal"]) == Vec3(0, -1, 0));
    a = cast(R"({"origin":[0,3,0],"direction":[0,-1,0]})", R"({"cone":{"radius":1,"half_height":1}})");
    CHECK(a["t"].get<double>() == doctest::Approx(2).epsilon(1e-15));
    CHECK(vecOf(a["normal"]).dot(Vec3(0, 1, 0)) > 0.4);  // in the apex's normal cone
    // Degenerate solids: a disc (half height 0) met edge-on enters through its rim with the rim's
    // in-plane normal; a cone of radius 0 is its axis segment, met at the apex from above.
    a = cast(R"({"origin":[-3,0,0.1],"direction":[1,0,0]})", R"({"cylinder":{"radius":1,"half_height":0}})");
    CHECK(a["t"].get<double>() == doctest::Approx(3 - std::sqrt(0.99)).epsilon(1e-14));
    CHECK(std::abs(vecOf(a["normal"]).y()) < 1e-12);
    a = cast(R"({"origin":[0,3,0],"direction":[0,-1,0]})", R"({"cone":{"radius":0,"half_height":1}})");
    CHECK(!a.contains("inside"));
    CHECK(a["t"].get<double>() == doctest::Approx(2).epsilon(1e-14));
    // max_t stops short of the surface.
    CHECK(cast(R"({"origin":[3,0,0],"direction":[-1,0,0]})", cyl + R"(,"max_t":1.99)")["hit"] == false);
}

TEST_CASE("time_of_impact: cylinders and cones, certified on random pairs") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const Solid::Kind kinds[] = {Solid::Cylinder, Solid::Cone, Solid::Sphere, Solid::Box};
    int hits = 0, overlapping = 0, misses = 0;
    for (int i = 0; i < 600; ++i) {
        const Solid a = randomSolid(rng, kinds[i % 2], Vec3::Zero());
        const Solid b = randomSolid(rng, kinds[(i / 2) % 4], 4 * Vec3(u(rng), u(rng), u(rng)).normalized());
        const Vec3 ma = 2 * Vec3(u(rng), u(rng), u(rng)), mb = -4 * b.c.normalized() + Vec3(u(rng), u(rng), u(rng));
        const Json ans = askOk(R"({"op":"time_of_impact","a":)" + a.json() + R"(,"b":)" + b.json() +
                             R"(,"motion_a":)" + vecText(ma) + R"(,"motion_b":)" + vecText(mb) + "}");
        if (ans["hit"] != true) {
            ++misses;
            continue;
        }
        if (ans.contains("initially_overlapping")) {
            ++overlapping;
            continue;
        }
        ++hits;
        const double t = ans["t"].get<double>();
        const Vec3 n = vecOf(ans["normal"]), pa = vecOf(ans["point_a"]), pb = vecOf(ans["point_b"]);
        const Solid at = moved(a, t * ma), bt = moved(b, t * mb);
        // Touching points at t. They come from the closest pair of a state 1e-10 to 1e-8 earlier (a
        // path closing slowly needs the larger step to be apart beyond the touching rule), moved
        // on with each shape, so a sideways motion parts them by up to ~1e-8 times its speed.
        CHECK(at.outside(pa) <= 1e-9);
        CHECK(bt.outside(pb) <= 1e-9);
        CHECK((pa - pb).norm() <= 1e-7);
        // Separated just before: n separates the shapes at t' = t − 1e-6 (1 − t).
        const double before = t - 1e-6;
        if (before > 0) {
            const Solid ab = moved(a, before * ma), bb = moved(b, before * mb);
            CHECK(-ab.supportValue(n) - bb.supportValue(-n) > 0);
        }
    }
    CHECK(hits > 150);
    MESSAGE("time_of_impact: " << hits << " hits, " << overlapping << " initially overlapping, " << misses << " misses");
}

TEST_CASE("time_of_impact: closed forms with a cylinder") {
    const std::string cyl = R"({"cylinder":{"radius":1,"half_height":1}})";
    // A unit sphere from x = 5 toward the side at speed 6: touches at x = 2, t = 1/2.
    Json a = askOk(R"({"op":"time_of_impact","a":)" + cyl + R"(,"b":{"sphere":{"center":[5,0,0],"radius":1}},"motion_b":[-6,0,0]})");
    CHECK(a["t"].get<double>() == doctest::Approx(0.5).epsilon(1e-14));
    CHECK((vecOf(a["normal"]) - Vec3(1, 0, 0)).norm() < 1e-12);
    // The cylinder rising into a box 3 above its top: t = 3 / 4, normal +y.
    a = askOk(R"({"op":"time_of_impact","a":)" + cyl +
            R"(,"b":{"box":{"half_extents":[1,1,1],"position":[0,5,0]}},"motion_a":[0,4,0]})");
    CHECK(a["t"].get<double>() == doctest::Approx(0.75).epsilon(1e-14));
    CHECK((vecOf(a["normal"]) - Vec3(0, 1, 0)).norm() < 1e-12);
    // Passing 1e-6 above the top: no contact; already touching: initially overlapping.
    CHECK(askOk(R"({"op":"time_of_impact","a":)" + cyl +
              R"(,"b":{"sphere":{"center":[5,2.000001,0],"radius":1}},"motion_b":[-10,0,0]})")["hit"] == false);
    CHECK(askOk(R"({"op":"time_of_impact","a":)" + cyl +
              R"(,"b":{"sphere":{"center":[2,0,0],"radius":1}},"motion_b":[1,0,0]})")["initially_overlapping"] == true);
    // A cone rising apex-first to a plane at y = 3: the apex (y = 1) gets there at t = 1/2.
    a = askOk(R"({"op":"time_of_impact","a":{"cone":{"radius":1,"half_height":1}},"b":{"plane":{"normal":[0,1,0],"offset":3}},"motion_a":[0,4,0]})");
    CHECK(a["t"].get<double>() == doctest::Approx(0.5).epsilon(1e-15));
}
