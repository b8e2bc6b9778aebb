#include "demos/check/check_values.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "demos/query/query.h"
#include "demos/query/query_json.h"
#include "demos/query/query_shapes.h"

namespace cdlab::demos {

// A difference or a tolerance: three digits say enough.
std::string num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// A value: enough digits to show where two answers part.
std::string value(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", x);
    return buf;
}

bool isVec(const Json& j) {
    return j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), [](const Json& x) { return x.is_number(); });
}

Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

void Size::add(const Json& j, const std::string& key) {
    if (isVec(j)) {
        const Vec3 p = vec(j);
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        largest = std::max(largest, p.cwiseAbs().maxCoeff());
    } else if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it)
            if (it.key() != "answer" && it.key() != "trace") add(it.value(), it.key());
    } else if (j.is_array()) {
        for (const Json& x : j) add(x);
    } else if (j.is_number() && key == "radius") {
        radius = std::max(radius, std::abs(j.get<double>()));
    }
}

double Size::tolerance(double relative) const {
    const double extent = lo.allFinite() && hi.allFinite() ? (hi - lo).maxCoeff() : 0.0;
    const double L = std::max(extent + 2 * radius, std::numeric_limits<double>::min());
    return relative * L + 16 * std::numeric_limits<double>::epsilon() * largest;
}

// Support value h_S(n) = max over S of x·n for the query's shapes (a compound: its pieces; a mesh:
// its vertices); nothing for unbounded shapes or what cannot be read.
std::optional<double> support(const Json& shape, const Vec3& n) {
    try {
        if (shape.is_object() && shape.size() == 1 && shape.contains("compound")) {
            std::optional<double> best;
            for (const Json& piece : shape["compound"]) {
                const std::optional<double> h = support(piece, n);
                if (!h) return std::nullopt;
                best = best ? std::max(*best, *h) : *h;
            }
            return best;
        }
        if (shape.is_object() && shape.size() == 1 && shape.contains("mesh")) {
            const Json& m = shape["mesh"];
            Transform pose;
            if (m.contains("position")) pose.position = vec(m["position"]);
            if (m.contains("rotation")) {
                const Json& q = m["rotation"];
                pose.rotation = Quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>()).normalized();
            }
            double best = -INFINITY;
            for (const Json& v : m["vertices"]) best = std::max(best, pose.apply(vec(v)).dot(n));
            return best;
        }
        const QueryShape s = parseQueryShape(JsonNode(shape, "$", "check"));
        if (!s.bounded()) return std::nullopt;
        return n.dot(supportPoint(s, n));
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

// Distance from a point to a query shape, by cdlab's own distance op (0 inside).
std::optional<double> distanceTo(const Vec3& p, const Json& shape) {
    const Json a = answerQuery(Json{{"op", "distance"}, {"a", {{"point", vecJson(p)}}}, {"b", shape}}.dump());
    if (a.contains("error") || !a.contains("distance")) return std::nullopt;
    return a["distance"].get<double>();
}

}  // namespace cdlab::demos
