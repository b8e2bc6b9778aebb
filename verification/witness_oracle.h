// Oracle for every field of a contact answer (issue 41, "an oracle for every field of every op"):
// given the two input bodies as vertex lists (polytopes) or core points + radius (spheres,
// capsules, rounded polytopes), and an answer (pointA, pointB, unit normal n from A toward B,
// signed depth s: the penetration depth, or minus the distance when apart), checks in long double
//   (i)   pointA lies on A and pointB on B: for a polytope the largest signed distance to the
//         facet planes of the hull of its vertices (the planes enumerated here by triples, no code
//         shared with core's hull); for a rounded body the distance to its core minus the radius;
//   (ii)  pointA − pointB = s · n  (penetration: depth · n; apart: −distance · n, i.e.
//         pointB − pointA = distance · n, GJK's separating axis);
//   (iii) n is a least-overlap direction: h_{A−B}(n) = s, with h the support function of the
//         Minkowski difference evaluated by brute force over the inputs (h_A(n) + h_B(−n)). For a
//         penetration h_{A−B}(n) >= depth for every unit n, with equality exactly on the
//         least-overlap directions (ties: any of them, which is the face preference's freedom);
//         apart, h_{A−B}(n) >= −distance with equality exactly on the separating axis.
// Header-only, core types only (no algorithm of core, no JSON). All differences are taken
// relative to one input vertex, so far offsets (1e9) do not swamp the shapes (long double holds
// the difference of two doubles within 2^11 of each other exactly).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "verification/long_double_geometry.h"

namespace cdlab::verification {

using long_double::LVec;
using long_double::toL;

/// A convex body as the oracle sees it: conv(points) grown by radius (radius 0: a polytope).
class WitnessBody {
public:
    /// The convex hull of `vertices` (duplicates and interior points allowed).
    static WitnessBody polytope(const std::vector<Vec3>& vertices) { return WitnessBody(vertices, 0.0L); }
    /// conv(core) grown by `radius`: a sphere (one core point), a capsule (two), a rounded polytope.
    static WitnessBody rounded(const std::vector<Vec3>& core, double radius) { return WitnessBody(core, radius); }

    /// Signed distance of x to the body (<= 0 on or inside), world units. For a polytope with a
    /// solid hull: the largest signed distance to its facet planes (exact inside, a lower bound
    /// of the true distance outside, which is 0 only on the body). Otherwise (flat or thinner
    /// core, or a radius): the distance to conv(core) by brute force over its triangles, minus
    /// the radius.
    long double signedDistance(const Vec3& x) const {
        const LVec p = toL(x) - ref_;
        long double planeMax = -std::numeric_limits<long double>::infinity();
        for (const Plane& f : planes_) planeMax = std::max(planeMax, f.n.dot(p) - f.offset);
        if (solid_ && radius_ == 0) return planeMax;
        if (solid_ && planeMax <= 0) return planeMax - radius_;
        return distanceToCore(p) - radius_;
    }

    /// Support value h(n) = max over the body of (x − ref)·n for the reference point `ref`.
    long double support(const LVec& n, const LVec& ref) const {
        long double h = -std::numeric_limits<long double>::infinity();
        const LVec shift = ref_ - ref;
        for (const LVec& p : pts_) h = std::max(h, (p + shift).dot(n));
        return h + radius_ * n.norm();
    }

    /// The ray o + t d, t >= 0, against the body: the first t at which it meets the body (-1: it
    /// never does). A solid polytope: Cyrus–Beck clipping against the facet planes (exact up to the
    /// planes' rounding); otherwise the first root of the convex f(t) = signedDistance(o + t d) on
    /// [0, tMax] (ternary search for the minimum, bisection below it).
    long double firstContact(const Vec3& o, const Vec3& d, long double tMax) const {
        if (solid_ && radius_ == 0) {
            const LVec lo = toL(o) - ref_, ld = toL(d);
            long double enter = 0, exit = tMax;
            for (const Plane& f : planes_) {
                const long double s0 = f.n.dot(lo) - f.offset, rate = f.n.dot(ld);
                if (rate == 0) {
                    if (s0 > 0) return -1;
                    continue;
                }
                const long double t = -s0 / rate;
                if (rate < 0) enter = std::max(enter, t);
                else exit = std::min(exit, t);
            }
            return enter <= exit ? enter : -1;
        }
        const LVec lo = toL(o), ld = toL(d);
        auto f = [&](long double t) {
            const LVec x = lo + t * ld;
            return signedDistance(Vec3(static_cast<double>(x.x()), static_cast<double>(x.y()),
                                       static_cast<double>(x.z())));
        };
        if (f(0) <= 0) return 0;
        long double a = 0, b = tMax;
        for (int i = 0; i < 200; ++i) {
            const long double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
            if (f(m1) < f(m2)) b = m2;
            else a = m1;
        }
        long double hi = (a + b) / 2, lo2 = 0;
        if (f(hi) > 0) return -1;
        for (int i = 0; i < 200; ++i) {
            const long double mid = (lo2 + hi) / 2;
            if (f(mid) > 0) lo2 = mid;
            else hi = mid;
        }
        return hi;
    }

    const LVec& reference() const { return ref_; }
    long double radius() const { return radius_; }
    bool solid() const { return solid_; }
    int facetPlanes() const { return static_cast<int>(planes_.size()); }
    /// The largest distance of a point of the body from its reference vertex (its size).
    long double size() const {
        long double m = 0;
        for (const LVec& p : pts_) m = std::max(m, p.norm());
        return m + radius_;
    }

private:
    struct Plane {
        LVec n;  // outward unit normal
        long double offset;
    };

    WitnessBody(const std::vector<Vec3>& v, long double radius) : radius_(radius) {
        if (v.empty()) return;
        ref_ = toL(v[0]);
        for (const Vec3& x : v) pts_.push_back(toL(x) - ref_);
        long double scale = 0;
        for (const LVec& p : pts_) scale = std::max(scale, p.norm());
        const int n = static_cast<int>(pts_.size());
        if (n < 4 || scale == 0) return;
        // Facet planes by triples: (i, j, k) spans a supporting plane iff no point lies strictly
        // on both sides (points within 1e-15 scale of the plane count as on it, so an accepted
        // plane supports the hull within that much: a point of the hull is never found farther
        // out than 1e-15 scale).
        const long double onTol = 1e-15L * scale;
        // A double prefilter (5x faster than x87): a well-conditioned triple (|cross| > 1e-6
        // scale^2, so its double normal is good to ~1e-10) with points more than 1e-9 scale on
        // both sides of its plane spans no facet. Every other triple is decided in long double.
        std::vector<Vec3> pd;
        for (const LVec& p : pts_) pd.push_back(p.cast<double>());
        const double sd = static_cast<double>(scale), margin = 1e-9 * sd;
        bool anyOff = false;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                for (int k = j + 1; k < n; ++k) {
                    const Vec3 nd = (pd[j] - pd[i]).cross(pd[k] - pd[i]);
                    const double lend = nd.norm();
                    if (lend > 1e-6 * sd * sd) {
                        const Vec3 u = nd / lend;
                        const double off = u.dot(pd[i]);
                        bool pos = false, neg = false;
                        for (int m = 0; m < n && !(pos && neg); ++m) {
                            const double s = u.dot(pd[m]) - off;
                            if (s > margin) pos = true;
                            if (s < -margin) neg = true;
                        }
                        if (pos && neg) {
                            anyOff = true;
                            continue;
                        }
                    }
                    LVec nrm = (pts_[j] - pts_[i]).cross(pts_[k] - pts_[i]);
                    const long double len = nrm.norm();
                    if (!(len > 1e-15L * scale * scale)) continue;
                    nrm /= len;
                    const long double off = nrm.dot(pts_[i]);
                    bool pos = false, neg = false;
                    for (int m = 0; m < n && !(pos && neg); ++m) {
                        const long double s = nrm.dot(pts_[m]) - off;
                        if (s > onTol) pos = true;
                        if (s < -onTol) neg = true;
                    }
                    if (pos || neg) anyOff = true;
                    if (pos && neg) continue;
                    if (!pos && !neg) continue;  // every point on it: a flat set, see below
                    if (pos) nrm = -nrm;
                    planes_.push_back({nrm, nrm.dot(pts_[i])});
                }
        // A solid hull has a point off the plane of some non-degenerate triple; a flat (or
        // collinear) set has none, and its planes do not bound it: brute force instead.
        solid_ = anyOff && !planes_.empty();
    }

    /// Distance from p (relative to ref_) to conv(pts_), by brute force over every point,
    /// segment and triangle of the points (exact outside the hull; inside a solid hull the plane
    /// test answers first).
    long double distanceToCore(const LVec& p) const {
        const int n = static_cast<int>(pts_.size());
        long double best = std::numeric_limits<long double>::infinity();
        for (int i = 0; i < n; ++i) {
            best = std::min(best, (pts_[i] - p).norm());
            for (int j = i + 1; j < n; ++j) {
                best = std::min(best, long_double::segmentDistanceL(pts_[i] - p, pts_[j] - p));
                for (int k = j + 1; k < n; ++k)
                    best = std::min(best, long_double::triangleDistanceL(pts_[i] - p, pts_[j] - p, pts_[k] - p));
            }
        }
        return best;
    }

    std::vector<LVec> pts_;  // relative to ref_
    LVec ref_ = LVec::Zero();
    long double radius_ = 0;
    std::vector<Plane> planes_;
    bool solid_ = false;
};

/// Support of A − B along n, h_A(n) + h_B(−n), relative to A's reference vertex (world units).
inline long double supportOfDifferenceL(const WitnessBody& a, const WitnessBody& b, const Vec3& n) {
    const LVec nl = toL(n);
    return a.support(nl, a.reference()) + b.support(-nl, a.reference());
}

/// Tolerances of the three checks, world units.
struct WitnessTolerances {
    double onBodyA = 0, onBodyB = 0;  ///< (i): signed distance of pointA to A, pointB to B
    double offset = 0;                ///< (ii): |pointA − pointB − s n|
    double normal = 0;                ///< (iii): |h_{A−B}(n) − s|
};

/// The measured size of every check (world units) and the first that failed.
struct WitnessCheck {
    enum class Failed { None, NotFinite, NotUnit, PointAOffBody, PointBOffBody, Offset, Normal };
    Failed failed = Failed::None;
    double size = 0;       ///< the failed check's measured value (0 when none failed)
    double tolerance = 0;  ///< and its tolerance
    double pointAOff = 0;  ///< signed distance of pointA to A (> 0: outside)
    double pointBOff = 0;  ///< signed distance of pointB to B
    double offset = 0;     ///< |pointA − pointB − s n|
    double normal = 0;     ///< |h_{A−B}(n) − s|
    double normalLength = 0;  ///< | |n| − 1 |
    bool ok() const { return failed == Failed::None; }
    std::string name() const {
        switch (failed) {
            case Failed::None: return "ok";
            case Failed::NotFinite: return "non-finite field";
            case Failed::NotUnit: return "normal not unit";
            case Failed::PointAOffBody: return "pointA off A";
            case Failed::PointBOffBody: return "pointB off B";
            case Failed::Offset: return "pointA - pointB != s n";
            case Failed::Normal: return "h_{A-B}(n) != s (not least overlap)";
        }
        return "?";
    }
};

/// Checks an answer (pointA, pointB, n, s) for bodies A and B; s = depth (penetration) or
/// −distance (apart), n unit from A toward B. Every measure is filled in; `failed` names the first
/// check past its tolerance in the order finite, unit, (i), (ii), (iii).
inline WitnessCheck checkWitness(const WitnessBody& a, const WitnessBody& b, const Vec3& pointA, const Vec3& pointB,
                                 const Vec3& n, double s, const WitnessTolerances& tol,
                                 double unitTolerance = 1e-12) {
    WitnessCheck r;
    const bool finite = pointA.allFinite() && pointB.allFinite() && n.allFinite() && std::isfinite(s);
    if (!finite) {
        r.failed = WitnessCheck::Failed::NotFinite;
        r.size = r.pointAOff = r.pointBOff = r.offset = r.normal = r.normalLength = INFINITY;
        r.tolerance = 0;
        return r;
    }
    const LVec nl = toL(n);
    r.normalLength = static_cast<double>(std::abs(nl.norm() - 1));
    r.pointAOff = static_cast<double>(a.signedDistance(pointA));
    r.pointBOff = static_cast<double>(b.signedDistance(pointB));
    // (ii) relative to A's reference: pointA − pointB exactly in long double.
    const LVec d = (toL(pointA) - a.reference()) - (toL(pointB) - a.reference());
    r.offset = static_cast<double>((d - static_cast<long double>(s) * nl).norm());
    r.normal = static_cast<double>(std::abs(supportOfDifferenceL(a, b, n) - static_cast<long double>(s)));
    auto fail = [&](WitnessCheck::Failed f, double size, double t) {
        if (r.failed != WitnessCheck::Failed::None || size <= t) return;
        r.failed = f;
        r.size = size;
        r.tolerance = t;
    };
    fail(WitnessCheck::Failed::NotUnit, r.normalLength, unitTolerance);
    fail(WitnessCheck::Failed::PointAOffBody, r.pointAOff, tol.onBodyA);
    fail(WitnessCheck::Failed::PointBOffBody, r.pointBOff, tol.onBodyB);
    fail(WitnessCheck::Failed::Offset, r.offset, tol.offset);
    fail(WitnessCheck::Failed::Normal, r.normal, tol.normal);
    return r;
}

/// A ray hit (t, point, normal) of the ray o + t d checked against the body, world units:
/// point = o + t d, point on the surface (|signed distance| small), no earlier hit (t = the first
/// contact), and the normal an outward normal there: unit, facing the ray (n · d <= 0 up to the
/// tolerance) and supporting the body at the point (h_body(n) = n · point).
struct RayHitCheck {
    enum class Failed { None, NotFinite, NotUnit, PointOffRay, PointOffSurface, NotFirstContact, Normal };
    Failed failed = Failed::None;
    double size = 0, tolerance = 0;
    double offRay = 0;       ///< |point − (o + t d)|
    double offSurface = 0;   ///< |signed distance of point|
    double earlier = 0;      ///< |t − first contact| · |d| (INFINITY when the oracle sees no contact)
    double support = 0;      ///< |h_body(n) − n · point|, plus max(0, n · d / |d|) · |point − o|
    double normalLength = 0;
    bool ok() const { return failed == Failed::None; }
};

struct RayHitTolerances {
    double point = 0, surface = 0, firstContact = 0, normal = 0;  // world units
};

inline RayHitCheck checkRayHit(const WitnessBody& body, const Vec3& o, const Vec3& d, double t, const Vec3& point,
                               const Vec3& normal, const RayHitTolerances& tol, double unitTolerance = 1e-12) {
    RayHitCheck r;
    if (!(o.allFinite() && d.allFinite() && point.allFinite() && normal.allFinite() && std::isfinite(t))) {
        r.failed = RayHitCheck::Failed::NotFinite;
        r.size = r.offRay = r.offSurface = r.earlier = r.support = r.normalLength = INFINITY;
        return r;
    }
    const LVec lo = toL(o), ld = toL(d), lp = toL(point), ln = toL(normal);
    r.offRay = static_cast<double>((lp - (lo + static_cast<long double>(t) * ld)).norm());
    r.offSurface = static_cast<double>(std::abs(body.signedDistance(point)));
    const long double first = body.firstContact(o, d, 2 * static_cast<long double>(t) + 1);
    r.earlier = first < 0 ? INFINITY : static_cast<double>(std::abs(static_cast<long double>(t) - first) * ld.norm());
    r.normalLength = static_cast<double>(std::abs(ln.norm() - 1));
    const long double facing = std::max(0.0L, ln.dot(ld) / ld.norm()) * (lp - lo).norm();
    r.support = static_cast<double>(std::abs(body.support(ln, body.reference()) - ln.dot(lp - body.reference())) +
                                    facing);
    auto fail = [&](RayHitCheck::Failed f, double size, double tl) {
        if (r.failed != RayHitCheck::Failed::None || size <= tl) return;
        r.failed = f;
        r.size = size;
        r.tolerance = tl;
    };
    fail(RayHitCheck::Failed::NotUnit, r.normalLength, unitTolerance);
    fail(RayHitCheck::Failed::PointOffRay, r.offRay, tol.point);
    fail(RayHitCheck::Failed::PointOffSurface, r.offSurface, tol.surface);
    fail(RayHitCheck::Failed::NotFirstContact, r.earlier, tol.firstContact);
    fail(RayHitCheck::Failed::Normal, r.support, tol.normal);
    return r;
}

}  // namespace cdlab::verification
