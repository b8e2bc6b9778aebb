// The shape-pair ops of `cdlab query` (intersect, distance, penetration): the query's JSON read into
// core's pair query (core/query/pair.h) and its result and traces written back as JSON.
#include "app/query/query_ops.h"

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "app/query/query_compound.h"
#include "app/query/query_feature_walk.h"
#include "app/query/query_json.h"
#include "app/query/query_shapes.h"
#include "core/query/pair.h"

namespace cdlab::demos {

namespace {

// A GJK trace as `cdlab query` writes it: each step's `simplex` lists the slots w0..w3 in order, and
// `region` spells the slots kept as letters A..D = w0..w3 (slotLetters: 0b0101 -> "AC", w0 and w2
// kept); the letters name slots, not the bodies A and B.
Json gjkTraceJson(const GjkTrace& t) {
    Json steps = Json::array();
    for (const GjkTraceStep& s : t.steps) {
        Json simplex = Json::array();
        for (int i = 0; i < s.simplexCount; ++i) simplex.push_back(vecJson(s.simplex[i].w));
        steps.push_back({{"iteration", s.iteration},
                         {"simplex", simplex},
                         {"direction", vecJson(s.direction)},
                         {"support", vecJson(s.support.w)},
                         {"support_a", vecJson(s.support.a)},
                         {"support_b", vecJson(s.support.b)},
                         {"region", slotLetters(s.keptSlots)},
                         {"v", vecJson(s.v)},
                         {"lower_bound", s.lowerBound},
                         {"upper_bound", s.upperBound},
                         {"terminated", s.terminated}});
    }
    return {{"algorithm", "gjk"}, {"termination", nameOf(t.termination)}, {"steps", steps}};
}

Json epaTraceJson(const EpaTrace& t) {
    Json steps = Json::array();
    for (const EpaTraceStep& s : t.steps)
        steps.push_back({{"iteration", s.iteration},
                         {"vertices", s.vertices.size()},
                         {"faces", s.faces.size()},
                         {"closest_normal", vecJson(s.closestNormal)},
                         {"closest_distance", s.closestDistance},
                         {"support", vecJson(s.support)},
                         {"removed_faces", s.removedFaces.size()},
                         {"horizon_edges", s.horizon.size()},
                         {"lower_bound", s.lowerBound},
                         {"upper_bound", s.upperBound}});
    return {{"algorithm", "epa"}, {"start", t.start}, {"termination", nameOf(t.termination)}, {"steps", steps}};
}

// Multiplies every length of a GJK / EPA trace (points, directions, bounds, distances) by `unit`:
// the algorithms ran on the query scaled by a power of two, the trace is given in world units;
// the support points of A and B (not their differences) get `origin` back (see pairOrigin).
void toWorldUnits(Json& algorithms, double unit, const Vec3& origin) {
    static const char* const kLengths[] = {"simplex",     "direction",   "support",         "support_a", "support_b",
                                           "v",           "lower_bound", "upper_bound",     "closest_distance"};
    const std::function<void(Json&)> scale = [&](Json& j) {
        if (j.is_number()) j = cleanZero(j.get<double>() * unit);
        else if (j.is_array())
            for (Json& x : j) scale(x);
    };
    for (Json& algorithm : algorithms)
        for (Json& step : algorithm["steps"]) {
            for (const char* key : kLengths)
                if (step.contains(key)) scale(step[key]);
            if (origin.isZero(0.0)) continue;
            for (const char* key : {"support_a", "support_b"})
                if (step.contains(key) && step[key].is_array() && step[key].size() == 3)
                    for (int i = 0; i < 3; ++i) step[key][i] = cleanZero(step[key][i].get<double>() + origin[i]);
        }
}

bool isBox(const QueryShape& s) { return s.kind == QueryShape::Kind::Aabb || s.kind == QueryShape::Kind::Obb; }

// The query's error for a failed pair query.
void requireOk(PairStatus status) {
    if (status != PairStatus::Ok) throw InputError(std::string("query: ") + describe(status));
}

}  // namespace

Json answerShapeQuery(const std::string& op, ObjectReader& r) {
    JsonNode an = r.get("a"), bn = r.get("b");
    if (isCompoundOrMesh(an) || isCompoundOrMesh(bn)) return answerCompoundQuery(op, r, an, bn);
    QueryShape a = parseQueryShape(an), b = parseQueryShape(bn);
    std::string method = "gjk";
    if (auto m = r.find("method")) {
        method = op == "intersect" ? m->asEnum({"gjk", "sat"}) : m->asEnum({"gjk", "vclip", "lin_canny"});
        if (method == "sat" && !(isBox(a) && isBox(b))) m->fail("method 'sat' needs two boxes (aabb or obb)");
    }
    const bool wantTrace = r.boolOr("trace", false);
    PairOptions options;
    options.depth = op == "penetration";
    if (auto d = r.find("initial_direction")) {
        // GJK's first support direction, so that a student's run can be compared from step 1.
        options.initialDirection = d->asVec3();
        if (options.initialDirection->isZero(0.0)) d->fail("initial_direction must be non-zero");
        if (method != "gjk") d->fail("initial_direction is GJK's; method '" + method + "' has no such start");
        if (!(a.bounded() && b.bounded())) d->fail("initial_direction needs two bounded shapes (GJK runs on them)");
    }
    r.finish();

    if (method == "vclip" || method == "lin_canny") return answerFeatureWalkQuery(op, method, a, b, an, bn, wantTrace);

    if (method == "sat") {
        SatTrace trace;
        const BoxSatResult s = boxPairSat(std::move(a), std::move(b), wantTrace ? &trace : nullptr);
        if (s.status != PairStatus::Ok) throw InputError("query: method 'sat': the box's axes overflow double precision");
        Json out = {{"intersect", s.intersect}};
        if (wantTrace) {  // intervals in the query's units
            const auto world = [&](double x) { return cleanZero(std::ldexp(x, s.exponent)); };
            Json axes = Json::array();
            for (const SatAxisStep& st : trace.steps)
                axes.push_back({{"axis", vecJson(st.axis)},
                                {"a", {world(st.minA), world(st.maxA)}},
                                {"b", {world(st.minB), world(st.maxB)}},
                                {"separating", st.separating}});
            out["trace"] = {{"algorithm", "sat"}, {"axes", axes}};
        }
        return out;
    }

    PairTrace trace;
    const PairResult ans = pairQuery(std::move(a), std::move(b), options, wantTrace ? &trace : nullptr);
    requireOk(ans.status);
    Json out;
    if (op == "intersect") {
        out = {{"intersect", ans.intersect}};
    } else if (op == "distance") {
        if (ans.intersect) out = {{"intersect", true}, {"distance", 0.0}};
        else
            out = {{"intersect", false},
                   {"distance", ans.distance},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
    } else {  // penetration
        if (ans.intersect)
            out = {{"intersect", true},
                   {"depth", ans.depth},
                   {"normal", vecJson(ans.normal)},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
        else
            out = {{"intersect", false},
                   {"distance", ans.distance},
                   {"normal", vecJson(ans.normal)},
                   {"point_a", vecJson(ans.pointA)},
                   {"point_b", vecJson(ans.pointB)}};
    }
    // The algorithms ran on the query scaled by a power of two (exact); the trace is in world units
    // (of the cores: spheres and capsules without their radii), "unit" 1 = world = unit * value.
    if (wantTrace && trace.gjkRan) {
        Json algorithms = Json::array({gjkTraceJson(trace.gjk)});
        if (trace.epaRan) algorithms.push_back(epaTraceJson(trace.epa));
        toWorldUnits(algorithms, trace.unit, trace.origin);
        out["trace"] = {{"unit", 1.0}, {"algorithms", algorithms}};
    }
    return out;
}

}  // namespace cdlab::demos
