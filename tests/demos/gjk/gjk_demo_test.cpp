// The GJK figures' configuration panel names what it draws from the origin (demos/gjk/gjk_demo.h,
// gjkStepVectors). Each label is parsed here and the vector drawn is compared with the trace
// quantity the label names: "d = −vₖ" must be −v of iteration k (the direction GJK searched), "vₖ"
// v after iteration k's reduction. The old label "d = −v" beside the new v was 23°–82° off
// (figure review 2026-11-29): this test fails on it.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/gjk_epa/gjk.h"
#include "core/geometry/shapes.h"
#include "app/catalog/catalog.h"
#include "demos/gjk/gjk_demo.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace gjk_demo_test {

/// The iteration number written in subscript digits after `prefix`, or -1.
int subscriptAfter(const std::string& label, const std::string& prefix) {
    if (label.rfind(prefix, 0) != 0) return -1;
    static const std::string digits[10] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
    std::size_t at = prefix.size();
    int n = 0, count = 0;
    while (at < label.size()) {
        int found = -1;
        for (int k = 0; k < 10; ++k)
            if (label.compare(at, digits[k].size(), digits[k]) == 0) found = k;
        if (found < 0) return -1;
        n = 10 * n + found;
        at += digits[found].size();
        ++count;
    }
    return count ? n : -1;
}

double angle(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

const GjkTraceStep* byIteration(const GjkTrace& t, int k) {
    for (const GjkTraceStep& s : t.steps)
        if (s.iteration == k) return &s;
    return nullptr;
}

}  // namespace gjk_demo_test

TEST_CASE("GJK figure: every vector drawn from the origin is the trace quantity its label names") {
    using namespace gjk_demo_test;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<Vec3> a, b;
        const Vec3 offset(3 * u(rng), 3 * u(rng), 3 * u(rng));
        for (int i = 0; i < 12; ++i) a.push_back(Vec3(u(rng), u(rng), u(rng)));
        for (int i = 0; i < 12; ++i) b.push_back(offset + Vec3(u(rng), u(rng), u(rng)));
        GjkTrace trace;
        gjkDistance(PolytopeShape(a), PolytopeShape(b), GjkOptions{}, &trace);
        for (int i = 0; i < int(trace.steps.size()); ++i) {
            for (const GjkDrawnVector& dv : gjkStepVectors(trace.steps, i)) {
                INFO("trial " << trial << ", step " << i << ", label '" << dv.label << "'");
                Vec3 named = Vec3::Zero();
                if (dv.label == "d (start)") {
                    CHECK(i == 0);
                    named = trace.steps[0].direction;  // the direction GJK started from
                } else if (const int k = subscriptAfter(dv.label, "d = −v"); k >= 0) {
                    const GjkTraceStep* s = byIteration(trace, k);
                    REQUIRE(s);
                    CHECK(k < trace.steps[std::size_t(i)].iteration);  // an earlier iteration's v
                    named = -s->v;
                } else if (const int k2 = subscriptAfter(dv.label, "v"); k2 >= 0) {
                    const GjkTraceStep* s = byIteration(trace, k2);
                    REQUIRE(s);
                    named = s->v;
                } else {
                    FAIL("a label that names no trace quantity");
                }
                if (named.norm() == 0 || dv.vector.norm() == 0) continue;
                // Directions: the same up to rounding (GJK searches along exactly −v); points: equal.
                CHECK(angle(dv.vector, named) <= 1e-6);
                if (!dv.arrow) CHECK((dv.vector - named).norm() <= 1e-12 * named.norm());
                ++checked;
            }
        }
    }
    CHECK(checked > 400);
}

TEST_CASE("GJK bounds: the long runs' bounds enclose the distance at every iteration and close monotonically") {
    // The "bounds" frame (runs of 10 iterations or more) plots lower_bound and upper_bound per step;
    // each must be a bound on the final distance, the lower one never falling, the upper one never rising.
    for (const char* name : {"sphere_box", "cylinder_cone"}) {
        const cdlab::demos::Json t =
            cdlab::demos::loadScene(std::string(CDLAB_SOURCE_DIR) + "/golden/gjk/" + name + ".json")->run(cdlab::demos::RunContext{}).trace;
        const cdlab::demos::Json& steps = t["steps"];
        REQUIRE(steps.size() >= 10);
        const double distance = t["distance"].get<double>(), slack = 1e-12 * (1 + distance);
        double lower = -INFINITY, upper = INFINITY;
        for (const cdlab::demos::Json& s : steps) {
            const double lo = s["lower_bound"].get<double>(), up = s["upper_bound"].get<double>();
            CHECK(lo <= distance + slack);
            CHECK(up >= distance - slack);
            CHECK(lo >= lower);
            CHECK(up <= upper + slack);
            lower = lo;
            upper = up;
        }
        CHECK(upper - lower < 1e-8 * (1 + distance));  // converged: the two meet
    }
}
