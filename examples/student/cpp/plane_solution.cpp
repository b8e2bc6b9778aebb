// The reference solution of plane.cpp's TODO (kept out of the handout: examples/student/README.md).
#include <algorithm>
#include <cmath>

#include "kit.h"

using kit::V3;

constexpr std::size_t kMaxPoints = 4;

kit::PlaneAnswer contact(const std::vector<V3>& body, V3 normal, double offset) {
    const double length = std::sqrt(dot(normal, normal));
    const V3 unit = (1 / length) * normal;
    std::vector<std::pair<double, V3>> heights;
    for (V3 v : body) heights.push_back({dot(unit, v) - offset / length, v});
    std::sort(heights.begin(), heights.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    const auto [lowest, v] = heights.front();
    if (lowest > 0) return {false, lowest, -unit, {{v, v - lowest * unit, 0}}};
    kit::PlaneAnswer r{true, -lowest, -unit, {}};
    for (std::size_t i = 0; i < heights.size() && i < kMaxPoints && heights[i].first <= 0; ++i)
        r.points.push_back({heights[i].second, heights[i].second - heights[i].first * unit, -heights[i].first});
    return r;
}

int main() { return kit::runPlaneCases(contact); }
