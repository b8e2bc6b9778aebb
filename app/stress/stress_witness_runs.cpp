// `cdlab stress`'s runners on core's query API (core/query): times of impact along sliding and
// grazing paths (timeOfImpactQuery) and distance / penetration of spheres, capsules and polytopes
// (pairQuery), each judged by an independent long double oracle (verification/witness_oracle.h,
// verification/cast_oracle.h), in world units, tolerances as the other witness cells
// (stress_tolerances.h): 1e-9 L + 8 u M.
//
// Time of impact: A translated by x touches B iff x lies in D = conv{b_j − a_i}, so A(t) and B(t)
// touch iff t m lies in D, m = motionA − motionB; sd(t) = the oracle's signed distance of t m to D
// (the largest signed distance to D's facet planes: exact inside, a lower bound outside that is 0
// only on D) is convex in t. The differences b_j − a_i are taken in double: exact (Sterbenz) where
// the pair's offset dominates, otherwise within u |b_j − a_i| <= 2 u M, inside the 8 u M term; m in
// long double (exact), t m rounded to double (u |m|, inside the 1e-9 L term, L >= |m|). Whether
// t is late is judged at a finer level: D's points exact in long double (ExactDifference), so that
// a path sliding inside a facet's plane by 1e-17 of its size (the reproducer toi_sliding_late, 70
// units of travel while overlapping) is seen overlapping from the stretch's start.
//
// Spheres and capsules: the pair's signed distance (distance apart, minus the depth overlapping) is
// the signed distance of the origin to conv{ca_i − cb_j} ⊕ ball(rA + rB): for two points or
// segments their long double distance minus the radii; with a polytope the witness oracle's on the
// differences (in double, as above), exact on both sides for a positive radius (the brute force
// over the difference's triangles outside its hull, the facet planes inside).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/stress/stress_engine.h"
#include "core/query/cast.h"
#include "core/query/pair.h"
#include "core/query/shape.h"
#include "verification/cast_oracle.h"

namespace cdlab::demos::stress_engine {

namespace {

using stress_cases::Family;
using stress_cases::RoundedCase;
using stress_cases::ToiCase;
using stress_tolerances::kAxisFactor;
using stress_tolerances::kBooleanBand;
using stress_tolerances::kDepthTol;
using stress_tolerances::kDistanceTol;
using verification::toL;
using verification::WitnessCheck;

/// {b_j − a_i} in double (file comment).
std::vector<Vec3> differencePoints(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    std::vector<Vec3> d;
    for (const Vec3& y : b)
        for (const Vec3& x : a) d.push_back(y - x);
    return d;
}

/// The vertices of a body at time t (one rounding of v + t m, computed in long double).
std::vector<Vec3> movedTo(const std::vector<Vec3>& v, const Vec3& motion, double t) {
    std::vector<Vec3> out;
    for (const Vec3& x : v) out.push_back((toL(x) + static_cast<long double>(t) * toL(motion)).cast<double>());
    return out;
}

/// The time of impact oracle: sd(t) of the relative path t m against D (file comment).
struct ToiOracle {
    WitnessBody d;
    verification::LVec m;
    long double sd(long double t) const { return d.signedDistance((t * m).cast<double>()); }
    long double minimum(long double tMax) const {
        return cast_oracle::minimumOfConvex([this](long double t) { return sd(t); }, tMax).value;
    }
};

/// D = conv{b_j − a_i} with its points exact: differences of doubles in long double (exact within
/// 2^11 of each other; the offset shared by both bodies cancels exactly), relative to b_0 − a_0. Its
/// facet planes by triples, each with a bound on its rounding: upper(x) <= −δ certifies x inside D
/// by at least δ (inside, upper is the signed distance plus the planes' rounding bounds, a few
/// 1e-19 of D's size on well-shaped facets; outside, the facet plane that separates makes it
/// positive). So a relative path 1e-17 of D's size inside a facet's plane is seen inside (the
/// WitnessBody D above rounds the differences to double, ~1e-16). Nearly collinear triples are
/// skipped (a facet of these bodies has a well-shaped one); a missing facet would make upper too
/// small, never too large.
class ExactDifference {
public:
    ExactDifference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) : ref_(toL(b[0]) - toL(a[0])) {
        for (const Vec3& y : b)
            for (const Vec3& x : a) p_.push_back(toL(y) - toL(x) - ref_);
        for (const verification::LVec& q : p_) scale_ = std::max(scale_, q.norm());
        const std::size_t n = p_.size();
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                for (std::size_t k = j + 1; k < n; ++k) addPlane(i, j, k);
    }
    /// The largest signed distance of x − ref to the facet planes plus each plane's rounding bound.
    long double upper(const verification::LVec& x) const {
        const verification::LVec y = x - ref_;
        long double h = -INFINITY;
        for (const Plane& f : planes_)
            h = std::max(h, f.n.dot(y) - f.offset + f.error * (1 + (y - p_[f.at]).norm() / scale_));
        return h;
    }
    long double scale() const { return scale_; }

private:
    struct Plane {
        verification::LVec n;
        long double offset, error;
        std::size_t at;
    };
    // The plane of (i, j, k) when no point lies beyond its rounding bound on both sides: n·p − offset
    // errs by at most ~28 ulps (2^-64) of scale^3 / |cross| (the cross product's relative error
    // times the points' distance), bounded here by 64 ulps + 1e-19 scale.
    void addPlane(std::size_t i, std::size_t j, std::size_t k) {
        verification::LVec n = (p_[j] - p_[i]).cross(p_[k] - p_[i]);
        const long double len = n.norm();
        if (!(len > 0)) return;
        const long double error = 64 * 0x1p-64L * scale_ * scale_ * scale_ / len + 1e-19L * scale_;
        if (error > 1e-9L * scale_) return;  // a nearly collinear triple: a facet has a better one
        n /= len;
        const long double offset = n.dot(p_[i]);
        bool above = false, below = false;
        for (std::size_t m = 0; m < p_.size() && !(above && below); ++m) {
            const long double s = n.dot(p_[m]) - offset;
            above = above || s > error;
            below = below || s < -error;
        }
        if (above == below) return;  // points on both sides, or all on it (D is solid here)
        planes_.push_back(above ? Plane{-n, -offset, error, i} : Plane{n, offset, error, i});
    }
    verification::LVec ref_;
    std::vector<verification::LVec> p_;
    long double scale_ = 0;
    std::vector<Plane> planes_;
};

/// The first t in [0, 1] at which the relative path certainly overlaps D (ExactDifference's upper
/// bound below −1e-19 of D's size and the path), or −1.
long double firstOverlap(const ToiCase& c) {
    const ExactDifference d(c.va, c.vb);
    const verification::LVec m = toL(c.motionA) - toL(c.motionB);
    const long double margin = 1e-19L * (d.scale() + m.norm());
    return cast_oracle::firstRootOfConvex([&](long double t) { return d.upper(t * m) + margin; }, 1);
}

std::string toiQuery(const ToiCase& c) {
    return "{\"op\":\"time_of_impact\",\"a\":" + polytopeJson(c.va) + ",\"b\":" + polytopeJson(c.vb) +
           ",\"motion_a\":" + vec(c.motionA) + ",\"motion_b\":" + vec(c.motionB) + "}";
}

/// A judged boolean: error 1 where decided and wrong.
void booleanCell(Engine& e, const std::string& family, const std::string& check, const std::string& text, double param,
                 bool got, bool expected, bool decided, int index, const std::function<std::string()>& query) {
    Check k;
    k.got = got;
    k.expected = expected;
    k.error = decided && got != expected ? 1.0 : 0.0;
    k.tolerance = 0.5;
    e.record(family, check, text, false, param, k, query, index);
}

/// A hit at t (not initially overlapping): touching at t (not early), no overlap before t (not
/// late), and the contact fields at t: points on A(t) and B(t), pointA = pointB, the normal a
/// touching direction, h_{A(t) − B(t)}(n) = 0.
void checkToiContact(Engine& e, const Family& f, int index, const ToiCase& c, const ToiOracle& o,
                     const TimeOfImpactResult& r, double L, double M, const std::function<std::string()>& query) {
    const double tol = kWitnessTol * L + 8 * kU * M;
    const double t = e.tampered("toi_t", r.t);
    const std::string text = "1e-9 L + 8uM";
    witnessCell(e, f.name, "toi apart at t", text, false, c.param, static_cast<double>(o.sd(t)), tol, L, index, query);
    witnessCell(e, f.name, "toi overlap before t", text, false, c.param, static_cast<double>(-o.minimum(t)), tol, L,
                index, query);
    // Late along the path: the path length from the first time the bodies certainly overlap (the
    // exact-differences oracle below) to t. A path sliding along a facet of D within rounding of its
    // plane touches over a whole stretch, where the two checks above accept any t; inside by 1e-17
    // W, its exact first contact is the stretch's start (toi_sliding_late, 70 units late).
    const long double overlap = firstOverlap(c);
    witnessCell(e, f.name, "toi t <= first overlap", "1e-9 L + 8uM (path length; D exact)", false, c.param,
                overlap < 0 ? 0.0 : static_cast<double>((t - overlap) * o.m.norm()), tol, L, index, query);
    const WitnessBody at = WitnessBody::polytope(movedTo(c.va, c.motionA, t));
    const WitnessBody bt = WitnessBody::polytope(movedTo(c.vb, c.motionB, t));
    verification::WitnessTolerances k;
    k.onBodyA = k.onBodyB = k.offset = k.normal = tol;
    const WitnessCheck w = verification::checkWitness(at, bt, r.pointA, r.pointB, r.normal, 0.0, k);
    witnessCell(e, f.name, "toi pointA on A(t)", text, false, c.param, w.pointAOff, tol, L, index, query);
    witnessCell(e, f.name, "toi pointB on B(t)", text, false, c.param, w.pointBOff, tol, L, index, query);
    witnessCell(e, f.name, "toi pointA = pointB", text, false, c.param, w.offset, tol, L, index, query);
    witnessCell(e, f.name, "toi normal |h_{A(t)-B(t)}(n)|", text, false, c.param,
                w.normalLength <= 1e-12 ? w.normal : INFINITY, tol, L, index, query);
}

// ---- Spheres and capsules ------------------------------------------------------------------------

QueryShape roundedShape(const std::vector<Vec3>& core, double r) {
    if (core.size() == 1) return QueryShape::sphere(core[0], r);
    if (core.size() == 2) return QueryShape::capsule(core[0], core[1], r);
    return QueryShape::polytope(core);
}

std::string roundedJson(const std::vector<Vec3>& core, double r) {
    if (core.size() == 1) return "{\"sphere\":{\"center\":" + vec(core[0]) + ",\"radius\":" + num(r) + "}}";
    if (core.size() == 2)
        return "{\"capsule\":{\"a\":" + vec(core[0]) + ",\"b\":" + vec(core[1]) + ",\"radius\":" + num(r) + "}}";
    return polytopeJson(core);
}

/// The pair's signed distance (file comment). Two points or segments: their distance in long double
/// (cast_oracle: the closed form from a point, a ternary search along a segment) minus the radii —
/// their difference is flat (a parallelogram at most), so this is exact on both sides, and the
/// facet planes of its four rounded points would not bound it. With a polytope: the origin against
/// conv{ca_i − cb_j} ⊕ ball(ra + rb) (ra + rb > 0: never two polytopes).
long double roundedSignedDistance(const RoundedCase& c) {
    const long double radii = static_cast<long double>(c.ra) + c.rb;
    if (c.ca.size() <= 2 && c.cb.size() <= 2)
        return cast_oracle::segmentSegmentDistance(toL(c.ca.front()), toL(c.ca.back()), toL(c.cb.front()),
                                                   toL(c.cb.back())) -
               radii;
    return WitnessBody::rounded(differencePoints(c.cb, c.ca), c.ra + c.rb).signedDistance(Vec3::Zero());
}

/// One pair query's answer against the oracle's signed distance `sd` (> 0 apart, −depth
/// overlapping): the verdict outside the boolean band, the distance or depth, and every witness
/// field (checkWitness: points on their bodies, pointA − pointB = s n, h_{A−B}(n) = s).
void checkRoundedAnswer(Engine& e, const Family& f, int index, const RoundedCase& c, const WitnessPair& w,
                        long double sd, bool depthAsked, const PairResult& p,
                        const std::function<std::string()>& query) {
    const std::string op = depthAsked ? "penetration" : "distance";
    const double band = kBooleanBand * w.L + 8 * kU * w.M;
    const bool hit = e.tampered("rounded_intersect", p.intersect ? 1.0 : 0.0) != 0.0;
    booleanCell(e, f.name, op + " intersect = oracle", "exact outside 1e-12 L + 8uM of touching", c.param, hit, sd <= 0,
                std::abs(sd) > band, index, query);
    if (hit && !depthAsked) return;
    const double value = hit ? p.depth : -p.distance;  // s: depth, or minus the distance
    Check v;
    v.got = hit ? p.depth : p.distance;
    v.expected = static_cast<double>(hit ? -sd : sd);
    v.error = std::abs(static_cast<double>(static_cast<long double>(value) + sd)) / w.L;
    v.tolerance = (hit ? kDepthTol : kDistanceTol) + 8 * kU * w.M / w.L;
    e.record(f.name, op + (hit ? " depth = oracle" : " distance = oracle"), hit ? "1e-10 L + 8uM" : "1e-12 L + 8uM",
             false, c.param, v, query, index);
    Vec3 pointA = p.pointA;
    pointA.x() = e.tampered("rounded_witness", pointA.x());
    verification::WitnessTolerances t = witnessTolerances(w);
    // The normal: EPA's tolerance (depth), GJK's axis tolerance apart (stress_tolerances.h).
    t.normal = hit ? v.tolerance * w.L : kAxisFactor * t.offset * (1.0 + 4.0 * w.L / p.distance);
    const WitnessCheck k = verification::checkWitness(w.a, w.b, pointA, p.pointB, p.normal, value, t);
    const std::string s = hit ? "depth" : "-d";
    witnessCell(e, f.name, op + " pointA on A", "1e-9 L_A + 8uM_A", false, c.param, k.pointAOff, t.onBodyA, w.La, index,
                query);
    witnessCell(e, f.name, op + " pointB on B", "1e-9 L_B + 8uM_B", false, c.param, k.pointBOff, t.onBodyB, w.Lb, index,
                query);
    witnessCell(e, f.name, op + " pA-pB = " + s + " n", "1e-9 L + 8uM", false, c.param, k.offset, t.offset, w.L, index,
                query);
    witnessCell(e, f.name, op + (hit ? " normal |h(n)-depth|" : " axis |h(n)+d|"),
                hit ? "1e-10 L + 8uM" : "4 tau (1 + 4 L/d), tau = 1e-9 L + 8uM", false, c.param,
                k.normalLength <= 1e-12 ? k.normal : INFINITY, t.normal, w.L, index, query);
}

}  // namespace

void runToi(Engine& e, const Family& f, int index, const ToiCase& c) {
    const Vec3 m = c.motionA - c.motionB;
    const ToiOracle o{WitnessBody::polytope(differencePoints(c.va, c.vb)), toL(c.motionA) - toL(c.motionB)};
    const double L = std::max(centroidRadius(c.va), centroidRadius(c.vb)) + m.norm();
    const double M = std::max(maxAbs(c.va), maxAbs(c.vb)) +
                     std::max(c.motionA.cwiseAbs().maxCoeff(), c.motionB.cwiseAbs().maxCoeff());
    const double tol = kWitnessTol * L + 8 * kU * M;
    const auto query = [&c] { return toiQuery(c); };
    const ImpactQueryResult q =
        timeOfImpactQuery(QueryShape::polytope(c.va), c.motionA, QueryShape::polytope(c.vb), c.motionB);
    booleanCell(e, f.name, "toi status Ok", "exact", c.param, q.status == PairStatus::Ok, true, true, index, query);
    if (q.status != PairStatus::Ok) return;
    const TimeOfImpactResult& r = q.result;
    const bool hit = e.tampered("toi_hit", r.hit ? 1.0 : 0.0) != 0.0;
    const long double lowest = o.minimum(1);
    const bool enters = lowest < 0;
    const bool decided = std::abs(lowest) > tol;
    booleanCell(e, f.name, "toi hit = oracle", "exact outside 1e-9 L + 8uM of touching", c.param, hit, enters, decided,
                index, query);
    if (!hit) return;
    const long double start = o.sd(0);
    booleanCell(e, f.name, "toi overlapping at 0 = oracle", "exact outside 1e-9 L + 8uM of touching", c.param,
                r.initiallyOverlapping, start <= 0, std::abs(start) > tol, index, query);
    if (!r.initiallyOverlapping) checkToiContact(e, f, index, c, o, r, L, M, query);
}

void runRounded(Engine& e, const Family& f, int index, const RoundedCase& c) {
    const double La = centroidRadius(c.ca) + c.ra, Lb = centroidRadius(c.cb) + c.rb;
    const double Ma = maxAbs(c.ca) + c.ra, Mb = maxAbs(c.cb) + c.rb;
    const WitnessPair w{WitnessBody::rounded(c.ca, c.ra), WitnessBody::rounded(c.cb, c.rb), La, Ma, Lb, Mb,
                        std::max(La, Lb), std::max(Ma, Mb)};
    const long double sd = roundedSignedDistance(c);
    const QueryShape a = roundedShape(c.ca, c.ra), b = roundedShape(c.cb, c.rb);
    for (const bool depth : {false, true}) {
        const char* op = depth ? "penetration" : "distance";
        const auto query = [&c, op] {
            return std::string("{\"op\":\"") + op + "\",\"a\":" + roundedJson(c.ca, c.ra) +
                   ",\"b\":" + roundedJson(c.cb, c.rb) + "}";
        };
        PairOptions options;
        options.depth = depth;
        const PairResult p = pairQuery(a, b, options);
        booleanCell(e, f.name, std::string(op) + " status Ok", "exact", c.param, p.status == PairStatus::Ok, true, true,
                    index, query);
        if (p.status == PairStatus::Ok) checkRoundedAnswer(e, f, index, c, w, sd, depth, p, query);
    }
}

}  // namespace cdlab::demos::stress_engine
