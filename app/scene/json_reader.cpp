#include "app/scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <vector>

#include "render/image.h"

namespace cdlab::demos {

namespace {

// The length of the UTF-8 sequence starting at s[i] and its code point, or 0 when the bytes there
// are not a valid (shortest-form, non-surrogate) sequence.
std::size_t utf8Sequence(const std::string& s, std::size_t i, std::uint32_t& code) {
    const auto byte = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(s[k])); };
    const std::uint32_t b0 = byte(i);
    std::size_t n = 0;
    if (b0 >= 0xc2 && b0 <= 0xdf) n = 2, code = b0 & 0x1f;
    else if (b0 >= 0xe0 && b0 <= 0xef) n = 3, code = b0 & 0x0f;
    else if (b0 >= 0xf0 && b0 <= 0xf4) n = 4, code = b0 & 0x07;
    else return 0;
    if (i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        const std::uint32_t b = byte(i + k);
        if ((b & 0xc0) != 0x80) return 0;
        code = (code << 6) | (b & 0x3f);
    }
    const std::uint32_t least = n == 2 ? 0x80 : n == 3 ? 0x800 : 0x10000;
    if (code < least || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
    return n;
}

}  // namespace

namespace {

std::string withoutNul(const std::string& text) {
    if (text.find('\0') == std::string::npos) return text;
    std::string out;
    for (const char c : text) c == '\0' ? out += "\\x00" : out += c;
    return out;
}

}  // namespace

InputError::InputError(const std::string& what) : std::runtime_error(withoutNul(what)) {}

std::string printable(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    char buf[16];
    for (std::size_t i = 0; i < s.size();) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            if (c == '\n') out += "\\n";
            else if (c == '\t') out += "\\t";
            else if (c == '\r') out += "\\r";
            else if (c < 0x20 || c == 0x7f) {
                std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(c));
                out += buf;
            } else out += char(c);
            ++i;
            continue;
        }
        std::uint32_t code = 0;
        const std::size_t n = utf8Sequence(s, i, code);
        if (n == 0) {  // not UTF-8: the byte, escaped
            std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(c));
            out += buf;
            ++i;
            continue;
        }
        // C1 controls, line and paragraph separators, bidirectional embeddings, overrides and isolates.
        const bool control = (code >= 0x80 && code <= 0x9f) || code == 0x2028 || code == 0x2029 ||
                             (code >= 0x202a && code <= 0x202e) || (code >= 0x2066 && code <= 0x2069) ||
                             code == 0x200e || code == 0x200f || code == 0x061c;
        if (control) {
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(code));
            out += buf;
        } else out.append(s, i, n);
        i += n;
    }
    return out;
}

namespace {

// Nesting deeper than this is refused: no scene or query needs more than ~8 levels, and a bound
// keeps hostile input ("[[[[..." a million deep) from costing memory and time downstream.
constexpr int kMaxJsonDepth = 64;

[[noreturn]] void failAtByte(const std::string& source, std::size_t index, const std::string& what) {
    throw InputError(source + ": byte " + std::to_string(index + 1) + ": " + what);
}

// Runs before the DOM parser, keeping only a depth counter: nlohmann builds the whole tree before
// anyone could look at its depth (a 60 MB "[[[[..." line peaked at 2.24 GB, an unclosed one ended
// in bad_alloc), and its lexer takes a NUL byte for the end of the input, silently dropping the
// rest of the text. Stops at the first NUL byte, at the first bracket that opens level 65, or
// where the containers or the values (a container, or a comma: one more member or element) pass
// kMaxJsonContainers or kMaxJsonValues. Brackets and commas inside strings do not count; a
// malformed text is left to the parser's own message.
void checkDepthAndNulBytes(const std::string& text, const std::string& source) {
    int depth = 0;
    std::size_t containers = 0, values = 0;
    bool inString = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\0') failAtByte(source, i, "NUL byte (U+0000) is not allowed");
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth)
                failAtByte(source, i, "nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels");
            if (++containers > kMaxJsonContainers)
                failAtByte(source, i, "more than " + std::to_string(kMaxJsonContainers) +
                                          " arrays and objects, the limit for one text");
            ++values;
        } else if ((c == '}' || c == ']') && depth > 0) {
            --depth;
        } else if (c == ',') {
            ++values;
        }
        if (values > kMaxJsonValues)
            failAtByte(source, i, "more than " + std::to_string(kMaxJsonValues) + " values, the limit for one text");
    }
}

// Scans text that already parsed as JSON (so at most kMaxJsonDepth deep) for what the DOM parser
// silently accepts: duplicate keys in one object (nlohmann keeps the last one — a typo'd duplicate
// would hide the first value). Reports the byte position like a syntax error.
void checkDuplicateKeys(const std::string& text, const std::string& source) {
    struct Level {
        bool object;
        bool expectKey;
        std::set<std::string> keys;
    };
    std::vector<Level> stack;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"') {
            const std::size_t start = i;
            bool escaped = false;
            for (++i; i < text.size(); ++i) {
                if (text[i] == '\\') escaped = true, ++i;
                else if (text[i] == '"') break;
            }
            if (!stack.empty() && stack.back().object && stack.back().expectKey) {
                std::string raw = text.substr(start, i - start + 1);
                // Keys with escapes are compared decoded ("a" and "\u0061" are the same key).
                std::string key = escaped ? Json::parse(raw).get<std::string>() : raw.substr(1, raw.size() - 2);
                if (!stack.back().keys.insert(key).second)
                    failAtByte(source, start,
                               "duplicate key " + Json(key).dump(-1, ' ', false, Json::error_handler_t::replace) +
                                   " in one object");
                stack.back().expectKey = false;
            }
        } else if (c == '{' || c == '[') {
            stack.push_back({c == '{', c == '{', {}});
        } else if (c == '}' || c == ']') {
            if (!stack.empty()) stack.pop_back();
        } else if (c == ',' && !stack.empty() && stack.back().object) {
            stack.back().expectKey = true;
        }
    }
}

}  // namespace

Json parseJson(const std::string& text, const std::string& source) {
    checkDepthAndNulBytes(text, source);
    try {
        Json json = Json::parse(text);
        checkDuplicateKeys(text, source);
        return json;
    } catch (const Json::parse_error& e) {
        // e.what() is "[json.exception.parse_error.101] parse error at line 1, column 5: ..."
        std::string what = e.what();
        auto colon = what.find("] ");
        if (colon != std::string::npos) what = what.substr(colon + 2);
        throw InputError(source + ": byte " + std::to_string(e.byte) + ": " + what);
    } catch (const Json::exception& e) {
        // e.g. out_of_range.406 "number overflow parsing '1e400'": a number no double holds.
        std::string what = e.what();
        auto colon = what.find("] ");
        if (colon != std::string::npos) what = what.substr(colon + 2);
        throw InputError(source + ": " + what);
    }
}

std::string readJsonText(const std::string& path) {
    std::string bytes, problem;
    if (!render::readFileBounded(path, kMaxJsonFileBytes, "a JSON file", bytes, problem))
        throw InputError(path + ": " + problem);
    return bytes;
}

Json readJsonFile(const std::string& path) { return parseJson(readJsonText(path), path); }

Json vec3Json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

void JsonNode::fail(const std::string& what) const { throw InputError(source_ + ": " + path_ + ": " + what); }

std::string JsonNode::describe(const Json& v) {
    switch (v.type()) {
        case Json::value_t::null: return "null";
        case Json::value_t::boolean: return v.get<bool>() ? "true" : "false";
        case Json::value_t::string: {
            std::string s = v.get<std::string>();
            if (s.size() > 24) s = s.substr(0, 24) + "...";
            return "a string " + Json(s).dump(-1, ' ', true, Json::error_handler_t::replace);
        }
        case Json::value_t::array: return "an array of " + std::to_string(v.size());
        case Json::value_t::object: return "an object";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float: return "the number " + v.dump();
        default: return "an unsupported value";
    }
}

double JsonNode::asNumber() const {
    if (!value_->is_number()) fail("expected a number, got " + describe(*value_));
    double x = value_->get<double>();
    if (!std::isfinite(x)) fail("number is not finite");
    return x;
}

double JsonNode::asPositive() const {
    double x = asNumber();
    if (!(x > 0)) fail("expected a positive number, got " + value_->dump());
    return x;
}

double JsonNode::asNonNegative() const {
    double x = asNumber();
    if (!(x >= 0)) fail("expected a non-negative number, got " + value_->dump());
    return x;
}

int JsonNode::asInt(int lo, int hi) const {
    double x = asNumber();
    if (x != std::floor(x) || x < lo || x > hi)
        fail("expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + value_->dump());
    return int(x);
}

bool JsonNode::asBool() const {
    if (!value_->is_boolean()) fail("expected true or false, got " + describe(*value_));
    return value_->get<bool>();
}

std::string JsonNode::asString() const {
    if (!value_->is_string()) fail("expected a string, got " + describe(*value_));
    return value_->get<std::string>();
}

std::string JsonNode::asEnum(const std::vector<std::string>& allowed) const {
    std::string s = asString();
    for (const auto& a : allowed)
        if (a == s) return s;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    fail("unknown value \"" + s + "\" (expected one of " + list + ")");
}

std::size_t JsonNode::size() const {
    if (!value_->is_array()) fail("expected an array, got " + describe(*value_));
    return value_->size();
}

JsonNode JsonNode::at(std::size_t index) const {
    if (index >= size()) fail("expected at least " + std::to_string(index + 1) + " elements");
    return JsonNode((*value_)[index], path_ + "[" + std::to_string(index) + "]", source_);
}

std::vector<JsonNode> JsonNode::items() const {
    std::vector<JsonNode> out;
    std::size_t n = size();
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]", source_);
    return out;
}

Vec3 JsonNode::asVec3() const {
    if (!value_->is_array() || value_->size() != 3) fail("expected [x, y, z], got " + describe(*value_));
    return Vec3(at(0).asNumber(), at(1).asNumber(), at(2).asNumber());
}

Quat JsonNode::asQuat() const {
    if (!value_->is_array() || value_->size() != 4)
        fail("expected a quaternion [w, x, y, z], got " + describe(*value_));
    Quat q(at(0).asNumber(), at(1).asNumber(), at(2).asNumber(), at(3).asNumber());
    // Non-unit quaternions are normalised (documented); a zero or non-finite one has no rotation.
    // Invariant: every finite non-zero quaternion is accepted. Its largest coefficient is first
    // brought into [0.5, 1) by a power of two (exact, and the same rotation), as normals and ray
    // directions are, so that the squared norm neither underflows ([1e-200, 1e-200, 0, 0]) nor
    // overflows ([1e200, ...]); for coefficients in the normal range the normalised result is the one
    // the unscaled division gives
    // (tests/app/query/hostile_query_test.cpp, "quaternions: ...").
    const double largest = q.coeffs().cwiseAbs().maxCoeff();
    if (!(largest > 0.0) || !std::isfinite(largest)) fail("quaternion has zero (or non-finite) length");
    int e = 0;
    std::frexp(largest, &e);
    q.coeffs() = q.coeffs().unaryExpr([e](double x) { return std::ldexp(x, -e); });
    q.coeffs() /= q.norm();
    return q;
}

std::vector<Vec3> JsonNode::asVec3List(std::size_t minCount) const {
    std::vector<Vec3> out;
    for (const JsonNode& item : items()) out.push_back(item.asVec3());
    if (out.size() < minCount)
        fail("expected at least " + std::to_string(minCount) + " points, got " + std::to_string(out.size()));
    return out;
}

ObjectReader::ObjectReader(const JsonNode& node) : node_(node) {
    if (!node.isObject()) node.fail("expected an object, got " + JsonNode::describe(node.raw()));
}

bool ObjectReader::has(const std::string& key) const {
    auto it = node_.raw().find(key);
    return it != node_.raw().end() && !it->is_null();
}

static std::string childPath(const std::string& parent, const std::string& key) {
    bool plain =
        !key.empty() &&
        key.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") == std::string::npos;
    return plain ? parent + "." + key : parent + "[" + Json(key).dump() + "]";
}

namespace {

// Keys compared for a "did you mean": at most this long (longer ones are no typo of a scene key)
// and at most this many of an object's keys looked at (a hostile object may hold millions).
constexpr std::size_t kSuggestKeyLength = 64;
constexpr std::size_t kSuggestKeys = 256;

// Levenshtein distance of two short strings (both at most kSuggestKeyLength bytes).
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The candidate nearest `word` within a typo's distance (a third of its length, at least 1, at
// most 3), or "" (test: tests/app/scene/scene_test.cpp, "did you mean").
template <class Range>
std::string nearestKey(const std::string& word, const Range& candidates) {
    if (word.size() > kSuggestKeyLength) return "";
    const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 3);
    std::string best;
    std::size_t bestDistance = allowed + 1, looked = 0;
    for (const std::string& c : candidates) {
        if (++looked > kSuggestKeys) break;
        if (c == word || c.size() > kSuggestKeyLength) continue;
        const std::size_t d = editDistance(word, c);
        if (d < bestDistance) bestDistance = d, best = c;
    }
    return best;
}

}  // namespace

JsonNode ObjectReader::get(const std::string& key) {
    seen_.insert(key);
    auto it = node_.raw().find(key);
    if (it == node_.raw().end()) {
        // A misspelt key beside it: name it (the user's "half_extent" for "half_extents").
        std::vector<std::string> present;
        for (auto m = node_.raw().begin(); m != node_.raw().end() && present.size() < kSuggestKeys; ++m)
            if (!seen_.count(m.key())) present.push_back(m.key());
        const std::string near = nearestKey(key, present);
        node_.fail("missing required key '" + key + "'" + (near.empty() ? "" : " ('" + near + "' is there: a typo?)"));
    }
    return JsonNode(*it, childPath(node_.path(), key), node_.source());
}

std::optional<JsonNode> ObjectReader::find(const std::string& key) {
    seen_.insert(key);
    auto it = node_.raw().find(key);
    if (it == node_.raw().end() || it->is_null()) return std::nullopt;
    return JsonNode(*it, childPath(node_.path(), key), node_.source());
}

double ObjectReader::numberOr(const std::string& key, double fallback) {
    auto n = find(key);
    return n ? n->asNumber() : fallback;
}

bool ObjectReader::boolOr(const std::string& key, bool fallback) {
    auto n = find(key);
    return n ? n->asBool() : fallback;
}

std::string ObjectReader::stringOr(const std::string& key, const std::string& fallback) {
    auto n = find(key);
    return n ? n->asString() : fallback;
}

void ObjectReader::finish() const {
    for (auto it = node_.raw().begin(); it != node_.raw().end(); ++it) {
        if (seen_.count(it.key())) continue;
        std::string known;
        for (const auto& k : seen_) known += (known.empty() ? "" : ", ") + k;
        const std::string near = nearestKey(it.key(), seen_);
        node_.fail("unknown key '" + it.key() + "'" + (near.empty() ? "" : ", did you mean '" + near + "'?") +
                   (known.empty() ? "" : " (known: " + known + ")"));
    }
}

}  // namespace cdlab::demos
