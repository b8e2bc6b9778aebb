#include "demos/lib/query.h"

#include <iostream>
#include <string>

#include "core/closest_point.h"
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
    ClosestPointOnTriangleResult res = closestPointOnTriangle(p, Triangle{v[0], v[1], v[2]});
    return {{"point", vecJson(res.point)}, {"region", toString(res.region)}};
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
            {"closest_point_triangle", "intersect", "distance", "penetration"});
        Json result;
        if (op == "closest_point_triangle") result = closestPointTriangle(r);
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
        out << "{\"id\":" << dump(id) << (body.size() > 2 ? "," + body.substr(1) : std::string("}")) << '\n';
    }
    out.flush();
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
