// `cdlab stress` (see stress.h for the checks). Families of hard inputs, each case drawn from
// (seed, family, index) only, so a failing case is replayable on its own; every failure is also
// written as a `cdlab query` line.
//
// Tolerances are stated relative to the problem size L (the larger circumradius of the two shapes
// about their vertex centroids; a triangle's longest edge) plus the rounding of the coordinates
// themselves, 8 u M (u = 2^-53, M = the largest |coordinate|): a world-frame answer cannot be more
// exact than its own coordinates, and with offsets of 1e9 at size 1 that term dominates.
#include "app/stress/stress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base/primitives.h"
#include "core/cast/ray_cast.h"
#include "core/closest/closest_point.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "core/overlap/sat_tests.h"
#include "app/bench/bench_inputs.h"
#include "app/bench/bench_measure.h"
#include "demos/draw/plot.h"
#include "app/measure/statistics.h"
#include "verification/least_overlap_oracle.h"
#include "verification/minkowski_hull_oracle.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "app/stress/stress_engine.h"
#include "app/stress/stress_families.h"
#include "app/stress/stress_tolerances.h"
// The exact (BigInt) Ericson region of the closest-point tests: header-only, independent of core.
#include "verification/closest_oracle.h"
// Every field of a contact answer: witnesses on their bodies, pointA - pointB = s n, n least overlap.
#include "verification/witness_oracle.h"

namespace cdlab::demos {

namespace {

using Clock = std::chrono::steady_clock;

using stress_engine::Check;
using stress_engine::Engine;
using stress_engine::jsonString;
using stress_engine::kU;
using stress_engine::maxAbs;
using stress_engine::maxNorm;
using stress_engine::num;
using stress_engine::polytopeJson;
using stress_engine::vec;
using stress_engine::WitnessPair;
using stress_engine::witnessCell;
using stress_engine::witnessPair;
using stress_engine::witnessTolerances;
using stress_tolerances::kDistanceTol;
using stress_tolerances::kDepthTol;
using stress_tolerances::kBooleanBand;
using stress_tolerances::kSatBand;
using stress_tolerances::kClosestTol;
using stress_tolerances::kFloatU;
using stress_tolerances::kWitnessTol;
using stress_tolerances::kAxisFactor;
using verification::WitnessBody;
using verification::WitnessCheck;
using stress_cases::BoxCase;
using stress_cases::Family;
using stress_cases::Kind;
using stress_cases::PolyCase;
using stress_cases::RayCase;
using stress_cases::TriCase;

// The cases and their families: app/stress/stress_families.h.

// ---- Reproducers ------------------------------------------------------------------------------

std::string obbJson(const Transformed<BoxShape>& b) {
    const Quat& q = b.transform.rotation;
    return "{\"obb\":{\"center\":" + vec(b.transform.position) + ",\"half_extents\":" + vec(b.shape.halfExtents) +
           ",\"rotation\":[" + num(q.w()) + "," + num(q.x()) + "," + num(q.y()) + "," + num(q.z()) + "]}}";
}

/// GJK's witnesses and separating axis (separated answers only): pointA on A, pointB on B,
/// pointA - pointB = -distance * axis, and h_{A-B}(axis) = -distance (the axis separates by the
/// distance), with the axis tolerance of stress_tolerances.h.
void checkGjkWitnesses(Engine& e, const std::string& family, const std::string& prefix, bool info, int index,
                       double param, const WitnessPair& w, const GjkResult& g,
                       const std::function<std::string()>& query) {
    if (g.intersect() || !(g.distance > 0)) return;  // intersecting: no axis; the verdict is judged apart
    Vec3 pointA = g.pointA;
    pointA.x() = e.tampered(prefix + "_witness", pointA.x());
    verification::WitnessTolerances t = witnessTolerances(w);
    t.normal = kAxisFactor * t.offset * (1.0 + 4.0 * w.L / g.distance);
    const WitnessCheck c =
        verification::checkWitness(w.a, w.b, pointA, g.pointB, g.separatingAxis, -g.distance, t);
    witnessCell(e, family, prefix + " pointA on A", "1e-9 L_A + 8uM_A", info, param, c.pointAOff, t.onBodyA, w.La,
                index, query);
    witnessCell(e, family, prefix + " pointB on B", "1e-9 L_B + 8uM_B", info, param, c.pointBOff, t.onBodyB, w.Lb,
                index, query);
    witnessCell(e, family, prefix + " pA-pB = -d n", "1e-9 L + 8uM", info, param, c.offset, t.offset, w.L, index,
                query);
    witnessCell(e, family, prefix + " axis |h(n)+d|", "4 tau (1 + 4 L/d), tau = 1e-9 L + 8uM", info, param,
                c.normalLength <= 1e-12 ? c.normal : INFINITY, t.normal, w.L, index, query);
}

/// EPA's witnesses and normal: pointA on A, pointB on B (Penetrating / Touching answers),
/// pointA - pointB = depth * n, and h_{A-B}(n) = depth (the cell the figures draw; tolerance
/// `normalTol`, relative to L).
void checkEpaWitnesses(Engine& e, const std::string& family, int index, double param, const WitnessPair& w,
                       const EpaResult& r, double normalTol, const std::string& normalText,
                       const std::function<std::string()>& query) {
    Vec3 pointA = r.pointA;
    pointA.x() = e.tampered("epa_witness", pointA.x());
    verification::WitnessTolerances t = witnessTolerances(w);
    t.normal = normalTol * w.L;
    const WitnessCheck c = verification::checkWitness(w.a, w.b, pointA, r.pointB, r.normal, r.depth, t);
    if (r.status == EpaStatus::Penetrating || r.status == EpaStatus::Touching) {
        witnessCell(e, family, "epa pointA on A", "1e-9 L_A + 8uM_A", false, param, c.pointAOff, t.onBodyA, w.La,
                    index, query);
        witnessCell(e, family, "epa pointB on B", "1e-9 L_B + 8uM_B", false, param, c.pointBOff, t.onBodyB, w.Lb,
                    index, query);
        witnessCell(e, family, "epa pA-pB = depth n", "1e-9 L + 8uM", false, param, c.offset, t.offset, w.L, index,
                    query);
    }
    Check n;
    n.got = static_cast<double>(verification::supportOfDifferenceL(w.a, w.b, r.normal));
    n.expected = r.depth;
    n.error = c.normalLength < 1e-12 ? c.normal / w.L : INFINITY;
    n.tolerance = normalTol;
    e.record(family, "epa_normal |h(n)-depth|", normalText, false, param, n, query, index);
}

PolytopeShape polytopeOf(const std::vector<Vec3>& v, bool raw) {
    if (raw) return PolytopeShape(v);
    const HullResult h = convexHull(v);
    return h.ok() ? PolytopeShape(h.polyhedron) : PolytopeShape(v);
}

std::vector<Vec3> toFloat(std::vector<Vec3> v) {
    for (Vec3& x : v) x = x.cast<float>().cast<double>();
    return v;
}

/// The verdict and depth the pair checks compare with: the hull oracle's, or the least-overlap
/// oracle's where it arbitrated (apart: the distance, a lower bound when arbitrated).
struct PairTruth {
    bool inside = false;
    double depth = 0.0, apart = 0.0;
    bool leastRan = false;
};

// Up to 12 vertices the least-overlap oracle (no hull: every triple normal and edge pair in long
// double with exact edge vectors, verification/least_overlap_oracle.h) arbitrates a verdict or depth
// the hull oracle disputes with the algorithms: the hull of the differences of a 1e-6 body at a 1e3
// one's face said apart where both bodies overlap by 6.6e-7 (exact rationals agree), and a depth of
// 9.8e-8 where it is 4.96e-7 (tiny against huge, 600 s #20595, #38997). The disagreement is an
// info row.
void arbitrateWithLeastOverlap(Engine& e, const std::string& family, int index, double param,
                               const std::vector<Vec3>& va, const std::vector<Vec3>& vb, const MinkowskiOracle& o,
                               double L, double M, const char* what, PairTruth& t) {
    const verification::least_overlap::LeastOverlap lo(va, vb);
    const double least = static_cast<double>(lo.leastOverlap());
    Check h;
    h.expected = least > 0 ? least : 0.0;
    h.got = o.inside ? o.depth : 0.0;
    h.error = (least > 0) != o.inside ? 1.0 : std::abs(h.got - h.expected) / L;
    h.tolerance = kDepthTol + 8 * kU * M / L;
    e.record(
        family, std::string("hull oracle = least overlap (") + what + ")", "1e-10 L + 8uM", true, param, h,
        [] { return std::string(); }, index);
    t.inside = least > 0;
    t.depth = t.inside ? least : 0.0;
    t.apart = t.inside ? 0.0 : -least;
    t.leastRan = true;
}

/// GJK distance (SV, Johnson), GJK intersect, EPA depth and normal of two vertex sets.
void checkPair(Engine& e, const std::string& family, int index, const std::vector<Vec3>& va,
               const std::vector<Vec3>& vb, const PolytopeShape& a, const PolytopeShape& b,
               const std::vector<Vec3>& algoA, const std::vector<Vec3>& algoB, bool floatRounded, double oracleSlack,
               double param) {
    const MinkowskiOracle o = minkowskiOracle(va, vb);
    const double L = std::max(centroidRadius(va), centroidRadius(vb));
    const double M = std::max(maxAbs(va), maxAbs(vb));
    // Float-rounded inputs: the answers may move by the rounding of the vertices (file comment).
    const double extra = (floatRounded ? kFloatU * (maxNorm(va) + maxNorm(vb)) / L : 0.0) + oracleSlack;
    const std::string ftext = std::string(floatRounded ? " + 2^-24 (|a|max+|b|max)" : "") +
                              (oracleSlack > 0 ? " + the hull oracle's 1e-10 L" : "");
    const std::string queryA = polytopeJson(algoA), queryB = polytopeJson(algoB);
    // The witnesses lie on the bodies the algorithms were given (float-rounded ones included).
    const WitnessPair w = witnessPair(algoA, algoB, L, std::max(maxAbs(algoA), maxAbs(algoB)));
    auto pairQuery = [&](const char* op, const char* method) {
        return [=, &queryA, &queryB] {
            return std::string("{\"op\":\"") + op + "\"" +
                   (method ? std::string(",\"method\":\"") + method + "\"" : "") + ",\"a\":" + queryA +
                   ",\"b\":" + queryB + "}";
        };
    };
    Check oc;
    oc.error = o.ok ? 0.0 : 1.0;  // informational: pairs the oracle could not judge
    oc.tolerance = 0.5;
    e.record(
        family, "oracle hull", "hull failed", true, param, oc, [] { return std::string(); }, index);
    if (!o.ok) return;
    const double dTol = kDistanceTol + 8 * kU * M / L + extra;
    double trueDistance = o.inside ? 0.0 : o.distance;
    // Up to 12 vertices a second oracle with no hull at all (every vertex-triangle and edge-edge
    // pair in long double, ~50 µs a pair) arbitrates when GJK and the hull oracle disagree: the
    // hull of rounded differences a_i - b_j of 10-vertex slivers and needles errs by up to
    // ~1e-11 L (an exact rational check of such a pair agreed with GJK to the last digit, not
    // with the hull). Always run below 7 vertices, on demand above.
    const bool arbitrable = !o.inside && va.size() <= 12 && vb.size() <= 12;
    bool arbitrated = false;
    if (!o.inside && va.size() <= 6 && vb.size() <= 6) {
        // Small sets: the brute force decides, and the hull oracle's disagreement is reported.
        const double bruteForce = oracleDistanceBruteForce(va, vb);
        Check h;
        h.expected = bruteForce;
        h.got = o.distance;
        h.error = std::abs(o.distance - bruteForce) / L;
        h.tolerance = dTol;
        e.record(
            family, "hull oracle = brute force", "1e-12 L + 8uM", true, param, h, [] { return std::string(); }, index);
        trueDistance = bruteForce;
        arbitrated = true;
    }
    for (const SimplexSolver solver : {SimplexSolver::SignedVolumes, SimplexSolver::Johnson}) {
        const bool sv = solver == SimplexSolver::SignedVolumes;
        GjkOptions opt;
        opt.solver = solver;
        const GjkResult g = gjkDistance(a, b, opt);
        if (arbitrable && !arbitrated && std::abs(g.distance - trueDistance) / L > dTol) {
            const double bruteForce = oracleDistanceBruteForce(va, vb);
            Check h;
            h.expected = bruteForce;
            h.got = o.distance;
            h.error = std::abs(o.distance - bruteForce) / L;
            h.tolerance = dTol;
            e.record(
                family, "hull oracle = brute force", "1e-12 L + 8uM", true, param, h, [] { return std::string(); },
                index);
            trueDistance = bruteForce;
            arbitrated = true;
        }
        const std::string check = sv ? "gjk_distance" : "gjk_distance Johnson";
        Check c;
        c.got = e.tampered(check, g.distance);
        c.expected = trueDistance;
        c.error = std::abs(c.got - trueDistance) / L;
        c.tolerance = dTol;
        c.iterations = g.iterations;
        c.capHit = g.termination == GjkTermination::MaxIterations;
        e.record(family, check, "1e-12 L + 8uM" + ftext, !sv, param, c, pairQuery("distance", nullptr), index);
        checkGjkWitnesses(e, family, sv ? "gjk" : "gjk Johnson", !sv, index, param, w, g,
                          pairQuery("distance", nullptr));
    }
    PairTruth truth{o.inside, o.depth, o.inside ? 0.0 : o.distance};
    const auto arbitrate = [&](const char* what) { arbitrateWithLeastOverlap(e, family, index, param, va, vb, o, L, M, what, truth); };
    const bool smallSets = va.size() <= 12 && vb.size() <= 12;
    // Boolean: judged outside the band where touching rounds either way.
    {
        GjkResult g;
        const bool hit = e.tampered("gjk_intersect", gjkIntersect(a, b, {}, nullptr, &g) ? 1.0 : 0.0) != 0.0;
        if (smallSets && hit != o.inside) arbitrate("verdict");
        const double margin = (truth.inside ? truth.depth : truth.apart) / L;
        Check c;
        c.got = hit;
        c.expected = truth.inside;
        c.error = hit != truth.inside && margin > kBooleanBand + 8 * kU * M / L + extra ? 1.0 : 0.0;
        c.tolerance = 0.5;
        c.iterations = g.iterations;
        c.capHit = g.termination == GjkTermination::MaxIterations;
        e.record(family, "gjk_intersect", "exact outside 1e-12 L of touching", false, param, c,
                 pairQuery("intersect", nullptr), index);
    }
    if (!truth.inside) return;
    EpaResult r = penetration(a, b);
    r.depth = e.tampered("epa_depth", r.depth);
    const double pTol = kDepthTol + 8 * kU * M / L + extra;
    if (smallSets && !truth.leastRan && std::abs(r.depth - truth.depth) / L > pTol) arbitrate("depth");
    Check c;
    c.got = r.depth;
    c.expected = truth.depth;
    c.error = std::abs(r.depth - truth.depth) / L;
    c.tolerance = pTol;
    c.iterations = r.iterations;
    c.capHit = r.termination == EpaTermination::MaxIterations || r.termination == EpaTermination::CapacityExceeded;
    e.record(family, "epa_depth", "1e-10 L + 8uM" + ftext, false, param, c, pairQuery("penetration", nullptr), index);
    // Witnesses and normal: the support of A - B along n must equal the depth (n attains the
    // minimum of h), pointA on A, pointB on B, pointA - pointB = depth n.
    checkEpaWitnesses(e, family, index, param, w, r, pTol, "1e-10 L + 8uM" + ftext, pairQuery("penetration", nullptr));
}

void runPoly(Engine& e, const Family& f, int index, PolyCase& c) {
    const std::vector<Vec3> algoA = c.floatRounded ? toFloat(c.va) : c.va;
    const std::vector<Vec3> algoB = c.floatRounded ? toFloat(c.vb) : c.vb;
    const PolytopeShape a = polytopeOf(algoA, c.raw), b = polytopeOf(algoB, c.raw);
    checkPair(e, f.name, index, c.va, c.vb, a, b, algoA, algoB, c.floatRounded, c.oracleSlack, c.param);
    // V-Clip slot: when core/feature_walk/vclip.h lands, add "vclip_distance" = the same oracle here.
}

void runBox(Engine& e, const Family& f, int index, BoxCase& c) {
    const std::vector<Vec3> va = boxCorners(c.a), vb = boxCorners(c.b);
    const MinkowskiOracle o = minkowskiOracle(va, vb);
    const double L = std::max(c.a.shape.halfExtents.norm(), c.b.shape.halfExtents.norm());
    const double M = std::max(maxAbs(va), maxAbs(vb));
    // GJK / EPA on the support mappings (not the corner lists): ties on whole faces.
    const MinkowskiOracle* oracle = &o;
    if (!oracle->ok) return;
    const WitnessPair w = witnessPair(va, vb, L, M);
    {
        const GjkResult g = gjkDistance(c.a, c.b);
        Check k;
        k.got = e.tampered("gjk_distance", g.distance);
        k.expected = o.inside ? 0.0 : o.distance;
        k.error = std::abs(k.got - k.expected) / L;
        k.tolerance = kDistanceTol + 8 * kU * M / L;
        k.iterations = g.iterations;
        k.capHit = g.termination == GjkTermination::MaxIterations;
        e.record(
            f.name, "gjk_distance", "1e-12 L + 8uM", false, c.param, k,
            [&] { return "{\"op\":\"distance\",\"a\":" + obbJson(c.a) + ",\"b\":" + obbJson(c.b) + "}"; }, index);
        checkGjkWitnesses(e, f.name, "gjk", false, index, c.param, w, g, [&] {
            return "{\"op\":\"distance\",\"a\":" + obbJson(c.a) + ",\"b\":" + obbJson(c.b) + "}";
        });
    }
    const double margin = (o.inside ? o.depth : o.distance) / L;
    const bool gjkHit = e.tampered("gjk_intersect", gjkIntersect(c.a, c.b) ? 1.0 : 0.0) != 0.0;
    {
        Check k;
        k.got = gjkHit;
        k.expected = o.inside;
        k.error = gjkHit != o.inside && margin > kBooleanBand + 8 * kU * M / L ? 1.0 : 0.0;
        k.tolerance = 0.5;
        e.record(
            f.name, "gjk_intersect", "exact outside 1e-12 L of touching", false, c.param, k,
            [&] { return "{\"op\":\"intersect\",\"a\":" + obbJson(c.a) + ",\"b\":" + obbJson(c.b) + "}"; }, index);
    }
    {
        // SAT = GJK = the oracle. SAT may say "overlap" for a pair separated by less than its
        // conservative band (kSatBand), never "separated" for a pair overlapping by more than the
        // boolean band.
        const Obb a = Obb::fromRotation(c.a.transform.position, c.a.shape.halfExtents, c.a.transform.rotation);
        const Obb b = Obb::fromRotation(c.b.transform.position, c.b.shape.halfExtents, c.b.transform.rotation);
        const bool satHit = e.tampered("sat_obb_obb", testObbObb(a, b).hit ? 1.0 : 0.0) != 0.0;
        const double band = (o.inside ? kBooleanBand : kSatBand) + 8 * kU * M / L;
        Check k;
        k.got = satHit;
        k.expected = o.inside;
        k.error = satHit != o.inside && margin > band ? 1.0 : 0.0;
        k.tolerance = 0.5;
        e.record(
            f.name, "sat_obb_obb = oracle (= GJK)", "exact outside 1e-8 L (sep.) / 1e-12 L (overlap)", false, c.param,
            k,
            [&] {
                return "{\"op\":\"intersect\",\"method\":\"sat\",\"a\":" + obbJson(c.a) + ",\"b\":" + obbJson(c.b) +
                       "}";
            },
            index);
    }
    if (!o.inside) return;
    EpaResult r = penetration(c.a, c.b);
    r.depth = e.tampered("epa_depth", r.depth);
    auto query = [&] { return "{\"op\":\"penetration\",\"a\":" + obbJson(c.a) + ",\"b\":" + obbJson(c.b) + "}"; };
    Check k;
    k.got = r.depth;
    k.expected = o.depth;
    k.error = std::abs(r.depth - o.depth) / L;
    k.tolerance = kDepthTol + 8 * kU * M / L;
    k.iterations = r.iterations;
    k.capHit = r.termination == EpaTermination::MaxIterations || r.termination == EpaTermination::CapacityExceeded;
    e.record(f.name, "epa_depth", "1e-10 L + 8uM", false, c.param, k, query, index);
    checkEpaWitnesses(e, f.name, index, c.param, w, r, k.tolerance, "1e-10 L + 8uM", query);
}

void runTri(Engine& e, const Family& f, int index, TriCase& c) {
    const ClosestPointOnTriangleResult r = closestPointOnTriangle(c.p, c.t);
    const double L = std::max({(c.t.b - c.t.a).norm(), (c.t.c - c.t.b).norm(), (c.t.a - c.t.c).norm()});
    const double M = std::max({c.p.cwiseAbs().maxCoeff(), c.t.a.cwiseAbs().maxCoeff(), c.t.b.cwiseAbs().maxCoeff(),
                               c.t.c.cwiseAbs().maxCoeff()});
    auto query = [&] {
        return "{\"op\":\"closest_point_triangle\",\"point\":" + vec(c.p) + ",\"triangle\":[" + vec(c.t.a) + "," +
               vec(c.t.b) + "," + vec(c.t.c) + "]}";
    };
    const double exact = oracleDistanceToTriangle(c.p, c.t);
    Check d;
    d.got = e.tampered("closest_distance", (c.p - r.point).norm());
    d.expected = exact;
    d.error = std::abs(d.got - exact) / L;
    d.tolerance = kClosestTol + 8 * kU * M / L;
    e.record(f.name, "closest_distance", "1e-12 L + 8uM", false, c.param, d, query, index);
    // Region: the exact rational Ericson region (BigInt), for non-collinear triangles (exactly).
    const oracle::BigVec A = oracle::toBig(c.t.a, oracle::commonShift({c.t.a, c.t.b, c.t.c}));
    const int K = oracle::commonShift({c.t.a, c.t.b, c.t.c});
    const oracle::BigVec B = oracle::toBig(c.t.b, K), C = oracle::toBig(c.t.c, K);
    const oracle::BigVec n = oracle::cross(oracle::sub(B, A), oracle::sub(C, A));
    if (n.v[0].sign == 0 && n.v[1].sign == 0 && n.v[2].sign == 0) return;
    const TriangleRegion truth = oracle::exactEricsonRegion(c.p, c.t.a, c.t.b, c.t.c);
    Check g;
    const double got = e.tampered("closest_region", static_cast<double>(static_cast<int>(r.region)));
    g.got = got;
    g.expected = static_cast<int>(truth);
    g.error = got == static_cast<double>(static_cast<int>(truth)) ? 0.0 : 1.0;
    g.tolerance = 0.5;
    e.record(f.name, "closest_region = exact", "exact", false, c.param, g, query, index);
}

/// A ray against a polytope: the verdict against the oracle's first contact (judged unless the
/// ray passes within rounding of the body), and every field of a hit (verification/witness_oracle.h):
/// point = o + t d, on the surface, no earlier contact, the normal outward and supporting there.
void runRay(Engine& e, const Family& f, int index, RayCase& c) {
    const ConvexCastHit h = castRayRoundedHull(c.ray, c.body);
    const WitnessBody body = WitnessBody::polytope(c.body);
    const double L = centroidRadius(c.body);
    const double M = std::max(maxAbs(c.body), c.ray.origin.cwiseAbs().maxCoeff());
    const double tMax = 4.0 * (L + (c.ray.origin - c.body[0]).norm()) / c.ray.direction.norm();
    const long double first = body.firstContact(c.ray.origin, c.ray.direction, tMax);
    auto query = [&] {
        return "{\"op\":\"raycast\",\"ray\":{\"origin\":" + vec(c.ray.origin) + ",\"direction\":" +
               vec(c.ray.direction) + "},\"shape\":" + polytopeJson(c.body) + "}";
    };
    const bool hit = e.tampered("ray_hit", h.hit ? 1.0 : 0.0) != 0.0;
    {
        Check k;
        k.got = hit;
        k.expected = first >= 0;
        k.error = c.judgeVerdict && hit != (first >= 0) ? 1.0 : 0.0;
        k.tolerance = 0.5;
        e.record(f.name, "ray hit = oracle", "exact unless within rounding of the body", false, c.param, k, query,
                 index);
    }
    if (!hit || first < 0 || h.inside) return;
    const double tol = kWitnessTol * L + 8 * kU * M;
    verification::RayHitTolerances t;
    t.point = t.surface = t.firstContact = t.normal = tol;
    Vec3 point = h.point;
    point.x() = e.tampered("ray_point", point.x());
    const verification::RayHitCheck r = verification::checkRayHit(body, c.ray.origin, c.ray.direction, h.t, point,
                                                                   h.normal, t);
    witnessCell(e, f.name, "ray point = o + t d", "1e-9 L + 8uM", false, c.param, r.offRay, tol, L, index, query);
    witnessCell(e, f.name, "ray point on surface", "1e-9 L + 8uM", false, c.param, r.offSurface, tol, L, index,
                query);
    witnessCell(e, f.name, "ray t = first contact", "1e-9 L + 8uM", false, c.param, r.earlier, tol, L, index, query);
    witnessCell(e, f.name, "ray normal outward, supporting", "1e-9 L + 8uM", false, c.param,
                r.normalLength <= 1e-12 ? r.support : INFINITY, tol, L, index, query);
}

}  // namespace

StressReport runStressSuite(const StressOptions& options) {
    StressReport report;
    Engine engine(options, report);
    const std::vector<Family> fam = stress_cases::stressFamilies();
    for (const Family& f : fam) report.familyParameter.push_back(f.parameter);
    std::vector<int> done(fam.size(), 0);
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    double nextProgress = 1.0;
    constexpr int kBatch = 10;
    const bool trace = std::getenv("CDLAB_STRESS_TRACE") != nullptr;
    for (;;) {
        const bool minimumDone =
            std::all_of(done.begin(), done.end(), [&](int n) { return n >= options.minCasesPerFamily; });
        if (minimumDone && elapsed() >= options.seconds) break;
        for (size_t fi = 0; fi < fam.size(); ++fi) {
            const Family& f = fam[fi];
            for (int k = 0; k < kBatch; ++k) {
                const int i = done[fi]++;
                // Case i of family fi depends on (seed, fi, i) only.
                std::seed_seq seq{static_cast<std::uint32_t>(options.seed),
                                  static_cast<std::uint32_t>(options.seed >> 32), static_cast<std::uint32_t>(fi),
                                  static_cast<std::uint32_t>(i)};
                std::mt19937_64 rng(seq);
                // A crash (not a failed check) leaves no report: CDLAB_STRESS_TRACE=1 names each
                // case before it runs, so the last line names the crashing one.
                if (trace) std::fprintf(stderr, "cdlab stress: %s #%d\n", f.name.c_str(), i);
                switch (f.kind) {
                    case Kind::Poly: {
                        PolyCase c;
                        f.poly(rng, c);
                        if (trace)
                            std::fprintf(stderr, "{\"op\":\"distance\",\"a\":%s,\"b\":%s}\n",
                                         polytopeJson(c.va).c_str(), polytopeJson(c.vb).c_str());
                        runPoly(engine, f, i, c);
                        break;
                    }
                    case Kind::Box: {
                        BoxCase c;
                        f.box(rng, c);
                        runBox(engine, f, i, c);
                        break;
                    }
                    case Kind::Ray: {
                        RayCase c;
                        f.ray(rng, c);
                        runRay(engine, f, i, c);
                        break;
                    }
                    case Kind::Tri: {
                        TriCase c;
                        f.tri(rng, c);
                        runTri(engine, f, i, c);
                        break;
                    }
                    case Kind::Toi: {
                        stress_cases::ToiCase c;
                        f.toi(rng, c);
                        stress_engine::runToi(engine, f, i, c);
                        break;
                    }
                    case Kind::Rounded: {
                        stress_cases::RoundedCase c;
                        f.rounded(rng, c);
                        stress_engine::runRounded(engine, f, i, c);
                        break;
                    }
                    case Kind::Contact: {
                        stress_cases::ContactCase c;
                        f.contact(rng, c);
                        stress_engine::runContact(engine, f, i, c);
                        break;
                    }
                }
            }
        }
        if (options.progress && elapsed() >= nextProgress) {
            int cases = 0, failures = 0;
            for (const StressCell& c : report.cells)
                if (!c.informational) cases += c.cases, failures += c.failures;
            std::fprintf(stderr, "\rcdlab stress: %5.1f / %.0f s, %d checks, %d failures", elapsed(), options.seconds,
                         cases, failures);
            std::fflush(stderr);
            nextProgress = elapsed() + 1.0;
        }
    }
    if (options.progress) std::fprintf(stderr, "\n");
    report.seconds = elapsed();
    for (const StressCell& c : report.cells) {
        if (c.informational) continue;
        report.totalCases += c.cases;
        report.totalFailures += c.failures;
    }
    return report;
}

std::string stressTable(const StressReport& report) {
    std::ostringstream out;
    char line[512];
    std::snprintf(line, sizeof line, "%-34s %-30s %7s %6s %9s %9s %9s %6s  %s\n", "family", "check", "cases", "fail",
                  "rate", "worst err", "err/tol", "iters", "tolerance (L = size)");
    out << line;
    std::string last;
    for (const StressCell& c : report.cells) {
        if (c.check == "oracle hull" && c.failures == 0) continue;
        std::snprintf(line, sizeof line, "%-34s %-30s %7d %6d %9.2g %9.2g %9.2g %6d  %s%s\n",
                      c.family == last ? "" : c.family.c_str(), c.check.c_str(), c.cases, c.failures,
                      c.cases ? double(c.failures) / c.cases : 0.0, c.worstError, c.worstRatio, c.maxIterations,
                      c.informational ? "(info) " : "", c.tolerance.c_str());
        out << line;
        last = c.family;
    }
    return out.str();
}

}  // namespace cdlab::demos
