// The GJK and EPA demos draw their frames from the traces checked here: every committed scene of
// golden/gjk and golden/epa is run numerically (RunContext{} without GL) and the trace must
// describe valid pictures: GJK's upper bound never grows and its regions name real sub-simplices;
// every EPA polytope is convex, closed (3D), contains the origin, and its closest-face distance
// (recomputed here from the vertices) never decreases. Polytope scenes are checked against a
// brute-force oracle: the facets of conv{a_i - b_j} found by testing every vertex triple (pair in 2D).
// The GIF writer is checked by decoding its output with giflib.
#include <doctest/doctest.h>

#include <gif_lib.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "app/catalog/catalog.h"
#include "app/scene/pair_scene.h"
#include "render/gif_writer.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

std::vector<std::string> scenesOf(const std::string& demo) {
    std::vector<std::string> out;
    for (const auto& f : findSceneFiles(std::string(CDLAB_SOURCE_DIR) + "/golden"))
        if (f.find("/golden/" + demo + "/") != std::string::npos) out.push_back(f);
    return out;
}

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

Json runNumeric(const std::string& file) { return loadScene(file)->run(RunContext{}).trace; }

// Penetration depth of polytopes by brute force over the difference cloud: the smallest distance of
// the origin to a supporting plane (3D: through 3 points, 2D: line through 2 points) that has every
// point on its other side. Independent of GJK / EPA.
double bruteDepth(const std::vector<Vec3>& c, bool planar) {
    double best = INFINITY;
    double scale = 0;
    for (const Vec3& p : c) scale = std::max(scale, p.norm());
    const double tol = 1e-12 * scale;
    const int n = int(c.size());
    auto consider = [&](const Vec3& normal, const Vec3& onPlane) {
        const double len = normal.norm();
        if (!(len > 1e-12 * scale * scale)) return;
        Vec3 u = normal / len;
        double h = u.dot(onPlane);
        bool pos = true, neg = true;
        for (const Vec3& q : c) {
            const double s = u.dot(q) - h;
            pos = pos && s <= tol;
            neg = neg && s >= -tol;
        }
        if (neg) u = -u, h = -h, pos = true;
        if (pos) best = std::min(best, h);
    };
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            if (planar) {
                const Vec3 e = c[j] - c[i];
                consider(Vec3(e.y(), -e.x(), 0), c[i]);
                continue;
            }
            for (int k = j + 1; k < n; ++k) consider((c[j] - c[i]).cross(c[k] - c[i]), c[i]);
        }
    return best;
}

}  // namespace

TEST_SUITE("gjk_epa_demo") {
    TEST_CASE("there are 3D and 2D scenes for both demos") {
        for (const std::string demo : {"gjk", "epa"}) {
            int twoD = 0, threeD = 0;
            for (const auto& f : scenesOf(demo)) (runNumeric(f)["dimension"] == 2 ? twoD : threeD)++;
            CHECK(twoD >= 2);
            CHECK(threeD >= 6);
        }
    }

    TEST_CASE("GJK traces: upper bound non-increasing, lower bound non-decreasing, valid regions") {
        for (const auto& file : scenesOf("gjk")) {
            CAPTURE(file);
            const Json t = runNumeric(file);
            const int dim = t["dimension"];
            const Json& steps = t["steps"];
            REQUIRE(steps.size() >= 1);
            double prevUpper = INFINITY, prevLower = 0;
            for (std::size_t i = 0; i < steps.size(); ++i) {
                const Json& s = steps[i];
                CAPTURE(i);
                const double upper = s["upper_bound"], lower = s["lower_bound"];
                CHECK(upper <= prevUpper * (1 + 1e-12));
                CHECK(lower >= prevLower - 1e-12);
                CHECK(lower <= upper * (1 + 1e-12) + 1e-15);
                prevUpper = upper;
                prevLower = lower;
                // Region: distinct slot letters in order, drawn from the slots the simplex has.
                const std::string region = s["region"];
                const int count = int(s["simplex"].size());
                CHECK(count >= 1);
                CHECK(count <= dim + 1);
                REQUIRE(!region.empty());
                CHECK(int(region.size()) <= count);
                for (std::size_t k = 0; k < region.size(); ++k) {
                    CHECK(region[k] >= 'A');
                    CHECK(region[k] < char('A' + count));
                    if (k > 0) CHECK(region[k] > region[k - 1]);
                }
                // v is the convex combination of the kept vertices with the recorded weights.
                if (!s["terminated"].get<bool>() || int(region.size()) < count) {
                    const Json& lambda = s["lambda"];
                    REQUIRE(lambda.size() == region.size());
                    Vec3 v = Vec3::Zero();
                    double sum = 0;
                    for (std::size_t k = 0; k < region.size(); ++k) {
                        const double l = lambda[k];
                        CHECK(l >= -1e-12);
                        sum += l;
                        v += l * vec(s["simplex"][region[k] - 'A']["w"]);
                    }
                    CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
                    CHECK((v - vec(s["v"])).norm() <= 1e-9 * (1 + upper));
                    // The new |v| never exceeds the old one (GJK's monotone descent).
                    CHECK(vec(s["v"]).norm() <= upper * (1 + 1e-12));
                }
                // The support point maximises -v... at least over the simplex vertices.
                const Vec3 d = vec(s["direction"]), w = vec(s["support"]["w"]);
                for (const Json& sv : s["simplex"])
                    CHECK(d.dot(vec(sv["w"])) <= d.dot(w) + 1e-12 * (1 + w.norm()) * d.norm());
            }
            if (t["status"] == "Separated") {
                const double dist = t["distance"];
                CHECK((vec(t["point_a"]) - vec(t["point_b"])).norm() == doctest::Approx(dist).epsilon(1e-9));
                CHECK(dist <= prevUpper * (1 + 1e-12));
                CHECK(dist >= double(t["lower_bound"]) * (1 - 1e-9));
            }
        }
    }

    TEST_CASE("EPA traces: every polytope convex, closed, contains the origin, closest distance non-decreasing") {
        for (const auto& file : scenesOf("epa")) {
            CAPTURE(file);
            const Json t = runNumeric(file);
            const bool planar = t["dimension"] == 2;
            double prevDist = -INFINITY, prevUpper = INFINITY;
            for (const Json& s : t["steps"]) {
                CAPTURE(s["iteration"].get<int>());
                std::vector<Vec3> v;
                for (const Json& p : s["vertices"]) v.push_back(vec(p));
                double scale = 0;
                for (const Vec3& p : v) scale = std::max(scale, p.norm());
                const double tol = 1e-12 * scale;  // rounding of plane tests at the polytope's scale
                const Json& faces = s["faces"];
                REQUIRE(faces.size() >= (planar ? 3u : 4u));
                double minDist = INFINITY;
                std::set<int> used;
                std::map<std::pair<int, int>, int> directed;
                for (const Json& f : faces) {
                    REQUIRE(f.size() == (planar ? 2u : 3u));
                    Vec3 n;
                    const Vec3 p0 = v[f[0].get<int>()];
                    if (planar) {
                        const Vec3 e = v[f[1].get<int>()] - p0;
                        n = Vec3(e.y(), -e.x(), 0).normalized();  // outward for a CCW polygon
                    } else {
                        n = (v[f[1].get<int>()] - p0).cross(v[f[2].get<int>()] - p0).normalized();
                    }
                    REQUIRE(n.allFinite());
                    const double d = n.dot(p0);
                    CHECK(d >= -tol);  // the origin is inside (or on) every face plane
                    minDist = std::min(minDist, d);
                    for (const Vec3& q : v) CHECK(n.dot(q) - d <= tol);  // convex: nothing in front of a face
                    for (std::size_t k = 0; k < f.size(); ++k) {
                        used.insert(f[k].get<int>());
                        directed[{f[k].get<int>(), f[(k + 1) % f.size()].get<int>()}]++;
                    }
                }
                // Closed: each directed edge once and its reverse once (3D); a single loop (2D).
                for (const auto& [e, count] : directed) {
                    CHECK(count == 1);
                    if (!planar) CHECK(directed.count({e.second, e.first}) == 1);
                }
                if (planar) CHECK(used.size() == faces.size());
                // The recorded closest face is the nearest one, at the recorded distance.
                const double dist = s["closest_distance"];
                CHECK(dist == doctest::Approx(minDist).epsilon(1e-9).scale(scale));
                CHECK(dist >= prevDist - tol);
                prevDist = dist;
                const double upper = s["upper_bound"];
                CHECK(upper <= prevUpper);
                CHECK(dist <= upper + tol);
                prevUpper = upper;
                // Removed faces: all of them see the support point; the closest face among them unless stopped.
                const Vec3 w = vec(s["support"]);
                for (const Json& k : s["removed_faces"]) {
                    const Json& f = faces[k.get<int>()];
                    const Vec3 p0 = v[f[0].get<int>()];
                    Vec3 n = planar ? Vec3((v[f[1].get<int>()] - p0).y(), -(v[f[1].get<int>()] - p0).x(), 0)
                                    : Vec3((v[f[1].get<int>()] - p0).cross(v[f[2].get<int>()] - p0));
                    CHECK(n.normalized().dot(w - p0) > 0);
                }
                if (!s["terminated"].get<bool>()) CHECK(!s["removed_faces"].empty());
            }
            if (t["status"] == "Penetrating") {
                const double depth = t["depth"];
                CHECK(depth > 0);
                CHECK((vec(t["point_a"]) - vec(t["point_b"]) - depth * vec(t["normal"])).norm() <= 1e-9 * (1 + depth));
            }
        }
    }

    TEST_CASE("EPA depth of polytope scenes matches the brute-force facet oracle") {
        int checked = 0;
        for (const auto& file : scenesOf("epa")) {
            CAPTURE(file);
            const Json scene = readJsonFile(file);
            const bool planar = scene.value("dimension", 3) == 2;
            JsonNode shapes(scene["shapes"], "$.shapes", file);
            const SceneShape a = parseSceneShape(shapes.at(0), planar), b = parseSceneShape(shapes.at(1), planar);
            if (!a.isPolytope() || !b.isPolytope()) continue;
            std::vector<Vec3> c;
            for (const Vec3& p : a.worldVertices())
                for (const Vec3& q : b.worldVertices()) c.push_back(p - q);
            const Json t = runNumeric(file);
            CHECK(double(t["depth"]) == doctest::Approx(std::max(0.0, bruteDepth(c, planar))).epsilon(1e-9).scale(1.0));
            ++checked;
        }
        CHECK(checked >= 4);
    }

    TEST_CASE("GIF writer: decodes to the frames' size and colours") {
        render::Image f1(40, 30), f2(40, 30);
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x) {
                std::uint8_t* p = f1.pixel(x, y);
                p[0] = x < 20 ? 255 : 0, p[1] = 0, p[2] = x < 20 ? 0 : 255, p[3] = 255;
                std::uint8_t* q = f2.pixel(x, y);
                q[0] = 0, q[1] = 200, q[2] = 0, q[3] = 255;
            }
        const std::string bytes = render::encodeGif({f1, f2});
        REQUIRE(bytes.size() > 20);
        CHECK(bytes.substr(0, 6) == "GIF89a");
        CHECK(render::encodeGif({f1, f2}) == bytes);  // deterministic
        struct Reader {
            const std::string* data;
            std::size_t pos = 0;
        } reader{&bytes};
        int error = 0;
        GifFileType* gif = DGifOpen(
            &reader,
            [](GifFileType* g, GifByteType* buf, int n) {
                auto* r = static_cast<Reader*>(g->UserData);
                const int k = int(std::min<std::size_t>(std::size_t(n), r->data->size() - r->pos));
                std::copy_n(r->data->data() + r->pos, k, buf);
                r->pos += std::size_t(k);
                return k;
            },
            &error);
        REQUIRE(gif != nullptr);
        REQUIRE(DGifSlurp(gif) == GIF_OK);
        CHECK(gif->SWidth == 40);
        CHECK(gif->SHeight == 30);
        REQUIRE(gif->ImageCount == 2);
        auto colorAt = [&](int image, int x, int y) {
            const SavedImage& im = gif->SavedImages[image];
            const ColorMapObject* map = im.ImageDesc.ColorMap ? im.ImageDesc.ColorMap : gif->SColorMap;
            return map->Colors[im.RasterBits[y * im.ImageDesc.Width + x]];
        };
        // Median cut on 5-bit colours: each channel within 8 of the input.
        GifColorType c = colorAt(0, 5, 5);
        CHECK(std::abs(int(c.Red) - 255) <= 8);
        CHECK(int(c.Blue) <= 8);
        c = colorAt(0, 35, 25);
        CHECK(std::abs(int(c.Blue) - 255) <= 8);
        c = colorAt(1, 10, 10);
        CHECK(std::abs(int(c.Green) - 200) <= 8);
        int e = 0;
        DGifCloseFile(gif, &e);
        CHECK_THROWS_AS(render::encodeGif({}), render::GifError);
        CHECK_THROWS_AS(render::encodeGif({f1, render::Image(10, 10)}), render::GifError);
    }

}  // TEST_SUITE
