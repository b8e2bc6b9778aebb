#include "demos/check/check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "demos/check/check_figure.h"
#include "demos/check/check_values.h"
#include "demos/check/trace_check.h"
#include "demos/harness/scene_runner.h"
#include "demos/query/query.h"
#include "demos/query/query_json.h"
#include "demos/query/query_shapes.h"

namespace cdlab::demos {

namespace {

constexpr double kUnitNormal = 1e-6;  // |n| may differ from 1 by this (a normalised double is ~1e-16 off)

class Checker {
public:
    Checker(const Json& query, const Json& mine, const Json& theirs, double tol)
        : q_(query), mine_(mine), theirs_(theirs), tol_(tol) {}

    std::vector<std::string> reasons;

    void run(const std::string& op) {
        if (theirs_.contains("error")) {
            if (!mine_.contains("error")) fail("cdlab answers an error (" + theirs_["error"].get<std::string>() + "), yours does not");
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

    void fail(const std::string& why) { reasons.push_back(why); }

    bool has(const std::string& key, bool wantVec) {
        const bool ok = mine_.contains(key) && (wantVec ? isVec(mine_[key]) : mine_[key].is_number());
        if (!ok) fail("your answer has no " + key + (wantVec ? " [x, y, z]" : " number"));
        return ok;
    }

    bool verdict(const std::string& key) {
        if (!mine_.contains(key) || !mine_[key].is_boolean()) {
            fail("your answer has no \"" + key + "\" (true or false)");
            return false;
        }
        if (mine_[key] != theirs_[key]) {
            fail("verdict differs: yours " + key + " = " + mine_[key].dump() + ", cdlab's " + theirs_[key].dump());
            return false;
        }
        return true;
    }

    void number(const std::string& key, double tol) {
        if (!has(key, false)) return;
        const double m = mine_[key].get<double>(), t = theirs_[key].get<double>();
        if (!(std::abs(m - t) <= tol))
            fail(key + " off by " + num(std::abs(m - t)) + " (yours " + value(m) + ", cdlab's " + value(t) +
                 "), over tolerance " + num(tol));
    }

    void point(const std::string& key) {
        if (!has(key, true)) return;
        const double d = (vec(mine_[key]) - vec(theirs_[key])).norm();
        if (!(d <= tol_)) fail(key + " off by " + num(d) + ", over tolerance " + num(tol_));
    }

    // A witness point must lie on (or in) its shape; it need not be cdlab's.
    void onShape(const std::string& key, const Json& shape, const char* name, const Vec3& shift = Vec3::Zero()) {
        if (!has(key, true)) return;
        const std::optional<double> d = distanceTo(vec(mine_[key]) - shift, shape);
        if (d && !(*d <= tol_)) fail(key + " is not on shape " + name + ": " + num(*d) + " from it");
    }

    bool unitNormal(const std::string& key) {
        if (!has(key, true)) return false;
        const double len = vec(mine_[key]).norm();
        if (!(std::abs(len - 1) <= kUnitNormal)) {
            fail(key + " is not a unit vector: |n| = " + num(len));
            return false;
        }
        return true;
    }

    // Overlapping: moving b by depth along your normal must leave the shapes touching, i.e. the
    // overlap of their projections on n, h_a(n) + h_b(-n), is cdlab's (minimal) depth.
    void separatingNormal(bool overlapping, const Vec3& shiftA = Vec3::Zero(), const Vec3& shiftB = Vec3::Zero()) {
        if (!unitNormal("normal")) return;
        const Vec3 n = vec(mine_["normal"]);
        const std::optional<double> ha = support(q_["a"], n), hb = support(q_["b"], -n);
        if (!ha || !hb) {  // a plane or a ray: compare with cdlab's normal
            const double d = (n - vec(theirs_["normal"])).norm();
            if (!(d <= kUnitNormal)) fail("normal differs from cdlab's by " + num(d));
            return;
        }
        const double overlap = *ha + shiftA.dot(n) + *hb - shiftB.dot(n);
        if (overlapping) {
            const double gap = overlap - theirs_["depth"].get<double>();
            if (!(gap <= tol_))
                fail("normal not a valid separating direction: moving b by the depth along it leaves an overlap of " +
                     num(gap) + " (support gap)");
        } else {
            const double gap = theirs_["distance"].get<double>() + overlap;
            if (!(gap <= tol_))
                fail("normal not a valid separating direction: the shapes' supports along it are " + num(-overlap) +
                     " apart, not the distance (support gap " + num(gap) + ")");
        }
    }

    // point_a − point_b = depth · normal (overlapping) or |point_b − point_a| = distance.
    void witnessRelation(bool overlapping) {
        if (!mine_.contains("point_a") || !mine_.contains("point_b") || !isVec(mine_["point_a"]) || !isVec(mine_["point_b"]))
            return;
        const Vec3 pa = vec(mine_["point_a"]), pb = vec(mine_["point_b"]);
        if (overlapping) {
            if (!mine_.contains("normal") || !isVec(mine_["normal"]) || !mine_["depth"].is_number()) return;
            const double off = (pa - pb - mine_["depth"].get<double>() * vec(mine_["normal"])).norm();
            if (!(off <= tol_)) fail("point_a − point_b is not depth · normal: off by " + num(off));
        } else if (mine_["distance"].is_number()) {
            const double off = std::abs((pb - pa).norm() - mine_["distance"].get<double>());
            if (!(off <= tol_)) fail("|point_b − point_a| differs from your distance by " + num(off));
        }
    }

    void distanceOp() {
        if (!verdict("intersect")) return;
        number("distance", tol_);
        if (theirs_["intersect"] == true) return;
        onShape("point_a", q_["a"], "a");
        onShape("point_b", q_["b"], "b");
        witnessRelation(false);
    }

    void penetrationOp() {
        if (!verdict("intersect")) return;
        const bool overlapping = theirs_["intersect"] == true;
        number(overlapping ? "depth" : "distance", tol_);
        separatingNormal(overlapping);
        onShape("point_a", q_["a"], "a");
        onShape("point_b", q_["b"], "b");
        witnessRelation(overlapping);
    }

    void closestPointOp() {
        point("point");
        if (!mine_.contains("region") || !mine_["region"].is_string()) return fail("your answer has no \"region\"");
        std::string mineR = mine_["region"];
        const std::string theirR = theirs_["region"];
        if (mineR == "AC") mineR = "CA";  // Ericson's name for the edge of c and a
        if (mineR == theirR) return;
        // A point on a region boundary: the two regions' features give the same closest point.
        const Vec3 p = vec(q_["point"]);
        const Vec3 v[3] = {vec(q_["triangle"][0]), vec(q_["triangle"][1]), vec(q_["triangle"][2])};
        const auto at = [&](char c) { return v[c - 'A']; };
        std::optional<Vec3> onFeature;
        if (mineR.size() == 1 && mineR[0] >= 'A' && mineR[0] <= 'C') onFeature = at(mineR[0]);
        else if (mineR == "AB" || mineR == "BC" || mineR == "CA") {
            const Vec3 a = at(mineR[0]), b = at(mineR[1]);
            const double t = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
            onFeature = a + t * (b - a);
        } else if (mineR == "ABC") {
            const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
            if (n.squaredNorm() > 0) onFeature = p - n * (n.dot(p - v[0]) / n.squaredNorm());
        }
        if (!onFeature || !((*onFeature - vec(theirs_["point"])).norm() <= tol_))
            fail("region differs: yours " + mineR + ", cdlab's " + theirR);
    }

    // As for the triangle: the point, and the region unless yours names a feature (vertex, edge,
    // face, or the inside "ABCD"; letters in any order) whose closest point is cdlab's point too.
    void closestPointTetrahedronOp() {
        point("point");
        if (!mine_.contains("region") || !mine_["region"].is_string()) return fail("your answer has no \"region\"");
        std::string mineR = mine_["region"];
        std::sort(mineR.begin(), mineR.end());
        const std::string theirR = theirs_["region"];
        if (mineR == theirR) return;
        if (mineR.empty() || mineR.size() > 4) return fail("region \"" + mineR + "\" names no feature of the tetrahedron");
        const Vec3 p = vec(q_["point"]);
        std::vector<Vec3> feature;
        for (const char c : mineR) {
            if (c < 'A' || c > 'D' || (!feature.empty() && mineR[feature.size() - 1] == c))
                return fail("region \"" + std::string(mine_["region"]) + "\" names no feature of the tetrahedron");
            feature.push_back(vec(q_["tetrahedron"][c - 'A']));
        }
        std::optional<Vec3> onFeature;
        if (feature.size() == 1) onFeature = feature[0];
        else if (feature.size() == 2) {
            const Vec3 a = feature[0], b = feature[1];
            const double t = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
            onFeature = a + t * (b - a);
        } else if (feature.size() == 3) {
            const Vec3 n = (feature[1] - feature[0]).cross(feature[2] - feature[0]);
            if (n.squaredNorm() > 0) onFeature = p - n * (n.dot(p - feature[0]) / n.squaredNorm());
        } else {
            onFeature = p;  // inside: the point itself
        }
        if (!onFeature || !((*onFeature - vec(theirs_["point"])).norm() <= tol_))
            fail("region differs: yours " + std::string(mine_["region"]) + ", cdlab's " + theirR);
    }

    void raycastOp() {
        if (!verdict("hit") || theirs_["hit"] == false) return;
        const Vec3 d = vec(q_["ray"]["direction"]);
        number("t", tol_ / std::max(d.norm(), 1e-300));
        point("point");
        const bool inside = theirs_.value("inside", false);
        if (mine_.value("inside", false) != inside)
            return fail(std::string("inside differs: cdlab's origin is ") + (inside ? "" : "not ") + "inside the shape");
        if (inside || !unitNormal("normal")) return;
        // The normal of a supporting plane at the hit point (any of the normal cone at an edge).
        const Vec3 n = vec(mine_["normal"]);
        const std::optional<double> h = support(q_["shape"], n);
        if (!h) {
            const Vec3 t = vec(theirs_["normal"]);
            if (!(std::min((n - t).norm(), (n + t).norm()) <= kUnitNormal)) fail("normal differs from cdlab's");
            return;
        }
        const double gap = *h - n.dot(vec(theirs_["point"]));
        if (!(gap <= tol_)) fail("normal is not outward at the hit point: the shape reaches " + num(gap) + " beyond its plane");
    }

    void timeOfImpactOp() {
        if (!verdict("hit") || theirs_["hit"] == false) return;
        const bool initially = theirs_.value("initially_overlapping", false);
        if (mine_.value("initially_overlapping", false) != initially)
            return fail(std::string("initially_overlapping differs: cdlab's is ") + (initially ? "true" : "false"));
        if (initially) return;
        const Vec3 ma = q_.contains("motion_a") ? vec(q_["motion_a"]) : Vec3::Zero();
        const Vec3 mb = q_.contains("motion_b") ? vec(q_["motion_b"]) : Vec3::Zero();
        number("t", tol_ / std::max((ma - mb).norm(), 1e-300));
        if (!mine_["t"].is_number()) return;
        const double t = mine_["t"].get<double>();
        onShape("point_a", q_["a"], "a (at time t)", t * ma);
        onShape("point_b", q_["b"], "b (at time t)", t * mb);
        // Touching at time t: the supports along n meet (overlap 0 = cdlab's depth 0).
        Json touching = theirs_;
        touching["depth"] = 0.0;
        Checker c(q_, mine_, touching, tol_);
        c.separatingNormal(true, t * ma, t * mb);
        reasons.insert(reasons.end(), c.reasons.begin(), c.reasons.end());
    }

    void contactOp() {
        if (!verdict("colliding")) return;
        const bool colliding = theirs_["colliding"] == true;
        number(colliding ? "depth" : "distance", tol_);
        separatingNormal(colliding);
        const char* list = colliding ? "points" : "closest";
        if (!mine_.contains(list) || !mine_[list].is_array() || mine_[list].empty())
            return fail(std::string("your answer has no \"") + list + "\" list");
        const std::size_t maxPoints = q_.value("max_points", std::size_t(4));
        if (colliding && mine_[list].size() > maxPoints)
            fail("more points (" + std::to_string(mine_[list].size()) + ") than max_points " + std::to_string(maxPoints));
        for (std::size_t i = 0; i < mine_[list].size(); ++i) {
            const Json& p = mine_[list][i];
            Checker c(q_, p, theirs_, tol_);
            c.onShape("point_a", q_["a"], "a");
            c.onShape("point_b", q_["b"], "b");
            if (colliding && p.contains("depth") && p["depth"].is_number() && mine_["depth"].is_number() &&
                p["depth"].get<double>() > mine_["depth"].get<double>() + tol_)
                c.fail("its depth is deeper than the contact's depth");
            for (const std::string& r : c.reasons) fail(std::string(list) + "[" + std::to_string(i) + "]: " + r);
        }
    }

    // Keys of cdlab's answer, compared recursively: numbers within tol_ (relative to the value
    // for large ones, as mass properties are).
    void generic(const Json& t, const Json& m, const std::string& path) {
        if (t.is_object()) {
            if (!m.is_object()) return fail((path.empty() ? "your answer" : path) + " is not an object");
            for (auto it = t.begin(); it != t.end(); ++it) {
                if (it.key() == "trace") continue;
                const std::string p = path.empty() ? it.key() : path + "." + it.key();
                if (!m.contains(it.key())) fail("your answer has no " + p);
                else generic(it.value(), m[it.key()], p);
            }
        } else if (t.is_array()) {
            if (!m.is_array() || m.size() != t.size()) return fail(path + " has not " + std::to_string(t.size()) + " entries");
            for (std::size_t i = 0; i < t.size(); ++i) generic(t[i], m[i], path + "[" + std::to_string(i) + "]");
        } else if (t.is_number()) {
            if (!m.is_number()) return fail(path + " is not a number");
            const double a = t.get<double>(), b = m.get<double>(), tol = std::max(tol_, 1e-9 * std::abs(a));
            if (!(std::abs(a - b) <= tol)) fail(path + " off by " + num(std::abs(a - b)) + ", over tolerance " + num(tol));
        } else if (t != m) {
            fail(path + " differs: yours " + m.dump() + ", cdlab's " + t.dump());
        }
    }
};

}  // namespace

CheckResult checkLine(const std::string& line, std::size_t lineNumber, const CheckOptions& options) {
    CheckResult r;
    Json q;
    try {
        q = parseJson(line, "check");
    } catch (const InputError& e) {
        r.reasons.push_back(std::string("line ") + std::to_string(lineNumber) + ": " + e.what());
        return r;
    }
    if (q.is_object() && q.contains("id")) r.id = q["id"];
    if (!q.is_object() || !q.contains("answer") || !q["answer"].is_object()) {
        r.reasons.push_back("line " + std::to_string(lineNumber) + ": expected a query with your \"answer\": {...}");
        return r;
    }
    const Json mine = q["answer"];
    q.erase("answer");
    double relative = options.tolerance;
    if (q.contains("tolerance")) {
        if (!q["tolerance"].is_number() || !(q["tolerance"].get<double>() > 0)) {
            r.reasons.push_back("line " + std::to_string(lineNumber) + ": \"tolerance\" must be a positive number");
            return r;
        }
        relative = q["tolerance"].get<double>();
        q.erase("tolerance");
    }
    std::optional<Json> trace;
    if (q.contains("trace") && !q["trace"].is_boolean()) {
        trace = q["trace"];
        q.erase("trace");
    }
    const Json theirs = answerQuery(q.dump(), lineNumber);
    r.query = q;
    r.yours = mine;
    r.cdlab = theirs;
    Size size;
    size.add(q);
    const double tol = size.tolerance(relative);
    const std::string op = q.value("op", "");
    try {
        Checker c(q, mine, theirs, tol);
        c.run(op);
        r.reasons = c.reasons;
        // A query cdlab answers with an error (and so do you) has no run to check a trace against.
        if (trace && r.reasons.empty() && !theirs.contains("error"))
            checkTrace(op, q, *trace, tol, r.reasons, r.traceDivergence, r.traceAlgorithm);
        if (trace) r.trace = *trace;
    } catch (const std::exception& e) {  // a key of yours with another type than cdlab's answer has
        r.reasons.push_back(std::string("your answer or trace could not be read (a key of the wrong type?): ") +
                            e.what());
    }
    r.pass = r.reasons.empty();
    return r;
}

namespace {

// --figures: the failing line's figure, or why it has none; the GL context is made on first use.
std::string figureFor(const CheckResult& r, std::size_t lineNumber, const CheckOptions& options,
                      std::unique_ptr<render::GlContext>& gl) {
    if (r.query.is_null()) return "no figure: the line could not be read";
    try {
        std::filesystem::create_directories(options.figuresDir);
        if (!gl) gl = createContext(false);
        const std::string path =
            (std::filesystem::path(options.figuresDir) / ("line_" + std::to_string(lineNumber) + ".png")).string();
        std::string title = "line " + std::to_string(lineNumber);
        if (!r.id.is_null()) title += " (id " + r.id.dump(-1, ' ', false, Json::error_handler_t::replace) + ")";
        const std::string why =
            r.query.value("op", "") == "closest_point_triangle"
                ? writeRegionFigure(*gl, r.query, r.cdlab, r.yours, title + ": closest_point_triangle", r.reasons, path)
            : r.traceDivergence >= 0 && (r.traceAlgorithm == "gjk" || r.traceAlgorithm == "epa")
                ? writeTraceStepFigure(*gl, r.query, r.trace, r.traceAlgorithm, r.traceDivergence,
                                       title + ": " + r.query.value("op", "") + ", " +
                                           (r.traceAlgorithm == "gjk" ? "GJK" : "EPA") + " iteration " +
                                           std::to_string(r.traceDivergence),
                                       r.reasons, path)
                : writeCheckFigure(*gl, r.query, r.cdlab, r.yours, title + ": " + r.query.value("op", ""), r.reasons,
                                   path);
        return why.empty() ? "figure " + path : why;
    } catch (const std::exception& e) {
        return std::string("no figure: ") + e.what();
    }
}

}  // namespace

int runCheck(std::istream& in, std::ostream& out, const CheckOptions& options) {
    std::string line;
    std::size_t lineNumber = 0, passed = 0, failed = 0;
    std::unique_ptr<render::GlContext> gl;  // --figures only
    while (std::getline(in, line)) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const CheckResult r = checkLine(line, lineNumber, options);
        out << "line " << lineNumber;
        if (!r.id.is_null()) out << " (id " << r.id.dump(-1, ' ', false, Json::error_handler_t::replace) << ")";
        if (r.pass) {
            out << ": pass\n";
            ++passed;
        } else {
            out << ": FAIL";
            for (std::size_t i = 0; i < r.reasons.size(); ++i) out << (i ? "; " : ": ") << r.reasons[i];
            if (!options.figuresDir.empty()) out << " [" << figureFor(r, lineNumber, options, gl) << "]";
            out << "\n";
            ++failed;
        }
    }
    out << passed << " passed, " << failed << " failed\n";
    out.flush();
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
