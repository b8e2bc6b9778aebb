#include "app/check/check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <streambuf>
#include <string>

#include "app/check/check_figure.h"
#include "app/check/check_values.h"
#include "app/check/trace_check.h"
#include "app/harness/scene_runner.h"
#include "app/query/query.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_shapes.h"
#include "core/contact/contact_sat.h"

namespace cdlab::demos {

namespace {

// The line's id as echoed in its verdict: compact JSON, at most 60 bytes, its colons written
// \u003a, so that the first ": " of a verdict line is always the one before "pass" or "FAIL".
std::string idText(const Json& id) {
    const std::string text = shortText(id.dump(-1, ' ', false, Json::error_handler_t::replace));
    std::string out;
    for (const char c : text) out += c == ':' ? std::string("\\u003a") : std::string(1, c);
    return out;
}

// 2^e such that the points divided by it have their largest |coordinate| in [0.5, 1) (exact:
// a power of two), so that squared lengths of 1e160 or 1e-160 coordinates neither overflow nor
// underflow; 1 for the zero or a non-finite set.
double commonScale(std::initializer_list<Vec3> points) {
    double m = 0;
    for (const Vec3& p : points) m = std::max(m, p.cwiseAbs().maxCoeff());
    if (!(m > 0) || !std::isfinite(m)) return 1.0;
    int e = 0;
    std::frexp(m, &e);
    return std::ldexp(1.0, e);
}

// The point of segment ab nearest p.
Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const double s = commonScale({p, a, b});
    const Vec3 ps = p / s, as = a / s, bs = b / s;
    const double len2 = (bs - as).squaredNorm();
    const double t = len2 > 0 ? std::clamp((ps - as).dot(bs - as) / len2, 0.0, 1.0) : 0.0;
    return a + t * (b - a);
}

// The projection of p on the plane of triangle abc (nothing when it is degenerate).
std::optional<Vec3> projectOnPlane(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double s = commonScale({p, a, b, c});
    const Vec3 ps = p / s, as = a / s, bs = b / s, cs = c / s;
    const Vec3 n = (bs - as).cross(cs - as);
    if (!(n.squaredNorm() > 0)) return std::nullopt;
    return Vec3(s * (ps - n * (n.dot(ps - as) / n.squaredNorm())));
}

constexpr double kUnitNormal = 1e-6;  // |n| may differ from 1 by this (a normalised double is ~1e-16 off)
constexpr std::size_t kMaxContactEntries = 64;  // the most "max_points" a contact query may ask for

// Compares your answer (mine_) with cdlab's (theirs_) for the query q_. Every key of the three is
// read through member() / numberMember() / vecMember(): a key missing from any of them is a reason
// naming it, never a read of a missing key (tests/app/check/check_test.cpp, "missing").
class Checker {
public:
    Checker(const Json& query, const Json& mine, const Json& theirs, double tol, const ShapeModel& a,
            const ShapeModel& b, const ShapeModel& shape)
        : q_(query), mine_(mine), theirs_(theirs), tol_(tol), a_(a), b_(b), shape_(shape) {}

    std::vector<std::string> reasons;

    void run(const std::string& op) {
        if (const Json* error = member(theirs_, "error")) {
            if (!member(mine_, "error"))
                fail("cdlab answers an error (" + (error->is_string() ? error->get<std::string>() : error->dump()) +
                     "), yours does not");
            return;
        }
        if (op == "intersect") verdict("intersect");
        else if (op == "distance") distanceOp();
        else if (op == "penetration") penetrationOp();
        else if (op == "closest_point_triangle") closestPointOp();
        else if (op == "closest_point_tetrahedron") closestPointTetrahedronOp();
        else if (op == "raycast") raycastOp();
        else if (op == "time_of_impact") timeOfImpactOp();
        else if (op == "contact") contactOp();
        else generic(theirs_, mine_, "");
    }

private:
    const Json& q_;
    const Json& mine_;
    const Json& theirs_;
    double tol_;
    const ShapeModel& a_;
    const ShapeModel& b_;
    const ShapeModel& shape_;

    void fail(const std::string& why) { reasons.push_back(why); }

    // `x`, or a reason naming what is missing when it is absent.
    template <class T>
    std::optional<T> required(std::optional<T> x, const std::string& whose, const std::string& key, const char* kind) {
        if (!x) fail(whose + " has no " + key + kind);
        return x;
    }
    // cdlab's, the query's or your number or vector `key` (a reason when it lacks it).
    std::optional<double> theirNumber(const std::string& key) {
        return required(numberMember(theirs_, key), "cdlab's answer", key, " number");
    }
    std::optional<Vec3> theirVec(const std::string& key) {
        return required(vecMember(theirs_, key), "cdlab's answer", key, " [x, y, z]");
    }
    std::optional<Vec3> queryVec(const std::string& key) {
        return required(vecMember(q_, key), "the query", key, " [x, y, z]");
    }
    std::optional<double> myNumber(const std::string& key) {
        return required(numberMember(mine_, key), "your answer", key, " number");
    }
    std::optional<Vec3> myVec(const std::string& key) {
        return required(vecMember(mine_, key), "your answer", key, " [x, y, z]");
    }
    // A boolean of an answer, `otherwise` when absent; a present non-boolean is a reason.
    bool flag(const Json& answer, const std::string& key, bool otherwise, const char* whose) {
        const Json* x = member(answer, key);
        if (!x) return otherwise;
        if (!x->is_boolean()) {
            fail(std::string(whose) + " \"" + key + "\" is not true or false");
            return otherwise;
        }
        return x->get<bool>();
    }

    bool verdict(const std::string& key) {
        const Json* m = member(mine_, key);
        if (!m || !m->is_boolean()) {
            fail("your answer has no \"" + key + "\" (true or false)");
            return false;
        }
        const Json* t = member(theirs_, key);
        if (!t || !t->is_boolean()) {
            fail("cdlab's answer has no \"" + key + "\" (true or false)");
            return false;
        }
        if (*m != *t) {
            fail("verdict differs: yours " + key + " = " + m->dump() + ", cdlab's " + t->dump());
            return false;
        }
        return true;
    }

    // cdlab's verdict `key` (read after verdict(key) agreed: present and boolean).
    bool theirVerdict(const std::string& key) {
        const Json* t = member(theirs_, key);
        return t && t->is_boolean() && t->get<bool>();
    }

    void number(const std::string& key, double tol) {
        const std::optional<double> m = myNumber(key);
        const std::optional<double> t = theirNumber(key);
        if (!m || !t) return;
        // |m - t| overflows to inf only when they differ by more than any tolerance.
        const double off = std::abs(*m - *t);
        if (!(off <= tol))
            fail(key + " off by " + num(off) + " (yours " + value(*m) + ", cdlab's " + value(*t) + "), over tolerance " +
                 num(tol));
    }

    void point(const std::string& key) {
        const std::optional<Vec3> m = myVec(key);
        const std::optional<Vec3> t = theirVec(key);
        if (!m || !t) return;
        const double d = length(*m - *t);
        if (!(d <= tol_)) fail(key + " off by " + num(d) + ", over tolerance " + num(tol_));
    }

    // A witness point must lie on (or in) its shape; it need not be cdlab's.
    void onShape(const std::string& key, const ShapeModel& shape, const char* name, const Vec3& shift = Vec3::Zero()) {
        const std::optional<Vec3> p = myVec(key);
        if (!p) return;
        const std::optional<double> d = shape.distanceTo(*p - shift);
        if (d && !(*d <= tol_)) fail(key + " is not on shape " + name + ": " + num(*d) + " from it");
    }

    bool unitNormal(const std::string& key) {
        const std::optional<Vec3> n = myVec(key);
        if (!n) return false;
        const double len = length(*n);
        if (!(std::abs(len - 1) <= kUnitNormal)) {
            fail(key + " is not a unit vector: |n| = " + num(len));
            return false;
        }
        return true;
    }

    // Overlapping: moving b by depth along your normal must leave the shapes touching, i.e. the
    // overlap of their projections on n, h_a(n) + h_b(-n), is cdlab's (minimal) depth.
    // depthGiven: the depth the normal must realise (a contact's own depth, see contactDepth);
    // otherwise cdlab's.
    void separatingNormal(bool overlapping, const Vec3& shiftA = Vec3::Zero(), const Vec3& shiftB = Vec3::Zero(),
                          std::optional<double> depthGiven = std::nullopt) {
        if (!unitNormal("normal")) return;
        const Vec3 n = *vecMember(mine_, "normal");
        const std::optional<double> ha = a_.support(n), hb = b_.support(-n);
        if (!ha || !hb) {  // a plane or a ray: compare with cdlab's normal
            const std::optional<Vec3> t = theirVec("normal");
            if (!t) return;
            const double d = length(n - *t);
            if (!(d <= kUnitNormal)) fail("normal differs from cdlab's by " + num(d));
            return;
        }
        const double overlap = *ha + shiftA.dot(n) + *hb - shiftB.dot(n);
        if (overlapping) {
            const std::optional<double> depth = depthGiven ? depthGiven : theirNumber("depth");
            if (!depth) return;
            const double gap = overlap - *depth;
            if (!(gap <= tol_))
                fail("normal not a valid separating direction: moving b by the depth along it leaves an overlap of " +
                     num(gap) + " (support gap)");
            else if (depthGiven && !(-gap <= tol_))
                fail("normal does not realise your depth: moving b by the depth along it leaves a gap of " + num(-gap));
        } else {
            const std::optional<double> distance = theirNumber("distance");
            if (!distance) return;
            const double gap = *distance + overlap;
            if (!(gap <= tol_))
                fail("normal not a valid separating direction: the shapes' supports along it are " + num(-overlap) +
                     " apart, not the distance (support gap " + num(gap) + ")");
        }
    }

    // point_a − point_b = depth · normal (overlapping) or |point_b − point_a| = distance; lengths
    // scaled so that coordinates of 1e160 or 1e-160 neither overflow nor underflow.
    void witnessRelation(bool overlapping) {
        const std::optional<Vec3> pa = vecMember(mine_, "point_a"), pb = vecMember(mine_, "point_b");
        if (!pa || !pb) return;
        if (overlapping) {
            const std::optional<Vec3> n = vecMember(mine_, "normal");
            const std::optional<double> depth = numberMember(mine_, "depth");
            if (!n || !depth) return;
            const double off = length(*pa - *pb - *depth * *n);
            if (!(off <= tol_)) fail("point_a − point_b is not depth · normal: off by " + num(off));
        } else if (const std::optional<double> distance = numberMember(mine_, "distance")) {
            const double off = std::abs(length(*pb - *pa) - *distance);
            if (!(off <= tol_)) fail("|point_b − point_a| differs from your distance by " + num(off));
        }
    }

    // Whether cdlab's answer gives `key`: a key it leaves out (an overlapping pair's depth under
    // method vclip) is not asked of yours either.
    bool given(const std::string& key) const { return member(theirs_, key) != nullptr; }

    void distanceOp() {
        if (!verdict("intersect")) return;
        if (given("distance")) number("distance", tol_);
        if (theirVerdict("intersect")) return;
        if (given("point_a")) onShape("point_a", a_, "a");
        if (given("point_b")) onShape("point_b", b_, "b");
        witnessRelation(false);
    }

    void penetrationOp() {
        if (!verdict("intersect")) return;
        const bool overlapping = theirVerdict("intersect");
        const char* size = overlapping ? "depth" : "distance";
        if (given(size)) number(size, tol_);
        if (given("normal") && given(size)) separatingNormal(overlapping);
        if (given("point_a")) onShape("point_a", a_, "a");
        if (given("point_b")) onShape("point_b", b_, "b");
        witnessRelation(overlapping);
    }

    // Your or cdlab's region name (a string), or a reason.
    std::optional<std::string> regionOf(const Json& answer, const std::string& whose) {
        const Json* r = member(answer, "region");
        return required(r && r->is_string() ? std::optional<std::string>(r->get<std::string>()) : std::nullopt, whose,
                        "\"region\"", "");
    }
    std::optional<std::string> myRegion() { return regionOf(mine_, "your answer"); }
    std::optional<std::string> theirRegion() { return regionOf(theirs_, "cdlab's answer"); }

    // The query's list `key` of `count` points.
    std::optional<std::vector<Vec3>> queryPoints(const std::string& key, std::size_t count) {
        const Json* list = member(q_, key);
        if (!list || !list->is_array() || list->size() != count ||
            !std::all_of(list->begin(), list->end(), [](const Json& x) { return isVec(x); })) {
            fail("the query has no " + key + " of " + std::to_string(count) + " points");
            return std::nullopt;
        }
        std::vector<Vec3> v;
        for (const Json& x : *list) v.push_back(vec(x));
        return v;
    }

    void closestPointOp() {
        point("point");
        const std::optional<std::string> mineGiven = myRegion();
        const std::optional<std::string> theirGiven = theirRegion();
        if (!mineGiven || !theirGiven) return;
        std::string mineR = *mineGiven;
        const std::string& theirR = *theirGiven;
        if (mineR == "AC") mineR = "CA";  // Ericson's name for the edge of c and a
        if (mineR == theirR) return;
        // A point on a region boundary: the two regions' features give the same closest point.
        const std::optional<Vec3> pGiven = queryVec("point");
        const std::optional<std::vector<Vec3>> v = queryPoints("triangle", 3);
        const std::optional<Vec3> theirPoint = theirVec("point");
        if (!pGiven || !v || !theirPoint) return;
        const Vec3 p = *pGiven;
        const auto at = [&](char c) { return (*v)[std::size_t(c - 'A')]; };
        std::optional<Vec3> onFeature;
        if (mineR.size() == 1 && mineR[0] >= 'A' && mineR[0] <= 'C') onFeature = at(mineR[0]);
        else if (mineR == "AB" || mineR == "BC" || mineR == "CA") onFeature = closestOnSegment(p, at(mineR[0]), at(mineR[1]));
        else if (mineR == "ABC") onFeature = projectOnPlane(p, (*v)[0], (*v)[1], (*v)[2]);
        if (!onFeature || !(length(*onFeature - *theirPoint) <= tol_))
            fail("region differs: yours " + shortText(*mineGiven) + ", cdlab's " + theirR);
    }

    // As for the triangle: the point, and the region unless yours names a feature (vertex, edge,
    // face, or the inside "ABCD"; letters in any order) whose closest point is cdlab's point too.
    void closestPointTetrahedronOp() {
        point("point");
        const std::optional<std::string> mineGiven = myRegion();
        const std::optional<std::string> theirGiven = theirRegion();
        if (!mineGiven || !theirGiven) return;
        std::string mineR = *mineGiven;
        const std::string& theirR = *theirGiven;
        if (mineR.size() > 4) return fail("region \"" + shortText(mineR) + "\" names no feature of the tetrahedron");
        std::sort(mineR.begin(), mineR.end());
        if (mineR == theirR) return;
        if (mineR.empty()) return fail("region \"\" names no feature of the tetrahedron");
        const std::optional<Vec3> pGiven = queryVec("point");
        const std::optional<std::vector<Vec3>> tet = queryPoints("tetrahedron", 4);
        const std::optional<Vec3> theirPoint = theirVec("point");
        if (!pGiven || !tet || !theirPoint) return;
        const Vec3 p = *pGiven;
        std::vector<Vec3> feature;
        for (const char c : mineR) {
            if (c < 'A' || c > 'D' || (!feature.empty() && mineR[feature.size() - 1] == c))
                return fail("region \"" + shortText(*mineGiven) + "\" names no feature of the tetrahedron");
            feature.push_back((*tet)[std::size_t(c - 'A')]);
        }
        std::optional<Vec3> onFeature;
        if (feature.size() == 1) onFeature = feature[0];
        else if (feature.size() == 2) onFeature = closestOnSegment(p, feature[0], feature[1]);
        else if (feature.size() == 3) onFeature = projectOnPlane(p, feature[0], feature[1], feature[2]);
        else {
            onFeature = p;  // inside: the point itself
        }
        if (!onFeature || !(length(*onFeature - *theirPoint) <= tol_))
            fail("region differs: yours " + shortText(*mineGiven) + ", cdlab's " + theirR);
    }

    void raycastOp() {
        if (!verdict("hit") || !theirVerdict("hit")) return;
        const Json* ray = member(q_, "ray");
        const std::optional<Vec3> d = ray ? vecMember(*ray, "direction") : std::nullopt;
        if (!d) return fail("the query has no ray direction [x, y, z]");
        number("t", tol_ / std::max(length(*d), 1e-300));
        point("point");
        const bool inside = flag(theirs_, "inside", false, "cdlab's");
        if (flag(mine_, "inside", false, "your") != inside)
            return fail(std::string("inside differs: cdlab's origin is ") + (inside ? "" : "not ") + "inside the shape");
        if (inside || !unitNormal("normal")) return;
        // The normal of a supporting plane at the hit point (any of the normal cone at an edge).
        const Vec3 n = *vecMember(mine_, "normal");
        const std::optional<double> h = shape_.support(n);
        if (!h) {
            const std::optional<Vec3> t = theirVec("normal");
            if (t && !(std::min(length(n - *t), length(n + *t)) <= kUnitNormal)) fail("normal differs from cdlab's");
            return;
        }
        const std::optional<Vec3> hit = theirVec("point");
        if (!hit) return;
        const double gap = *h - n.dot(*hit);
        if (!(gap <= tol_)) fail("normal is not outward at the hit point: the shape reaches " + num(gap) + " beyond its plane");
    }

    void timeOfImpactOp() {
        if (!verdict("hit") || !theirVerdict("hit")) return;
        const bool initially = flag(theirs_, "initially_overlapping", false, "cdlab's");
        if (flag(mine_, "initially_overlapping", false, "your") != initially)
            return fail(std::string("initially_overlapping differs: cdlab's is ") + (initially ? "true" : "false"));
        if (initially) return;
        const Vec3 ma = vecMember(q_, "motion_a").value_or(Vec3::Zero());
        const Vec3 mb = vecMember(q_, "motion_b").value_or(Vec3::Zero());
        number("t", tol_ / std::max(length(ma - mb), 1e-300));
        const std::optional<double> tGiven = numberMember(mine_, "t");
        if (!tGiven) return;
        const double t = *tGiven;
        onShape("point_a", a_, "a (at time t)", t * ma);
        onShape("point_b", b_, "b (at time t)", t * mb);
        // Touching at time t: the supports along n meet (overlap 0 = cdlab's depth 0).
        Json touching = theirs_;
        touching["depth"] = 0.0;
        Checker c(q_, mine_, touching, tol_, a_, b_, shape_);
        c.separatingNormal(true, t * ma, t * mb);
        reasons.insert(reasons.end(), c.reasons.begin(), c.reasons.end());
    }

    // A colliding contact's depth: the least overlap, or, with the face preference of the SAT
    // (core/contact/contact_sat.h, faceBiasRelative f), a face axis whose overlap is at most
    // (1 + f) x the least overlap: depth <= least overlap · (1 + f) + tolerance. cdlab's depth D
    // obeys the same bound, so the least overlap lies in [(D - tol) / (1 + f), D]: yours passes in
    // [(D - tol) / (1 + f) - tol, D · (1 + f) + tol], and your normal must realise your depth (the
    // overlap of the projections on it is your depth). Returns your depth when it passes.
    std::optional<double> contactDepth() {
        const std::optional<double> m = myNumber("depth");
        const std::optional<double> t = theirNumber("depth");
        if (!m || !t) return std::nullopt;
        const double f = SatContactOptions{}.faceBiasRelative;
        const double lo = (*t - tol_) / (1 + f) - tol_, hi = *t * (1 + f) + tol_;
        if (!(*m >= lo && *m <= hi)) {
            fail("depth " + value(*m) + " outside [" + value(lo) + ", " + value(hi) + "] (cdlab's " + value(*t) +
                 ": the least overlap, or a face axis within " + num(f) + " of it, within tolerance " + num(tol_) + ")");
            return std::nullopt;
        }
        return m;
    }

    void contactOp() {
        if (!verdict("colliding")) return;
        const bool colliding = theirVerdict("colliding");
        const char* size = colliding ? "depth" : "distance";
        if (!colliding) {
            if (given(size)) number(size, tol_);
            if (given("normal") && given(size)) separatingNormal(false);
        } else if (given(size)) {
            const std::optional<double> depth = contactDepth();
            if (depth && given("normal")) separatingNormal(true, Vec3::Zero(), Vec3::Zero(), depth);
        }
        const char* list = colliding ? "points" : "closest";
        const Json* entries = member(mine_, list);
        if (!entries || !entries->is_array() || entries->empty())
            return fail(std::string("your answer has no \"") + list + "\" list");
        const Json* maxGiven = member(q_, "max_points");
        const std::size_t maxPoints =
            maxGiven && maxGiven->is_number_unsigned() ? std::min<std::size_t>(maxGiven->get<std::size_t>(), kMaxContactEntries) : 4;
        if (colliding && entries->size() > maxPoints)
            return fail("more points (" + std::to_string(entries->size()) + ") than max_points " + std::to_string(maxPoints));
        if (entries->size() > kMaxContactEntries)
            return fail(std::string("more ") + list + " entries (" + std::to_string(entries->size()) + ") than the " +
                        std::to_string(kMaxContactEntries) + " a contact may have");
        const std::optional<double> myDepth = numberMember(mine_, "depth");
        for (std::size_t i = 0; i < entries->size(); ++i) {
            const Json& p = (*entries)[i];
            Checker c(q_, p, theirs_, tol_, a_, b_, shape_);
            c.onShape("point_a", a_, "a");
            c.onShape("point_b", b_, "b");
            const std::optional<double> depth = numberMember(p, "depth");
            if (colliding && depth && myDepth && *depth > *myDepth + tol_) c.fail("its depth is deeper than the contact's depth");
            for (const std::string& r : c.reasons) fail(std::string(list) + "[" + std::to_string(i) + "]: " + r);
        }
    }

    // Keys of cdlab's answer, compared recursively: numbers within tol_ (relative to the value
    // for large ones, as mass properties are). The echoed "id" and cdlab's own "trace" are not
    // part of the answer.
    void generic(const Json& t, const Json& m, const std::string& path) {
        if (t.is_object()) {
            if (!m.is_object()) return fail((path.empty() ? "your answer" : path) + " is not an object");
            for (auto it = t.begin(); it != t.end(); ++it) {
                if (path.empty() && (it.key() == "trace" || it.key() == "id")) continue;
                const std::string p = path.empty() ? it.key() : path + "." + it.key();
                const Json* mine = member(m, it.key());
                if (!mine) fail("your answer has no " + p);
                else generic(it.value(), *mine, p);
            }
        } else if (t.is_array()) {
            if (!m.is_array() || m.size() != t.size()) return fail(path + " has not " + std::to_string(t.size()) + " entries");
            for (std::size_t i = 0; i < t.size(); ++i) generic(t[i], m[i], path + "[" + std::to_string(i) + "]");
        } else if (t.is_number()) {
            if (!m.is_number()) return fail(path + " is not a number");
            const double a = t.get<double>(), b = m.get<double>(), tol = std::max(tol_, 1e-9 * std::abs(a));
            if (!(std::abs(a - b) <= tol)) fail(path + " off by " + num(std::abs(a - b)) + ", over tolerance " + num(tol));
        } else if (t != m) {
            fail(path + " differs: yours " + shortText(m.dump(-1, ' ', false, Json::error_handler_t::replace)) +
                 ", cdlab's " + shortText(t.dump(-1, ' ', false, Json::error_handler_t::replace)));
        }
    }
};

// checkLine's work; may throw (checkLine turns any exception into a reason).
CheckResult checkOneLine(const std::string& line, std::size_t lineNumber, const CheckOptions& options) {
    CheckResult r;
    const std::string where = "line " + std::to_string(lineNumber) + ": ";
    if (line.size() > kMaxQueryLineBytes) {
        r.reasons.push_back(where + "the line is " + std::to_string(line.size()) + " bytes, over the limit of " +
                            std::to_string(kMaxQueryLineBytes >> 20) + " MiB for one line");
        return r;
    }
    if (!(options.tolerance > 0) || !(options.tolerance <= kMaxCheckTolerance)) {
        r.reasons.push_back(where + "the check's tolerance " + num(options.tolerance) + " is not in (0, " +
                            num(kMaxCheckTolerance) + "]");
        return r;
    }
    Json q;
    try {
        q = parseJson(line, "check");
    } catch (const InputError& e) {
        r.reasons.push_back(where + e.what());
        return r;
    }
    if (const Json* id = member(q, "id")) r.id = *id;
    const Json* answer = member(q, "answer");
    if (!answer || !answer->is_object()) {
        r.reasons.push_back(where + "expected a query with your \"answer\": {...}");
        return r;
    }
    const Json* opGiven = member(q, "op");
    if (!opGiven || !opGiven->is_string()) {
        r.reasons.push_back(where + "expected \"op\": the name of the query's operation, a string" +
                            (opGiven ? ", got " + shortText(opGiven->dump(-1, ' ', false, Json::error_handler_t::replace)) : ""));
        return r;
    }
    const std::string op = opGiven->get<std::string>();
    const Json mine = *answer;
    q.erase("answer");
    double relative = options.tolerance;
    if (const Json* lineTolerance = member(q, "tolerance")) {
        if (!lineTolerance->is_number() || !(lineTolerance->get<double>() > 0)) {
            r.reasons.push_back(where + "\"tolerance\" must be a positive number");
            return r;
        }
        relative = lineTolerance->get<double>();
        if (!(relative <= options.tolerance)) {
            r.reasons.push_back(where + "\"tolerance\" " + num(relative) + " is over the check's tolerance " +
                                num(options.tolerance) + " (--tolerance): a line may tighten it, never loosen it");
            return r;
        }
        q.erase("tolerance");
    }
    std::optional<Json> trace;
    if (const Json* given = member(q, "trace"); given && !given->is_boolean()) {
        trace = *given;
        q.erase("trace");
    }
    const Json theirs = answerQuery(q.dump(), lineNumber);
    r.query = q;
    r.yours = mine;
    r.cdlab = theirs;
    // The query's shapes, read once for every comparison and trace step of this line.
    const ShapeModel a = member(q, "a") ? ShapeModel(*member(q, "a")) : ShapeModel();
    const ShapeModel b = member(q, "b") ? ShapeModel(*member(q, "b")) : ShapeModel();
    const ShapeModel shape = member(q, "shape") ? ShapeModel(*member(q, "shape")) : ShapeModel();
    Size size;
    size.add(q);
    for (const ShapeModel* s : {&a, &b, &shape}) size.addBox(*s);
    const double tol = size.tolerance(relative);
    try {
        Checker c(q, mine, theirs, tol, a, b, shape);
        c.run(op);
        // The trace is checked whatever the answer's verdict, its first broken step reported first: a
        // wrong distance is the symptom, the step the cause (check_test "the broken step of a wrong
        // answer"). A query cdlab answers with an error has no run to check a trace against. A trace
        // that cannot be read says so beside the answer's reasons, which stay.
        if (trace && !member(theirs, "error")) {
            try {
                checkTrace(op, q, *trace, tol, a, b, r.reasons, r.traceDivergence, r.traceAlgorithm);
            } catch (const std::bad_alloc&) {
                throw;
            } catch (const std::exception& e) {
                r.reasons.push_back(std::string("your trace could not be read (a key of the wrong type?): ") + e.what());
            }
        }
        r.reasons.insert(r.reasons.end(), c.reasons.begin(), c.reasons.end());
        if (trace) r.trace = *trace;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {  // a key of yours with another type than cdlab's answer has
        r.reasons.push_back(std::string("your answer or trace could not be read (a key of the wrong type?): ") +
                            e.what());
    }
    r.pass = r.reasons.empty();
    return r;
}

}  // namespace

namespace {

// A failed line with one reason; with no reason when even that cannot be allocated (runCheck then
// prints the line's FAIL bare). Never throws: checkLine is noexcept.
CheckResult failedLine(std::size_t lineNumber, const char* what, const char* detail = "") noexcept {
    CheckResult r;
    try {
        r.reasons.push_back("line " + std::to_string(lineNumber) + ": " + what + detail);
    } catch (...) {
    }
    return r;
}

}  // namespace

CheckResult checkLine(const std::string& line, std::size_t lineNumber, const CheckOptions& options) noexcept {
    try {
        return checkOneLine(line, lineNumber, options);
    } catch (const std::bad_alloc&) {
        return failedLine(lineNumber, "out of memory checking this line");
    } catch (const std::exception& e) {
        return failedLine(lineNumber, "could not be checked: ", e.what());
    } catch (...) {
        return failedLine(lineNumber, "could not be checked");
    }
}

bool selfCheckPasses(const std::string& queryLine, std::string* why) {
    const Json theirs = answerQuery(queryLine);
    if (member(theirs, "error")) return true;  // nothing to feed back
    Json line;
    try {
        line = parseJson(queryLine, "check");
    } catch (const std::exception&) {
        return true;  // not reached: answerQuery read the line with the same reader
    }
    if (!line.is_object()) return true;
    line["answer"] = theirs;
    const CheckResult r = checkLine(line.dump(-1, ' ', false, Json::error_handler_t::replace), 1, CheckOptions{});
    if (!r.pass && why) {
        *why = "";
        for (const std::string& x : r.reasons) *why += (why->empty() ? "" : "; ") + x;
    }
    return r.pass;
}

namespace {

// --figures: the failing line's figure, or why it has none; the GL context is made on first use.
std::string figureFor(const CheckResult& r, std::size_t lineNumber, const CheckOptions& options,
                      std::unique_ptr<render::GlContext>& gl) {
    if (r.query.is_null()) return "no figure: the line could not be read";
    // The reasons as the verdict line prints them (printable): what your answer echoes cannot put
    // lines of its own on the figure either (check_figure_test "escaped on the figure").
    std::vector<std::string> reasons;
    for (const std::string& reason : r.reasons) reasons.push_back(printable(reason));
    try {
        const bool traceFigure = r.traceDivergence >= 0 && (r.traceAlgorithm == "gjk" || r.traceAlgorithm == "epa") &&
                                 r.query.value("op", "") != "closest_point_triangle";
        if (traceFigure)  // refused before a GL context is made or any hull built
            if (const std::string why = traceFigureRefusal(r.query); !why.empty()) return why;
        std::filesystem::create_directories(options.figuresDir);
        if (!gl) gl = createContext(false);
        const std::string path =
            (std::filesystem::path(options.figuresDir) / ("line_" + std::to_string(lineNumber) + ".png")).string();
        std::string title = "line " + std::to_string(lineNumber);
        if (!r.id.is_null()) title += " (id " + printable(idText(r.id)) + ")";
        const std::string why =
            r.query.value("op", "") == "closest_point_triangle"
                ? writeRegionFigure(*gl, r.query, r.cdlab, r.yours, title + ": closest_point_triangle", reasons, path)
            : r.traceDivergence >= 0 && (r.traceAlgorithm == "gjk" || r.traceAlgorithm == "epa")
                ? writeTraceStepFigure(*gl, r.query, r.trace, r.traceAlgorithm, r.traceDivergence,
                                       title + ": " + r.query.value("op", "") + ", " +
                                           (r.traceAlgorithm == "gjk" ? "GJK" : "EPA") + " iteration " +
                                           std::to_string(r.traceDivergence),
                                       reasons, path)
                : writeCheckFigure(*gl, r.query, r.cdlab, r.yours, title + ": " + r.query.value("op", ""), reasons,
                                   path);
        return why.empty() ? "figure " + path : why;
    } catch (const std::exception& e) {
        return std::string("no figure: ") + e.what();
    }
}

}  // namespace

namespace {

enum class CheckLineRead { Line, TooLong, End };

// Reads one line (the '\n' dropped) keeping at most `limit` bytes; a longer line is read to its
// end without being kept, its length counted in `length`, so the next line is still checked.
CheckLineRead readCheckLine(std::streambuf& in, std::string& line, std::size_t limit, std::size_t& length) {
    line.clear();
    length = 0;
    bool any = false;
    for (;;) {
        const int c = in.sbumpc();
        if (c == std::char_traits<char>::eof())
            return !any ? CheckLineRead::End : length > limit ? CheckLineRead::TooLong : CheckLineRead::Line;
        any = true;
        if (c == '\n') return length > limit ? CheckLineRead::TooLong : CheckLineRead::Line;
        if (length < limit) {
            // Grown by doubling, but never past the limit: the buffer holds at most `limit` bytes.
            if (line.size() == line.capacity()) line.reserve(std::min(limit, std::max<std::size_t>(2 * line.capacity(), 64)));
            line.push_back(char(c));
        }
        ++length;
    }
}

}  // namespace

int runCheck(std::istream& in, std::ostream& out, const CheckOptions& options) {
    std::string line;
    std::size_t lineNumber = 0, passed = 0, failed = 0, length = 0;
    std::unique_ptr<render::GlContext> gl;  // --figures only
    // Reading stops when the verdicts can no longer be written (a full disk, a closed pipe).
    for (CheckLineRead read; out && (read = readCheckLine(*in.rdbuf(), line, kMaxQueryLineBytes, length)) != CheckLineRead::End;) {
        ++lineNumber;
        CheckResult r;
        if (read == CheckLineRead::TooLong) {
            line.clear();
            line.shrink_to_fit();
            r.reasons.push_back("line " + std::to_string(lineNumber) + ": the line is " + std::to_string(length) +
                                " bytes, over the limit of " + std::to_string(kMaxQueryLineBytes >> 20) +
                                " MiB for one line");
        } else {
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            r = checkLine(line, lineNumber, options);
        }
        // The verdict line is built whole and escaped (printable): whatever your answer holds,
        // it prints as one line with no terminal control (tests/app/check/check_test.cpp, "escaped").
        std::string verdict = "line " + std::to_string(lineNumber);
        if (!r.id.is_null()) verdict += " (id " + idText(r.id) + ")";
        if (r.pass) {
            verdict += ": pass";
            ++passed;
        } else {
            verdict += ": FAIL";
            for (std::size_t i = 0; i < r.reasons.size(); ++i) verdict += (i ? "; " : ": ") + r.reasons[i];
            if (!options.figuresDir.empty()) verdict += " [" + figureFor(r, lineNumber, options, gl) + "]";
            ++failed;
        }
        out << printable(verdict) << "\n";
    }
    out << passed << " passed, " << failed << " failed\n";
    out.flush();
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
