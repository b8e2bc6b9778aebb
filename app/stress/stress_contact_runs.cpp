// `cdlab stress`'s runner for the contact op: core's contactQuery (core/query/contact.h, called as
// `cdlab query`'s "contact" calls it) on the family "contact manifolds" (stress_families.h,
// ContactCase), every field of the answer judged by long double oracles computed from the input
// doubles only (verification/least_overlap_oracle.h, verification/witness_oracle.h; nothing of
// core's hull, GJK or SAT). L: the pair's size, L_body: one body's, M: the largest coordinate:
//  - colliding = the oracle's verdict (least overlap D* > 0), exact outside 1e-12 L + 8uM of touching;
//  - colliding: D* − tol <= depth <= 1.02 D* + band (the face preference, docs/query.md) and
//    h_{A−B}(normal) = depth within tol, tol = 1e-10 L + 8uM (the penetration depth's, docs/accuracy.md's
//    accuracy table); band = the SAT's touching band, 1e-9 of the larger bounding-box diagonal +
//    128 u M (core/contact/contact_sat.h's contract). At least one point; every point: point_a on
//    A and point_b on B within 1e-9 L_body + 8uM_body, point_a − point_b = depth_i · normal within
//    1e-9 L + 8uM, −band <= depth_i <= depth + 1e-9 L + 8uM (a point within the band above the
//    reference face carries its separation as a negative depth);
//  - separated: the distance = the oracle's within 1e-12 L + 8uM; the closest pair on its bodies,
//    point_b − point_a = distance · normal, and the normal separating by the distance (GJK's axis
//    tolerance, stress_tolerances.h);
//  - the features: feature_a holds every point_a and feature_b every point_b (their vertex count
//    fits their type), within 1e-9 L_body + 8uM_body; and the features that the normal comes from
//    are support sets along it (face A: feature_a; face B: feature_b; edge-edge and separated:
//    both): each of their vertices within 2e-9 diag_body + 128 u M_body of h_A(n) (of h_B(−n)),
//    twice core's feature band (diag_body: the body's bounding-box diagonal).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "app/stress/stress_engine.h"
#include "core/query/contact.h"
#include "core/query/shape.h"
#include "verification/least_overlap_oracle.h"

namespace cdlab::demos::stress_engine {

namespace contact_runs {

using stress_cases::ContactCase;
using stress_cases::Family;
using stress_tolerances::kAxisFactor;
using stress_tolerances::kBooleanBand;
using stress_tolerances::kDepthTol;
using stress_tolerances::kDistanceTol;
using stress_tolerances::kWitnessTol;
using verification::LVec;
using verification::toL;
using verification::WitnessCheck;

constexpr double kFacePreference = 1.02;  // 1 + faceBiasRelative (core/contact/contact_sat.h)

/// One case's bodies, sizes and oracles.
struct Judge {
    const Family& f;
    int index;
    const ContactCase& c;
    WitnessPair w;
    const verification::least_overlap::LeastOverlap& o;
    long double signedDistance;  // o's: the distance apart, −D* overlapping
    std::function<std::string()> query;
};

/// A judged boolean: error 1 where decided and wrong.
void contactBoolean(Engine& e, const Judge& j, const std::string& check, const std::string& text, bool got,
                    bool expected, bool decided) {
    Check k;
    k.got = got;
    k.expected = expected;
    k.error = decided && got != expected ? 1.0 : 0.0;
    k.tolerance = 0.5;
    e.record(j.f.name, check, text, false, j.c.param, k, j.query, j.index);
}

/// A length judged against `expected` within `tol` (world units), reported relative to L.
void contactLength(Engine& e, const Judge& j, const std::string& check, const std::string& text, double got,
                   double expected, double error, double tol) {
    Check k;
    k.got = got;
    k.expected = expected;
    k.error = std::isfinite(error) ? std::max(0.0, error) / j.w.L : INFINITY;
    k.tolerance = tol / j.w.L;
    e.record(j.f.name, check, text, false, j.c.param, k, j.query, j.index);
}

/// The distance from x to conv(points) (brute force over their triangles; 1 or 2 points: the
/// point, the segment), long double.
long double distanceToHull(const std::vector<Vec3>& points, const Vec3& x) {
    std::vector<LVec> p;
    for (const Vec3& v : points) p.push_back(toL(v) - toL(x));
    if (p.size() == 1) return p[0].norm();
    if (p.size() == 2) return long_double::segmentDistanceL(p[0], p[1]);
    long double best = std::numeric_limits<long double>::infinity();
    for (size_t i = 0; i < p.size(); ++i)
        for (size_t k = i + 1; k < p.size(); ++k)
            for (size_t l = k + 1; l < p.size(); ++l) best = std::min(best, long_double::triangleDistanceL(p[i], p[k], p[l]));
    return best;
}

/// A feature's input vertices, or none when its indices or vertex count do not fit its type.
std::vector<Vec3> featurePoints(const ContactFeature& f, const std::vector<Vec3>& body) {
    using T = ContactFeature::Type;
    const size_t n = f.vertices.size();
    const bool fits = (f.type == T::Vertex && n == 1) || (f.type == T::Edge && n == 2) || (f.type == T::Face && n >= 3);
    std::vector<Vec3> out;
    for (int i : f.vertices) {
        if (i < 0 || i >= static_cast<int>(body.size())) return {};
        out.push_back(body[i]);
    }
    return fits ? out : std::vector<Vec3>{};
}

/// The diagonal of the bounding box of v.
double bboxDiagonal(const std::vector<Vec3>& v) {
    Vec3 lo = v[0], hi = v[0];
    for (const Vec3& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    return (hi - lo).norm();
}

/// How far the feature's vertices fall short of the body's support value along n, relative to the
/// support tolerance: twice core's feature band (vertices within 1e-9 of the body's bounding-box
/// diagonal + 64 ulps of the support form a feature, core/contact/contact_plane.h), 2e-9 diagonal +
/// 128 u M_body. INFINITY: no valid feature.
double supportShortfall(const std::vector<Vec3>& feature, const std::vector<Vec3>& body, const Vec3& n) {
    if (feature.empty()) return INFINITY;
    const double tol = 2 * kWitnessTol * bboxDiagonal(body) + 128 * kU * maxAbs(body);
    const LVec ref = toL(body[0]), nl = toL(n);
    long double h = -std::numeric_limits<long double>::infinity(), low = -h;
    for (const Vec3& x : body) h = std::max(h, (toL(x) - ref).dot(nl));
    for (const Vec3& x : feature) low = std::min(low, (toL(x) - ref).dot(nl));
    return static_cast<double>(h - low) / tol;
}

/// feature_a holds every point_a and feature_b every point_b; the features named by the axis support n.
void checkFeatures(Engine& e, const Judge& j, const ContactResult& r) {
    const std::vector<Vec3> fa = featurePoints(r.featureA, j.c.va), fb = featurePoints(r.featureB, j.c.vb);
    double offA = fa.empty() ? INFINITY : 0.0, offB = fb.empty() ? INFINITY : 0.0;
    for (const ContactPoint& p : r.points) {
        if (!fa.empty()) offA = std::max(offA, static_cast<double>(distanceToHull(fa, p.pointA)));
        if (!fb.empty()) offB = std::max(offB, static_cast<double>(distanceToHull(fb, p.pointB)));
    }
    const verification::WitnessTolerances t = witnessTolerances(j.w);
    witnessCell(e, j.f.name, "contact feature_a holds pointA", "1e-9 L_A + 8uM_A", false, j.c.param, offA, t.onBodyA,
                j.w.La, j.index, j.query);
    witnessCell(e, j.f.name, "contact feature_b holds pointB", "1e-9 L_B + 8uM_B", false, j.c.param, offB, t.onBodyB,
                j.w.Lb, j.index, j.query);
    const bool supportsA = !r.colliding || r.axis != SatAxisKind::FaceB;
    const bool supportsB = !r.colliding || r.axis != SatAxisKind::FaceA;
    double shortfall = 0;  // relative to the support tolerance
    if (supportsA) shortfall = std::max(shortfall, supportShortfall(fa, j.c.va, r.normal));
    if (supportsB) shortfall = std::max(shortfall, supportShortfall(fb, j.c.vb, -r.normal));
    Check k;
    k.error = shortfall;
    k.tolerance = 1.0;
    e.record(j.f.name, "contact features support n", "2e-9 diag_body + 128uM_body (ratio)", false, j.c.param, k, j.query,
             j.index);
}

/// A colliding answer: the depth against D*, the normal realising it, every manifold point.
void checkColliding(Engine& e, const Judge& j, const ContactResult& r) {
    const double tol = kDepthTol * j.w.L + 8 * kU * j.w.M;
    const double least = static_cast<double>(j.o.leastOverlap());
    const std::string text = "1e-10 L + 8uM";
    contactLength(e, j, "contact depth >= D*", text, r.depth, least, least - r.depth, tol);
    // The face preference's bound (core/contact/contact_sat.h, step 3; docs/accuracy.md): 1.02 D* plus the SAT's
    // touching band, 1e-9 of the larger bounding-box diagonal + 128 u M: inside that band a face
    // axis is kept over a better edge or face axis.
    const double band = kWitnessTol * std::max(bboxDiagonal(j.c.va), bboxDiagonal(j.c.vb)) + 128 * kU * j.w.M;
    contactLength(e, j, "contact depth <= 1.02 D* + band", "1e-9 diag + 128uM", r.depth, least,
                  r.depth - kFacePreference * least, band);
    const bool unit = std::abs(toL(r.normal).norm() - 1) <= 1e-12L;
    const long double along = j.o.overlapAlong(toL(r.normal));
    contactLength(e, j, "contact normal |h(n)-depth|", text, r.depth, static_cast<double>(along),
                  unit ? static_cast<double>(std::abs(along - r.depth)) : INFINITY, tol);
    contactBoolean(e, j, "contact points >= 1", "exact", !r.points.empty(), true, true);
    if (r.points.empty()) return;
    const verification::WitnessTolerances t = witnessTolerances(j.w);
    double onA = 0, onB = 0, offset = 0, below = 0, above = 0;
    for (const ContactPoint& p : r.points) {
        Vec3 pointA = p.pointA;
        pointA.x() = e.tampered("contact_witness", pointA.x());
        const WitnessCheck k = verification::checkWitness(j.w.a, j.w.b, pointA, p.pointB, r.normal, p.depth, t);
        onA = std::max(onA, k.pointAOff);
        onB = std::max(onB, k.pointBOff);
        offset = std::max(offset, k.offset);
        below = std::max(below, -p.depth);
        above = std::max(above, p.depth - r.depth);
        if (!std::isfinite(p.depth)) below = above = INFINITY;
    }
    witnessCell(e, j.f.name, "contact pointA on A", "1e-9 L_A + 8uM_A", false, j.c.param, onA, t.onBodyA, j.w.La,
                j.index, j.query);
    witnessCell(e, j.f.name, "contact pointB on B", "1e-9 L_B + 8uM_B", false, j.c.param, onB, t.onBodyB, j.w.Lb,
                j.index, j.query);
    witnessCell(e, j.f.name, "contact pA-pB = depth_i n", "1e-9 L + 8uM", false, j.c.param, offset, t.offset, j.w.L,
                j.index, j.query);
    // A point up to the touching band above the reference face carries its separation as a
    // negative depth (core/contact/contact_stages.cpp, clipWith).
    witnessCell(e, j.f.name, "contact depth_i >= -band", "1e-9 diag + 128uM", false, j.c.param, below, band, j.w.L,
                j.index, j.query);
    witnessCell(e, j.f.name, "contact depth_i <= depth", "1e-9 L + 8uM", false, j.c.param, above, t.offset, j.w.L,
                j.index, j.query);
}

/// A separated answer: the distance, the closest pair, the normal separating by the distance.
void checkSeparated(Engine& e, const Judge& j, const ContactResult& r) {
    const double expected = static_cast<double>(std::max(0.0L, j.signedDistance));
    contactLength(e, j, "contact distance = oracle", "1e-12 L + 8uM", r.distance, expected,
                  std::abs(r.distance - expected), kDistanceTol * j.w.L + 8 * kU * j.w.M);
    contactBoolean(e, j, "contact points >= 1", "exact", !r.points.empty(), true, true);
    if (r.points.empty()) return;
    verification::WitnessTolerances t = witnessTolerances(j.w);
    t.normal = kAxisFactor * t.offset * (1.0 + 4.0 * j.w.L / r.distance);
    double onA = 0, onB = 0, offset = 0, axis = 0;
    for (const ContactPoint& p : r.points) {
        Vec3 pointA = p.pointA;
        pointA.x() = e.tampered("contact_witness", pointA.x());
        const WitnessCheck k = verification::checkWitness(j.w.a, j.w.b, pointA, p.pointB, r.normal, -r.distance, t);
        onA = std::max(onA, k.pointAOff);
        onB = std::max(onB, k.pointBOff);
        offset = std::max(offset, k.offset);
        axis = std::max(axis, k.normalLength <= 1e-12 ? k.normal : INFINITY);
    }
    witnessCell(e, j.f.name, "contact closest pointA on A", "1e-9 L_A + 8uM_A", false, j.c.param, onA, t.onBodyA,
                j.w.La, j.index, j.query);
    witnessCell(e, j.f.name, "contact closest pointB on B", "1e-9 L_B + 8uM_B", false, j.c.param, onB, t.onBodyB,
                j.w.Lb, j.index, j.query);
    witnessCell(e, j.f.name, "contact pB-pA = distance n", "1e-9 L + 8uM", false, j.c.param, offset, t.offset, j.w.L,
                j.index, j.query);
    witnessCell(e, j.f.name, "contact axis |h(n)+d|", "4 tau (1 + 4 L/d), tau = 1e-9 L + 8uM", false, j.c.param, axis,
                t.normal, j.w.L, j.index, j.query);
}

}  // namespace contact_runs

void runContact(Engine& e, const stress_cases::Family& f, int index, const stress_cases::ContactCase& c) {
    using namespace contact_runs;
    const double L = std::max(centroidRadius(c.va), centroidRadius(c.vb));
    const double M = std::max(maxAbs(c.va), maxAbs(c.vb));
    const verification::least_overlap::LeastOverlap o(c.va, c.vb);
    const Judge j{f,
                  index,
                  c,
                  witnessPair(c.va, c.vb, L, M),
                  o,
                  o.signedDistance(),
                  [&c] {
                      return "{\"op\":\"contact\",\"a\":" + polytopeJson(c.va) + ",\"b\":" + polytopeJson(c.vb) + "}";
                  }};
    const ContactResult r = contactQuery(QueryShape::polytope(c.va), QueryShape::polytope(c.vb));
    contactBoolean(e, j, "contact status Ok", "exact", r.status == ContactStatus::Ok, true, true);
    if (r.status != ContactStatus::Ok) return;
    const long double sd = j.signedDistance;
    contactBoolean(e, j, "contact colliding = oracle", "exact outside 1e-12 L + 8uM of touching", r.colliding, sd <= 0,
                   std::abs(sd) > kBooleanBand * L + 8 * kU * M);
    if (r.colliding) checkColliding(e, j, r);
    else checkSeparated(e, j, r);
    checkFeatures(e, j, r);
}

}  // namespace cdlab::demos::stress_engine
