// An engine developer's program on cdlab's installed core (find_package(cdlab), or the source tree's
// core/ by add_subdirectory): the pair query of core/query/pair.h, the same function `cdlab query`
// answers with. Three modes (tests/install/consumer_test.sh runs them):
//   consumer           GJK distance of two unit cubes 1 apart; exit 0 when it is 1
//   consumer lines     prints the query lines of kPairs (coordinates with 17 digits: exact)
//   consumer compare   reads `cdlab query`'s answers to those lines and checks that every number of
//                      every answer is the double this program computes, bit for bit
#include <cdlab/core/cdlab.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

using cdlab::QueryShape;
using cdlab::Vec3;

namespace {

struct Pair {
    const char* op;  // "penetration" or "distance"
    QueryShape a, b;
    std::string aJson, bJson;
};

std::string vec(const Vec3& v) {
    char s[96];
    std::snprintf(s, sizeof s, "[%.17g,%.17g,%.17g]", v.x(), v.y(), v.z());
    return s;
}
std::string num(double x) {
    char s[32];
    std::snprintf(s, sizeof s, "%.17g", x);
    return s;
}

std::vector<Pair> pairs() {
    std::vector<Pair> p;
    const auto sphere = [](Vec3 c, double r) {
        return std::make_pair(QueryShape::sphere(c, r), "{\"sphere\":{\"center\":" + vec(c) + ",\"radius\":" + num(r) + "}}");
    };
    const auto capsule = [](Vec3 a, Vec3 b, double r) {
        return std::make_pair(QueryShape::capsule(a, b, r),
                              "{\"capsule\":{\"a\":" + vec(a) + ",\"b\":" + vec(b) + ",\"radius\":" + num(r) + "}}");
    };
    const auto aabb = [](Vec3 lo, Vec3 hi) {
        return std::make_pair(QueryShape::aabb(lo, hi), "{\"aabb\":{\"min\":" + vec(lo) + ",\"max\":" + vec(hi) + "}}");
    };
    const auto cylinder = [](Vec3 c, double h, double r) {
        return std::make_pair(QueryShape::cylinder(c, h, r), "{\"cylinder\":{\"center\":" + vec(c) + ",\"half_height\":" + num(h) +
                                                                 ",\"radius\":" + num(r) + "}}");
    };
    const auto plane = [](Vec3 n, double d) {
        return std::make_pair(QueryShape::plane(n, d), "{\"plane\":{\"normal\":" + vec(n) + ",\"offset\":" + num(d) + "}}");
    };
    const auto add = [&](const char* op, const auto& a, const auto& b) { p.push_back({op, a.first, b.first, a.second, b.second}); };
    for (const char* op : {"penetration", "distance"}) {
        add(op, sphere(Vec3(0.1, 0.2, 0.3), 0.7), aabb(Vec3(0.5, -1, -1), Vec3(2, 1, 1)));
        add(op, capsule(Vec3(-1, 0, 0), Vec3(1, 0.3, 0), 0.25), capsule(Vec3(0.2, -1, 0.6), Vec3(0.1, 1, 0.7), 0.125));
        add(op, cylinder(Vec3(0, 0, 0), 1, 1), sphere(Vec3(1.9, 1.8, 0.1), 0.5));
        add(op, aabb(Vec3(1e9, 0, 0), Vec3(1e9 + 1, 1, 1)), aabb(Vec3(1e9 + 0.75, 0.5, 0.25), Vec3(1e9 + 2, 3, 2)));
        add(op, plane(Vec3(0, 1, 0.1), 0.5), sphere(Vec3(3, 0.8, -1), 0.5));
    }
    return p;
}

// The number after "key": in an answer line (nlohmann-json writes doubles that read back exactly).
bool field(const std::string& line, const std::string& key, int index, double& out) {
    std::size_t at = line.find("\"" + key + "\":");
    if (at == std::string::npos) return false;
    const char* s = line.c_str() + at + key.size() + 3;
    if (*s == '[') ++s;
    for (int i = 0; i < index; ++i) s = std::strchr(s, ',') + 1;
    char* end = nullptr;
    out = std::strtod(s, &end);
    return end != s;
}

int compare() {
    const std::vector<Pair> ps = pairs();
    int bad = 0;
    std::string line;
    for (const Pair& p : ps) {
        if (!std::getline(std::cin, line)) {
            std::printf("FAIL missing answer\n");
            return 1;
        }
        cdlab::PairOptions o;
        o.depth = std::strcmp(p.op, "penetration") == 0;
        const cdlab::PairResult r = cdlab::pairQuery(p.a, p.b, o);
        const bool intersect = line.find("\"intersect\":true") != std::string::npos;
        std::vector<std::pair<std::string, double>> want;
        if (r.intersect && o.depth) want = {{"depth", r.depth}};
        else want = {{"distance", r.distance}};
        const auto add = [&](const char* key, const Vec3& v) {
            for (int i = 0; i < 3; ++i) want.push_back({std::string(key) + "#" + std::to_string(i), v[i]});
        };
        if (o.depth || !r.intersect) add("point_a", r.pointA), add("point_b", r.pointB);
        if (o.depth) add("normal", r.normal);
        if (intersect != r.intersect) ++bad, std::printf("FAIL %s: intersect differs\n", line.c_str());
        for (const auto& [key, value] : want) {
            const std::size_t hash = key.find('#');
            double got = 0;
            if (!field(line, key.substr(0, hash), hash == std::string::npos ? 0 : std::stoi(key.substr(hash + 1)), got) ||
                !(got == value)) {  // the same double (a zero's sign aside: the query writes 0 for −0)
                ++bad;
                std::printf("FAIL %s: %s is %.17g here\n", line.c_str(), key.c_str(), value);
            }
        }
    }
    std::printf("compare: %zu answers of cdlab query, %s\n", ps.size(), bad ? "DIFFERENT" : "bit for bit the installed core's");
    return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 1 && std::strcmp(argv[1], "lines") == 0) {
        int id = 0;
        for (const Pair& p : pairs())
            std::printf("{\"id\":%d,\"op\":\"%s\",\"a\":%s,\"b\":%s}\n", id++, p.op, p.aJson.c_str(), p.bJson.c_str());
        return 0;
    }
    if (argc > 1 && std::strcmp(argv[1], "compare") == 0) return compare();
    std::vector<Vec3> a, b;
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        a.push_back(corner);
        b.push_back(corner + Vec3(2, 0, 0));
    }
    const cdlab::GjkResult r = cdlab::gjkDistance(cdlab::PolytopeShape(a), cdlab::PolytopeShape(b));
    std::printf("distance %.17g\n", r.distance);
    return std::abs(r.distance - 1.0) < 1e-15 ? 0 : 1;
}
