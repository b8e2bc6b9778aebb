// golden/mtd_backtracking/toi_* run numerically; the time of impact recomputed without the ray cast:
// two spheres by the quadratic |Δc + t Δm| = r_A + r_B (Ericson §5.5.8), two axis-aligned boxes by
// the slab entry and exit times of A's motion relative to B; every bisection bracket checked with
// the same closed-form overlap tests (separated at lo, overlapping at hi), and the cast's t inside it.
#include <doctest/doctest.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace toi_3d_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }
Vec3 positionOf(const Json& shape) {
    const Json& s = shape.begin().value();
    return s.contains("position") ? vec(s["position"]) : Vec3::Zero();
}

}  // namespace toi_3d_test

TEST_CASE("3D time of impact: the cast's t, normal and contact recomputed, every bisection bracket holds it") {
    using namespace toi_3d_test;
    for (const char* name : {"toi_spheres", "toi_boxes"}) {
        CAPTURE(name);
        const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/mtd_backtracking/" + name + ".json";
        const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
        const Json &A = s["shapes"][0], &B = s["shapes"][1];
        const Vec3 ma = vec(s["motion"]["a"]), mb = vec(s["motion"]["b"]);
        const Vec3 ca = positionOf(A), cb = positionOf(B);
        double toi = -1;
        Vec3 normal = Vec3::Zero();
        std::function<bool(double)> overlapAt;
        if (A.contains("sphere")) {
            const double r = A["sphere"]["radius"].get<double>() + B["sphere"]["radius"].get<double>();
            const Vec3 d0 = cb - ca, dm = mb - ma;
            // |d0 + t dm|² = r²: a t² + 2 b t + c = 0, the smaller root.
            const double a = dm.dot(dm), b = d0.dot(dm), c = d0.dot(d0) - r * r;
            const double disc = b * b - a * c;
            REQUIRE(disc > 0);
            toi = (-b - std::sqrt(disc)) / a;
            normal = (d0 + toi * dm).normalized();
            overlapAt = [=](double tt) { return (d0 + tt * dm).norm() <= r; };
            CHECK((vec(t["point_a"]) - (ca + toi * ma + A["sphere"]["radius"].get<double>() * normal)).norm() <= 1e-9);
        } else {
            const Vec3 ha = vec(A["box"]["half_extents"]), hb = vec(B["box"]["half_extents"]);
            const Vec3 d = ma - mb;  // A's motion relative to B
            double enter = -INFINITY, leave = INFINITY;
            int axis = -1;
            for (int k = 0; k < 3; ++k) {
                // A's interval [ca - ha + t d, ca + ha + t d] meets [cb - hb, cb + hb].
                const double lo = cb[k] - hb[k] - (ca[k] + ha[k]), hi = cb[k] + hb[k] - (ca[k] - ha[k]);
                double t0 = d[k] != 0 ? lo / d[k] : (0 >= lo && 0 <= hi ? -INFINITY : INFINITY);
                double t1 = d[k] != 0 ? hi / d[k] : (0 >= lo && 0 <= hi ? INFINITY : -INFINITY);
                if (t0 > t1) std::swap(t0, t1);
                if (t0 > enter) enter = t0, axis = k;
                leave = std::min(leave, t1);
            }
            REQUIRE(enter <= leave);
            toi = enter;
            normal = Vec3::Unit(axis) * (d[axis] > 0 ? 1.0 : -1.0);
            overlapAt = [=](double tt) {
                for (int k = 0; k < 3; ++k)
                    if (std::abs(cb[k] - (ca[k] + tt * d[k])) > ha[k] + hb[k]) return false;
                return true;
            };
        }
        REQUIRE(t["hit"].get<bool>());
        CHECK(t["t"].get<double>() == doctest::Approx(toi).epsilon(1e-12));
        CHECK((vec(t["normal"]) - normal).norm() <= 1e-9);
        const Json& bis = t["bisection"];
        REQUIRE(bis.size() == s["bisection_steps"].get<std::size_t>());
        double lo = 0, hi = 1;
        for (const Json& b : bis) {
            CHECK(b["lo"].get<double>() == lo);
            CHECK(b["hi"].get<double>() == hi);
            CHECK(!overlapAt(lo));
            CHECK(overlapAt(hi));
            const double mid = 0.5 * (lo + hi);
            CHECK(b["mid"].get<double>() == mid);
            CHECK(b["overlapping"].get<bool>() == overlapAt(mid));
            (overlapAt(mid) ? hi : lo) = mid;
        }
        CHECK(lo <= toi);
        CHECK(toi <= hi);
    }
}
