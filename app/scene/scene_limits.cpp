#include "app/scene/scene_limits.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cdlab::demos {

namespace {

std::string number(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

// UTF-8 code points: every byte but the continuation bytes 10xxxxxx (the parser refused invalid UTF-8).
std::size_t characterCount(const std::string& text) {
    return std::size_t(
        std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

std::string memberPath(const std::string& parent, const std::string& key) {
    const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    });
    return plain ? parent + "." + key
                 : parent + "[" + Json(key).dump(-1, ' ', false, Json::error_handler_t::replace) + "]";
}

// Depth-first over the value (at most 64 levels: the reader refused deeper nesting).
void requireTextLengths(const Json& value, const std::string& path, const std::string& source) {
    if (value.is_string()) {
        const std::size_t chars = characterCount(value.get_ref<const std::string&>());
        const bool title = path == "$.title", caption = path == "$.caption";
        const std::size_t limit = title ? kMaxTitleChars : caption ? kMaxCaptionChars : kMaxLabelChars;
        const bool label = path.size() >= 6 && path.compare(path.size() - 6, 6, ".label") == 0;
        if (chars > limit)
            JsonNode(value, path, source)
                .fail("the text is " + std::to_string(chars) + " characters, above the limit of " +
                      std::to_string(limit) + " for " +
                      (title     ? "a title"
                       : caption ? "a caption"
                       : label   ? "a label"
                                 : "a scene text") +
                      " (texts are drawn on the frames)");
    } else if (value.is_object()) {
        for (auto it = value.begin(); it != value.end(); ++it)
            if (it.key() != "_comment") requireTextLengths(it.value(), memberPath(path, it.key()), source);
    } else if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i)
            requireTextLengths(value[i], path + "[" + std::to_string(i) + "]", source);
    }
}

}  // namespace

void requireTextLengths(const JsonNode& scene) { requireTextLengths(scene.raw(), scene.path(), scene.source()); }

double sceneCoordinate(const JsonNode& node) {
    const double x = node.asNumber();
    if (std::abs(x) > kMaxSceneCoordinate)
        node.fail("coordinate " + number(x) + " is beyond the limit of ±" + number(kMaxSceneCoordinate) +
                  " for a drawn scene (figures are drawn in float32)");
    return x;
}

Vec3 sceneVec3(const JsonNode& node) {
    if (!node.isArray() || node.size() != 3) node.fail("expected [x, y, z], got " + JsonNode::describe(node.raw()));
    return Vec3(sceneCoordinate(node.at(0)), sceneCoordinate(node.at(1)), sceneCoordinate(node.at(2)));
}

Vec3 sceneVec2(const JsonNode& node) {
    if (!node.isArray() || node.size() != 2) node.fail("expected [x, y], got " + JsonNode::describe(node.raw()));
    return Vec3(sceneCoordinate(node.at(0)), sceneCoordinate(node.at(1)), 0.0);
}

namespace {

std::vector<Vec3> sceneList(const JsonNode& node, std::size_t minCount, std::size_t maxCount, Vec3 (*read)(const JsonNode&)) {
    const std::size_t n = node.size();
    if (n < minCount) node.fail("expected at least " + std::to_string(minCount) + " points, got " + std::to_string(n));
    requireAtMost(node, double(n), double(maxCount), "the number of points", "the limit of a scene list");
    std::vector<Vec3> out;
    out.reserve(n);
    for (const JsonNode& item : node.items()) out.push_back(read(item));
    return out;
}

}  // namespace

std::vector<Vec3> sceneVec3List(const JsonNode& node, std::size_t minCount, std::size_t maxCount) {
    return sceneList(node, minCount, maxCount, sceneVec3);
}

std::vector<Vec3> sceneVec2List(const JsonNode& node, std::size_t minCount, std::size_t maxCount) {
    return sceneList(node, minCount, maxCount, sceneVec2);
}

double sceneSize(const JsonNode& node) {
    const double x = node.asPositive();
    if (x < kMinSceneSize || x > kMaxSceneCoordinate)
        node.fail("size " + number(x) + " is outside [" + number(kMinSceneSize) + ", " + number(kMaxSceneCoordinate) +
                  "], the sizes a figure can draw (float32)");
    return x;
}

Vec3 sceneSizes(const JsonNode& node) {
    if (!node.isArray() || node.size() != 3) node.fail("expected [x, y, z], got " + JsonNode::describe(node.raw()));
    return Vec3(sceneSize(node.at(0)), sceneSize(node.at(1)), sceneSize(node.at(2)));
}

void requireAtMost(const JsonNode& node, double value, double limit, const std::string& what, const std::string& why) {
    if (!(value <= limit))
        node.fail(what + " is " + number(value) + ", above the limit of " + number(limit) + " (" + why + ")");
}

void requireAtLeast(const JsonNode& node, double value, double limit, const std::string& what, const std::string& why) {
    if (!(value >= limit))
        node.fail(what + " is " + number(value) + ", below the limit of " + number(limit) + " (" + why + ")");
}

}  // namespace cdlab::demos
