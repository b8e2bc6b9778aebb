// `closest_point_tetrahedron` against a brute-force oracle sharing no code with core: inside by the
// signs of four long-double volumes, else the nearest of the four faces, each by the unconstrained
// projection when it falls in the face, else the nearest of its three edges; the region named by
// which of a, b, c, d the oracle point needs.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <sstream>
#include <string>

#include "app/query/query.h"
#include "tests/app/query/ask.h"

using namespace cdlab::demos;
using cdlab::Vec3;

namespace {

using Real = long double;
using P = std::array<Real, 3>;

P sub(const P& a, const P& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Real dot(const P& a, const P& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P cross(const P& a, const P& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
P lerp(const P& a, const P& b, Real t) { return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])}; }

// Nearest point of the segment ab to p, with its weight on b.
P onSegment(const P& p, const P& a, const P& b, Real& t) {
    const P ab = sub(b, a);
    t = std::clamp(dot(sub(p, a), ab) / dot(ab, ab), Real(0), Real(1));
    return lerp(a, b, t);
}

struct Near {
    P point{0, 0, 0};
    Real weight[4] = {0, 0, 0, 0};  // barycentric weights on a, b, c, d
    Real d2 = INFINITY;
};

Near nearestOnFace(const P& p, const P* v, const int idx[3]) {
    const P &a = v[idx[0]], &b = v[idx[1]], &c = v[idx[2]];
    const P n = cross(sub(b, a), sub(c, a));
    const Real nn = dot(n, n);
    // Barycentric of the projection: areas of the sub-triangles over the whole.
    const P q = sub(p, {n[0] * dot(sub(p, a), n) / nn, n[1] * dot(sub(p, a), n) / nn, n[2] * dot(sub(p, a), n) / nn});
    const Real wa = dot(cross(sub(b, q), sub(c, q)), n) / nn, wb = dot(cross(sub(c, q), sub(a, q)), n) / nn;
    const Real wc = 1 - wa - wb;
    Near best;
    if (wa >= 0 && wb >= 0 && wc >= 0) {
        best = {q, {0, 0, 0, 0}, dot(sub(p, q), sub(p, q))};
        best.weight[idx[0]] = wa, best.weight[idx[1]] = wb, best.weight[idx[2]] = wc;
        return best;
    }
    for (int e = 0; e < 3; ++e) {
        const int i = idx[e], j = idx[(e + 1) % 3];
        Real t;
        const P s = onSegment(p, v[i], v[j], t);
        const Real d2 = dot(sub(p, s), sub(p, s));
        if (d2 < best.d2) {
            best = {s, {0, 0, 0, 0}, d2};
            best.weight[i] = 1 - t, best.weight[j] = t;
        }
    }
    return best;
}

Real volume(const P& a, const P& b, const P& c, const P& d) { return dot(sub(b, a), cross(sub(c, a), sub(d, a))); }

using cdlab::test::vecText;

}  // namespace

TEST_CASE("closest_point_tetrahedron: point and region against a brute-force oracle") {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    int regionsCompared = 0, inside = 0;
    for (int i = 0; i < 3000; ++i) {
        Vec3 w[4];
        for (Vec3& x : w) x = Vec3(u(rng), u(rng), u(rng));
        Vec3 pw = 1.6 * Vec3(u(rng), u(rng), u(rng));
        if (i % 5 == 0) {  // a point inside: random positive weights of the corners
            const double c[4] = {std::abs(u(rng)) + 0.01, std::abs(u(rng)) + 0.01, std::abs(u(rng)) + 0.01,
                                 std::abs(u(rng)) + 0.01};
            pw = (c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3]) / (c[0] + c[1] + c[2] + c[3]);
        }
        P v[4], p{pw.x(), pw.y(), pw.z()};
        for (int k = 0; k < 4; ++k) v[k] = {w[k].x(), w[k].y(), w[k].z()};
        const Real whole = volume(v[0], v[1], v[2], v[3]);
        if (std::abs(whole) < 1e-3) continue;  // nearly flat: not this test's concern
        const Json a = answerQuery(R"({"op":"closest_point_tetrahedron","point":)" + vecText(pw) + R"(,"tetrahedron":[)" +
                                   vecText(w[0]) + "," + vecText(w[1]) + "," + vecText(w[2]) + "," + vecText(w[3]) + "]}");
        REQUIRE_MESSAGE(!a.contains("error"), a.dump());
        // Inside: p replaces each vertex in turn without changing the volume's sign.
        const Real s[4] = {volume(p, v[1], v[2], v[3]), volume(v[0], p, v[2], v[3]), volume(v[0], v[1], p, v[3]),
                           volume(v[0], v[1], v[2], p)};
        if (std::all_of(s, s + 4, [&](Real x) { return x * whole > 0; })) {
            ++inside;
            CHECK(a["region"] == "ABCD");
            CHECK((Vec3(a["point"][0], a["point"][1], a["point"][2]) - pw).norm() == 0);
            continue;
        }
        static const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
        Near best;
        for (const auto& f : faces)
            if (const Near n = nearestOnFace(p, v, f); n.d2 < best.d2) best = n;
        const Vec3 got(a["point"][0], a["point"][1], a["point"][2]);
        const Vec3 want(double(best.point[0]), double(best.point[1]), double(best.point[2]));
        CHECK((got - want).norm() <= 1e-12);
        // The region: the vertices with a weight clearly above 0 (skip points near a boundary).
        std::string region;
        bool clear = true;
        for (int k = 0; k < 4; ++k) {
            if (best.weight[k] > 1e-9) region += char('A' + k);
            else if (best.weight[k] > 1e-12) clear = false;
        }
        if (!clear) continue;
        ++regionsCompared;
        CHECK_MESSAGE(a["region"] == region, a.dump() << " oracle " << region);
    }
    CHECK(regionsCompared > 1500);
    CHECK(inside > 300);
}

TEST_CASE("closest_point_tetrahedron: trace and bad input") {
    const Json a = answerQuery(
        R"({"op":"closest_point_tetrahedron","point":[0.5,-1,0.2],"tetrahedron":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],"trace":true})");
    CHECK(a["region"] == "ABD");
    CHECK(a["trace"]["tests"].back()["accepted"] == true);
    CHECK(a["trace"]["tests"].back()["region"] == "ABD");
    const Json e = answerQuery(R"({"op":"closest_point_tetrahedron","point":[0,0,0],"tetrahedron":[[0,0,0],[1,0,0]]})");
    REQUIRE(e.contains("error"));
    CHECK(e["error"].get<std::string>().find("$.tetrahedron") != std::string::npos);
}
