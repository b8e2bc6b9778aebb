// Pair queries on the shapes of core/query/shape.h: intersect, distance and penetration of any two
// of them — the answers `cdlab query` prints (its "intersect", "distance" and "penetration" ops),
// `cdlab check` judges against, and an engine links.
//
//   Two bounded shapes: GJK and EPA on the polytope cores, the radii added in closed form
//     (core/gjk_epa/margins.h, marginPairOnCores), a cylinder's or cone's axis or normal polished
//     to the minimum of its support gap (core/gjk_epa/direction_refinement.h).
//   A plane: the span of the other shape's signed distances, in closed form (core/query/touch.h).
//   A ray: closest points in closed form against a ray or a plane; against a bounded shape, the
//     segment of the ray that provably holds the answer, then as two bounded shapes.
// Every pair is first scaled by a power of two (normalisingExponent: exact) and moved next to the
// origin where it lies far from it for its size; answers are in the input's units. Touching is
// decided by the one rule of core/base/touch_rule.h (planes: relative to their offsets).
#pragma once

#include <optional>

#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "core/overlap/sat_tests.h"
#include "core/query/shape.h"

namespace cdlab {

struct PairOptions {
    /// Penetration asked for: an overlapping pair gets its depth, normal and deepest points (EPA may
    /// run). false: an overlapping pair answers only `intersect`.
    bool depth = true;
    /// GJK's first search direction (two bounded shapes only; non-zero): a student's run can be
    /// compared from its first step.
    std::optional<Vec3> initialDirection = std::nullopt;
};

enum class PairStatus {
    Ok,
    NonFiniteSupport,      ///< GJK met a non-finite support point (coordinates overflow)
    EpaFailed,             ///< EPA met invalid support points
    UnboundedPenetration,  ///< penetration of two non-parallel planes: no translation separates them
    Overflow,              ///< the answer overflows double precision (coordinates too large)
    InvalidInput,          ///< shapes of kinds the operation does not take, or a zero initial direction
    WorkLimit,             ///< the work the input asks for is over the operation's limit (its result says which)
};
/// One sentence for each status (the query format's error text after "query: ").
const char* describe(PairStatus status);

struct PairResult {
    PairStatus status = PairStatus::Ok;
    bool intersect = false;
    double distance = 0.0;        ///< separated: > 0
    double depth = 0.0;           ///< intersecting, depth asked: >= 0
    Vec3 normal = Vec3::UnitX();  ///< from A toward B: translating B by depth · normal separates
    Vec3 pointA = Vec3::Zero();   ///< separated: closest points; intersecting: deepest points
    Vec3 pointB = Vec3::Zero();
    bool hasWitness = false;      ///< pointA, pointB and normal are set
};

/// The algorithms' traces of one pair query. They ran on the pair scaled and moved (see the file
/// comment): a trace length times `unit` is in the input's units, and the support points of A and B
/// (not their differences) need `origin` added after that.
struct PairTrace {
    bool gjkRan = false, epaRan = false;
    GjkTrace gjk;
    EpaTrace epa;
    double unit = 1.0;
    Vec3 origin = Vec3::Zero();
};

/// Intersect / distance / penetration of a and b (see PairOptions and the file comment).
PairResult pairQuery(QueryShape a, QueryShape b, const PairOptions& options = {}, PairTrace* trace = nullptr);

/// The separating-axis test of two boxes (aabb or obb kinds, else InvalidInput), on the pair scaled
/// by a power of two; trace intervals times 2^exponent (std::ldexp) are in the input's units.
struct BoxSatResult {
    PairStatus status = PairStatus::Ok;  ///< Overflow: a box's axes overflow double precision
    bool intersect = false;
    int exponent = 0;
};
BoxSatResult boxPairSat(QueryShape a, QueryShape b, SatTrace* trace = nullptr);

/// The oriented box of an aabb or obb query shape (corner i has bit k of i choosing + along axis k).
Obb obbOfBoxShape(const QueryShape& box);

}  // namespace cdlab
