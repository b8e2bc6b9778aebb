// The engine of `cdlab stress` (stress.h), shared by its runners (stress.cpp: polytope pairs, boxes,
// triangles, rays; stress_witness_runs.cpp: times of impact, spheres and capsules;
// stress_contact_runs.cpp: contact manifolds): the report's
// cells (Engine::record), the tamper hook, the witness oracle's tolerances and cells, and the
// reproducers' JSON (`cdlab query` lines, %.17g numbers).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/measure/statistics.h"
#include "app/stress/stress.h"
#include "app/stress/stress_families.h"
#include "app/stress/stress_tolerances.h"
#include "core/base/types.h"
// Every field of a contact answer: witnesses on their bodies, pointA - pointB = s n, n least overlap.
#include "verification/witness_oracle.h"

namespace cdlab::demos::stress_engine {

constexpr double kU = 0x1p-53;  // unit roundoff of double

using stress_tolerances::kWitnessTol;
using verification::WitnessBody;

// ---- Reproducers ------------------------------------------------------------------------------

inline std::string num(double x) {
    if (!std::isfinite(x)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

inline std::string vec(const Vec3& v) { return "[" + num(v.x()) + "," + num(v.y()) + "," + num(v.z()) + "]"; }

inline std::string polytopeJson(const std::vector<Vec3>& v) {
    std::string s = "{\"polytope\":{\"vertices\":[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + vec(v[i]);
    return s + "],\"position\":[0,0,0],\"rotation\":[1,0,0,0]}}";
}

inline std::string jsonString(const std::string& s) { return nlohmann::json(s).dump(); }

struct Check {
    double error = 0;      // relative to L (booleans: 0 / 1)
    double tolerance = 0;  // same unit
    int iterations = 0;
    bool capHit = false;
    double expected = 0, got = 0;  // for the reproducer's id
};

class Engine {
public:
    Engine(const StressOptions& options, StressReport& report) : options_(options), report_(report) {}

    void record(const std::string& family, const std::string& check, const std::string& toleranceText, bool info,
                double param, const Check& c, const std::function<std::string()>& query, int index) {
        const auto key = family + "\n" + check;
        auto it = index_.find(key);
        if (it == index_.end()) {
            it = index_.emplace(key, report_.cells.size()).first;
            StressCell cell;
            cell.family = family;
            cell.check = check;
            cell.informational = info;
            cell.tolerance = toleranceText;
            report_.cells.push_back(cell);
        }
        StressCell& cell = report_.cells[it->second];
        ++cell.cases;
        const bool nan = !std::isfinite(c.error);
        const double ratio = c.tolerance > 0 ? c.error / c.tolerance : (c.error > 0 ? INFINITY : 0.0);
        if (nan) cell.worstError = INFINITY;
        else cell.worstError = std::max(cell.worstError, c.error);
        cell.worstRatio = nan ? INFINITY : std::max(cell.worstRatio, ratio);
        cell.maxIterations = std::max(cell.maxIterations, c.iterations);
        cell.iterationCapHits += c.capHit;
        if (cell.samples.size() < 4000) cell.samples.emplace_back(param, nan ? INFINITY : c.error);
        const bool failed = nan || ratio > 1.0 || c.capHit;
        if (!failed) return;
        ++cell.failures;
        if (info) return;
        if (static_cast<int>(report_.failureLines.size()) >= options_.maxFailureLines) return;
        char what[256];
        std::snprintf(what, sizeof what, "stress %s / %s #%d: expected %.17g, got %.17g, error %.3g > %.3g%s",
                      family.c_str(), check.c_str(), index, c.expected, c.got, c.error, c.tolerance,
                      c.capHit ? " (iteration cap)" : "");
        std::string line = query();
        line.insert(1, "\"id\":" + jsonString(what) + ",");
        report_.failureLines.push_back(line);
    }

    double tampered(const std::string& check, double value) const {
        if (options_.tamper) options_.tamper(check, value);
        return value;
    }

private:
    const StressOptions& options_;
    StressReport& report_;
    std::map<std::string, size_t> index_;
};

inline double maxAbs(const std::vector<Vec3>& v) {
    double m = 0;
    for (const Vec3& x : v) m = std::max(m, x.cwiseAbs().maxCoeff());
    return m;
}

inline double maxNorm(const std::vector<Vec3>& v) {
    double m = 0;
    for (const Vec3& x : v) m = std::max(m, x.norm());
    return m;
}

/// The two bodies as the witness oracle sees them (the vertex lists the algorithms were given),
/// with each body's size and largest |coordinate| and the pair's (file comment).
struct WitnessPair {
    WitnessBody a, b;
    double La = 0, Ma = 0, Lb = 0, Mb = 0;
    double L = 0, M = 0;
};

inline WitnessPair witnessPair(const std::vector<Vec3>& va, const std::vector<Vec3>& vb, double L, double M) {
    return {WitnessBody::polytope(va), WitnessBody::polytope(vb), centroidRadius(va), maxAbs(va), centroidRadius(vb),
            maxAbs(vb), L, M};
}

inline verification::WitnessTolerances witnessTolerances(const WitnessPair& w) {
    verification::WitnessTolerances t;
    t.onBodyA = kWitnessTol * w.La + 8 * kU * w.Ma;
    t.onBodyB = kWitnessTol * w.Lb + 8 * kU * w.Mb;
    t.offset = kWitnessTol * w.L + 8 * kU * w.M;
    return t;
}

/// One cell per measured field of the witness oracle's answer: the error relative to `scale`.
inline void witnessCell(Engine& e, const std::string& family, const std::string& check, const std::string& text,
                        bool info, double param, double value, double tol, double scale, int index,
                        const std::function<std::string()>& query) {
    Check k;
    k.got = value;
    k.expected = 0;
    k.error = std::isfinite(value) ? std::max(0.0, value) / scale : INFINITY;
    k.tolerance = tol / scale;
    e.record(family, check, text, info, param, k, query, index);
}

// ---- The runners of stress_witness_runs.cpp --------------------------------------------------------

/// A time of impact along a sliding or grazing relative path (stress_families.h, ToiCase).
void runToi(Engine& e, const stress_cases::Family& f, int index, const stress_cases::ToiCase& c);
/// Distance and penetration of spheres, capsules and polytopes (stress_families.h, RoundedCase).
void runRounded(Engine& e, const stress_cases::Family& f, int index, const stress_cases::RoundedCase& c);

// ---- The runner of stress_contact_runs.cpp ----------------------------------------------------------

/// Every field of a contact answer of two polytopes (stress_families.h, ContactCase).
void runContact(Engine& e, const stress_cases::Family& f, int index, const stress_cases::ContactCase& c);

}  // namespace cdlab::demos::stress_engine
