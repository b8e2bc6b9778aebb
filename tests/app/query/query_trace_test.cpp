// Query traces a student can compare with: GJK / EPA traces in world units with support pairs,
// GJK started from a given "initial_direction", and closest_point_triangle's region tests with
// their values — each checked against numbers computed here from the input.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "app/query/query.h"
#include "tests/app/query/ask.h"

using cdlab::demos::answerQuery;
using cdlab::demos::Json;

namespace {

using cdlab::test::ask;

double dot3(const Json& a, const Json& b) {
    return a[0].get<double>() * b[0].get<double>() + a[1].get<double>() * b[1].get<double>() +
           a[2].get<double>() * b[2].get<double>();
}

}  // namespace

TEST_SUITE("query") {
    TEST_CASE("trace: GJK in world units, with support pairs, from a given initial direction") {
        // Boxes at 1e6: the trace's points are where the shapes are, not in normalised units.
        const Json a = {{"aabb", {{"min", {1e6, 0, 0}}, {"max", {1e6 + 1, 1, 1}}}}};
        const Json b = {{"aabb", {{"min", {1e6 + 3, 0, 0}}, {"max", {1e6 + 4, 1, 1}}}}};
        const Json d = {-1, 2, 3};
        const Json ans = ask({{"op", "distance"}, {"a", a}, {"b", b}, {"trace", true}, {"initial_direction", d}});
        REQUIRE(ans.contains("trace"));
        CHECK(ans["trace"]["unit"] == 1.0);
        const Json& steps = ans["trace"]["algorithms"][0]["steps"];
        REQUIRE(steps.size() >= 1);
        // Every support pair lies on the boxes (world coordinates) and w = a - b.
        for (const Json& s : steps) {
            const Json& sa = s["support_a"];
            const Json& sb = s["support_b"];
            CHECK(sa[0].get<double>() >= 1e6);
            CHECK(sa[0].get<double>() <= 1e6 + 1);
            CHECK(sb[0].get<double>() >= 1e6 + 3);
            for (int i = 0; i < 3; ++i) CHECK(s["support"][i].get<double>() == sa[i].get<double>() - sb[i].get<double>());
        }
        // The start: the first simplex point is A - B's extreme along the initial direction: a's
        // corner at (1e6 + 0, 1, 1), b's at (1e6 + 4, 0, 0) for d = (-1, 2, 3).
        const Json& first = steps[0]["simplex"][0];
        CHECK(first[0].get<double>() == -4.0);
        CHECK(first[1].get<double>() == 1.0);
        CHECK(first[2].get<double>() == 1.0);
        CHECK(ans["distance"].get<double>() == 2.0);
        // The distance's bounds are world lengths.
        CHECK(steps.back()["upper_bound"].get<double>() == doctest::Approx(2.0).epsilon(1e-12));
    }

    TEST_CASE("trace: initial_direction errors") {
        const Json a = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}};
        const Json b = {{"sphere", {{"center", {3, 0, 0}}, {"radius", 1}}}};
        const auto error = [&](const Json& extra) {
            Json q = {{"op", "distance"}, {"a", a}, {"b", b}};
            for (auto it = extra.begin(); it != extra.end(); ++it) q[it.key()] = it.value();
            const Json r = ask(q);
            return r.contains("error") ? r["error"].get<std::string>() : std::string();
        };
        CHECK(error({{"initial_direction", {0, 0, 0}}}).find("non-zero") != std::string::npos);
        CHECK(error({{"initial_direction", {1, 0, 0}}, {"method", "vclip"}}).find("GJK's") != std::string::npos);
        CHECK(error({{"initial_direction", {1, 0, 0}}}).empty());
    }

    TEST_CASE("trace: closest_point_triangle lists Ericson's tests with their values") {
        const Json p = {0.2, -1, 0}, a = {0, 0, 0}, b = {1, 0, 0}, c = {0, 1, 0};
        const Json ans = ask({{"op", "closest_point_triangle"}, {"point", p}, {"triangle", {a, b, c}}, {"trace", true}});
        CHECK(ans["region"] == "AB");
        const Json& tests = ans["trace"]["tests"];
        REQUIRE(tests.size() == 3);
        CHECK(tests[0]["region"] == "A");
        CHECK(tests[0]["accepted"] == false);
        // d1 = (b - a).(p - a), computed here.
        const Json ba = {1, 0, 0}, pa = p;
        CHECK(tests[0]["terms"][0]["name"] == "d1");
        CHECK(tests[0]["terms"][0]["value"].get<double>() == dot3(ba, pa));
        CHECK(tests[0]["terms"][0]["sign"] == 1);
        CHECK(tests[2]["region"] == "AB");
        CHECK(tests[2]["accepted"] == true);
    }
}
