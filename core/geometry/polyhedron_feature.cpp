#include "core/geometry/polyhedron_feature.h"

namespace cdlab {

const char* nameOf(FeatureType type) {
    switch (type) {
        case FeatureType::None: return "none";
        case FeatureType::Vertex: return "vertex";
        case FeatureType::Edge: return "edge";
        case FeatureType::Face: return "face";
    }
    return "none";
}

std::string featureLabel(const FeatureRef& feature) {
    switch (feature.type) {
        case FeatureType::Vertex: return "V" + std::to_string(feature.index);
        case FeatureType::Edge: return "E" + std::to_string(feature.index);
        case FeatureType::Face: return "F" + std::to_string(feature.index);
        case FeatureType::None: break;
    }
    return "-";
}

}  // namespace cdlab
