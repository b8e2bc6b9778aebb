// The feature walks on the query's shapes (`cdlab query` distance / penetration with method "vclip"
// or "lin_canny"): a polyhedral shape's convex hull (coplanar faces merged) as a V-Clip polyhedron in
// a body frame at its first vertex, the pair scaled by a power of two (exact), then one cold walk —
// V-Clip (Mirtich 1998, core/feature_walk/vclip.h) or Lin–Canny (Lin & Canny 1991,
// core/feature_walk/lin_canny.h) — decided by the touching rule of every pair query.
// Tests: tests/app/query/*feature_walk*_test.cpp, *vclip*_test.cpp.
#pragma once

#include <string>

#include "core/feature_walk/lin_canny.h"
#include "core/feature_walk/vclip.h"
#include "core/geometry/convex_hull.h"
#include "core/query/pair.h"
#include "core/query/shape.h"

namespace cdlab {

/// One body of a walk: its hull as a V-Clip polyhedron and the frame's origin.
struct WalkBody {
    enum class Status {
        Ok,
        NotPolyhedron,   ///< not a polytope, aabb or obb
        DegenerateHull,  ///< the hull is not solid (hullStatus, message)
        BuildFailed,     ///< buildVClipPolyhedron refused (message)
    };
    Status status = Status::Ok;
    HullStatus hullStatus = HullStatus::Ok;
    std::string message;
    VClipPolyhedron polyhedron;
    Transform pose;  ///< translation to the body frame's origin (the first vertex, scaled by 2^k)
};

/// The body of shape s in the pair's scaling 2^k (k = normalisingExponent(a, b)). Far from the
/// world origin (offsets 1e4 × the size) the body frame keeps the plane offsets small: v − origin is
/// exact for the shape's own vertices (Sterbenz), so the distance loses no digits to the offset.
WalkBody walkBodyOf(const QueryShape& s, int k);

struct WalkPairResult {
    PairStatus status = PairStatus::Ok;  ///< Overflow: the answer overflows; InvalidInput: the walk failed
    bool intersect = false;              ///< the walk's verdict, or a distance within the touching rule
    double distance = 0.0;
    Vec3 normal = Vec3::Zero(), pointA = Vec3::Zero(), pointB = Vec3::Zero();  ///< separated: input units
    bool cycle = false;        ///< Lin–Canny: the walk cycled (penetrating bodies, usually)
    std::string walkStatus;    ///< the walk's status name and
    std::string message;       ///<   message when it failed
};

/// V-Clip (linCanny false) or Lin–Canny on the two bodies of the pair (a, b) scaled by 2^k; touch is
/// the pair's touching tolerance in the scaled units. Traces: optional, the walk's (scaled units).
WalkPairResult walkPair(const WalkBody& a, const WalkBody& b, int k, double touch, bool linCanny,
                        VClipTrace* vclipTrace = nullptr, LinCannyTrace* linCannyTrace = nullptr);

}  // namespace cdlab
