// golden/drop/impulse_* run numerically: the contact, the relative velocity, both terms of 1/k and
// Baraff's j recomputed from the scene's box (inertia m/12 (b² + c², ...), rotated by the scene's
// quaternion) without core's rigid body; the solver's answer checked against the laws it must obey
// whatever the algorithm: the impulses change momentum and angular momentum by exactly their sum
// and moment, the friction impulse lies in the cone and in the tangent plane, each point ends
// non-approaching, and a point still pushing (λ_n > 0) ends at its target velocity.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"
#include "tests/scene_error.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace impulse_figure_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

struct Box {
    double m;
    Eigen::Matrix3d invInertiaWorld;
    std::vector<Vec3> contacts;
    Vec3 v, w;
};

Box boxOf(const Json& s) {
    Box b;
    b.m = s["mass"].get<double>();
    const Vec3 h = vec(s["box"]["half_extents"]), d = 2 * h;
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    if (s.contains("rotation"))
        q = Eigen::Quaterniond(s["rotation"][0].get<double>(), s["rotation"][1].get<double>(), s["rotation"][2].get<double>(),
                               s["rotation"][3].get<double>())
                .normalized();
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Vec3 I = b.m / 12 * Vec3(d.y() * d.y() + d.z() * d.z(), d.x() * d.x() + d.z() * d.z(), d.x() * d.x() + d.y() * d.y());
    b.invInertiaWorld = R * I.cwiseInverse().asDiagonal() * R.transpose();
    std::vector<Vec3> corners;
    double low = INFINITY;
    for (int k = 0; k < 8; ++k) {
        corners.push_back(R * Vec3(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()));
        low = std::min(low, corners.back().z());
    }
    for (const Vec3& c : corners)
        if (c.z() <= low + 1e-9 * h.maxCoeff()) b.contacts.push_back(c);
    b.v = s.contains("velocity") ? vec(s["velocity"]) : Vec3::Zero();
    b.w = s.contains("angular_velocity") ? vec(s["angular_velocity"]) : Vec3::Zero();
    return b;
}

}  // namespace impulse_figure_test

TEST_CASE("impulse figure: the contact's numbers recomputed, the solver's answer obeys the impulse laws") {
    using namespace impulse_figure_test;
    for (const char* name : {"impulse_corner", "impulse_face"}) {
        CAPTURE(name);
        const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/drop/" + name + ".json";
        const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
        const Box b = boxOf(s);
        const Vec3 n = Vec3::UnitZ();
        const double e = s["restitution"].get<double>(), mu = s["friction"].get<double>();
        const Json& pts = t["points"];
        REQUIRE(pts.size() == b.contacts.size());
        Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
        const Vec3 v1 = vec(t["velocity_after"]), w1 = vec(t["angular_velocity_after"]);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            CAPTURE(i);
            const Json& p = pts[i];
            const Vec3 r = b.contacts[i];  // the centre of mass is at the origin
            CHECK((vec(p["point"]) - r).norm() <= 1e-15);
            CHECK((vec(p["r"]) - r).norm() <= 1e-15);
            const Vec3 vp = b.v + b.w.cross(r);
            CHECK((vec(p["velocity_before"]) - vp).norm() <= 1e-14);
            CHECK(p["normal_velocity_before"].get<double>() == doctest::Approx(vp.dot(n)).epsilon(1e-14));
            const double angular = n.dot((b.invInertiaWorld * r.cross(n)).cross(r));
            CHECK(p["inverse_mass_term"].get<double>() == doctest::Approx(1 / b.m).epsilon(1e-15));
            CHECK(p["angular_term"].get<double>() == doctest::Approx(angular).epsilon(1e-12));
            CHECK(p["normal_mass"].get<double>() == doctest::Approx(1 / (1 / b.m + angular)).epsilon(1e-12));
            if (i == 0)
                CHECK(t["closed_form_j"].get<double>() ==
                      doctest::Approx(vp.dot(n) < 0 ? -(1 + e) * vp.dot(n) / (1 / b.m + angular) : 0.0).epsilon(1e-12));
            // The solver's impulse at this point: λ_n n + λ_t, λ_t tangent and inside the cone.
            const double ln = p["normal_impulse"].get<double>();
            const Vec3 lt = vec(p["tangent_impulse"]);
            CHECK(ln >= 0);
            CHECK(std::abs(lt.dot(n)) <= 1e-12 * (1 + lt.norm()));
            CHECK(lt.norm() <= mu * ln * (1 + 1e-12) + 1e-15);
            sum += ln * n + lt;
            moment += r.cross(ln * n + lt);
            // Where it ends: its velocity from the body's, not approaching, at its target while pushing.
            const Vec3 vpAfter = v1 + w1.cross(r);
            CHECK((vec(p["velocity_after"]) - vpAfter).norm() <= 1e-12);
            CHECK(vpAfter.dot(n) >= -1e-9);
            const double target = p["bounce"].get<bool>() ? -e * vp.dot(n) : p["target_velocity"].get<double>();
            if (ln > 1e-9) CHECK(vpAfter.dot(n) == doctest::Approx(target).epsilon(1e-6));
        }
        // Momentum and angular momentum about the centre change by the impulses' sum and moment.
        CHECK((b.m * (v1 - b.v) - sum).norm() <= 1e-12 * (1 + sum.norm()));
        const Eigen::Matrix3d inertiaWorld = b.invInertiaWorld.inverse();
        CHECK((inertiaWorld * (w1 - b.w) - moment).norm() <= 1e-9 * (1 + moment.norm()));
        // The sweeps: one row per sweep, the last one the final impulses.
        const Json& history = t["history"];
        REQUIRE(history.size() == static_cast<std::size_t>(s.value("iterations", 16) + t["history_restitution"].get<int>()));
        for (std::size_t i = 0; i < pts.size(); ++i)
            CHECK(history.back()[i].get<double>() == pts[i]["normal_impulse"].get<double>());
    }
}

TEST_CASE("impulse figure: a scene out of range is one error naming its key") {
    const std::string base = R"({"demo": "drop", "figure": "impulse", "title": "t", )";
    const std::pair<const char*, const char*> bad[] = {
        {R"("box": {"half_extents": [0.5, -0.3, 0.2]}})", "box.half_extents"},
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "restitution": 2})", "restitution"},
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "iterations": 65})", "iterations"},
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "velocity": [1e9, 0, 0]})", "velocity"},
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "mass": 0})", "mass"},
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "body": {}})", "body"},
        {R"("box": {"half_extents": [100, 1e-5, 1e-5]}})", "box.half_extents"},  // no valid inertia (crashed once)
        {R"("box": {"half_extents": [0.5, 0.3, 0.2]}, "mass": 1e-300})", "mass"}};
    for (const auto& [keys, what] : bad) {
        CAPTURE(keys);
        const std::string error = test::sceneTextError(base + keys);
        CHECK(error.find(what) != std::string::npos);
    }
    CHECK(test::sceneTextError(base + R"("box": {"half_extents": [0.5, 0.3, 0.2]}})") == "");
}
