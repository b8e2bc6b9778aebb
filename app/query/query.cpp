#include "app/query/query.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "core/closest/closest_point.h"
#include "app/query/query_cast.h"
#include "app/query/query_contact.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_ops.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

namespace {

constexpr const char* kSource = "query";

// Ericson's tests of one closest-point query as JSON: each region tried, its condition, its terms
// (value in double, exact sign) and whether it was accepted.
template <class Test>
Json regionTestsJson(const std::vector<Test>& tests) {
    Json out = Json::array();
    for (const auto& test : tests) {
        Json terms = Json::array();
        for (int i = 0; i < test.termCount; ++i) {
            const PredicateSign& term = test.terms[std::size_t(i)];
            terms.push_back({{"name", term.name},
                             {"formula", term.formula},
                             {"value", cleanZero(term.value)},
                             {"sign", term.sign},
                             {"exact_fallback", term.exactFallback}});
        }
        out.push_back({{"region", nameOf(test.candidate)},
                       {"condition", test.condition},
                       {"terms", terms},
                       {"accepted", test.accepted}});
    }
    return out;
}

Json closestPointTriangle(ObjectReader& r) {
    Vec3 p = r.get("point").asVec3();
    JsonNode t = r.get("triangle");
    if (t.size() != 3) t.fail("expected [a, b, c]");
    std::vector<Vec3> v = t.asVec3List();
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    // Core decides the region exactly and rounds the point once for every finite input
    // (core/base/exact_predicates.h); scaling the query by a power of two would flush coordinates of
    // 1e-300 beside 1e300 to zero.
    ClosestPointTrace trace;
    const ClosestPointOnTriangleResult res =
        closestPointOnTriangle(p, Triangle{v[0], v[1], v[2]}, wantTrace ? &trace : nullptr);
    Json out = {{"point", vecJson(res.point)}, {"region", nameOf(res.region)}};
    // Ericson's region tests in his order (§5.1.5), each term with its value in plain double
    // arithmetic and the sign of its exact value (the one the decision used).
    if (wantTrace) out["trace"] = {{"algorithm", "ericson_regions"}, {"tests", regionTestsJson(trace.tests)}};
    return out;
}

// The point's closest point of the solid tetrahedron and the Voronoi region holding it (Ericson
// §5.1.6; core decides every region exactly): "ABCD" when the point is inside.
Json closestPointTetrahedron(ObjectReader& r) {
    Vec3 p = r.get("point").asVec3();
    JsonNode t = r.get("tetrahedron");
    if (t.size() != 4) t.fail("expected [a, b, c, d]");
    std::vector<Vec3> v = t.asVec3List();
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    TetrahedronTrace trace;
    const ClosestPointOnTetrahedronResult res =
        closestPointOnTetrahedron(p, Tetrahedron{v[0], v[1], v[2], v[3]}, wantTrace ? &trace : nullptr);
    Json out = {{"point", vecJson(res.point)}, {"region", nameOf(res.region)}};
    if (wantTrace) out["trace"] = {{"algorithm", "ericson_regions"}, {"tests", regionTestsJson(trace.tests)}};
    return out;
}

// Reads a line's top-level "id" while the parser streams through it, building no tree: the parser
// keeps one bit per open bracket (60 MB of "[[[..." inside an object: ~8 MB, where its DOM took
// 2.2 GB), and a line that is not an object stops at its first bracket. An id that is itself an
// array or object is copied only up to kMaxIdDepth levels and kMaxIdValues values (past them the
// line has no usable id). As nlohmann's DOM does, the last of duplicate "id" keys wins. Test:
// "hostile query" / "a refused nested line costs its own size, and the lines after it are answered".
class TopLevelIdReader {
public:
    using number_integer_t = Json::number_integer_t;
    using number_unsigned_t = Json::number_unsigned_t;
    using number_float_t = Json::number_float_t;
    using string_t = Json::string_t;
    using binary_t = Json::binary_t;

    const Json& id() const { return id_; }
    /// No id container left open: the id read (or null) is whole, even where the line breaks off later.
    bool idComplete() const { return stack_.empty(); }

    bool null() { return value(Json(nullptr)); }
    bool boolean(bool v) { return value(Json(v)); }
    bool number_integer(number_integer_t v) { return value(Json(v)); }
    bool number_unsigned(number_unsigned_t v) { return value(Json(v)); }
    bool number_float(number_float_t v, const string_t&) { return value(Json(v)); }
    bool string(string_t& v) { return value(Json(v)); }
    bool binary(binary_t&) { return value(Json(nullptr)); }
    bool start_object(std::size_t) { return open(Json::object()); }
    bool start_array(std::size_t) { return open(Json::array()); }
    bool key(string_t& k) {
        if (depth_ == 1) capturing_ = k == "id";
        else if (!stack_.empty()) key_ = k;
        return true;
    }
    bool end_object() { return close(); }
    bool end_array() { return close(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) { return false; }

private:
    static constexpr std::size_t kMaxIdDepth = 16;
    static constexpr std::size_t kMaxIdValues = 1024;

    // Where a value goes: the id being copied (inside it: its innermost open container).
    bool value(Json v) {
        if (!stack_.empty()) return add(std::move(v)) != nullptr;
        if (depth_ == 1 && capturing_) id_ = std::move(v), capturing_ = false;
        return true;
    }
    bool open(Json container) {
        ++depth_;
        if (depth_ == 1) return container.is_object();  // a line that is not an object has no id
        if (stack_.empty() && !(depth_ == 2 && capturing_)) return true;
        if (stack_.size() >= kMaxIdDepth) return false;
        Json* slot = stack_.empty() ? &(id_ = std::move(container)) : add(std::move(container));
        if (!slot) return false;
        stack_.push_back(slot);
        return true;
    }
    bool close() {
        --depth_;
        if (!stack_.empty()) {
            stack_.pop_back();
            if (stack_.empty()) capturing_ = false;
        }
        return true;
    }
    // Appends to the innermost open container of the id; null past kMaxIdValues.
    Json* add(Json v) {
        if (++values_ > kMaxIdValues) return nullptr;
        Json& parent = *stack_.back();
        if (parent.is_array()) {
            parent.push_back(std::move(v));
            return &parent.back();
        }
        Json& slot = parent[key_];
        slot = std::move(v);
        return &slot;
    }

    Json id_ = nullptr;
    std::size_t depth_ = 0;
    bool capturing_ = false;    // the next value at depth 1 is the id
    std::vector<Json*> stack_;  // the open containers of the id being copied, outermost first
    std::string key_;
    std::size_t values_ = 0;
};

// The id of a line the strict reader refused (a duplicate key, say) when the whole line is JSON, so
// that its error answer can still be matched to the query; null otherwise. Never throws.
Json lenientId(const std::string& line, const Json& id) noexcept {
    try {
        if (!id.is_null()) return id;
        // An id read before the line breaks off (unclosed, or nested too deep further on) is kept.
        TopLevelIdReader reader;
        if (Json::sax_parse(line, &reader) || reader.idComplete()) return reader.id();
    } catch (...) {  // out of memory: the answer goes without its id
    }
    return nullptr;
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
            {"closest_point_triangle", "closest_point_tetrahedron", "intersect", "distance", "penetration", "contact", "mass_properties", "raycast",
             "time_of_impact"});
        Json result;
        if (op == "closest_point_triangle") result = closestPointTriangle(r);
        else if (op == "closest_point_tetrahedron") result = closestPointTetrahedron(r);
        else if (op == "contact" || op == "mass_properties") result = answerContactQuery(op, r);
        else if (op == "raycast" || op == "time_of_impact") result = answerCastQuery(op, r);
        else result = answerShapeQuery(op, r);
        answer["id"] = id;
        for (auto it = result.begin(); it != result.end(); ++it) answer[it.key()] = it.value();
    } catch (const InputError& e) {
        answer = {{"id", lenientId(line, id)}, {"error", e.what()}};
    } catch (const std::bad_alloc&) {
        answer = {{"id", lenientId(line, id)}, {"error", "query: not enough memory to answer this line"}};
    } catch (const std::exception& e) {
        answer = {{"id", lenientId(line, id)}, {"error", std::string("internal error: ") + e.what()}};
    }
    return answer;
}

Json answerQuery(const std::string& line, std::size_t lineNumber) {
    Json answer = answerQuery(line);
    if (answer.contains("error")) {
        // "query: $.a: ..." -> "query: line 7: $.a: ...": the answer names the line it answers.
        std::string text = answer["error"].get<std::string>();
        const std::string prefix = "query: ";
        const std::string where = "line " + std::to_string(lineNumber) + ": ";
        if (text.rfind(prefix, 0) == 0) text.insert(prefix.size(), where);
        else text = prefix + where + text;
        answer["error"] = text;
    }
    return answer;
}

namespace {

enum class LineRead { Line, TooLong, End };

// Reads one line (the '\n' dropped) keeping at most `limit` bytes; a longer line is read to its
// end and reported, so the next line is still answered.
LineRead readLine(std::streambuf& in, std::string& line, std::size_t limit) {
    line.clear();
    bool any = false, tooLong = false;
    for (;;) {
        const int c = in.sbumpc();
        if (c == std::char_traits<char>::eof())
            return !any ? LineRead::End : tooLong ? LineRead::TooLong : LineRead::Line;
        any = true;
        if (c == '\n') return tooLong ? LineRead::TooLong : LineRead::Line;
        if (line.size() < limit) line.push_back(char(c));
        else tooLong = true;
    }
}

// One answer line: "id" first, then the answer's keys; invalid UTF-8 in echoed strings is replaced.
void writeAnswer(std::ostream& out, Json a) {
    const auto dump = [](const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); };
    Json id = a["id"];
    a.erase("id");
    std::string body = dump(a);
    out << "{\"id\":" << dump(id);
    if (body.size() > 2) out << ',' << std::string_view(body).substr(1) << '\n';
    else out << "}\n";
}

}  // namespace

int runQueries(std::istream& in, std::ostream& out) {
    std::string line;
    bool failed = false;
    std::size_t lineNumber = 0;
    for (LineRead read; (read = readLine(*in.rdbuf(), line, kMaxQueryLineBytes)) != LineRead::End && out;) {
        ++lineNumber;
        if (read == LineRead::TooLong) {
            failed = true;
            writeAnswer(out, {{"id", nullptr},
                              {"error", "query: line " + std::to_string(lineNumber) + ": longer than the limit of " +
                                            std::to_string(kMaxQueryLineBytes >> 20) + " MiB for one query line"}});
            continue;
        }
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        // Whatever one line throws (std::bad_alloc building its answer), it gets an error answer and
        // the next line is still read.
        try {
            Json a = answerQuery(line, lineNumber);
            if (a.contains("error")) failed = true;
            writeAnswer(out, std::move(a));
        } catch (const std::exception& e) {
            failed = true;
            const bool memory = dynamic_cast<const std::bad_alloc*>(&e) != nullptr;
            writeAnswer(out, {{"id", nullptr},
                              {"error", "query: line " + std::to_string(lineNumber) + ": " +
                                            (memory ? std::string("not enough memory to answer this line")
                                                    : std::string("internal error: ") + e.what())}});
        }
    }
    // Answers that cannot be written (a full disk, a closed pipe) are an output error, not success.
    errno = 0;
    out.flush();
    if (!out) {
        std::cerr << "cdlab query: cannot write the answers to standard output"
                  << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
        return 2;
    }
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
