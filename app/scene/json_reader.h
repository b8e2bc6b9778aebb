// Strict JSON reading for scene files and queries: every error names the file, the JSON path
// ($.queries[3][1]) or byte position, and what is wrong; unknown keys are errors (no silent typos).
#pragma once

#include <cstddef>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/base/types.h"

namespace cdlab::demos {

using Json = nlohmann::json;

/// One-line input error: "<source>: <where>: <what>". Exit status 2 where it reaches main().
/// A message that names what in the input is wrong. NUL bytes from the input ("\u0000" in a key)
/// are written \x00 when it is made: what() is a C string, and everything after a raw NUL would be
/// lost (hostile_query_test "an escaped NUL does not cut the error message").
struct InputError : std::runtime_error {
    explicit InputError(const std::string& what);
    explicit InputError(const char* what) : InputError(std::string(what)) {}
};

/// `text` safe to print on a terminal, as one line: C0 controls and DEL (\n, \t, \r, \x1b ...),
/// C1 controls, line / paragraph separators and bidirectional overrides (\u0085, \u2028, \u202e
/// ...) and the bytes of invalid UTF-8 (\xff ...) are escaped; everything else, "é" included, is
/// kept. Every line cdlab prints that holds text from a file goes through it (hostile_harness_test
/// "control characters from files are escaped", check_test "escaped").
std::string printable(const std::string& s);

/// Largest JSON file read (scene, golden trace, figures manifest): the largest golden scene is a
/// few KB and a 10^5-vertex polytope ~6 MB, so 16 MiB leaves room and bounds what a file costs.
constexpr std::size_t kMaxJsonFileBytes = std::size_t(16) << 20;

/// The most arrays and objects, and the most values of any kind, one text may hold: each costs
/// its node in the tree (16 bytes, and ~64 more for a container), so a 64 MiB query line of "{},"
/// costs ~0.6 GB, not 3.6 GB; two 10^6-vertex polytopes (8·10^6 values) still read.
constexpr std::size_t kMaxJsonContainers = 4'000'000;
constexpr std::size_t kMaxJsonValues = 10'000'000;

/// Parses text; a syntax error becomes "<source>: byte N: <what>". Before parsing, a NUL byte,
/// nesting deeper than 64 levels, and more containers or values than the limits above are refused
/// with their byte position (no tree is built for them; hostile_harness_test "a line of millions of
/// empty objects builds no tree").
Json parseJson(const std::string& text, const std::string& source);
/// Reads a file of at most kMaxJsonFileBytes: "<path>: cannot open: <reason>", "<path>: is a
/// directory, not a file", "<path>: larger than the 16 MiB limit for a JSON file".
std::string readJsonText(const std::string& path);
/// readJsonText + parseJson.
Json readJsonFile(const std::string& path);

/// [x, y, z] as a JSON array (for traces; negative zeros kept as computed).
Json vec3Json(const Vec3& v);

/// A view of one JSON value with its path, for typed, checked access.
class JsonNode {
public:
    JsonNode(const Json& value, std::string path, std::string source)
        : value_(&value), path_(std::move(path)), source_(std::move(source)) {}

    const Json& raw() const { return *value_; }
    const std::string& path() const { return path_; }
    const std::string& source() const { return source_; }

    [[noreturn]] void fail(const std::string& what) const;

    bool isObject() const { return value_->is_object(); }
    bool isArray() const { return value_->is_array(); }

    double asNumber() const;       // finite number
    double asPositive() const;     // finite, > 0
    double asNonNegative() const;  // finite, >= 0
    int asInt(int lo, int hi) const;
    bool asBool() const;
    std::string asString() const;
    std::string asEnum(const std::vector<std::string>& allowed) const;
    Vec3 asVec3() const;  // [x, y, z]
    Quat asQuat() const;  // [w, x, y, z], non-zero; normalised
    std::vector<Vec3> asVec3List(std::size_t minCount = 0) const;
    std::size_t size() const;  // array length (fails on non-arrays)
    JsonNode at(std::size_t index) const;
    std::vector<JsonNode> items() const;  // array elements (fails on non-arrays)

    static std::string describe(const Json& value);  // "a string \"x\"", "an array", ...

private:
    const Json* value_;
    std::string path_;
    std::string source_;
};

/// Reads an object's members by name; finish() rejects members nobody asked for.
class ObjectReader {
public:
    explicit ObjectReader(const JsonNode& node);
    bool has(const std::string& key) const;
    JsonNode get(const std::string& key);                  // required
    std::optional<JsonNode> find(const std::string& key);  // optional (null counts as absent)
    double number(const std::string& key) { return get(key).asNumber(); }
    double numberOr(const std::string& key, double fallback);
    bool boolOr(const std::string& key, bool fallback);
    std::string stringOr(const std::string& key, const std::string& fallback);
    /// Marks keys as known without reading them (e.g. comments like "_note").
    void ignore(const std::string& key) { seen_.insert(key); }
    const JsonNode& node() const { return node_; }
    /// Fails on the first member not read ("unknown key 'colour'"), listing the known ones.
    void finish() const;

private:
    JsonNode node_;
    std::set<std::string> seen_;
};

}  // namespace cdlab::demos
