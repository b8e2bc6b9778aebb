// `cdlab query` with method "vclip": answers against GJK's answers to the same line and a long
// double brute-force oracle over the hulls' features (verification/feature_walk_oracle.h); the answer
// keys; errors for non-polyhedral and flat shapes; exact power-of-two scale invariance.
#include <doctest/doctest.h>

#include <cmath>

#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "verification/feature_walk_oracle.h"
#include "app/query/query.h"

using cdlab::Vec3;
using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

// The answer without the echoed "id" key.
Json askWithoutId(const Json& q) {
    Json a = answerQuery(q.dump());
    a.erase("id");
    return a;
}

Json jsonVec(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json polytope(const std::vector<Vec3>& vs) {
    Json list = Json::array();
    for (const Vec3& v : vs) list.push_back(jsonVec(v));
    return {{"polytope", {{"vertices", list}}}};
}

std::vector<Vec3> cloud(cdlab::presets::SplitMix64& rng, int n, double size, const Vec3& centre) {
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) v.push_back(centre + size * rng.inUnitBall());
    return v;
}

double featureWalkOracle(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool& intersect) {
    const cdlab::HullResult ha = cdlab::convexHull(a), hb = cdlab::convexHull(b);
    REQUIRE(ha.ok());
    REQUIRE(hb.ok());
    const cdlab::test::OracleDistance o = cdlab::test::oracleDistance(ha.polyhedron, {}, hb.polyhedron, {});
    intersect = o.intersect;
    return static_cast<double>(o.distance);
}

}  // namespace

TEST_SUITE("query_vclip") {
    TEST_CASE("random polytopes, aabbs and obbs: vclip agrees with gjk and the brute-force oracle") {
        cdlab::presets::SplitMix64 rng(4242);
        int separated = 0, intersecting = 0;
        for (int trial = 0; trial < 120; ++trial) {
            const double size = trial % 3 == 0 ? 1e-3 : (trial % 3 == 1 ? 1.0 : 1e3);
            const double offset = (trial / 3) % 2 == 0 ? 0.0 : 1e4;
            const Vec3 ca = Vec3(offset, -offset, 0.5 * offset), cb = ca + 2.2 * size * rng.inUnitBall();
            Json a, b;
            std::vector<Vec3> va, vb;
            if (trial % 4 == 3) {
                // An aabb against an obb.
                const Vec3 h = size * Vec3(0.5, 0.3, 0.7);
                a = {{"aabb", {{"min", jsonVec(ca - h)}, {"max", jsonVec(ca + h)}}}};
                for (int i = 0; i < 8; ++i)
                    va.push_back(ca + Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
                const cdlab::Quat q = cdlab::Quat(0.9, 0.1, -0.3, 0.2).normalized();
                const Vec3 e = size * Vec3(0.4, 0.6, 0.2);
                b = {{"obb",
                      {{"center", jsonVec(cb)}, {"half_extents", jsonVec(e)}, {"rotation", {q.w(), q.x(), q.y(), q.z()}}}}};
                for (int i = 0; i < 8; ++i)
                    vb.push_back(q * Vec3(i & 1 ? e.x() : -e.x(), i & 2 ? e.y() : -e.y(), i & 4 ? e.z() : -e.z()) + cb);
            } else {
                va = cloud(rng, 10, size, ca);
                vb = cloud(rng, 12, size, cb);
                a = polytope(va);
                b = polytope(vb);
            }
            const Json v = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", a}, {"b", b}});
            const Json g = askWithoutId({{"op", "distance"}, {"a", a}, {"b", b}});
            REQUIRE_MESSAGE(!v.contains("error"), v.dump());
            REQUIRE_MESSAGE(!g.contains("error"), g.dump());
            bool oi = false;
            const double od = featureWalkOracle(va, vb, oi);
            CAPTURE(trial);
            CAPTURE(v.dump());
            CAPTURE(g.dump());
            CHECK(v["intersect"].get<bool>() == oi);
            if (oi) {
                ++intersecting;
                CHECK(v == Json{{"intersect", true}, {"distance", 0.0}});
            } else {
                ++separated;
                const double d = v["distance"].get<double>();
                CHECK(std::abs(d - od) <= 1e-10 * size);
                CHECK(std::abs(d - g["distance"].get<double>()) <= 1e-10 * size);
                const Vec3 pa(v["point_a"][0].get<double>(), v["point_a"][1].get<double>(),
                              v["point_a"][2].get<double>());
                const Vec3 pb(v["point_b"][0].get<double>(), v["point_b"][1].get<double>(),
                              v["point_b"][2].get<double>());
                CHECK(std::abs((pb - pa).norm() - d) <= 1e-10 * size + 1e-15 * offset);
            }
        }
        CHECK(separated > 20);
        CHECK(intersecting > 20);
    }

    TEST_CASE("penetration keys: separated like gjk's, penetrating gives the verdict only") {
        const Json box = {{"aabb", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
        const Json far = {{"aabb", {{"min", {2, -0.5, -0.5}}, {"max", {3, 0.5, 0.5}}}}};
        const Json near = {{"aabb", {{"min", {0.5, -0.5, -0.5}}, {"max", {3, 0.5, 0.5}}}}};
        const Json s = askWithoutId({{"op", "penetration"}, {"method", "vclip"}, {"a", box}, {"b", far}});
        const Json g = askWithoutId({{"op", "penetration"}, {"a", box}, {"b", far}});
        REQUIRE_MESSAGE(!s.contains("error"), s.dump());
        for (const auto& [key, value] : g.items()) CHECK_MESSAGE(s.contains(key), key);
        CHECK(s.size() == g.size());
        CHECK(s["distance"].get<double>() == 1.0);
        CHECK(s["normal"] == Json::array({1.0, 0.0, 0.0}));
        CHECK(s["point_a"][0].get<double>() == 1.0);
        CHECK(s["point_b"][0].get<double>() == 2.0);
        const Json p = askWithoutId({{"op", "penetration"}, {"method", "vclip"}, {"a", box}, {"b", near}});
        CHECK(p == Json{{"intersect", true}});
        const Json t = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", box}, {"b", far}, {"trace", true}});
        REQUIRE(t.contains("trace"));
        CHECK(t["trace"]["algorithms"][0]["algorithm"] == "vclip");
        CHECK(t["trace"]["algorithms"][0]["steps"].size() >= 1);
    }

    TEST_CASE("errors: non-polyhedral shapes, flat hulls, lin_canny") {
        const Json box = {{"aabb", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
        const Json sphere = {{"sphere", {{"center", {3, 0, 0}}, {"radius", 1}}}};
        Json e = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", box}, {"b", sphere}});
        REQUIRE(e.contains("error"));
        CHECK(e["error"].get<std::string>().find("needs polyhedra (polytope, aabb, obb)") != std::string::npos);
        CHECK(e["error"].get<std::string>().find("$.b") != std::string::npos);
        const Json flat = polytope({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)});
        e = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", flat}, {"b", box}});
        REQUIRE(e.contains("error"));
        CHECK(e["error"].get<std::string>().find("$.a") != std::string::npos);
        CHECK(e["error"].get<std::string>().find("AllCoplanar") != std::string::npos);
        const Json flatBox = {{"aabb", {{"min", {-1, -1, 0}}, {"max", {1, 1, 0}}}}};
        e = askWithoutId({{"op", "penetration"}, {"method", "vclip"}, {"a", box}, {"b", flatBox}});
        CHECK(e.contains("error"));
        // lin_canny: the same shape rules, and on coincident boxes a penetration verdict, never a distance.
        e = askWithoutId({{"op", "distance"}, {"method", "lin_canny"}, {"a", box}, {"b", sphere}});
        REQUIRE(e.contains("error"));
        CHECK(e["error"].get<std::string>().find("$.b") != std::string::npos);
        e = askWithoutId({{"op", "distance"}, {"method", "lin_canny"}, {"a", box}, {"b", box}});
        if (!e.contains("error")) CHECK(e["intersect"] == true);
        else CHECK(e["error"].get<std::string>().find("cycle detected") != std::string::npos);
    }

    TEST_CASE("scale 1e-300 and 1e300: the same answer times the scale, exactly") {
        const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0.3, 0.4, 0.5)};
        const std::vector<Vec3> b = {Vec3(2, 1, 1), Vec3(3, 1, 1), Vec3(2, 2.5, 1), Vec3(2.2, 1.1, 3)};
        const Json base = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", polytope(a)}, {"b", polytope(b)}});
        REQUIRE_MESSAGE(!base.contains("error"), base.dump());
        for (int k : {-996, -500, 500, 1000}) {
            const double s = std::ldexp(1.0, k);
            std::vector<Vec3> as, bs;
            for (const Vec3& v : a) as.push_back(s * v);
            for (const Vec3& v : b) bs.push_back(s * v);
            const Json r = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", polytope(as)}, {"b", polytope(bs)}});
            REQUIRE_MESSAGE(!r.contains("error"), r.dump());
            CAPTURE(k);
            CHECK(r["distance"].get<double>() == s * base["distance"].get<double>());
            for (int i = 0; i < 3; ++i) CHECK(r["point_a"][i].get<double>() == s * base["point_a"][i].get<double>());
        }
        // 1e-300 literally (not a power of two): agrees with gjk to rounding.
        std::vector<Vec3> as, bs;
        for (const Vec3& v : a) as.push_back(1e-300 * v);
        for (const Vec3& v : b) bs.push_back(1e-300 * v);
        const Json r = askWithoutId({{"op", "distance"}, {"method", "vclip"}, {"a", polytope(as)}, {"b", polytope(bs)}});
        const Json g = askWithoutId({{"op", "distance"}, {"a", polytope(as)}, {"b", polytope(bs)}});
        REQUIRE_MESSAGE(!r.contains("error"), r.dump());
        CHECK(std::abs(r["distance"].get<double>() - g["distance"].get<double>()) <=
              1e-12 * g["distance"].get<double>());
    }
}
