// `cdlab query` "contact" answers against oracles that share no code with core/contact_*:
// long double vertex depths for planes, brute-force facets of the Minkowski difference for
// polytope pairs, containment of every contact point in both shapes, the conventions
// (point_a − point_b = depth·n, translating b by depth·n separates), scales and errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "app/query/query.h"

using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

using V = std::array<double, 3>;
using L = long double;

Json arr(const V& v) { return Json::array({v[0], v[1], v[2]}); }
V array3(const Json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }
L dotL(const V& a, const V& b) { return (L)a[0] * b[0] + (L)a[1] * b[1] + (L)a[2] * b[2]; }

// A random convex polytope: points on a random ellipsoid (world frame, no pose).
std::vector<V> randomPoints(std::mt19937_64& rng, int n, double size, const V& c) {
    std::normal_distribution<double> g(0, 1);
    std::vector<V> p;
    for (int i = 0; i < n; ++i) {
        V u{g(rng), g(rng), g(rng)};
        const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        p.push_back({c[0] + size * u[0] / len, c[1] + 0.7 * size * u[1] / len, c[2] + 0.5 * size * u[2] / len});
    }
    return p;
}
Json polytope(const std::vector<V>& p) {
    Json v = Json::array();
    for (const V& x : p) v.push_back(arr(x));
    return {{"polytope", {{"vertices", v}}}};
}

// Facets of conv(p) by brute force over triples (long double): outward unit normal and offset.
struct Facet {
    std::array<L, 3> n;
    L d;
};
std::vector<Facet> facets(const std::vector<V>& p) {
    std::vector<Facet> out;
    const size_t m = p.size();
    L scale = 0;
    for (const V& x : p) scale = std::max(scale, (L)std::max({std::abs(x[0]), std::abs(x[1]), std::abs(x[2])}));
    for (size_t i = 0; i < m; ++i)
        for (size_t j = i + 1; j < m; ++j)
            for (size_t k = j + 1; k < m; ++k) {
                std::array<L, 3> u, w, n;
                for (int c = 0; c < 3; ++c) u[c] = (L)p[j][c] - p[i][c], w[c] = (L)p[k][c] - p[i][c];
                n = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
                const L len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                if (!(len > 0)) continue;
                for (L& c : n) c /= len;
                const L d = n[0] * p[i][0] + n[1] * p[i][1] + n[2] * p[i][2];
                bool pos = false, neg = false;
                for (const V& x : p) {
                    const L s = n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - d;
                    if (s > 1e-13L * scale) pos = true;
                    if (s < -1e-13L * scale) neg = true;
                }
                if (pos && neg) continue;
                if (pos) out.push_back({{-n[0], -n[1], -n[2]}, -d});
                else out.push_back({n, d});
            }
    return out;
}
bool inside(const std::vector<Facet>& f, const V& x, L tol) {
    for (const Facet& q : f)
        if (q.n[0] * x[0] + q.n[1] * x[1] + q.n[2] * x[2] - q.d > tol) return false;
    return true;
}

// Penetration depth of A and B: min over facets of conv{a - b} of the facet offset (> 0 inside).
L minkowskiDepth(const std::vector<V>& a, const std::vector<V>& b) {
    std::vector<V> w;
    for (const V& x : a)
        for (const V& y : b) w.push_back({x[0] - y[0], x[1] - y[1], x[2] - y[2]});
    L best = INFINITY;
    for (const Facet& f : facets(w)) best = std::min(best, f.d);
    return best;  // < 0: origin outside (then -best is a lower bound of the distance)
}

// |x - y| within 1e-9 relative plus an absolute allowance for the coordinates' rounding.
bool close(double x, double y, double tol) { return std::abs(x - y) <= 1e-9 * std::abs(y) + tol; }

Json query(const Json& a, const Json& b, int maxPoints = 4) {
    Json q = {{"op", "contact"}, {"a", a}, {"b", b}};
    if (maxPoints != 4) q["max_points"] = maxPoints;
    return answerQuery(q.dump());
}

}  // namespace

TEST_SUITE("query_contact") {
    TEST_CASE("polytope vs plane: depth vs long double vertex depths, points on/below the plane, both orders") {
        std::mt19937_64 rng(17);
        int colliding = 0;
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                for (int k = 0; k < 20; ++k) {
                    const std::vector<V> p = randomPoints(rng, 12, scale, {offset, -offset, offset});
                    std::normal_distribution<double> g(0, 1);
                    const V n{g(rng), g(rng), 3.0};
                    const L nl = std::sqrt(dotL(n, n));
                    const double d = (double)(dotL(n, {offset, -offset, offset}) +
                                              nl * scale * std::uniform_real_distribution<double>(-0.6, 0.6)(rng));
                    // Oracle: the deepest vertex below n·x = d.
                    L deepest = -INFINITY;
                    for (const V& x : p) deepest = std::max(deepest, -(dotL(n, x) - d) / nl);
                    const Json plane = {{"plane", {{"normal", arr(n)}, {"offset", d}}}};
                    const double tol = 1e-12 * (scale + offset);
                    for (bool planeIsB : {true, false}) {
                        const Json r = planeIsB ? query(polytope(p), plane) : query(plane, polytope(p));
                        REQUIRE(!r.contains("error"));
                        CAPTURE(r.dump());
                        CHECK(r["colliding"].get<bool>() == (deepest >= -tol));
                        if (!r["colliding"].get<bool>()) {
                            CHECK(r["distance"].get<double>() == doctest::Approx((double)-deepest).epsilon(1e-9));
                            continue;
                        }
                        ++colliding;
                        CHECK(close(r["depth"].get<double>(), (double)deepest, tol));
                        const V nn = array3(r["normal"]);  // A → B: body → plane is -n̂
                        CHECK(dotL(nn, n) / nl == doctest::Approx(planeIsB ? -1.0 : 1.0));
                        CHECK(r["points"].size() <= 4);
                        CHECK(close(r["points"][0]["depth"].get<double>(), (double)deepest, tol));
                        for (const Json& c : r["points"]) {
                            const V pa = array3(c["point_a"]), pb = array3(c["point_b"]);
                            const V body = planeIsB ? pa : pb, onPlane = planeIsB ? pb : pa;
                            CHECK(std::abs((double)((dotL(n, onPlane) - d) / nl)) <= tol);
                            CHECK((double)((dotL(n, body) - d) / nl) <= tol);
                            const double depth = c["depth"].get<double>();
                            for (int i = 0; i < 3; ++i) CHECK(std::abs(pa[i] - pb[i] - depth * nn[i]) <= tol);
                            CHECK(inside(facets(p), body, 1e-9L * (scale + offset)));
                        }
                    }
                }
            }
        }
        CHECK(colliding > 50);
    }

    TEST_CASE("polytope pairs: depth vs the Minkowski facet oracle, points inside both") {
        std::mt19937_64 rng(29);
        int colliding = 0, separated = 0;
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e5}) {
                for (int k = 0; k < 12; ++k) {
                    std::normal_distribution<double> g(0, 1);
                    const V c{offset, offset, -offset};
                    const std::vector<V> a = randomPoints(rng, 7, scale, c);
                    const std::vector<V> b = randomPoints(
                        rng, 7, scale,
                        {c[0] + 0.8 * scale * g(rng), c[1] + 0.8 * scale * g(rng), c[2] + 0.5 * scale * g(rng)});
                    const L oracle = minkowskiDepth(a, b);
                    const Json r = query(polytope(a), polytope(b));
                    REQUIRE(!r.contains("error"));
                    CAPTURE(r.dump());
                    const double tol = 1e-11 * (scale + offset);
                    if (oracle > tol) {
                        ++colliding;
                        REQUIRE(r["colliding"].get<bool>());
                        // The manifold's axis may be a face preferred within 2% (stability bias).
                        CHECK(r["depth"].get<double>() >= (double)oracle - tol);
                        CHECK(r["depth"].get<double>() <= (double)oracle * 1.02 + 1e-8 * scale + tol);
                        const V n = array3(r["normal"]);
                        const std::vector<Facet> fa = facets(a), fb = facets(b);
                        for (const Json& p : r["points"]) {
                            CHECK(inside(fa, array3(p["point_a"]), 1e-9L * (scale + offset)));
                            CHECK(inside(fb, array3(p["point_b"]), 1e-9L * (scale + offset)));
                        }
                        // Translating b by depth·n separates: the oracle depth of the moved pair is ~0.
                        const double depth = r["depth"].get<double>();
                        std::vector<V> moved = b;
                        for (V& y : moved)
                            for (int i = 0; i < 3; ++i) y[i] += depth * n[i];
                        CHECK(minkowskiDepth(a, moved) <= 1e-9L * scale + tol);
                    } else if (oracle < -tol) {
                        ++separated;
                        CHECK(!r["colliding"].get<bool>());
                        CHECK(r["distance"].get<double>() >= (double)-oracle - tol);
                        const V pa = array3(r["closest"][0]["point_a"]), pb = array3(r["closest"][0]["point_b"]);
                        const double dist =
                            std::sqrt((double)((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                                               (pa[2] - pb[2]) * (pa[2] - pb[2])));
                        CHECK(close(dist, r["distance"].get<double>(), tol));
                        CHECK(r["feature_a"]["vertices"].size() >= 1);
                    }
                }
            }
        }
        CHECK(colliding > 15);
        CHECK(separated > 10);
    }

    TEST_CASE("boxes: face-on stack gives 4 points and the faces, crossed edges 1 point") {
        const Json ground = {{"aabb", {{"min", {-2, -2, -1}}, {"max", {2, 2, 0}}}}};
        const Json cube = {
            {"obb", {{"center", {0.1, 0.2, 0.49}}, {"half_extents", {0.5, 0.5, 0.5}}, {"rotation", {0.9, 0, 0, 0.3}}}}};
        Json r = query(ground, cube);
        REQUIRE(r["colliding"].get<bool>());
        CHECK(r["depth"].get<double>() == doctest::Approx(0.01));
        CHECK(r["points"].size() == 4);
        CHECK(r["feature_a"]["type"] == "face");
        // aabb corner k has bit i set for +max on axis i: the top face is {4, 5, 6, 7}.
        std::vector<int> top = r["feature_a"]["vertices"].get<std::vector<int>>();
        std::sort(top.begin(), top.end());
        CHECK(top == std::vector<int>{4, 5, 6, 7});
        CHECK(r["feature_b"]["type"] == "face");
        CHECK(array3(r["normal"]) == V{0, 0, 1});
        // max_points 1: the deepest point only.
        CHECK(query(ground, cube, 1)["points"].size() == 1);
        // Edge on edge: two long boxes crossed at 90 degrees, rotated 45 degrees about their axes.
        const double s = std::sqrt(0.5);
        const Json a = {{"obb",
                         {{"center", {0, 0, 0}},
                          {"half_extents", {2, 0.5, 0.5}},
                          {"rotation", {std::cos(M_PI / 8), std::sin(M_PI / 8), 0, 0}}}}};
        const Json b = {{"obb",
                         {{"center", {0, 0, 2 * s - 0.01}},
                          {"half_extents", {0.5, 2, 0.5}},
                          {"rotation", {std::cos(M_PI / 8), 0, std::sin(M_PI / 8), 0}}}}};
        r = query(a, b);
        REQUIRE(r["colliding"].get<bool>());
        CHECK(r["axis"] == "edge-edge");
        CHECK(r["points"].size() == 1);
        CHECK(r["feature_a"]["type"] == "edge");
        CHECK(r["feature_b"]["type"] == "edge");
        CHECK(r["depth"].get<double>() == doctest::Approx(0.01));
    }

    TEST_CASE("tiny and huge scales scale exactly") {
        for (double unit : {1e-300, 1e-3, 1e3, 1e300}) {
            const Json box = {{"aabb", {{"min", {-unit, -unit, -unit}}, {"max", {unit, unit, unit}}}}};
            const Json plane = {{"plane", {{"normal", {0, 0, 1}}, {"offset", -0.75 * unit}}}};
            const Json r = query(box, plane);
            REQUIRE(!r.contains("error"));
            CHECK(r["depth"].get<double>() == doctest::Approx(0.25 * unit).epsilon(1e-15));
            CHECK(r["points"].size() == 4);
        }
    }

    TEST_CASE("errors: unsupported shapes, two planes, zero normal, flat polytope") {
        const Json box = {{"aabb", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
        CHECK(query({{"segment", {{0, 0, 0}, {1, 0, 0}}}}, box).contains("error"));  // spheres and capsules are taken
        const Json plane = {{"plane", {{"normal", {0, 0, 1}}, {"offset", 0}}}};
        CHECK(query(plane, plane).contains("error"));
        CHECK(query(box, {{"plane", {{"normal", {0, 0, 0}}, {"offset", 0}}}}).contains("error"));
        const Json flat = polytope({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
        const Json r = query(flat, plane);
        REQUIRE(r.contains("error"));
        CHECK(r["error"].get<std::string>().find("solid") != std::string::npos);
        CHECK(
            answerQuery(
                R"({"op":"contact","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"plane":{"normal":[0,0,1],"offset":0}},"bogus":1})")
                .contains("error"));
    }
}
