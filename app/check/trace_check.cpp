#include "app/check/trace_check.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/closest/closest_point.h"
#include "app/check/check_values.h"
#include "app/query/query.h"
#include "app/query/query_json.h"

namespace cdlab::demos {

namespace {

// The convex hull of points (a point, segment, triangle or polytope), read as a query shape.
ShapeModel hullOf(const std::vector<Vec3>& pts) {
    Json shape;
    if (pts.size() == 1) shape = {{"point", vecJson(pts[0])}};
    else if (pts.size() == 2) shape = {{"segment", {vecJson(pts[0]), vecJson(pts[1])}}};
    else if (pts.size() == 3) shape = {{"triangle", {vecJson(pts[0]), vecJson(pts[1]), vecJson(pts[2])}}};
    else {
        Json v = Json::array();
        for (const Vec3& p : pts) v.push_back(vecJson(p));
        shape = {{"polytope", {{"vertices", v}}}};
    }
    return ShapeModel(shape);
}

// The steps of a trace: {"steps": [...]} or the array itself.
const Json* stepsOf(const Json& trace) {
    const Json* steps = member(trace, "steps");
    if (steps && steps->is_array()) return steps;
    return trace.is_array() ? &trace : nullptr;
}

// A support point given as a point of A − B or as the pair {"a", "b"} (then also each of the pair).
struct GivenSupport {
    Vec3 w;
    std::optional<Vec3> a, b;
};

std::optional<GivenSupport> supportPoint(const Json* s) {
    if (!s) return std::nullopt;
    if (isVec(*s)) return GivenSupport{vec(*s), std::nullopt, std::nullopt};
    const std::optional<Vec3> a = vecMember(*s, "a"), b = vecMember(*s, "b");
    if (a && b) return GivenSupport{Vec3(*a - *b), a, b};
    return std::nullopt;
}

// A point as the verdicts print it: six digits a coordinate, enough to find the vertex in a list.
std::string pointText(const Vec3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
    return buf;
}

// A support w given alone and short of h_{A−B}(u): which of s_A(u), s_B(−u) was not extreme, told
// only where the shapes are the hulls of their vertices (a support function of theirs returns a
// vertex). Every way of writing w as a vertex of A minus a vertex of B is read, with every extreme
// vertex (ties included): if all of them have B's vertex extreme and A's not, s_A fell short; the
// other way round s_B; neither extreme, both; ways of more than one kind: either. No way at all: w
// is no support of these polytopes. "" for other shapes, or past kMaxSupportPairs vertex pairs.
// check_test "names the support that is not extreme".
constexpr double kMaxSupportPairs = 1e6;
std::string whichSupportShort(const Vec3& w, const Vec3& u, const ShapeModel& shapeA, const ShapeModel& shapeB,
                              double tol, const std::string& along) {
    const std::vector<Vec3>* va = shapeA.vertices();
    const std::vector<Vec3>* vb = shapeB.vertices();
    const std::optional<double> ha = shapeA.support(u), hb = shapeB.support(-u);
    if (!va || !vb || !ha || !hb || double(va->size()) * double(vb->size()) > kMaxSupportPairs) return "";
    bool onlyA = false, onlyB = false, both = false;  // the kinds of ways w = a − b
    Vec3 someA = Vec3::Zero(), someB = Vec3::Zero();
    for (const Vec3& a : *va)
        for (const Vec3& b : *vb) {
            if (!(length(a - b - w) <= tol)) continue;
            const bool aExtreme = a.dot(u) >= *ha - tol, bExtreme = b.dot(-u) >= *hb - tol;
            if (aExtreme && bExtreme) continue;  // not reached: then w would be extreme
            if (!aExtreme && bExtreme) onlyA = true, someA = a;
            else if (aExtreme && !bExtreme) onlyB = true, someB = b;
            else both = true;
        }
    const int kinds = int(onlyA) + int(onlyB) + int(both);
    if (kinds == 0)
        return "w is no vertex of A minus a vertex of B: no support function of these polytopes returns it";
    if (kinds > 1)
        return "s_A or s_B is not extreme (w is a vertex of A minus a vertex of B in more than one way: give the "
               "pair {\"a\", \"b\"} to tell)";
    if (onlyA)
        return "s_A is not extreme: your w is a − s_B(−" + along + ") with a = " + pointText(someA) + " of A, reaching " +
               value(someA.dot(u)) + " along " + along + ", where A reaches " + value(*ha);
    if (onlyB)
        return "s_B is not extreme: your w is s_A(" + along + ") − b with b = " + pointText(someB) + " of B, reaching " +
               value(-someB.dot(u)) + " along −(" + along + "), where B reaches " + value(*hb);
    return "neither s_A nor s_B is extreme: w is a vertex of A minus a vertex of B, neither of them extreme";
}

// Rule 1 of GJK and EPA: the support w is extreme in A − B along the unit direction u, w·u =
// h_A(u) + h_B(−u) within tol, from both sides: not short of it (another point reaches further) and
// not beyond it (no point of A − B does). Given the pair {a, b}, each is held to its own shape. ""
// when it holds (or no support value can be computed: planes, rays), else the reason's detail.
std::string supportRuleBreak(const GivenSupport& given, const Vec3& u, const ShapeModel& shapeA,
                             const ShapeModel& shapeB, double tol, const std::string& along) {
    const std::optional<double> ha = shapeA.support(u), hb = shapeB.support(-u);
    if (!ha || !hb) return "";
    const double reach = given.w.dot(u), h = *ha + *hb;
    std::string detail;
    if (given.a && given.b) {
        const double ra = given.a->dot(u), rb = given.b->dot(-u);
        if (ra > *ha + tol) detail = "your a reaches " + value(ra) + " along " + along + ", beyond A's extreme " + value(*ha) + ": not a point of A";
        else if (rb > *hb + tol) detail = "your b reaches " + value(rb) + " along −(" + along + "), beyond B's extreme " + value(*hb) + ": not a point of B";
        else if (ra < *ha - tol) detail = "your a is not extreme in A along " + along + ": it reaches " + value(ra) + ", A reaches " + value(*ha);
        else if (rb < *hb - tol) detail = "your b is not extreme in B along −(" + along + "): it reaches " + value(rb) + ", B reaches " + value(*hb);
    } else if (reach < h - tol) {
        detail = whichSupportShort(given.w, u, shapeA, shapeB, tol, along);
    }
    if (std::abs(reach - h) <= tol && detail.empty()) return "";
    std::string why = "yours reaches " + value(reach) + " along it, A − B reaches " + value(h);
    if (reach > h + tol) why += " (yours lies beyond A − B)";
    return detail.empty() ? why : why + "; " + detail;
}

// "w(0), w(2)": simplex points named by the iteration whose support each is.
std::string names(const std::vector<int>& from) {
    std::string text;
    for (std::size_t i = 0; i < from.size() && i < 6; ++i) text += (i ? ", w(" : "w(") + std::to_string(from[i]) + ")";
    if (from.size() > 6) text += " and " + std::to_string(from.size() - 6) + " more";
    return text;
}

// What a simplex reduction should have kept: the smallest subset of the simplex (its points named by
// iteration) whose hull is as near the origin as the whole simplex's — the feature whose Voronoi
// region holds the origin — stated as that region and the points to keep. Simplices of more than 6
// points (a trace giving no simplex for many steps) get the distance alone.
// check_test "names the region a wrong reduction missed".
std::string subSimplexAdvice(const std::vector<Vec3>& pool, const std::vector<int>& from, double best, double tol) {
    const std::string whole = pool.size() > 4 ? "the " + std::to_string(pool.size()) + " points since the last simplex given, " +
                                                    names(from) + ", are " + num(best) + " from the origin"
                                              : "the simplex " + names(from) + " is " + num(best) + " from the origin";
    if (pool.size() > 6) return whole;
    for (std::size_t size = 1; size <= std::min<std::size_t>(pool.size(), 4); ++size)
        for (unsigned mask = 1; mask < (1u << pool.size()); ++mask) {
            if (static_cast<std::size_t>(std::popcount(mask)) != size) continue;
            std::vector<Vec3> subset;
            std::vector<int> subsetFrom;
            for (std::size_t i = 0; i < pool.size(); ++i)
                if (mask & (1u << i)) subset.push_back(pool[i]), subsetFrom.push_back(from[i]);
            const std::optional<double> d = hullOf(subset).distanceTo(Vec3::Zero());
            if (!d || !(*d <= best + tol)) continue;
            if (size == 4)
                return "the origin is inside the tetrahedron " + names(subsetFrom) + ": keep all four";
            static const char* const kFeature[] = {"", "vertex", "edge", "face"};
            return "the simplex " + names(from) + " is nearest the origin on its " + kFeature[size] + " " +
                   names(subsetFrom) + " (the origin is in that " + kFeature[size] + "'s Voronoi region): keep " +
                   names(subsetFrom) + ", " + num(best) + " from the origin";
        }
    return whole;
}

// Your GJK trace, step by step, against the rule every step must follow (so ties are not
// divergences): the support point is extreme along your direction (h_{A−B}(d), both ways); the
// simplex kept holds the point of the simplex nearest the origin; the next direction points from
// that point toward the origin. The first step that breaks one is reported.
void checkGjkTrace(const Json& query, const Json& trace, double tol, const ShapeModel& shapeA,
                   const ShapeModel& shapeB, std::vector<std::string>& reasons, int& divergence) {
    if (!member(query, "a") || !member(query, "b")) return reasons.push_back("trace: the query needs a and b");
    const Json* steps = stepsOf(trace);
    if (!steps) return reasons.push_back("trace: expected {\"steps\": [...]} (docs/check.md)");
    if (steps->size() > kMaxTraceSteps)
        return reasons.push_back("trace: " + std::to_string(steps->size()) + " steps, over the limit of " +
                                 std::to_string(kMaxTraceSteps) + " steps a trace may have");
    // The points a step may keep: the last simplex given plus every support since. Steps without
    // "simplex" only append their support (amortised O(1) a step: the check is linear in the
    // steps, tests/app/check/check_test.cpp "step limit").
    std::vector<Vec3> pool;
    std::vector<int> poolFrom;  // the iteration whose support each pool point is: named w(k) in verdicts
    std::optional<Vec3> closest;
    for (std::size_t k = 0; k < steps->size(); ++k) {
        const Json& s = (*steps)[k];
        const std::string at = "trace: iteration " + std::to_string(k) + ": ";
        divergence = static_cast<int>(k);  // where a failure returns below
        const std::optional<Vec3> dGiven = vecMember(s, "direction");
        const std::optional<GivenSupport> given = supportPoint(member(s, "support"));
        if (!dGiven || !given)
            return reasons.push_back(at + "expected \"direction\" [x,y,z] and \"support\" (a point of A − B, or {\"a\", \"b\"})");
        const Vec3 d = *dGiven;
        const Vec3 w = given->w;
        if (closest && length(*closest) > tol) {
            const Vec3 toward = -unit(*closest);
            if (!(length(d) > 0) || !(length(unit(d) - toward) <= 1e-6))
                return reasons.push_back(at + "the search direction does not point from the simplex's closest point " +
                                         "toward the origin");
        }
        if (!(length(d) > 0))  // no support point is defined along a zero direction
            return reasons.push_back(at + "the search direction is zero: no support point is "
                                          "extreme along it");
        const std::string why = supportRuleBreak(*given, unit(d), shapeA, shapeB, tol, "d");
        if (!why.empty()) return reasons.push_back(at + "different support point for the same direction: " + why);
        pool.push_back(w);
        poolFrom.push_back(static_cast<int>(k));
        const Json* simplex = member(s, "simplex");
        if (!simplex) {  // your reduction is not given: the next direction cannot be checked against it
            closest.reset();
            continue;
        }
        if (!simplex->is_array()) return reasons.push_back(at + "simplex: expected a list of points [x, y, z]");
        if (simplex->empty() || simplex->size() > 4) return reasons.push_back(at + "the simplex kept has 1 to 4 points");
        std::vector<Vec3> next;
        std::vector<int> nextFrom;
        for (const Json& p : *simplex) {
            if (!isVec(p)) return reasons.push_back(at + "simplex: expected a list of points [x, y, z]");
            next.push_back(vec(p));
            // The latest match: a support that reappears is named by its latest iteration.
            const auto match = std::find_if(pool.rbegin(), pool.rend(), [&](const Vec3& y) { return length(y - next.back()) <= tol; });
            if (match == pool.rend()) return reasons.push_back(at + "the simplex keeps a point that was not in it");
            nextFrom.push_back(poolFrom[pool.size() - 1 - static_cast<std::size_t>(match - pool.rbegin())]);
        }
        const ShapeModel kept = hullOf(next);
        const std::optional<double> best = hullOf(pool).distanceTo(Vec3::Zero()), mineD = kept.distanceTo(Vec3::Zero());
        if (best && mineD && !(*mineD <= *best + tol))
            return reasons.push_back(at + "wrong sub-simplex kept: " + subSimplexAdvice(pool, poolFrom, *best, tol) +
                                     "; yours, " + names(nextFrom) + ", is " + num(*mineD) + " from it");
        pool = next;
        poolFrom = nextFrom;
        // The closest point of the kept simplex, for the next direction: by the distance op's witness.
        closest = next.size() == 1 ? std::optional<Vec3>(next[0]) : kept.closestPointTo(Vec3::Zero());
    }
    divergence = -1;  // every step follows the rules
}


// Your EPA steps: each expands the closest face of a polytope inside A − B (unit normal n, distance
// d) by the support point along n. Rules: n unit; the support extreme along n; d never above the
// penetration depth (the polytope lies inside A − B) and never below the previous step's d (the
// polytope only grows); with your "polytope" (its triangles), the face is its closest one.
void checkEpaTrace(const Json& query, const Json& trace, double tol, const ShapeModel& shapeA, const ShapeModel& shapeB,
                   std::vector<std::string>& reasons, int& divergence) {
    const Json* qa = member(query, "a");
    const Json* qb = member(query, "b");
    if (!qa || !qb) return reasons.push_back("trace (epa): the query needs a and b");
    const Json* steps = stepsOf(trace);
    if (!steps) return reasons.push_back("trace (epa): expected {\"steps\": [...]} (docs/check.md)");
    if (steps->size() > kMaxTraceSteps)
        return reasons.push_back("trace (epa): " + std::to_string(steps->size()) + " steps, over the limit of " +
                                 std::to_string(kMaxTraceSteps) + " steps a trace may have");
    const Json answer = answerQuery(Json{{"op", "penetration"}, {"a", *qa}, {"b", *qb}}.dump());
    // cdlab's depth (NaN: none, e.g. the shapes do not overlap).
    const double depth = numberMember(answer, "depth").value_or(NAN);
    double previous = -INFINITY;
    for (std::size_t k = 0; k < steps->size(); ++k) {
        divergence = static_cast<int>(k);
        const Json& s = (*steps)[k];
        const std::string at = "trace (epa): iteration " + std::to_string(k) + ": ";
        const Json* n = member(s, "normal") ? member(s, "normal") : member(s, "closest_normal");
        const Json* d = member(s, "distance") ? member(s, "distance") : member(s, "closest_distance");
        const std::optional<GivenSupport> w = supportPoint(member(s, "support"));
        if (!n || !isVec(*n) || !d || !d->is_number() || !w)
            return reasons.push_back(at + "expected \"normal\" [x,y,z], \"distance\" and \"support\"");
        const Vec3 normal = vec(*n);
        const double dist = d->get<double>();
        if (!(std::abs(length(normal) - 1) <= 1e-6)) return reasons.push_back(at + "the face normal is not unit");
        const std::string why = supportRuleBreak(*w, unit(normal), shapeA, shapeB, tol, "n");
        if (!why.empty()) return reasons.push_back(at + "different support point for the face's normal: " + why);
        if (dist > depth + tol)  // false for a NaN depth
            return reasons.push_back(at + "the face is " + value(dist) + " from the origin, beyond the depth " +
                                     value(depth) + ": your polytope is not inside A − B");
        if (dist < previous - tol)
            return reasons.push_back(at + "the closest face came nearer (" + value(previous) + " → " + value(dist) +
                                     "): the polytope only grows, so its closest face cannot");
        previous = dist;
        if (const Json* polytope = member(s, "polytope"); polytope && polytope->is_array()) {
            double nearest = INFINITY;
            for (const Json& f : *polytope) {
                if (!f.is_array() || f.size() != 3 || !isVec(f[0]) || !isVec(f[1]) || !isVec(f[2]))
                    return reasons.push_back(at + "polytope: expected triangles [[x,y,z] x 3]");
                const Vec3 p0 = vec(f[0]), e = (vec(f[1]) - p0).cross(vec(f[2]) - p0);
                if (length(e) > 0) nearest = std::min(nearest, std::abs(unit(e).dot(p0)));
            }
            if (nearest < dist - tol)
                return reasons.push_back(at + "not the closest face of your polytope: a face lies " + value(nearest) +
                                         " from the origin, yours " + value(dist));
        }
    }
    divergence = -1;
}

// Ericson's region tests for the closest point of a triangle to p (Real-Time Collision Detection
// §5.1.5): the values d1..d6, va, vb, vc and each region's condition.
struct RegionTerms {
    double d1, d2, d3, d4, d5, d6, va, vb, vc;
    double scale;  // |ab|·|ap|-sized: the magnitude of a d term
};

RegionTerms regionTerms(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
    const Vec3 ab = b - a, ac = c - a;
    RegionTerms t{};
    t.d1 = ab.dot(p - a), t.d2 = ac.dot(p - a), t.d3 = ab.dot(p - b), t.d4 = ac.dot(p - b);
    t.d5 = ab.dot(p - c), t.d6 = ac.dot(p - c);
    t.va = t.d3 * t.d6 - t.d5 * t.d4, t.vb = t.d5 * t.d2 - t.d1 * t.d6, t.vc = t.d1 * t.d4 - t.d3 * t.d2;
    const double L = std::max({ab.norm(), ac.norm(), (p - a).norm(), (p - b).norm(), (p - c).norm()});
    t.scale = L * L;
    return t;
}

std::optional<double> termValue(const RegionTerms& t, const std::string& name) {
    if (name == "d1") return t.d1;
    if (name == "d2") return t.d2;
    if (name == "d3") return t.d3;
    if (name == "d4") return t.d4;
    if (name == "d5") return t.d5;
    if (name == "d6") return t.d6;
    if (name == "va") return t.va;
    if (name == "vb") return t.vb;
    if (name == "vc") return t.vc;
    return std::nullopt;
}

// A region's condition as sign tests x >= 0 (or x <= 0): 1 holds, -1 fails, 0 undecided (some x
// within `eps` of 0 that could flip it: a point on the region's boundary).
int regionCondition(const std::string& region, const RegionTerms& t, double eps2, double eps4) {
    struct Sign {
        double x;
        bool nonNegative;
        double eps;
    };
    std::vector<Sign> s;
    if (region == "A") s = {{t.d1, false, eps2}, {t.d2, false, eps2}};
    else if (region == "B") s = {{t.d3, true, eps2}, {t.d4 - t.d3, false, eps2}};
    else if (region == "AB") s = {{t.vc, false, eps4}, {t.d1, true, eps2}, {t.d3, false, eps2}};
    else if (region == "C") s = {{t.d6, true, eps2}, {t.d5 - t.d6, false, eps2}};
    else if (region == "AC" || region == "CA") s = {{t.vb, false, eps4}, {t.d2, true, eps2}, {t.d6, false, eps2}};
    else if (region == "BC") s = {{t.va, false, eps4}, {t.d4 - t.d3, true, eps2}, {t.d5 - t.d6, true, eps2}};
    else if (region == "ABC") s = {{t.va, true, eps4}, {t.vb, true, eps4}, {t.vc, true, eps4}};
    else return -2;  // not a region name
    bool undecided = false;
    for (const Sign& c : s) {
        const double v = c.nonNegative ? c.x : -c.x;  // holds when v >= 0
        if (v < -c.eps) return -1;
        if (v <= c.eps) undecided = true;
    }
    return undecided ? 0 : 1;
}

// Your region tests for closest_point_triangle: {"tests": [{"region": R, "terms": [{"name", "value"}],
// "accepted": bool}, ...]} in the order you made them. Each value must be the term's value (by
// Ericson's formulas) and each decision the condition's, except where the point lies on the region's
// boundary (a term within the tolerance of 0): either decision passes there.
void checkRegionTrace(const Json& query, const Json& trace, double tol, std::vector<std::string>& reasons,
                      int& divergence) {
    const Json* tests = member(trace, "tests");
    if (!tests || !tests->is_array()) return reasons.push_back("trace (regions): expected {\"tests\": [...]} (docs/check.md)");
    if (tests->size() > kMaxTraceSteps)
        return reasons.push_back("trace (regions): " + std::to_string(tests->size()) + " tests, over the limit of " +
                                 std::to_string(kMaxTraceSteps) + " a trace may have");
    const Json tri0 = query.value("triangle", Json());
    if (!isVec(query.value("point", Json())) || !tri0.is_array() || tri0.size() != 3 || !isVec(tri0[0]) ||
        !isVec(tri0[1]) || !isVec(tri0[2]))
        return reasons.push_back("trace (regions): the query needs \"point\" and \"triangle\"");
    const RegionTerms t = regionTerms(vec(tri0[0]), vec(tri0[1]), vec(tri0[2]), vec(query.value("point", Json())));
    const double L = std::sqrt(t.scale);
    const double rel = std::max(tol / std::max(L, 1e-300), 1e-12);  // your tolerance, relative
    const double eps2 = rel * t.scale, eps4 = rel * t.scale * t.scale;
    for (std::size_t k = 0; k < tests->size(); ++k) {
        divergence = static_cast<int>(k);
        const Json& test = (*tests)[k];
        const std::string region = test.is_object() ? test.value("region", "") : "";
        const std::string at = "trace (regions): test " + std::to_string(k) + " (" + shortText(region) + "): ";
        const int holds = regionCondition(region, t, eps2, eps4);
        if (holds == -2) return reasons.push_back(at + "not a region of the triangle (A, B, C, AB, BC, AC, ABC)");
        if (const Json* terms = member(test, "terms"); terms && terms->is_array())
            for (const Json& term : *terms) {
                const std::string name = term.is_object() ? term.value("name", "") : "";
                const std::optional<double> expected = termValue(t, name);
                const std::optional<double> given = numberMember(term, "value");
                if (!expected || !given)
                    return reasons.push_back(at + "a term needs \"name\" (d1..d6, va, vb, vc) and \"value\"");
                const double eps = name[0] == 'v' ? eps4 : eps2;
                const double mine = *given;
                if (!(std::abs(mine - *expected) <= eps + 1e-12 * std::abs(*expected)))
                    return reasons.push_back(at + name + " = " + value(mine) + ", but it is " + value(*expected));
            }
        const Json* acceptedGiven = member(test, "accepted");
        if (!acceptedGiven || !acceptedGiven->is_boolean())
            return reasons.push_back(at + "expected \"accepted\": true or false");
        const bool accepted = acceptedGiven->get<bool>();
        if (holds == 1 && !accepted) return reasons.push_back(at + "rejected, but the point lies in this region");
        if (holds == -1 && accepted) return reasons.push_back(at + "accepted, but the point lies outside this region");
        if (accepted) {  // the region found: later tests are not made
            divergence = -1;
            return;
        }
    }
    divergence = static_cast<int>(tests->size());
    reasons.push_back("trace (regions): no test accepted a region");
}

// The closest point of tetrahedron feature `region` ("A", "BD", "ACD", "ABCD": letters in order) to p,
// or nothing when the name is not a feature.
std::optional<Vec3> tetrahedronFeaturePoint(const std::string& region, const Vec3 v[4], const Vec3& p) {
    std::vector<Vec3> f;
    for (std::size_t i = 0; i < region.size(); ++i) {
        const char c = region[i];
        if (c < 'A' || c > 'D' || (i > 0 && region[i - 1] >= c)) return std::nullopt;
        f.push_back(v[c - 'A']);
    }
    if (f.size() == 1) return f[0];
    if (f.size() == 2) {
        const double t = std::clamp((p - f[0]).dot(f[1] - f[0]) / std::max((f[1] - f[0]).squaredNorm(), 1e-300), 0.0, 1.0);
        return Vec3(f[0] + t * (f[1] - f[0]));
    }
    if (f.size() == 3) return closestPointOnTriangle(p, Triangle{f[0], f[1], f[2]}).point;
    if (f.size() == 4) return p;  // inside: the point itself
    return std::nullopt;
}

// Your region tests for closest_point_tetrahedron, the same schema as the triangle's. A test of
// region R holds when cdlab's region is R, and may go either way when R's feature holds cdlab's
// closest point too (p on the boundary between the two regions); a term whose name cdlab's own
// trace of that region uses (Ericson §5.1.6 as core tests it: "(p-a).(b-a)", ...) must have its value.
void checkTetrahedronRegionTrace(const Json& query, const Json& trace, double tol, std::vector<std::string>& reasons,
                                 int& divergence) {
    const Json* tests = member(trace, "tests");
    if (!tests || !tests->is_array()) return reasons.push_back("trace (regions): expected {\"tests\": [...]} (docs/check.md)");
    if (tests->size() > kMaxTraceSteps)
        return reasons.push_back("trace (regions): " + std::to_string(tests->size()) + " tests, over the limit of " +
                                 std::to_string(kMaxTraceSteps) + " a trace may have");
    const Json tet = query.value("tetrahedron", Json());
    if (!isVec(query.value("point", Json())) || !tet.is_array() || tet.size() != 4 ||
        !std::all_of(tet.begin(), tet.end(), [](const Json& x) { return isVec(x); }))
        return reasons.push_back("trace (regions): the query needs \"point\" and \"tetrahedron\"");
    const Vec3 v[4] = {vec(tet[0]), vec(tet[1]), vec(tet[2]), vec(tet[3])}, p = vec(query.value("point", Json()));
    TetrahedronTrace mine;
    const ClosestPointOnTetrahedronResult cdlab = closestPointOnTetrahedron(p, Tetrahedron{v[0], v[1], v[2], v[3]}, &mine);
    double scale = 0;
    for (const Vec3& x : v) scale = std::max(scale, (x - p).squaredNorm());
    // A term's tolerance in its own units: (p-x).(y-x) is a length², an edge's in-face side a
    // length⁴, a face's plane side (orient3d) a length³ — your tolerance times L^(power − 1).
    const double L = std::sqrt(scale);
    const auto epsOf = [&](const std::string& name) {
        const std::size_t bar = name.find('|'), open = name.find('(');
        const int power = name.rfind("side(", 0) == 0 && bar != std::string::npos ? (bar - open - 1 == 2 ? 4 : 3) : 2;
        return std::max(tol * std::pow(L, power - 1), 1e-12 * std::pow(L, power));
    };
    for (std::size_t k = 0; k < tests->size(); ++k) {
        divergence = static_cast<int>(k);
        const Json& test = (*tests)[k];
        std::string region = test.is_object() ? test.value("region", "") : "";
        std::sort(region.begin(), region.end());
        const std::string at = "trace (regions): test " + std::to_string(k) + " (" + shortText(region) + "): ";
        const std::optional<Vec3> onFeature = tetrahedronFeaturePoint(region, v, p);
        if (!onFeature) return reasons.push_back(at + "not a region of the tetrahedron (A..D, AB..CD, ABC..BCD, ABCD)");
        if (const Json* terms = member(test, "terms"); terms && terms->is_array())
            for (const Json& term : *terms) {
                const std::string name = term.is_object() ? term.value("name", "") : "";
                const std::optional<double> given = numberMember(term, "value");
                if (!given) return reasons.push_back(at + "a term needs \"name\" and \"value\"");
                for (const auto& known : mine.tests) {
                    if (nameOf(known.candidate) != region) continue;
                    for (int i = 0; i < known.termCount; ++i)
                        if (name == known.terms[std::size_t(i)].name) {
                            const double expected = known.terms[std::size_t(i)].value, yours = *given;
                            if (!(std::abs(yours - expected) <= epsOf(name) + 1e-12 * std::abs(expected)))
                                return reasons.push_back(at + name + " = " + value(yours) + ", but it is " + value(expected));
                        }
                }
            }
        const Json* acceptedGiven = member(test, "accepted");
        if (!acceptedGiven || !acceptedGiven->is_boolean())
            return reasons.push_back(at + "expected \"accepted\": true or false");
        const bool accepted = acceptedGiven->get<bool>();
        const bool holds = region == nameOf(cdlab.region);
        const bool tie = !holds && (*onFeature - cdlab.point).norm() <= tol;
        if (holds && !accepted) {
            // On the boundary of cdlab's region (a term exactly 0) your tests may reject it and
            // accept a neighbour that holds the same closest point: look at the region you accept.
            bool neighbourTie = false;
            for (std::size_t later = k + 1; later < tests->size(); ++later) {
                const Json& next = (*tests)[later];
                if (!next.is_object() || !next.value("accepted", false)) continue;
                std::string name = next.value("region", "");
                std::sort(name.begin(), name.end());
                const std::optional<Vec3> q = tetrahedronFeaturePoint(name, v, p);
                neighbourTie = q && (*q - cdlab.point).norm() <= tol;
                break;
            }
            if (!neighbourTie) return reasons.push_back(at + "rejected, but the point lies in this region");
            continue;
        }
        if (!holds && !tie && accepted) return reasons.push_back(at + "accepted, but the point lies outside this region");
        if (accepted) {
            divergence = -1;
            return;
        }
    }
    divergence = static_cast<int>(tests->size());
    reasons.push_back("trace (regions): no test accepted a region");
}

}  // namespace

void checkTrace(const std::string& op, const Json& query, const Json& trace, double tol, const ShapeModel& a,
                const ShapeModel& b, std::vector<std::string>& reasons, int& divergence, std::string& algorithm) {
    if (const Json* several = member(trace, "algorithms"); several && several->is_array()) {
        if (several->size() > kMaxTraceAlgorithms)
            return reasons.push_back("trace: " + std::to_string(several->size()) +
                                     " traces in \"algorithms\", over the limit of " + std::to_string(kMaxTraceAlgorithms));
        for (const Json& one : *several) {
            if (member(one, "algorithms")) return reasons.push_back("trace: \"algorithms\" inside \"algorithms\"");
            checkTrace(op, query, one, tol, a, b, reasons, divergence, algorithm);
            if (!reasons.empty()) return;
        }
        return;
    }
    if (!trace.is_object())
        return reasons.push_back("trace: expected an object {\"algorithm\": ..., \"steps\": [...]}, got " +
                                 JsonNode::describe(trace));
    const Json* named = member(trace, "algorithm");
    if (named && !named->is_string())
        return reasons.push_back("trace: \"algorithm\" must be a string (gjk, epa or ericson_regions), got " +
                                 JsonNode::describe(*named));
    algorithm = named ? named->get<std::string>() : std::string();
    const bool regionOp = op == "closest_point_triangle" || op == "closest_point_tetrahedron";
    if (algorithm.empty()) algorithm = regionOp ? "ericson_regions" : "gjk";
    if (algorithm == "ericson_regions") {
        if (!regionOp)
            return reasons.push_back("trace: region tests are checked for closest_point_triangle and _tetrahedron");
        if (op == "closest_point_tetrahedron") return checkTetrahedronRegionTrace(query, trace, tol, reasons, divergence);
        return checkRegionTrace(query, trace, tol, reasons, divergence);
    }
    if (op != "intersect" && op != "distance" && op != "penetration")
        return reasons.push_back("trace: " + shortText(algorithm) +
                                 " traces are checked for intersect, distance and penetration");
    if (algorithm == "epa") {
        if (op != "penetration") return reasons.push_back("trace: EPA steps are checked for penetration");
        return checkEpaTrace(query, trace, tol, a, b, reasons, divergence);
    }
    if (algorithm != "gjk")
        return reasons.push_back("trace: unknown algorithm '" + shortText(algorithm) + "' (gjk, epa, ericson_regions)");
    checkGjkTrace(query, trace, tol, a, b, reasons, divergence);
}

}  // namespace cdlab::demos
