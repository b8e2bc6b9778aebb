#include "core/contact/contact_stages.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <type_traits>
#include <vector>

#include "core/base/tolerances.h"
#include "core/cast/ray_cast.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/touching_pair.h"

namespace cdlab::detail {

namespace {

// Appends x; false when a fixed buffer is full (FixedCapacityVector::push_back refuses), true for
// a std::pmr::vector (it grows).
template <class Buffer, class T>
bool append(Buffer& out, const T& x) {
    if constexpr (std::is_same_v<decltype(out.push_back(x)), bool>) {
        return out.push_back(x);
    } else {
        out.push_back(x);
        return true;
    }
}

// Sutherland–Hodgman against one plane (Ericson §8.3.4): keep n · x <= d. Buffer: a
// FixedCapacityVector for small polygons, a std::pmr::vector otherwise. In exact arithmetic a
// convex k-gon gains at most one point; with rounding, signs can alternate along an edge lying in
// the plane and it can gain more: false when a fixed buffer overflows (the caller starts over
// with growing buffers).
template <class Buffer>
bool clipPolygon(const Buffer& poly, const Vec3& n, double d, Buffer& out) {
    out.clear();
    const size_t k = poly.size();
    if (k == 0) return true;
    const double s0 = n.dot(poly[0]) - d;
    double sp = s0;  // each vertex's distance taken once, carried to the next edge
    for (size_t i = 0; i < k; ++i) {
        const Vec3& p = poly[i];
        const Vec3& q = poly[i + 1 == k ? 0 : i + 1];
        const double sq = i + 1 == k ? s0 : n.dot(q) - d;
        if (sp <= 0.0 && !append(out, p)) return false;
        if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))
            if (!append(out, Vec3(p + (sp / (sp - sq)) * (q - p)))) return false;
        sp = sq;
    }
    return true;
}

// A contact point from a point p of the incident body and its projection onRef on the reference
// plane, in the A/B convention (pointA belongs to A).
ContactPoint incidentPoint(const Vec3& p, const Vec3& onRef, double depth, bool referenceOnA, const Vec3& origin) {
    return referenceOnA ? ContactPoint{onRef + origin, p + origin, depth} : ContactPoint{p + origin, onRef + origin, depth};
}

}  // namespace

const char* poseProblem(const Transform& pose) {
    // x * 0 is 0 for finite x and NaN for inf or NaN: one sum of seven products, no branch per
    // coefficient (Eigen's allFinite is called out of line by GCC, in the hot path of every query).
    const Vec3& p = pose.position;
    const Quat& q = pose.rotation;
    const double zero = p.x() * 0.0 + p.y() * 0.0 + p.z() * 0.0 + q.x() * 0.0 + q.y() * 0.0 + q.z() * 0.0 + q.w() * 0.0;
    if (!(zero == 0.0)) return "pose is not finite";
    if (std::abs(pose.rotation.squaredNorm() - 1.0) > kUnitQuaternionTolerance)
        return "pose rotation is not a unit quaternion";
    return "";
}

const char* unitPlane(const Plane& plane, Vec3& n, double& d) {
    // A normal already unit to rounding (|n|² within 4 ulps of 1, false for NaN and inf) is taken
    // as given: its normalisation would move it by an ulp at most.
    if (std::abs(plane.normal.squaredNorm() - 1.0) <= 4.0 * kMachineEpsilon && std::isfinite(plane.offset)) {
        n = plane.normal;
        d = plane.offset;
        return "";
    }
    const double m = plane.normal.cwiseAbs().maxCoeff();
    if (!std::isfinite(m) || !std::isfinite(plane.offset)) return "plane normal or offset is not finite";
    if (!(m > 0.0)) return "plane normal is zero";
    const Vec3 s = plane.normal / m;
    const double len = s.norm();
    n = s / len;
    d = (plane.offset / m) / len;
    return "";
}

double satTolerance(const SatContactOptions& options, double size, double maxCoord) {
    return options.tolerance && *options.tolerance >= 0.0 ? *options.tolerance
                                                          : kTouchingBandRelative * size + ulps(64, maxCoord);
}

SatChosenAxis chooseSatAxis(const SatBestAxes& b, double tol, const SatContactOptions& options) {
    SatChosenAxis c;
    const double maxSep = c.maxSep = std::max({b.faceA.separation, b.faceB.separation, b.edge.separation});
    c.best = b.faceA;
    c.chosen = b.faceAIndex;
    if (maxSep > tol) {  // separated: the axis of largest separation, no preference needed
        if (b.faceB.separation == maxSep) c.best = b.faceB, c.chosen = b.faceBIndex;
        if (b.edge.separation == maxSep && c.best.separation != maxSep) c.best = b.edge, c.chosen = b.edgeIndex;
    } else {
        const double biasAbs = std::max(0.0, options.faceBiasAbsolute);
        // x wins when the kept axis's overlap exceeds x's by more than faceBiasRelative of x's own
        // overlap: the kept depth is then at most least overlap · (1 + faceBiasRelative) + biasAbs +
        // tol (the bias taken of the kept overlap allowed least / (1 − bias): 2.04 %, cdlab stress
        // "contact manifolds" seed 1 #324).
        const auto better = [&](const SatAxisRecord& x) {
            return x.separation > c.best.separation + options.faceBiasRelative * std::abs(x.separation) + biasAbs + tol;
        };
        if (b.faceB.indexB >= 0 && better(b.faceB)) c.best = b.faceB, c.chosen = b.faceBIndex;
        if (b.edge.indexA >= 0 && better(b.edge)) c.best = b.edge, c.chosen = b.edgeIndex;
    }
    return c;
}

namespace {

// The touching pair of the reference and incident vertex sets overlapping by `depth` along the
// reference normal nr (core/gjk_epa/touching_pair.h, the incident set pushed clear along nr).
// Test: cdlab stress "contact manifolds" (seed 1 #175, #2264, #2523).
bool touchingPairAlong(std::span<const Vec3> reference, std::span<const Vec3> incident, const Vec3& nr, double depth,
                       Vec3& pr, Vec3& pi) {
    if (reference.empty() || incident.empty() || !(depth >= 0)) return false;
    double M = 0;
    for (const Vec3& v : reference) M = std::max(M, v.cwiseAbs().maxCoeff());
    for (const Vec3& v : incident) M = std::max(M, v.cwiseAbs().maxCoeff());
    return cdlab::touchingPairAlong(PolytopeShape(std::vector<Vec3>(reference.begin(), reference.end())),
                                    PolytopeShape(std::vector<Vec3>(incident.begin(), incident.end())), nr, depth, M,
                                    pr, pi);
}

// The exact touching pair along nr: the incident body pushed along nr by the least t that leaves it
// only touching the reference body, t = max{s : s·nr ∈ R − I}, the exit of the ray from the origin
// along nr through the difference R − I — cast back from outside it (start T·nr, T twice the
// difference's largest norm). The hit's core point Σ w_k (r − i)_k gives pr = Σ w_k r and
// pi = Σ w_k i, each on its body to rounding, with pr − pi = t·nr up to rounding: no lateral
// offset, where GJK's closest points at a push δ lean off nr by up to δ (their offset, shared out
// between the points, left pointA 3e-10 inside A, off every feature: cdlab stress "contact
// manifolds" 600 s #9758, #19637, #33558). The difference has |R|·|I| points, only on this rare
// path (a face axis kept by preference whose clip keeps nothing). False when the cast misses.
bool exactTouchingPairAlong(std::span<const Vec3> reference, std::span<const Vec3> incident, const Vec3& nr, Vec3& pr,
                            Vec3& pi) {
    if (reference.empty() || incident.empty()) return false;
    std::vector<Vec3> difference;
    difference.reserve(reference.size() * incident.size());
    double far = 0;
    for (const Vec3& r : reference)
        for (const Vec3& i : incident) difference.push_back(r - i), far = std::max(far, difference.back().norm());
    if (!(far > 0) || !std::isfinite(far)) return false;
    const ConvexCastHit h = castRayRoundedHull(Ray{2 * far * nr, -nr}, difference);
    if (!h.hit || h.inside || h.count == 0) return false;
    const std::size_t nI = incident.size();
    pr = pi = Vec3::Zero();
    for (int k = 0; k < h.count; ++k) {
        pr += h.weight[k] * reference[std::size_t(h.index[k]) / nI];
        pi += h.weight[k] * incident[std::size_t(h.index[k]) % nI];
    }
    return pr.allFinite() && pi.allFinite();
}

// clipIncidentFace with its polygons in `poly` / `next` and the kept points in `pts` (empty, with
// room for incident.size() + reference.size() points).
template <class Polygon, class Points>
bool clipWith(Polygon& poly, Polygon& next, Points& pts, std::span<const Vec3> reference, const Vec3& nr,
              double dRef, std::span<const Vec3> incident, std::span<const Vec3> incidentVertices,
              std::span<const Vec3> referenceVertices, bool referenceOnA,
              const Vec3& origin, double tol, const SatContactOptions& options, SatContactResult& r,
              SatContactTrace* trace, std::span<const Plane> sidePlanes, bool touchingFallback) {
    if (trace) {
        trace->referenceOnA = referenceOnA;
        for (const Vec3& p : reference) trace->referencePolygon.push_back(p + origin);
        for (const Vec3& p : incident) trace->incidentPolygon.push_back(p + origin);
    }
    for (const Vec3& p : incident)
        if (!append(poly, p)) return false;
    Polygon* in = &poly;
    Polygon* out = &next;
    // Side planes of the reference face: edge e_i = r_{i+1} - r_i (CCW about nr), outward
    // normal e_i x nr.
    for (size_t i = 0; i < reference.size() && !in->empty(); ++i) {
        Vec3 sn;
        double sd;
        if (sidePlanes.size() == reference.size()) {
            sn = sidePlanes[i].normal;
            sd = sidePlanes[i].offset;
        } else {
            const Vec3 e = reference[(i + 1) % reference.size()] - reference[i];
            sn = e.cross(nr).normalized();
            sd = sn.dot(reference[i]);
        }
        if (!clipPolygon(*in, sn, sd, *out)) return false;
        if (trace) {
            SatClipStep step{static_cast<int>(i), sn, sd + sn.dot(origin), {}, {}};
            for (const Vec3& p : *in) step.before.push_back(p + origin);
            for (const Vec3& p : *out) step.after.push_back(p + origin);
            trace->clipSteps.push_back(step);
        }
        std::swap(in, out);
    }
    // Keep the points behind the reference plane or within the touching band above it: depth = -s
    // with s = nr · p − d, negative (a separation) for a point up to tol above the plane, so that
    // pointA − pointB = depth · normal holds for every point (cdlab stress "contact manifolds").
    for (const Vec3& p : *in) {
        const double s = nr.dot(p) - dRef;
        if (s <= tol && !append(pts, incidentPoint(p, p - s * nr, -s, referenceOnA, origin))) return false;
    }
    if (pts.empty()) {
        r.clipKeptNothing = true;
        if (!touchingFallback) return true;
        // Nothing survived the clip (the face axis kept by preference where the bodies meet beside
        // the reference face): the touching pair of the bodies, else the deepest incident vertex.
        Vec3 pr, pi;
        if (exactTouchingPairAlong(referenceVertices, incidentVertices, nr, pr, pi)) {
            pts.push_back(incidentPoint(pi, pr, nr.dot(pr - pi), referenceOnA, origin));
        } else if (touchingPairAlong(referenceVertices, incidentVertices, nr, r.depth, pr, pi)) {
            // The pair's offset off the normal (GJK's closest points at δ) shared between the two
            // points in proportion to their bodies' sizes (the on-body tolerances scale with them),
            // so that pointA − pointB = depth_i · normal holds.
            const double depthI = nr.dot(pr - pi);
            const Vec3 lateral = (pr - pi) - depthI * nr;
            const auto extent = [](std::span<const Vec3> v) {
                Vec3 lo = v.front(), hi = v.front();
                for (const Vec3& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
                return (hi - lo).norm() + 8 * DBL_EPSILON * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
            };
            const double er = extent(referenceVertices), ei = extent(incidentVertices);
            const double wr = er + ei > 0 ? er / (er + ei) : 0.5;
            pr -= wr * lateral;
            pi += (1 - wr) * lateral;
            pts.push_back(incidentPoint(pi, pr, depthI, referenceOnA, origin));
        } else {
            size_t v = 0;
            for (size_t i = 1; i < incidentVertices.size(); ++i)
                if (nr.dot(incidentVertices[i]) < nr.dot(incidentVertices[v])) v = i;
            const Vec3& p = incidentVertices[v];
            const double s = nr.dot(p) - dRef;
            pts.push_back(incidentPoint(p, p - s * nr, -s, referenceOnA, origin));
        }
    }
    std::vector<ManifoldReductionStep>* steps = trace ? &trace->reduction : nullptr;
    const std::span<const ContactPoint> kept(pts.data(), pts.size());
    for (int i : reduceContactPolygon(kept, nr, options.maxPoints, steps)) r.manifold.push_back(kept[i]);
    if (trace) trace->clipped.assign(kept.begin(), kept.end());
    return true;
}

}  // namespace

void recordChosenAxis(const SatChosenAxis& c, double tol, SatContactResult& r) {
    r.separation = c.maxSep;
    r.normal = c.best.axis;
    r.axisKind = c.best.kind;
    r.depth = std::max(0.0, -c.best.separation);
    r.status = c.maxSep > tol     ? SatContactStatus::Separated
               : c.maxSep >= -tol ? SatContactStatus::Touching
                                  : SatContactStatus::Penetrating;
}

void clipIncidentFace(std::span<const Vec3> reference, const Vec3& nr, double dRef, std::span<const Vec3> incident,
                      std::span<const Vec3> incidentVertices, std::span<const Vec3> referenceVertices,
                      bool referenceOnA, const Vec3& origin, double tol,
                      const SatContactOptions& options, SatContactResult& r, SatContactTrace* trace,
                      std::pmr::memory_resource* memory, std::span<const Plane> sidePlanes, bool touchingFallback) {
    // Clipping by k side planes adds one point per plane in exact arithmetic; the inline buffers
    // leave room for rounding to add more, and a polygon that still overflows them (nothing is
    // written to r before the end) is clipped again in growing buffers. Traced runs take those
    // directly, so no step is recorded twice.
    const size_t capacity = incident.size() + reference.size();
    constexpr int kInline = 24;  // box faces (8 at most in exact arithmetic), hull triangles and quads
    if (!trace && 2 * capacity <= size_t(kInline)) {
        FixedCapacityVector<Vec3, kInline> poly, next;
        FixedCapacityVector<ContactPoint, kInline> pts;
        if (clipWith(poly, next, pts, reference, nr, dRef, incident, incidentVertices, referenceVertices, referenceOnA, origin, tol,
                     options, r, trace, sidePlanes, touchingFallback))
            return;
    }
    std::pmr::vector<Vec3> poly(memory), next(memory);
    std::pmr::vector<ContactPoint> pts(memory);
    poly.reserve(capacity);
    next.reserve(capacity);
    pts.reserve(capacity);
    clipWith(poly, next, pts, reference, nr, dRef, incident, incidentVertices, referenceVertices, referenceOnA, origin, tol, options, r,
             trace, sidePlanes, touchingFallback);
}

}  // namespace cdlab::detail
