#include "demos/lib/query.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <string_view>

#include "core/closest_point.h"
#include "demos/lib/query_contact.h"
#include "demos/lib/query_ops.h"
#include "demos/lib/query_shapes.h"

namespace cdlab::demos {

namespace {

constexpr const char* kSource = "query";

Json vecJson(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json closestPointTriangle(ObjectReader& r) {
    Vec3 p = r.get("point").asVec3();
    JsonNode t = r.get("triangle");
    if (t.size() != 3) t.fail("expected [a, b, c]");
    std::vector<Vec3> v = t.asVec3List();
    r.finish();
    // Scale by a power of two (exact) so the largest coordinate is in [0.5, 1): the exact region
    // predicates hold for magnitudes in [2^-200, 2^240], and this brings 1e-300 or 1e300 inputs there.
    double m = std::max({p.cwiseAbs().maxCoeff(), v[0].cwiseAbs().maxCoeff(), v[1].cwiseAbs().maxCoeff(),
                         v[2].cwiseAbs().maxCoeff()});
    int e = 0;
    if (m > 0) std::frexp(m, &e);
    const auto scale = [](const Vec3& x, int k) { return Vec3(x.unaryExpr([k](double c) { return std::ldexp(c, k); })); };
    ClosestPointOnTriangleResult res =
        closestPointOnTriangle(scale(p, -e), Triangle{scale(v[0], -e), scale(v[1], -e), scale(v[2], -e)});
    return {{"point", vecJson(scale(res.point, e))}, {"region", toString(res.region)}};
}

}  // namespace

Json answerQuery(const std::string& line) {
    Json answer = Json::object();
    Json id = nullptr;
    try {
        Json q = parseJson(line, kSource);
        JsonNode root(q, "$", kSource);
        if (q.is_object() && q.contains("id")) id = q["id"];
        ObjectReader r(root);
        r.ignore("id");
        std::string op = r.get("op").asEnum(
            {"closest_point_triangle", "intersect", "distance", "penetration", "contact", "mass_properties"});
        Json result;
        if (op == "closest_point_triangle") result = closestPointTriangle(r);
        else if (op == "contact" || op == "mass_properties") result = answerContactQuery(op, r);
        else result = answerShapeQuery(op, r);
        answer["id"] = id;
        for (auto it = result.begin(); it != result.end(); ++it) answer[it.key()] = it.value();
    } catch (const InputError& e) {
        answer = {{"id", id}, {"error", e.what()}};
    } catch (const std::exception& e) {
        answer = {{"id", id}, {"error", std::string("internal error: ") + e.what()}};
    }
    return answer;
}

int runQueries(std::istream& in, std::ostream& out) {
    std::string line;
    bool failed = false;
    while (std::getline(in, line)) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        Json a = answerQuery(line);
        if (a.contains("error")) failed = true;
        // "id" first, then the answer's keys; invalid UTF-8 in echoed strings is replaced.
        const auto dump = [](const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); };
        Json id = a["id"];
        a.erase("id");
        std::string body = dump(a);
        out << "{\"id\":" << dump(id);
        if (body.size() > 2) out << ',' << std::string_view(body).substr(1) << '\n';
        else out << "}\n";
    }
    out.flush();
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
