// The EPA figures' blow-up and witness frames draw trace.json's "blow_up" and "witness" (core's
// EpaTrace). Here their numbers are recomputed from the scenes' boxes alone: the corners from the
// half extents, position and rotation; the support of A − B along a direction by brute force over
// corner pairs; the weights of the projection on the nearest face by a least-squares solve (Eigen's
// QR); for axis-aligned boxes the depth as the least overlap of their intervals.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace epa_witness_frames_test {

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

std::vector<Vec3> corners(const Json& shape) {
    const Json& b = shape["box"];
    const Vec3 h = vec(b["half_extents"]);
    const Vec3 c = b.contains("position") ? vec(b["position"]) : Vec3::Zero();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    if (b.contains("rotation"))
        q = Eigen::Quaterniond(b["rotation"][0].get<double>(), b["rotation"][1].get<double>(),
                               b["rotation"][2].get<double>(), b["rotation"][3].get<double>())
                .normalized();
    std::vector<Vec3> out;
    for (int k = 0; k < 8; ++k)
        out.push_back(c + q * Vec3(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()));
    return out;
}

bool isOneOf(const Vec3& p, const std::vector<Vec3>& set) {
    for (const Vec3& v : set)
        if ((v - p).norm() <= 1e-12 * (1 + v.norm())) return true;
    return false;
}

}  // namespace epa_witness_frames_test

TEST_CASE("EPA witness frame: weights, face points and witnesses recomputed from the boxes") {
    using namespace epa_witness_frames_test;
    for (const char* name : {"box_box", "deep_penetration", "touching"}) {
        CAPTURE(name);
        const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/epa/" + name + ".json";
        const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
        const std::vector<Vec3> A = corners(s["shapes"][0]), B = corners(s["shapes"][1]);
        if (!t.contains("witness")) {
            CHECK(std::string(name) == "touching");  // decided during the blow-up: no face, no witness step
            continue;
        }
        const Json& w = t["witness"];
        const Vec3 p = vec(w["projection"]);
        CHECK(p.norm() == doctest::Approx(t["depth"].get<double>()).epsilon(1e-12));
        // The nearest face's weights by least squares: p - w0 = l1 (w1 - w0) + l2 (w2 - w0).
        const Json& nf = w["nearest_face"];
        Eigen::Matrix<double, 3, 2> m;
        m.col(0) = vec(nf["w"][1]) - vec(nf["w"][0]);
        m.col(1) = vec(nf["w"][2]) - vec(nf["w"][0]);
        const Eigen::Vector2d l = m.colPivHouseholderQr().solve(p - vec(nf["w"][0]));
        const double mine[3] = {1 - l[0] - l[1], l[0], l[1]};
        for (int k = 0; k < 3; ++k) CHECK(nf["weights"][k].get<double>() == doctest::Approx(mine[k]).epsilon(1e-9));
        CHECK(w["covered"].get<bool>() == (std::min({mine[0], mine[1], mine[2]}) < 0));
        // The face that gave the witnesses: corners of A and of B, convex weights, p on it.
        const Json& uf = w["used_face"];
        Vec3 pa = Vec3::Zero(), pb = Vec3::Zero(), pw = Vec3::Zero();
        double sum = 0;
        for (int k = 0; k < 3; ++k) {
            const double lk = uf["weights"][k].get<double>();
            CHECK(lk >= 0);
            sum += lk;
            CHECK(isOneOf(vec(uf["a"][k]), A));
            CHECK(isOneOf(vec(uf["b"][k]), B));
            CHECK((vec(uf["w"][k]) - (vec(uf["a"][k]) - vec(uf["b"][k]))).norm() <= 1e-15);
            pa += lk * vec(uf["a"][k]), pb += lk * vec(uf["b"][k]), pw += lk * vec(uf["w"][k]);
        }
        CHECK(sum == doctest::Approx(1).epsilon(1e-14));
        CHECK((pw - p).norm() <= 1e-12);
        CHECK((vec(w["point_a"]) - pa).norm() <= 1e-12);
        CHECK((vec(w["point_b"]) - pb).norm() <= 1e-12);
        CHECK((vec(w["point_a"]) - vec(w["point_b"]) - p).norm() <= 1e-12);
        if (!s["shapes"][0]["box"].contains("rotation") && !s["shapes"][1]["box"].contains("rotation")) {
            // Axis-aligned boxes: A − B is a box, the depth is the least interval overlap.
            double depth = INFINITY;
            for (int k = 0; k < 3; ++k) {
                double alo = INFINITY, ahi = -INFINITY, blo = INFINITY, bhi = -INFINITY;
                for (const Vec3& v : A) alo = std::min(alo, v[k]), ahi = std::max(ahi, v[k]);
                for (const Vec3& v : B) blo = std::min(blo, v[k]), bhi = std::max(bhi, v[k]);
                depth = std::min(depth, std::min(ahi - blo, bhi - alo));
            }
            CHECK(p.norm() == doctest::Approx(depth).epsilon(1e-12));
        }
    }
}

TEST_CASE("EPA blow-up frame: each direction is orthogonal to GJK's simplex and its support is A − B's") {
    using namespace epa_witness_frames_test;
    const std::string file = std::string(CDLAB_SOURCE_DIR) + "/golden/epa/touching.json";
    const Json s = readJsonFile(file), t = loadScene(file)->run(RunContext{}).trace;
    const std::vector<Vec3> A = corners(s["shapes"][0]), B = corners(s["shapes"][1]);
    REQUIRE(t.contains("blow_up"));
    const Json& simplex = t["gjk"]["simplex"];
    REQUIRE(simplex.size() == 3);  // a triangle blown up
    CHECK(t["start"] == "triangle blown up");
    for (const Json& b : t["blow_up"]) {
        const Vec3 d = vec(b["direction"]);
        CHECK(d.norm() == doctest::Approx(1).epsilon(1e-15));
        for (std::size_t i = 1; i < simplex.size(); ++i)
            CHECK(std::abs(d.dot(vec(simplex[i]) - vec(simplex[0]))) <= 1e-12);
        double best = -INFINITY;
        for (const Vec3& a : A)
            for (const Vec3& c : B) best = std::max(best, d.dot(a - c));
        CHECK(b["support_value"].get<double>() == doctest::Approx(best).epsilon(1e-12));
        CHECK(d.dot(vec(b["support"])) == doctest::Approx(best).epsilon(1e-12));
        // Touching exactly when A − B reaches no further than the origin's plane along d.
        CHECK((t["termination"] == "Touching") == (std::abs(best) <= 1e-12));
    }
}
