// The trace JSON the feature-walk demos (vclip, lin_canny) share: a step's plane tests, the fields
// every walk step has and the fields every walk result has. VClipTraceStep and LinCannyTraceStep
// (and their results) spell these fields the same way on purpose (core/feature_walk/lin_canny.h).
#pragma once

#include <vector>

#include "core/feature_walk/vclip.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos::walkfigure {

/// A feature as the demos' traces name it: "V3", "E12", "F0".
inline Json featureJson(const VClipFeature& f) { return nameOf(f); }

inline Json planeTestsJson(const std::vector<VClipPlaneTest>& tests) {
    Json planes = Json::array();
    for (const VClipPlaneTest& p : tests)
        planes.push_back({{"region_body", p.regionBody},
                          {"owner", featureJson(p.owner)},
                          {"neighbor", featureJson(p.neighbor)},
                          {"plane", p.plane},
                          {"signed_distance", p.signedDistance},
                          {"violated", p.violated},
                          {"maximal", p.maximal}});
    return planes;
}

/// The fields of a VClipTraceStep or a LinCannyTraceStep that both walks record.
template <class Step>
Json walkStepJson(const Step& st) {
    return {{"step", st.step},
            {"state", nameOf(st.state)},
            {"feature_a", featureJson(st.featureA)},
            {"feature_b", featureJson(st.featureB)},
            {"kind", nameOf(st.kind)},
            {"updated_body", st.updatedBody},
            {"from", featureJson(st.from)},
            {"to", featureJson(st.to)},
            {"rule", st.rule},
            {"local_minimum", st.localMinimum},
            {"distance_before", st.distanceBefore},
            {"distance_after", st.distanceAfter},
            {"distance_change", st.distanceChange},
            {"closest_a", vec3Json(st.closestA)},
            {"closest_b", vec3Json(st.closestB)},
            {"planes", planeTestsJson(st.planes)}};
}

/// The fields of a VClipResult or a LinCannyResult that both walks report.
template <class Result>
Json walkResultJson(const Result& r) {
    return {{"status", nameOf(r.status)},
            {"penetration", nameOf(r.penetration)},
            {"distance", r.distance},
            {"point_a", vec3Json(r.pointA)},
            {"point_b", vec3Json(r.pointB)},
            {"feature_a", featureJson(r.featureA)},
            {"feature_b", featureJson(r.featureB)},
            {"steps", r.steps}};
}

}  // namespace cdlab::demos::walkfigure
