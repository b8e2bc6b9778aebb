#include "demos/scene/scene_limits.h"

#include <cmath>
#include <sstream>

namespace cdlab::demos {

namespace {

std::string number(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

}  // namespace

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

std::vector<Vec3> sceneVec3List(const JsonNode& node, std::size_t minCount, std::size_t maxCount) {
    const std::size_t n = node.size();
    if (n < minCount) node.fail("expected at least " + std::to_string(minCount) + " points, got " + std::to_string(n));
    requireAtMost(node, double(n), double(maxCount), "the number of points", "the limit of a scene list");
    std::vector<Vec3> out;
    out.reserve(n);
    for (const JsonNode& item : node.items()) out.push_back(sceneVec3(item));
    return out;
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

}  // namespace cdlab::demos
