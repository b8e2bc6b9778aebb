#include "app/query/query_limits.h"

#include <string>

namespace cdlab::demos {

void requireHullVerticesWithinLimit(std::size_t vertices, const char* op, const JsonNode& node) {
    if (vertices > kMaxHullVertices)
        node.fail(std::string(op) + " builds the shape's convex hull and takes at most " +
                  std::to_string(kMaxHullVertices) + " vertices, got " + std::to_string(vertices) +
                  " (distance, intersect and penetration take more)");
}

void requireEdgePairsWithinLimit(int edgesA, int edgesB, const JsonNode& node) {
    const double pairs = double(edgesA) * double(edgesB);
    if (pairs > kMaxSatEdgePairs)
        node.fail("contact of two colliding polytopes tests every edge pair of their hulls: " + std::to_string(edgesA) +
                  " x " + std::to_string(edgesB) + " edges is above the limit of " +
                  std::to_string(static_cast<long long>(kMaxSatEdgePairs)) + " pairs");
}

}  // namespace cdlab::demos
