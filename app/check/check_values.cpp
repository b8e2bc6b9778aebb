#include "app/check/check_values.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "app/query/query.h"
#include "app/query/query_json.h"
#include "core/query/pair.h"

namespace cdlab::demos {

// A difference or a tolerance: three digits say enough.
std::string num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// A value: enough digits to show where two answers part.
std::string value(double x) {
    if (x == 0) x = 0;  // -0 prints as 0
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", x);
    return buf;
}

bool isVec(const Json& j) {
    return j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), [](const Json& x) { return x.is_number(); });
}

Vec3 vec(const Json& j) {
    if (!isVec(j)) throw std::invalid_argument("expected [x, y, z], got " + shortText(j.dump(-1, ' ', false, Json::error_handler_t::replace)));
    return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

double length(const Vec3& v) {
    if (v.hasNaN()) return NAN;
    const double m = v.cwiseAbs().maxCoeff();
    if (!(m > 0) || !std::isfinite(m)) return m;
    return m * (v / m).norm();
}

Vec3 unit(const Vec3& v) {
    if (v.hasNaN()) return v;
    const double m = v.cwiseAbs().maxCoeff();
    if (!(m > 0) || !std::isfinite(m)) return v;
    const Vec3 s = v / m;
    return s / s.norm();
}

const Json* member(const Json& j, const std::string& key) {
    if (!j.is_object()) return nullptr;
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
}

std::optional<double> numberMember(const Json& j, const std::string& key) {
    const Json* m = member(j, key);
    if (!m || !m->is_number()) return std::nullopt;
    return m->get<double>();
}

std::optional<Vec3> vecMember(const Json& j, const std::string& key) {
    const Json* m = member(j, key);
    if (!m || !isVec(*m)) return std::nullopt;
    return vec(*m);
}

std::string shortText(const std::string& s) {
    if (s.size() <= 60) return s;
    std::size_t cut = 57;  // never inside a UTF-8 sequence
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    return s.substr(0, cut) + "...";
}

void Size::add(const Json& j, const std::string& key) {
    if (isVec(j)) {
        const Vec3 p = vec(j);
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        largest = std::max(largest, p.cwiseAbs().maxCoeff());
    } else if (j.is_object()) {
        // Directions have no length: a ray's direction, a plane's normal and GJK's initial
        // direction may be scaled at will and must not scale the tolerance with them
        // (tests/app/check/check_test.cpp, "a line's tolerance may only tighten the check's").
        for (auto it = j.begin(); it != j.end(); ++it)
            if (it.key() != "answer" && it.key() != "trace" && it.key() != "direction" && it.key() != "normal" &&
                it.key() != "initial_direction")
                add(it.value(), it.key());
    } else if (j.is_array()) {
        for (const Json& x : j) add(x);
    } else if (j.is_number() && key == "radius") {
        radius = std::max(radius, std::abs(j.get<double>()));
    }
}

void Size::addBox(const ShapeModel& shape) {
    Vec3 l, h;
    for (int i = 0; i < 3; ++i) {
        const std::optional<double> up = shape.support(Vec3::Unit(i)), down = shape.support(-Vec3::Unit(i));
        if (!up || !down || !std::isfinite(*up) || !std::isfinite(*down)) return;
        h[i] = *up;
        l[i] = -*down;
    }
    lo = lo.cwiseMin(l);
    hi = hi.cwiseMax(h);
    largest = std::max({largest, l.cwiseAbs().maxCoeff(), h.cwiseAbs().maxCoeff()});
}

double Size::tolerance(double relative) const {
    const double extent = lo.allFinite() && hi.allFinite() ? (hi - lo).maxCoeff() : 0.0;
    const double L = std::max(extent + 2 * radius, std::numeric_limits<double>::min());
    return relative * L + 16 * std::numeric_limits<double>::epsilon() * largest;
}

ShapeModel::ShapeModel(const Json& shape) {
    try {
        if (const Json* pieces = shape.is_object() && shape.size() == 1 ? member(shape, "compound") : nullptr) {
            if (!pieces->is_array()) return;
            for (const Json& piece : *pieces) pieces_.emplace_back(piece);
            text_ = std::make_shared<const std::string>(shape.dump());
            form_ = Form::Compound;
            return;
        }
        if (const Json* m = shape.is_object() && shape.size() == 1 ? member(shape, "mesh") : nullptr) {
            const Json* vertices = member(*m, "vertices");
            if (!vertices || !vertices->is_array()) return;
            Transform pose;
            if (const std::optional<Vec3> p = vecMember(*m, "position")) pose.position = *p;
            if (const Json* q = member(*m, "rotation")) {
                if (!q->is_array() || q->size() != 4 || !std::all_of(q->begin(), q->end(), [](const Json& x) { return x.is_number(); }))
                    return;
                pose.rotation = Quat((*q)[0].get<double>(), (*q)[1].get<double>(), (*q)[2].get<double>(), (*q)[3].get<double>()).normalized();
            }
            meshVertices_.reserve(vertices->size());
            for (const Json& v : *vertices) meshVertices_.push_back(pose.apply(vec(v)));
            if (meshVertices_.empty()) return;
            text_ = std::make_shared<const std::string>(shape.dump());
            form_ = Form::Mesh;
            return;
        }
        shape_ = parseQueryShape(JsonNode(shape, "$", "check"));
        form_ = Form::Shape;
    } catch (const std::exception&) {
        form_ = Form::None;
        pieces_.clear();
        meshVertices_.clear();
    }
}

std::optional<double> ShapeModel::support(const Vec3& n) const {
    switch (form_) {
        case Form::None: return std::nullopt;
        case Form::Compound: {
            std::optional<double> best;
            for (const ShapeModel& piece : pieces_) {
                const std::optional<double> h = piece.support(n);
                if (!h) return std::nullopt;
                best = best ? std::max(*best, *h) : *h;
            }
            return best;
        }
        case Form::Mesh: {
            double best = -INFINITY;
            for (const Vec3& v : meshVertices_) best = std::max(best, v.dot(n));
            return best;
        }
        case Form::Shape:
            if (!shape_.bounded()) return std::nullopt;
            return n.dot(supportPoint(shape_, n));
    }
    return std::nullopt;
}

const std::vector<Vec3>* ShapeModel::vertices() const {
    if (form_ == Form::Mesh) return &meshVertices_;
    if (form_ != Form::Shape || !shape_.bounded() || shape_.isCurved() || shape_.radius != 0) return nullptr;
    return &shape_.vertices;
}

std::optional<double> ShapeModel::distanceTo(const Vec3& p) const {
    try {
        if (form_ == Form::Shape) {
            const PairResult a = pairQuery(QueryShape::point(p), shape_, PairOptions{.depth = false});
            if (a.status != PairStatus::Ok) return std::nullopt;
            return a.intersect ? 0.0 : a.distance;
        }
        if (!text_) return std::nullopt;
        // A compound or a mesh: the query's own distance op on the shape's JSON text.
        const Json a = answerQuery("{\"op\":\"distance\",\"a\":{\"point\":" + vecJson(p).dump() + "},\"b\":" + *text_ + "}");
        return numberMember(a, "distance");
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

std::optional<Vec3> ShapeModel::closestPointTo(const Vec3& p) const {
    if (form_ != Form::Shape) return std::nullopt;
    try {
        const PairResult a = pairQuery(QueryShape::point(p), shape_, PairOptions{.depth = false});
        if (a.status != PairStatus::Ok) return std::nullopt;
        return a.intersect ? p : a.pointB;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace cdlab::demos
