// Every exactness reproducer of tests/data/exact-2026-11-29/ (its README: query lines an exact-rational
// oracle answered differently from `cdlab query`, NAME.expected.json the exact answer), answered
// in-process by the query tool (answerQuery, as `cdlab query` answers a line) and judged field by
// field with the tolerances of docs/accuracy.md's "What each answer meets":
//   - against the exact answer of NAME.expected.json where the folder gives one (verdict, depth,
//     the normals of least overlap, distance, t, the hit point, the entry face's normal);
//   - against independent oracles in long double for every other field: h_{A−B}(n) by brute force
//     over the inputs (verification/witness_oracle.h's support), witnesses on their bodies (the
//     distance to the triangles of the body's points, exact outside it), point_a − point_b = depth·n,
//     the least overlap of two polytopes over every vertex-triple normal and every cross product of a
//     vertex difference of A with one of B, the distance of the origin to conv(B − A) over its
//     triangles, ray and time-of-impact roots in closed form (spheres) or by conservative advancement
//     on an exact signed distance (polytopes: of the origin against the shape or conv(B − A); a sphere
//     against a cylinder), contact features against the support sets along the normal;
//   - and what the folder's README states: more.jsonl's sphere_far_raycast t = 999999999 and
//     sphere_far_toi t = (4e18 − 2) / 4.01e18 (both come out of the closed forms), the boxes and
//     spheres of toi_large_motion.jsonl 3 apart (no initially_overlapping), quaternion_underflow.jsonl
//     answered, not refused.
// Sizes as in `cdlab stress`: L_body a body's circumradius about its vertex centroid (+ its radius),
// L the larger of the two, M the largest |coordinate| (for a time of impact, also at the contact
// time), u = 2^-53. Witnesses, contact points and touching points: on their bodies within
// 1e-9 L_body + 8uM, point_a − point_b within 1e-9 L + 8uM (the penetration row, as `cdlab stress`
// checks it). The oracles' own error is long double's rounding times the conditioning: about 3e-8 on
// penetration_witness_pair's B (a sliver of relative volume 1e-14, 1e6 across), where the tolerance
// is 1.3e-3. Every check names the file, the query's id and the field, with the measured error and
// its tolerance; an answer key no check judges fails as "unjudged".
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/query/query.h"
#include "core/base/types.h"
#include "verification/long_double_geometry.h"
#include "verification/witness_oracle.h"

namespace exact_reproducers {

using cdlab::Vec3;
using cdlab::demos::Json;
using cdlab::long_double::LVec;
using cdlab::long_double::toL;
using cdlab::verification::WitnessBody;
using LMat = Eigen::Matrix<long double, 3, 3>;

constexpr double kU = 0x1p-53;
constexpr double kDepthTol = 1e-10;     // penetration depth and normal, contact depth: 1e-10 L + 8uM
constexpr double kDistanceTol = 1e-12;  // distance: 1e-12 L + 8uM
constexpr double kWitnessTol = 1e-9;    // witnesses: 1e-9 L_body + 8uM on their body, 1e-9 L + 8uM apart
constexpr double kRayTol = 1e-12;       // raycast, time of impact: the first hit within 1e-12 of the size
constexpr double kRoundings = 8;        // spheres and capsules: t within 8 roundings of the exact root
constexpr double kFaceBias = 0.02;      // contact's face preference: depth <= least overlap · 1.02 + tol
constexpr double kAxisFactor = 4;       // a separating axis from witnesses: |h(n) + d| <= 4 tau (1 + 4 L / d)
constexpr double kAngleTol = 1e-9;      // a normal equal to an exact one, radians
constexpr double kUnitTol = 1e-12;      // | |n| − 1 |

const std::string kFolder = CDLAB_SOURCE_DIR "/tests/data/exact-2026-11-29/";

// The reproducer files, one TEST_CASE each (the coverage case checks the folder holds exactly these).
const std::vector<std::string> kFiles = {"contact_edge_edge_depth0",
                                         "contact_face_bias",
                                         "contact_needle_refused",
                                         "contact_parallel_edges_depth",
                                         "contact_points_pair",
                                         "contact_tiny_cube_refused",
                                         "more",
                                         "penetration_needle_far",
                                         "penetration_witness_obb",
                                         "penetration_witness_off_shape",
                                         "penetration_witness_pair",
                                         "penetration_witness_parallel_edges",
                                         "quaternion_underflow",
                                         "raycast_face_plane_t0",
                                         "raycast_face_plane_wrong_t",
                                         "toi_large_motion",
                                         "toi_sliding_early",
                                         "toi_sliding_late"};

// ---- JSON ------------------------------------------------------------------------------------------

double num(const Json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

Vec3 vec(const Json& j) {
    if (!j.is_array() || j.size() != 3) return Vec3::Constant(NAN);
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = j[i].is_number() ? j[i].get<double>() : NAN;
    return v;
}

Vec3 vecAt(const Json& j, const char* key) { return j.contains(key) ? vec(j[key]) : Vec3::Constant(NAN); }

std::string text(long double x) {
    std::ostringstream s;
    s.precision(17);
    s << static_cast<double>(x);
    return s.str();
}

std::string text(const Vec3& v) { return "[" + text(v.x()) + ", " + text(v.y()) + ", " + text(v.z()) + "]"; }

// ---- Checks ------------------------------------------------------------------------------------------

/// One query's checks: each names the file, the id and the field, with the measured error and its
/// tolerance (NaN measures fail).
struct Judge {
    std::string file, id;
    int checks = 0;

    void le(const std::string& field, long double measured, double tol, const std::string& detail = "") {
        ++checks;
        std::ostringstream s;
        s.precision(4);
        s << file << " / " << id << " / " << field << ": measured " << static_cast<double>(measured) << ", tolerance "
          << tol;
        if (!detail.empty()) s << " (" << detail << ")";
        CHECK_MESSAGE(measured <= tol, s.str());
    }
    void ok(const std::string& field, bool good, const std::string& detail = "") {
        ++checks;
        CHECK_MESSAGE(good, (file + " / " + id + " / " + field + (detail.empty() ? "" : ": " + detail)));
    }
    /// The answer's keys are exactly `expected` (a key no check judges is an unjudged field).
    void keys(const Json& answer, const std::set<std::string>& expected) {
        std::set<std::string> got;
        std::string unjudged, missing;
        for (auto it = answer.begin(); it != answer.end(); ++it) got.insert(it.key());
        for (const std::string& k : got)
            if (!expected.count(k)) unjudged += " " + k;
        for (const std::string& k : expected)
            if (!got.count(k)) missing += " " + k;
        ok("the answer's keys", unjudged.empty() && missing.empty(),
           "unjudged (not a key of this answer kind):" + unjudged + ", missing:" + missing);
    }
};

/// |‖n‖ − 1|, the smallest angle between n and one of `exact` (unit vectors), radians.
long double unitError(const Vec3& n) { return std::abs(toL(n).norm() - 1); }

long double angleTo(const Vec3& n, const std::vector<Vec3>& exact) {
    long double best = INFINITY;
    const LVec m = toL(n).normalized();
    for (const Vec3& e : exact) {
        const LVec f = toL(e).normalized();
        best = std::min(best, 2 * std::asin(std::min(1.0L, (m - f).norm() / 2)));
    }
    return best;
}

// ---- Convex hulls by brute force ---------------------------------------------------------------------

/// The distance from the origin to the union of the points, segments and triangles of `p`: the
/// distance to conv(p) when the origin is outside it (the hull's boundary is a union of such
/// triangles, every other one lies inside), with no facet to identify (slivers and needles included).
long double skeletonDistance(const std::vector<LVec>& p) {
    long double best = INFINITY;
    const size_t n = p.size();
    for (size_t i = 0; i < n; ++i) {
        best = std::min(best, p[i].norm());
        for (size_t j = i + 1; j < n; ++j) {
            best = std::min(best, cdlab::long_double::segmentDistanceL(p[i], p[j]));
            for (size_t k = j + 1; k < n; ++k)
                best = std::min(best, cdlab::long_double::triangleDistanceL(p[i], p[j], p[k]));
        }
    }
    return best;
}

/// Whether the origin lies in a (closed, non-degenerate) tetrahedron of four of `p`: in conv(p)
/// (Carathéodory), by barycentric coordinates in long double.
bool insideHull(const std::vector<LVec>& p) {
    const size_t n = p.size();
    auto det = [](const LVec& a, const LVec& b, const LVec& c) { return a.dot(b.cross(c)); };
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k)
                for (size_t l = k + 1; l < n; ++l) {
                    const LVec e1 = p[j] - p[i], e2 = p[k] - p[i], e3 = p[l] - p[i];
                    const long double d = det(e1, e2, e3);
                    if (d == 0) continue;
                    const long double b1 = det(-p[i], e2, e3) / d, b2 = det(e1, -p[i], e3) / d,
                                      b3 = det(e1, e2, -p[i]) / d;
                    if (b1 >= 0 && b2 >= 0 && b3 >= 0 && b1 + b2 + b3 <= 1) return true;
                }
    return false;
}

/// Signed distance of x to conv(p) (<= 0 inside: minus the distance to the nearest triangle).
long double hullSignedDistance(const std::vector<LVec>& pts, const LVec& x) {
    std::vector<LVec> p;
    for (const LVec& q : pts) p.push_back(q - x);
    const long double d = skeletonDistance(p);
    return insideHull(p) ? -d : d;
}

/// Conservative advancement: the first s in [0, len] with f(s) <= eps, for f 1-Lipschitz in s and
/// convex (a signed distance along a straight path): each step s += f(s) stays before the first
/// root. {hit, s}; nullopt when it has not converged within `cap` steps.
std::optional<std::pair<bool, long double>> advance(const std::function<long double(long double)>& f, long double len,
                                                    long double eps, int cap) {
    long double s = 0;
    for (int i = 0; i < cap; ++i) {
        const long double g = f(s);
        if (g <= eps) return std::pair(true, s);
        s += g;
        if (s > len) return std::pair(false, s);
    }
    return std::nullopt;
}

// ---- Bodies as the oracles see them -------------------------------------------------------------------

/// A convex body: conv(pts) (a polytope: its vertices, in the order features name them; a box's corner
/// k has bit i set for the + side of axis i), conv(core) ⊕ ball(radius) (sphere, point, capsule), or a
/// cylinder (centre, unit axis, radius, half height).
struct Body {
    enum class Kind { Polytope, Rounded, Cylinder };
    Kind kind = Kind::Polytope;
    std::vector<Vec3> pts;
    double radius = 0, halfHeight = 0;
    LVec center = LVec::Zero(), axis = LVec::UnitY();
    std::optional<WitnessBody> oracle;  // polytope, rounded

    static Body polytope(std::vector<Vec3> v) {
        Body b;
        b.pts = std::move(v);
        b.oracle = WitnessBody::polytope(b.pts);
        return b;
    }
    static Body rounded(std::vector<Vec3> core, double r) {
        Body b;
        b.kind = Kind::Rounded;
        b.pts = std::move(core);
        b.radius = r;
        b.oracle = WitnessBody::rounded(b.pts, r);
        return b;
    }
    bool pointCore() const { return kind == Kind::Rounded && pts.size() == 1; }

    Body moved(const LVec& shift) const {
        Body b = *this;
        for (Vec3& p : b.pts) p = (toL(p) + shift).cast<double>();
        b.center += shift;
        if (kind == Kind::Polytope) b.oracle = WitnessBody::polytope(b.pts);
        if (kind == Kind::Rounded) b.oracle = WitnessBody::rounded(b.pts, radius);
        return b;
    }
    LVec reference() const { return kind == Kind::Cylinder ? center : toL(pts[0]); }

    /// Signed distance of x (<= 0 on or inside; exact outside, inside minus the distance to the
    /// nearest triangle of the points). Polytope and rounded bodies by brute force over the points'
    /// triangles (WitnessBody's facet planes miss a sliver facet of contact_tiny_cube_refused's A).
    long double signedDistance(const Vec3& x) const { return signedDistanceL(toL(x)); }
    long double signedDistanceL(const LVec& x) const {
        if (kind != Kind::Cylinder) {
            std::vector<LVec> p;
            for (const Vec3& q : pts) p.push_back(toL(q));
            return hullSignedDistance(p, x) - radius;
        }
        const LVec d = x - center;
        const long double y = d.dot(axis), rho = (d - y * axis).norm();
        const long double dr = rho - radius, dy = std::abs(y) - halfHeight;
        if (dr <= 0 && dy <= 0) return std::max(dr, dy);
        return std::hypot(std::max(dr, 0.0L), std::max(dy, 0.0L));
    }
    /// The nearest point of a cylinder to an outside point x.
    LVec cylinderClosest(const LVec& x) const {
        const LVec d = x - center;
        const long double y = d.dot(axis);
        const LVec radial = d - y * axis;
        const long double rho = radial.norm();
        return center +
               std::clamp(y, -static_cast<long double>(halfHeight), static_cast<long double>(halfHeight)) * axis +
               (rho > radius ? radial * (radius / rho) : radial);
    }
    /// max over the body of (x − ref)·n.
    long double support(const LVec& n, const LVec& ref) const {
        if (kind != Kind::Cylinder) return oracle->support(n, ref);
        const long double na = n.dot(axis);
        return (center - ref).dot(n) + halfHeight * std::abs(na) +
               radius * std::sqrt(std::max(0.0L, n.squaredNorm() - na * na));
    }
    /// L_body: the circumradius about the vertex centroid, plus the radius.
    double size() const {
        if (kind == Kind::Cylinder) return std::hypot(radius, halfHeight);
        LVec c = LVec::Zero();
        for (const Vec3& p : pts) c += toL(p);
        c /= static_cast<long double>(pts.size());
        long double r = 0;
        for (const Vec3& p : pts) r = std::max(r, (toL(p) - c).norm());
        return static_cast<double>(r) + radius;
    }
    /// M_body: the largest |coordinate| of a point of the body (bound).
    double maxCoord() const {
        if (kind == Kind::Cylinder)
            return static_cast<double>(center.cwiseAbs().maxCoeff()) + std::hypot(radius, halfHeight);
        double m = 0;
        for (const Vec3& p : pts) m = std::max(m, p.cwiseAbs().maxCoeff());
        return m + radius;
    }
};

/// h_{A−B}(n) = h_A(n) + h_B(−n), relative to A's reference point.
long double supportOfDifference(const Body& a, const Body& b, const Vec3& n) {
    const LVec nl = toL(n), ref = a.reference();
    return a.support(nl, ref) + b.support(-nl, ref);
}

/// A quaternion [w, x, y, z] as a rotation matrix (scaled by its largest component first, so that
/// 1e-200 and 1e200 normalise like 1).
LMat rotationOf(const Json& q) {
    if (!q.is_array() || q.size() != 4) return LMat::Identity();
    long double c[4], scale = 0, len = 0;
    for (int i = 0; i < 4; ++i) {
        c[i] = q[i].get<double>();
        scale = std::max(scale, std::abs(c[i]));
    }
    if (!(scale > 0)) return LMat::Identity();
    for (long double& x : c) {
        x /= scale;
        len += x * x;
    }
    for (long double& x : c) x /= std::sqrt(len);
    const long double w = c[0], x = c[1], y = c[2], z = c[3];
    LMat r;
    r << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
        2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
        2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
    return r;
}

/// The 8 corners of a box: corner k = center + R (s ∘ e), s_i = + where bit i of k is set.
std::vector<Vec3> boxCorners(const LVec& center, const LMat& r, const Vec3& e) {
    std::vector<Vec3> v;
    for (int k = 0; k < 8; ++k) {
        LVec s;
        for (int i = 0; i < 3; ++i) s[i] = (k >> i & 1 ? 1.0L : -1.0L) * e[i];
        v.push_back((center + r * s).cast<double>());
    }
    return v;
}

LVec centerOf(const Json& s) { return toL(s.contains("center") ? vec(s["center"]) : vecAt(s, "position")); }

/// The query's shape as a Body (nullopt: a kind these oracles do not know).
std::optional<Body> parseShape(const Json& shape) {
    if (!shape.is_object() || shape.size() != 1) return std::nullopt;
    const std::string kind = shape.begin().key();
    const Json& s = shape.begin().value();
    const LMat r = s.is_object() && s.contains("rotation") ? rotationOf(s["rotation"]) : LMat::Identity();
    if (kind == "polytope" || kind == "hull") {
        const LVec p = s.contains("position") ? toL(vec(s["position"])) : LVec::Zero();
        std::vector<Vec3> v;
        for (const Json& x : s.at("vertices")) v.push_back((r * toL(vec(x)) + p).cast<double>());
        return Body::polytope(v);
    }
    if (kind == "aabb") {
        const Vec3 lo = vec(s.at("min")), hi = vec(s.at("max"));
        std::vector<Vec3> v;
        for (int k = 0; k < 8; ++k)
            v.push_back(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
        return Body::polytope(v);
    }
    if (kind == "obb" || kind == "box") {
        const LVec c = s.contains("center") || s.contains("position") ? centerOf(s) : LVec::Zero();
        return Body::polytope(boxCorners(c, r, vec(s.at("half_extents"))));
    }
    if (kind == "sphere") return Body::rounded({centerOf(s).cast<double>()}, num(s, "radius"));
    if (kind == "point") return Body::rounded({vec(s)}, 0.0);
    if (kind == "capsule") return Body::rounded({vec(s.at("a")), vec(s.at("b"))}, num(s, "radius"));
    if (kind == "cylinder") {
        Body b;
        b.kind = Body::Kind::Cylinder;
        b.radius = num(s, "radius");
        if (s.contains("a")) {
            const LVec a = toL(vec(s["a"])), c = toL(vec(s.at("b")));
            b.center = (a + c) / 2;
            b.halfHeight = static_cast<double>((c - a).norm() / 2);
            b.axis = (c - a).normalized();
        } else {
            b.center = s.contains("center") || s.contains("position") ? centerOf(s) : LVec::Zero();
            b.halfHeight = num(s, "half_height");
            b.axis = r * LVec::UnitY();
        }
        return b;
    }
    return std::nullopt;
}

/// The tolerances' sizes of a pair (file comment).
struct Scale {
    double La = 0, Lb = 0, Ma = 0, Mb = 0, L = 0, M = 0;
    double depth() const { return kDepthTol * L + 8 * kU * M; }
    double distance() const { return kDistanceTol * L + 8 * kU * M; }
    double onA() const { return kWitnessTol * La + 8 * kU * Ma; }
    double onB() const { return kWitnessTol * Lb + 8 * kU * Mb; }
    double offset() const { return kWitnessTol * L + 8 * kU * M; }
};

Scale scaleOf(const Body& a, const Body& b) {
    Scale s;
    s.La = a.size();
    s.Lb = b.size();
    s.Ma = a.maxCoord();
    s.Mb = b.maxCoord();
    s.L = std::max(s.La, s.Lb);
    s.M = std::max(s.Ma, s.Mb);
    return s;
}

// ---- Oracles ----------------------------------------------------------------------------------------------

/// The least overlap h_{A−B}(u) of two polytopes over every vertex-triple normal of each and every
/// cross product of a vertex difference of A with one of B, both orientations: a superset of the
/// separating-axis candidates, each a valid direction, so its minimum is the penetration depth
/// (negative: separated, a lower bound of −distance).
long double leastOverlap(const Body& a, const Body& b) {
    const LVec ref = toL(a.pts[0]);
    std::vector<LVec> pa, pb, axes;
    for (const Vec3& p : a.pts) pa.push_back(toL(p) - ref);
    for (const Vec3& p : b.pts) pb.push_back(toL(p) - ref);
    for (const std::vector<LVec>* s : {&pa, &pb})
        for (size_t i = 0; i < s->size(); ++i)
            for (size_t j = i + 1; j < s->size(); ++j)
                for (size_t k = j + 1; k < s->size(); ++k) axes.push_back(((*s)[j] - (*s)[i]).cross((*s)[k] - (*s)[i]));
    for (size_t i = 0; i < pa.size(); ++i)
        for (size_t j = i + 1; j < pa.size(); ++j)
            for (size_t k = 0; k < pb.size(); ++k)
                for (size_t l = k + 1; l < pb.size(); ++l) axes.push_back((pa[j] - pa[i]).cross(pb[l] - pb[k]));
    long double best = INFINITY;
    for (LVec u : axes) {
        const long double len = u.norm();
        if (!(len > 0)) continue;
        u /= len;
        for (int sign : {1, -1}) {
            long double maxA = -INFINITY, minB = INFINITY;
            for (const LVec& p : pa) maxA = std::max(maxA, sign * u.dot(p));
            for (const LVec& p : pb) minB = std::min(minB, sign * u.dot(p));
            best = std::min(best, maxA - minB);
        }
    }
    return best;
}

/// The points b_j − a_i (long double, duplicates dropped): conv of them is the cores' B − A.
std::vector<LVec> differencePoints(const Body& a, const Body& b) {
    std::vector<LVec> d;
    for (const Vec3& q : b.pts)
        for (const Vec3& p : a.pts) {
            const LVec x = toL(q) - toL(p);
            if (std::find(d.begin(), d.end(), x) == d.end()) d.push_back(x);
        }
    return d;
}

/// The distance between two polytopes or rounded bodies (cores + radii): the origin against
/// conv{b_j − a_i} by brute force; nullopt for a cylinder.
std::optional<long double> exactDistance(const Body& a, const Body& b) {
    if (a.kind == Body::Kind::Cylinder || b.kind == Body::Kind::Cylinder) return std::nullopt;
    const std::vector<LVec> d = differencePoints(a, b);
    if (insideHull(d)) return 0.0L;
    return std::max(0.0L, skeletonDistance(d) - a.radius - b.radius);
}

/// The first t >= 0 at which the origin moving along v (t in [0, tMax]) is within R of p0: closed form,
/// cancellation-free (nullopt: never). normal: (x(t) − p0) / R, unit.
struct SphereRoot {
    long double t;
    LVec normal;
};
std::optional<SphereRoot> sphereRoot(const LVec& p0, const LVec& v, long double r, long double tMax) {
    const long double c = p0.squaredNorm() - r * r;
    if (c <= 0) return SphereRoot{0, LVec::Zero()};
    const long double vv = v.squaredNorm(), b = v.dot(p0), disc = vv * r * r - v.cross(p0).squaredNorm();
    if (b <= 0 || disc < 0) return std::nullopt;
    const long double t = c / (b + std::sqrt(disc));
    if (t > tMax) return std::nullopt;
    return SphereRoot{t, (t * v - p0) / r};
}

/// What an answer is judged against: the expected file's exact fields, else the oracles'.
struct Exact {
    std::optional<bool> verdict;  // intersect / colliding / hit
    std::optional<long double> depth, distance, t;
    std::vector<Vec3> normals;  // least-overlap normals, the entry face's, the time of impact's
    std::optional<Vec3> point;  // raycast
    bool initiallyOverlapping = false;
    std::string source;
};

Exact fromExpectedFile(const Json& e) {
    Exact x;
    x.source = "expected file";
    for (const char* k : {"intersect", "hit"})
        if (e.contains(k)) x.verdict = e[k].get<bool>();
    if (e.contains("depth")) x.depth = e["depth"].get<double>();
    if (e.contains("distance")) x.distance = e["distance"].get<double>();
    if (e.contains("t")) x.t = e["t"].get<double>();
    if (e.contains("point")) x.point = vec(e["point"]);
    if (e.contains("normal(s) of least overlap"))
        for (const Json& n : e["normal(s) of least overlap"]) x.normals.push_back(vec(n));
    for (const char* k : {"normal_of_entry_face", "normal"})
        if (e.contains(k)) x.normals.push_back(vec(e[k]));
    return x;
}

/// The exact verdict and depth or distance of a pair (polytopes: least overlap; else the distance).
Exact pairOracle(const Body& a, const Body& b) {
    Exact x;
    if (a.kind == Body::Kind::Polytope && b.kind == Body::Kind::Polytope) {
        const long double lo = leastOverlap(a, b);
        if (lo >= 0) {
            x.verdict = true;
            x.depth = lo;
            x.source = "oracle: least overlap";
            return x;
        }
    }
    if (const auto d = exactDistance(a, b)) {
        x.verdict = *d == 0;
        if (*d > 0) x.distance = *d;
        x.source = "oracle: distance to conv(B - A)";
    }
    return x;
}

/// The ray o + t d against a body: a sphere in closed form, anything else by conservative advancement
/// on its signed distance.
Exact rayOracle(const Body& s, const Vec3& o, const Vec3& d, long double tMax) {
    Exact x;
    if (s.pointCore()) {
        x.source = "oracle: closed form";
        const auto root = sphereRoot(toL(s.pts[0]) - toL(o), toL(d), s.radius, tMax);
        x.verdict = root.has_value();
        if (root) {
            x.t = root->t;
            x.point = (toL(o) + root->t * toL(d)).cast<double>();
            if (root->t > 0) x.normals.push_back(root->normal.cast<double>());
        }
    } else {
        const LVec lo = toL(o), u = toL(d).normalized();
        const long double len = tMax * toL(d).norm(), eps = 4 * kU * (s.size() + s.maxCoord());
        const auto r = advance([&](long double t) { return s.signedDistanceL(lo + t * u); }, len, eps, 10000);
        if (!r) return x;  // no convergence: no oracle
        x.source = "oracle: conservative advancement";
        x.verdict = r->first;
        if (r->first) x.t = r->second / toL(d).norm(), x.point = (lo + r->second * u).cast<double>();
    }
    return x;
}

/// The first contact of a (moving by ma) and b (by mb), t in [0, 1]: two spheres in closed form, two
/// polytopes by conservative advancement of the origin along ma − mb against conv(B − A), a sphere
/// against anything else by conservative advancement of its centre on the other's signed distance.
/// The normal (a toward b) where it is unique and computable.
Exact toiOracle(const Body& a, const Body& b, const Vec3& ma, const Vec3& mb) {
    Exact x;
    const LVec v = toL(ma) - toL(mb);  // the origin's path against B − A
    if (a.pointCore() && b.pointCore()) {
        x.source = "oracle: closed form";
        const auto root = sphereRoot(toL(b.pts[0]) - toL(a.pts[0]), v, a.radius + b.radius, 1);
        x.verdict = root.has_value();
        if (root) x.t = root->t, x.initiallyOverlapping = root->t == 0;
        if (root && root->t > 0) x.normals.push_back((-root->normal).cast<double>());
    } else if (a.kind == Body::Kind::Polytope && b.kind == Body::Kind::Polytope) {
        const std::vector<LVec> d = differencePoints(a, b);
        const LVec u = v.normalized();
        const long double eps = 4 * kU * (a.size() + b.size() + a.maxCoord() + b.maxCoord());
        const auto r = advance([&](long double s) { return hullSignedDistance(d, s * u); }, v.norm(), eps, 1000);
        if (!r) return x;  // no convergence: no oracle
        x.source = "oracle: conservative advancement on B - A";
        x.verdict = r->first;
        if (r->first) x.t = r->second / v.norm(), x.initiallyOverlapping = r->second == 0;
    } else if (a.pointCore() || b.pointCore()) {
        const Body& p = a.pointCore() ? a : b;
        const Body& other = a.pointCore() ? b : a;
        const LVec w = a.pointCore() ? LVec(v) : LVec(-v);  // p's motion relative to the other
        const LVec c = toL(p.pts[0]), u = w.normalized();
        const long double eps = 4 * kU * (other.size() + other.maxCoord() + p.radius);
        const auto r =
            advance([&](long double s) { return other.signedDistanceL(c + s * u) - p.radius; }, w.norm(), eps, 100000);
        if (!r) return x;  // no convergence: no oracle
        x.source = "oracle: conservative advancement";
        x.verdict = r->first;
        if (!r->first) return x;
        const long double s = r->second;
        x.t = s / w.norm();
        x.initiallyOverlapping = s == 0;
        if (s > 0 && other.kind == Body::Kind::Cylinder) {
            const LVec q = c + s * u;
            const LVec n = (q - other.cylinderClosest(q)).normalized();  // other toward p
            x.normals.push_back((a.pointCore() ? LVec(-n) : n).cast<double>());
        }
    }
    return x;
}

// ---- Judging one answer per op ------------------------------------------------------------------------------

/// A separated pair: the distance against the exact one, the axis n (|h_{A−B}(n) + d| within
/// 4 tau (1 + 4 L / d), `cdlab stress`'s rule for GJK's axis), every witness pair on its bodies with
/// point_b − point_a = d n. No n given (the distance op): n = (point_b − point_a) / |...|.
void judgeSeparated(Judge& j, const Body& a, const Body& b, const Scale& s, const Exact& ex, double d,
                    std::optional<Vec3> n, const std::vector<std::pair<Vec3, Vec3>>& pairs) {
    j.ok("distance: an exact distance to judge it by", ex.distance.has_value(), ex.source);
    if (ex.distance)
        j.le("distance |d - exact|", std::abs(d - *ex.distance), s.distance(),
             "returned " + text(d) + ", exact " + text(*ex.distance));
    j.ok("witness pairs", !pairs.empty());
    if (!n && !pairs.empty()) n = (pairs[0].second - pairs[0].first).normalized();
    if (n) {
        j.le("normal | |n| - 1 |", unitError(*n), kUnitTol, text(*n));
        const double tau = s.offset();
        j.le("normal: separating axis |h_{A-B}(n) + d|", std::abs(supportOfDifference(a, b, *n) + d),
             kAxisFactor * tau * (1 + 4 * s.L / d));
    }
    for (size_t i = 0; i < pairs.size(); ++i) {
        const std::string k = pairs.size() > 1 ? "[" + std::to_string(i) + "]" : "";
        const auto& [pa, pb] = pairs[i];
        j.le("point_a" + k + " on A", a.signedDistance(pa), s.onA(), text(pa));
        j.le("point_b" + k + " on B", b.signedDistance(pb), s.onB(), text(pb));
        if (n) j.le("point_b" + k + " - point_a = d n", (toL(pb) - toL(pa) - d * toL(*n)).norm(), s.offset());
    }
}

void judgePenetration(Judge& j, const Body& a, const Body& b, const Json& ans, const Exact& ex) {
    const Scale s = scaleOf(a, b);
    const bool intersect = ans.value("intersect", false);
    j.ok("intersect", ex.verdict && intersect == *ex.verdict,
         "returned " + std::to_string(intersect) + ", " + ex.source);
    const Vec3 n = vecAt(ans, "normal"), pa = vecAt(ans, "point_a"), pb = vecAt(ans, "point_b");
    if (!intersect) {
        j.keys(ans, {"id", "intersect", "distance", "normal", "point_a", "point_b"});
        judgeSeparated(j, a, b, s, ex, num(ans, "distance"), n, {{pa, pb}});
        return;
    }
    j.keys(ans, {"id", "intersect", "depth", "normal", "point_a", "point_b"});
    const double depth = num(ans, "depth"), tol = s.depth();
    j.ok("depth: an exact depth to judge it by", ex.depth.has_value(), ex.source);
    const long double exact = ex.depth.value_or(NAN);
    j.le("depth |depth - exact|", std::abs(depth - exact), tol, "returned " + text(depth) + ", exact " + text(exact));
    j.le("normal | |n| - 1 |", unitError(n), kUnitTol, text(n));
    const long double gap = std::abs(supportOfDifference(a, b, n) - exact), angle = angleTo(n, ex.normals);
    j.ok("normal: h_{A-B}(n) = exact depth, or a least-overlap normal", gap <= tol || angle <= kAngleTol,
         "|h(n) - depth| " + text(gap) + " (tolerance " + text(tol) + "), angle to the nearest listed normal " +
             text(angle) + " (tolerance " + text(kAngleTol) + "), n " + text(n));
    j.le("point_a on A", a.signedDistance(pa), s.onA(), text(pa));
    j.le("point_b on B", b.signedDistance(pb), s.onB(), text(pb));
    j.le("point_a - point_b = depth n", (toL(pa) - toL(pb) - depth * toL(n)).norm(), s.offset());
}

void judgeDistance(Judge& j, const Body& a, const Body& b, const Json& ans, const Exact& ex) {
    const Scale s = scaleOf(a, b);
    const bool intersect = ans.value("intersect", false);
    j.ok("intersect", ex.verdict && intersect == *ex.verdict,
         "returned " + std::to_string(intersect) + ", " + ex.source);
    if (intersect) {
        j.keys(ans, {"id", "intersect", "distance"});
        j.ok("distance 0", num(ans, "distance") == 0);
        return;
    }
    j.keys(ans, {"id", "intersect", "distance", "point_a", "point_b"});
    judgeSeparated(j, a, b, s, ex, num(ans, "distance"), std::nullopt,
                   {{vecAt(ans, "point_a"), vecAt(ans, "point_b")}});
}

/// A contact feature: {"type", "vertices"} naming input vertices (1, 2 or >= 3 distinct, valid).
std::optional<std::vector<int>> featureOf(Judge& j, const std::string& name, const Json& f, const Body& body) {
    const std::string type = f.value("type", "");
    std::vector<int> v;
    if (f.contains("vertices"))
        for (const Json& i : f["vertices"]) v.push_back(i.is_number_integer() ? i.get<int>() : -1);
    const size_t want = type == "vertex" ? 1 : type == "edge" ? 2 : 3;
    bool good = body.kind == Body::Kind::Polytope && (type == "vertex" || type == "edge" || type == "face") &&
                (type == "face" ? v.size() >= want : v.size() == want) &&
                std::set<int>(v.begin(), v.end()).size() == v.size();
    for (int i : v) good = good && i >= 0 && i < static_cast<int>(body.pts.size());
    j.ok(name + " well formed", good, f.dump());
    return good ? std::optional(v) : std::nullopt;
}

/// How far the feature's vertices lie below the body's support plane along n.
long double supportGap(const Body& body, const std::vector<int>& f, const LVec& n) {
    const LVec ref = body.reference();
    const long double h = body.support(n, ref);
    long double gap = 0;
    for (int i : f) gap = std::max(gap, h - n.dot(toL(body.pts[i]) - ref));
    return gap;
}

/// A face of the body: the plane of its best-conditioned vertex triple holds all its vertices and has
/// no vertex of the body above it. Returns that excess and the plane's outward normal.
std::pair<long double, LVec> facetFit(const Body& body, const std::vector<int>& f) {
    LVec best = LVec::Zero();
    for (size_t i = 0; i < f.size(); ++i)
        for (size_t k = i + 1; k < f.size(); ++k)
            for (size_t l = k + 1; l < f.size(); ++l) {
                const LVec p = toL(body.pts[f[i]]);
                const LVec c = (toL(body.pts[f[k]]) - p).cross(toL(body.pts[f[l]]) - p);
                if (c.norm() > best.norm()) best = c;
            }
    const LVec p0 = toL(body.pts[f[0]]);
    LVec n = best.normalized(), centroid = LVec::Zero();
    for (const Vec3& p : body.pts) centroid += toL(p);
    if (n.dot(centroid / static_cast<long double>(body.pts.size()) - p0) > 0) n = -n;
    long double excess = 0;
    for (const Vec3& p : body.pts) excess = std::max(excess, n.dot(toL(p) - p0));
    for (int i : f) excess = std::max(excess, std::abs(n.dot(toL(body.pts[i]) - p0)));
    return {excess, n};
}

/// Distance from x to the convex hull of the feature's vertices.
long double distanceToFeature(const Body& body, const std::vector<int>& f, const Vec3& x) {
    std::vector<LVec> v;
    for (int i : f) v.push_back(toL(body.pts[i]) - toL(x));
    if (v.size() == 1) return v[0].norm();
    if (v.size() == 2) return cdlab::long_double::segmentDistanceL(v[0], v[1]);
    long double best = INFINITY;
    for (size_t i = 1; i + 1 < v.size(); ++i)
        best = std::min(best, cdlab::long_double::triangleDistanceL(v[0], v[i], v[i + 1]));
    return best;
}

/// Contact features: the reference feature (both for an edge-edge axis; a separated pair's closest
/// features) lies in its body's support set along ±n, an incident face is a face of its body turned
/// against the other, and each feature holds its points (`closest`: the witnesses or the manifold).
void judgeFeatures(Judge& j, const Body& a, const Body& b, const Scale& s, const Json& ans, const Vec3& n,
                   bool colliding, const std::vector<std::pair<Vec3, Vec3>>& closest) {
    const auto fa = featureOf(j, "feature_a", ans.value("feature_a", Json::object()), a);
    const auto fb = featureOf(j, "feature_b", ans.value("feature_b", Json::object()), b);
    if (!fa || !fb) return;
    const LVec nl = toL(n);
    const std::string axis = ans.value("axis", "");
    const std::string ta = ans["feature_a"]["type"], tb = ans["feature_b"]["type"];
    if (colliding) {
        j.ok("axis",
             (axis == "face A" && ta == "face") || (axis == "face B" && tb == "face") ||
                 (axis == "edge-edge" && ta == "edge" && tb == "edge"),
             axis + " with " + ta + " / " + tb);
    }
    const bool refA = !colliding || axis != "face B", refB = !colliding || axis != "face A";
    if (refA) j.le("feature_a in A's support set along n", supportGap(a, *fa, nl), s.onA());
    if (refB) j.le("feature_b in B's support set along -n", supportGap(b, *fb, -nl), s.onB());
    if (colliding && !refA && ta == "face") {
        const auto [excess, normal] = facetFit(a, *fa);
        j.le("feature_a (incident) a face of A", excess, s.onA());
        j.ok("feature_a (incident) faces B", normal.dot(nl) > 0, "outward normal . n = " + text(normal.dot(nl)));
    }
    if (colliding && !refB && tb == "face") {
        const auto [excess, normal] = facetFit(b, *fb);
        j.le("feature_b (incident) a face of B", excess, s.onB());
        j.ok("feature_b (incident) faces A", normal.dot(nl) < 0, "outward normal . n = " + text(normal.dot(nl)));
    }
    // Each feature holds its points (docs/accuracy.md, "What each answer meets"): the closest points when apart, the
    // manifold's points when colliding (stress "contact manifolds" 600 s #9758: a touching pair
    // shifted off its normal left point_a 3e-10 inside A, on no feature).
    const std::string what = colliding ? "point" : "closest point";
    for (const auto& [pa, pb] : closest) {
        j.le(what + "_a on feature_a", distanceToFeature(a, *fa, pa), s.onA());
        j.le(what + "_b on feature_b", distanceToFeature(b, *fb, pb), s.onB());
    }
}

void judgeContact(Judge& j, const Body& a, const Body& b, const Json& ans, const Exact& ex) {
    const Scale s = scaleOf(a, b);
    const bool colliding = ans.value("colliding", false);
    j.ok("colliding", ex.verdict && colliding == *ex.verdict,
         "returned " + std::to_string(colliding) + ", " + ex.source);
    const Vec3 n = vecAt(ans, "normal");
    if (!colliding) {
        j.keys(ans, {"id", "colliding", "distance", "normal", "closest", "feature_a", "feature_b"});
        std::vector<std::pair<Vec3, Vec3>> pairs;
        for (const Json& p : ans.value("closest", Json::array()))
            pairs.emplace_back(vecAt(p, "point_a"), vecAt(p, "point_b"));
        judgeSeparated(j, a, b, s, ex, num(ans, "distance"), n, pairs);
        judgeFeatures(j, a, b, s, ans, n, false, pairs);
        return;
    }
    std::set<std::string> keys = {"id", "colliding", "depth", "normal", "points", "feature_a", "feature_b"};
    if (a.kind == Body::Kind::Polytope && b.kind == Body::Kind::Polytope) keys.insert("axis");
    j.keys(ans, keys);
    const double depth = num(ans, "depth"), tol = s.depth();
    // The face preference's bound (docs/accuracy.md, core/contact/contact_sat.h): least overlap · 1.02 plus
    // the SAT's touching band, 1e-9 of the larger bounding-box diagonal + 128 u M; a manifold point
    // up to that band above the reference face carries its separation as a negative depth.
    const auto diagonal = [](const Body& body) {
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (const Vec3& p : body.pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        return body.pts.empty() ? 0.0 : (hi - lo).norm() + 2 * body.radius;
    };
    const double band = kWitnessTol * std::max(diagonal(a), diagonal(b)) + 128 * kU * s.M;
    j.ok("depth: an exact least overlap to judge it by", ex.depth.has_value(), ex.source);
    const long double least = ex.depth.value_or(NAN);
    const std::string both = "returned " + text(depth) + ", least overlap " + text(least);
    j.le("depth >= least overlap - tol", least - depth, tol, both);
    j.le("depth <= least overlap * 1.02 + band", depth - least * (1 + kFaceBias), band, both);
    j.le("normal | |n| - 1 |", unitError(n), kUnitTol, text(n));
    j.le("normal: h_{A-B}(n) = depth", std::abs(supportOfDifference(a, b, n) - depth), tol, text(n));
    const Json points = ans.value("points", Json::array());
    j.ok("points: at least one", !points.empty());
    std::vector<std::pair<Vec3, Vec3>> pairs;
    for (size_t i = 0; i < points.size(); ++i) {
        const std::string k = "points[" + std::to_string(i) + "]";
        const Vec3 pa = vecAt(points[i], "point_a"), pb = vecAt(points[i], "point_b");
        pairs.emplace_back(pa, pb);
        const double di = num(points[i], "depth");
        j.keys(points[i], {"point_a", "point_b", "depth"});
        j.le(k + ".point_a on A", a.signedDistance(pa), s.onA(), text(pa));
        j.le(k + ".point_b on B", b.signedDistance(pb), s.onB(), text(pb));
        j.le(k + ": point_a - point_b = depth_i n", (toL(pa) - toL(pb) - di * toL(n)).norm(), s.offset());
        j.le(k + ".depth in [-band, depth + tol]", std::max(-di - band + tol, di - depth), tol, text(di));
    }
    judgeFeatures(j, a, b, s, ans, n, true, pairs);
}

void judgeRaycast(Judge& j, const Json& q, const Json& ans, Exact ex) {
    const auto shape = parseShape(q.at("shape"));
    j.ok("shape: an oracle for it", shape.has_value(), q.at("shape").dump().substr(0, 40));
    if (!shape) return;
    const Vec3 o = vec(q.at("ray").at("origin")), d = vec(q.at("ray").at("direction"));
    const long double tMax = q.contains("max_t") ? num(q, "max_t") : INFINITY;
    const Exact mine = rayOracle(*shape, o, d, std::isfinite(tMax) ? tMax : 1e300L);
    if (!ex.verdict) ex = mine;
    if (!ex.point && ex.t) ex.point = (toL(o) + *ex.t * toL(d)).cast<double>();
    if (ex.normals.empty()) ex.normals = mine.normals;
    const bool hit = ans.value("hit", false);
    j.ok("hit", ex.verdict && hit == *ex.verdict, "returned " + std::to_string(hit) + ", " + ex.source);
    if (!hit) return j.keys(ans, {"id", "hit"});
    const double t = num(ans, "t");
    const Vec3 p = vecAt(ans, "point"), n = vecAt(ans, "normal");
    const double M = std::max({shape->maxCoord(), o.cwiseAbs().maxCoeff(), ex.point.value_or(p).cwiseAbs().maxCoeff()});
    const double tol = kRayTol * shape->size() + 8 * kU * M;
    const long double exactT = ex.t.value_or(NAN);
    const std::string both = "returned " + text(t) + ", exact " + text(exactT);
    if (exactT == 0) j.ok("t = 0 (the origin on or inside)", t == 0, both);
    else if (shape->kind == Body::Kind::Rounded)  // spheres and capsules: 8 roundings of the root
        j.le("t |t - exact| / |exact| (roundings)", std::abs(t - exactT) / (kU * std::abs(exactT)), kRoundings, both);
    else j.le("t: |t - exact| |d|", std::abs(t - exactT) * toL(d).norm(), tol, both);
    j.le("point |point - exact|", (toL(p) - toL(ex.point.value_or(Vec3::Constant(NAN)))).norm(), tol, text(p));
    j.le("point on the surface", std::abs(shape->signedDistance(p)), tol);
    if (ex.t == 0.0L) {
        j.keys(ans, {"id", "hit", "t", "point", "inside"});
        return j.ok("inside", ans.value("inside", false));
    }
    j.keys(ans, {"id", "hit", "t", "point", "normal"});
    j.le("normal | |n| - 1 |", unitError(n), kUnitTol, text(n));
    if (!ex.normals.empty()) return j.le("normal: angle to the exact one", angleTo(n, ex.normals), kAngleTol, text(n));
    const LVec ref = shape->reference();
    j.le("normal supports the shape at the point", std::abs(shape->support(toL(n), ref) - toL(n).dot(toL(p) - ref)),
         tol);
    j.ok("normal faces the ray", n.dot(d) <= 0, text(n));
}

void judgeTimeOfImpact(Judge& j, const Body& a, const Body& b, const Json& q, const Json& ans, Exact ex) {
    const Vec3 ma = q.contains("motion_a") ? vec(q["motion_a"]) : Vec3::Zero();
    const Vec3 mb = q.contains("motion_b") ? vec(q["motion_b"]) : Vec3::Zero();
    const Exact mine = toiOracle(a, b, ma, mb);
    if (!ex.verdict) ex = mine;
    if (ex.normals.empty()) ex.normals = mine.normals;
    const bool hit = ans.value("hit", false);
    j.ok("hit", ex.verdict && hit == *ex.verdict, "returned " + std::to_string(hit) + ", " + ex.source);
    if (!hit) return j.keys(ans, {"id", "hit"});
    const bool initially = ans.value("initially_overlapping", false);
    j.ok("initially_overlapping", initially == ex.initiallyOverlapping, "returned " + std::to_string(initially));
    if (initially) return j.keys(ans, {"id", "hit", "t", "initially_overlapping"});
    j.keys(ans, {"id", "hit", "t", "normal", "point_a", "point_b"});
    const double t = num(ans, "t");
    const Body at = a.moved(t * toL(ma)), bt = b.moved(t * toL(mb));
    Scale s = scaleOf(a, b);
    s.M = std::max({s.M, at.maxCoord(), bt.maxCoord()}), s.Ma = std::max(s.Ma, at.maxCoord()),
    s.Mb = std::max(s.Mb, bt.maxCoord());
    const long double exactT = ex.t.value_or(NAN);
    const std::string both = "returned " + text(t) + ", exact " + text(exactT);
    const bool rounded = a.kind == Body::Kind::Rounded && b.kind == Body::Kind::Rounded;
    if (rounded)  // spheres and capsules: 8 roundings of the root
        j.le("t |t - exact| / |exact| (roundings)", std::abs(t - exactT) / (kU * std::abs(exactT)), kRoundings, both);
    else  // the cast along ma − mb against B − A: the hit within 1e-12 of the size
        j.le("t: |t - exact| |ma - mb|", std::abs(t - exactT) * (toL(ma) - toL(mb)).norm(),
             kRayTol * s.L + 8 * kU * s.M, both);
    const Vec3 n = vecAt(ans, "normal"), pa = vecAt(ans, "point_a"), pb = vecAt(ans, "point_b");
    j.le("normal | |n| - 1 |", unitError(n), kUnitTol, text(n));
    if (!ex.normals.empty()) j.le("normal: angle to the exact one", angleTo(n, ex.normals), kAngleTol, text(n));
    else  // touching along n at time t: h_{A(t)−B(t)}(n) = 0
        j.le("normal: touching along it |h_{A(t)-B(t)}(n)|", std::abs(supportOfDifference(at, bt, n)), s.depth(),
             text(n));
    j.le("point_a on A at time t", at.signedDistance(pa), s.onA(), text(pa));
    j.le("point_b on B at time t", bt.signedDistance(pb), s.onB(), text(pb));
    j.le("point_a = point_b (touching)", (toL(pa) - toL(pb)).norm(), s.offset());
}

/// One query line: answered (not refused) with its id, then judged by op.
void judgeLine(Judge& j, const Json& q, const std::string& line, size_t lineNumber,
               const std::optional<Json>& expected) {
    const Json ans = cdlab::demos::answerQuery(line, lineNumber);
    j.ok("answered, not refused", !ans.contains("error"), ans.value("error", ""));
    if (ans.contains("error")) return;
    j.ok("id", ans.value("id", Json()) == q.at("id"));
    const std::string op = q.at("op");
    if (op == "raycast") return judgeRaycast(j, q, ans, expected ? fromExpectedFile(*expected) : Exact{});
    const auto a = parseShape(q.at("a")), b = parseShape(q.at("b"));
    j.ok("shapes: an oracle for them", a && b, q.at("a").dump().substr(0, 40) + " / " + q.at("b").dump().substr(0, 40));
    if (!a || !b) return;
    if (op == "time_of_impact")
        return judgeTimeOfImpact(j, *a, *b, q, ans, expected ? fromExpectedFile(*expected) : Exact{});
    Exact ex = expected ? fromExpectedFile(*expected) : pairOracle(*a, *b);
    if (op == "penetration") return judgePenetration(j, *a, *b, ans, ex);
    if (op == "contact") return judgeContact(j, *a, *b, ans, ex);
    if (op == "distance") return judgeDistance(j, *a, *b, ans, ex);
    j.ok("op: an oracle for it", false, op);
}

/// Every query line of NAME.jsonl (lines without an "op" are the folder's comments), judged against
/// NAME.expected.json's exact answer for the query it names, else against the oracles.
void judgeFile(const std::string& name, const std::string& folder = kFolder) {
    std::ifstream in(folder + name + ".jsonl");
    REQUIRE_MESSAGE(in, (folder + name + ".jsonl"));
    std::optional<Json> expected;
    if (std::ifstream e(folder + name + ".expected.json"); e) expected = Json::parse(e);
    int queries = 0, checks = 0, expectedUsed = 0;
    size_t lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const Json q = Json::parse(line);
        if (!q.contains("op")) {
            CHECK_MESSAGE(  // a comment of the folder, not a query
                (q.contains("id") && q["id"].is_string() && q["id"].get<std::string>().rfind("_comment", 0) == 0),
                (name + ": line " + std::to_string(lineNumber) + " has no op: a comment"));
            continue;
        }
        ++queries;
        Judge j{name, q.contains("id") ? (q["id"].is_string() ? q["id"].get<std::string>() : q["id"].dump())
                                       : "line " + std::to_string(lineNumber)};
        const bool mine = expected && expected->at("returned").at("id") == q.at("id");
        expectedUsed += mine;
        judgeLine(j, q, line, lineNumber, mine ? std::optional(expected->at("expected_exact")) : std::nullopt);
        checks += j.checks;
    }
    const std::string summary = name + ": " + std::to_string(queries) + " queries, " + std::to_string(checks) +
                                " checks, " + std::to_string(expectedUsed) + " judged by the expected file";
    CHECK_MESSAGE(queries > 0, summary);
    CHECK_MESSAGE(expectedUsed == (expected ? 1 : 0), summary);  // the expected file names a query of the file
    CHECK_MESSAGE(checks >= 8 * queries, summary);
}

}  // namespace exact_reproducers

TEST_SUITE("exact_reproducers") {
    TEST_CASE("exact reproducers: the folder holds the files judged below, each .expected.json with its .jsonl") {
        std::set<std::string> jsonl, expected;
        for (const auto& e : std::filesystem::directory_iterator(exact_reproducers::kFolder)) {
            const std::string f = e.path().filename().string();
            if (f.size() > 14 && f.substr(f.size() - 14) == ".expected.json")
                expected.insert(f.substr(0, f.size() - 14));
            else if (e.path().extension() == ".jsonl") jsonl.insert(e.path().stem().string());
        }
        CHECK(jsonl == std::set<std::string>(exact_reproducers::kFiles.begin(), exact_reproducers::kFiles.end()));
        for (const std::string& f : expected)
            CHECK_MESSAGE(jsonl.count(f), (f + ".expected.json has no " + f + ".jsonl"));
    }
    TEST_CASE("exact reproducers: contact_edge_edge_depth0") {
        exact_reproducers::judgeFile("contact_edge_edge_depth0");
    }
    TEST_CASE("exact reproducers: contact_face_bias") { exact_reproducers::judgeFile("contact_face_bias"); }
    TEST_CASE("exact reproducers: contact_needle_refused") { exact_reproducers::judgeFile("contact_needle_refused"); }
    TEST_CASE("exact reproducers: contact_parallel_edges_depth") {
        exact_reproducers::judgeFile("contact_parallel_edges_depth");
    }
    TEST_CASE("exact reproducers: contact_points_pair") { exact_reproducers::judgeFile("contact_points_pair"); }
    TEST_CASE("exact reproducers: contact_tiny_cube_refused") {
        exact_reproducers::judgeFile("contact_tiny_cube_refused");
    }
    TEST_CASE("exact reproducers: more (axis-aligned box witnesses, far sphere ray and time of impact)") {
        exact_reproducers::judgeFile("more");
    }
    TEST_CASE("exact reproducers: penetration_needle_far") { exact_reproducers::judgeFile("penetration_needle_far"); }
    TEST_CASE("exact reproducers: penetration_witness_obb") { exact_reproducers::judgeFile("penetration_witness_obb"); }
    TEST_CASE("exact reproducers: penetration_witness_off_shape") {
        exact_reproducers::judgeFile("penetration_witness_off_shape");
    }
    TEST_CASE("exact reproducers: penetration_witness_pair") {
        exact_reproducers::judgeFile("penetration_witness_pair");
    }
    TEST_CASE("exact reproducers: penetration_witness_parallel_edges") {
        exact_reproducers::judgeFile("penetration_witness_parallel_edges");
    }
    TEST_CASE("exact reproducers: quaternion_underflow") { exact_reproducers::judgeFile("quaternion_underflow"); }
    TEST_CASE("exact reproducers: raycast_face_plane_t0") { exact_reproducers::judgeFile("raycast_face_plane_t0"); }
    TEST_CASE("exact reproducers: raycast_face_plane_wrong_t") {
        exact_reproducers::judgeFile("raycast_face_plane_wrong_t");
    }
    TEST_CASE("exact reproducers: toi_large_motion") { exact_reproducers::judgeFile("toi_large_motion"); }
    TEST_CASE("exact reproducers: toi_sliding_early") { exact_reproducers::judgeFile("toi_sliding_early"); }
    TEST_CASE("exact reproducers: toi_sliding_late") { exact_reproducers::judgeFile("toi_sliding_late"); }
    // cdlab stress "contact manifolds" (2026-11-29): a face kept by the 2 % preference taken of its own
    // overlap (#324), within the SAT band (#44), a clip that kept no point (#175, #2523), a point
    // within the band above the reference face (#430), a split quad's other triangle (#411, #682).
    TEST_CASE("stress reproducers: contact manifolds") {
        exact_reproducers::judgeFile("contact_manifolds", std::string(CDLAB_SOURCE_DIR) + "/tests/data/stress-2026-11-29/");
    }
}
