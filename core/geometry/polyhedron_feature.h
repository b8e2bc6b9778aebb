// Naming a feature of a convex polyhedron (core/geometry/polyhedron.h): a vertex, an edge or a face
// by its index. Contact manifolds, feature distances and the feature walks all report features so.
#pragma once

#include <string>

namespace cdlab {

/// The kind of a polyhedron feature (closed: a face includes its edges and vertices).
enum class FeatureType { None, Vertex, Edge, Face };

/// "none", "vertex", "edge", "face".
const char* nameOf(FeatureType type);

/// A feature of a ConvexPolyhedron: index into vertices(), edges() or faces() by type.
struct FeatureRef {
    FeatureType type = FeatureType::None;
    int index = -1;
    bool operator==(const FeatureRef&) const = default;
};

/// "V3", "E5", "F2" (or "-" for None).
std::string featureLabel(const FeatureRef& feature);

}  // namespace cdlab
