#include "core/query/cast.h"

#include <algorithm>
#include <cmath>

#include "core/cast/ray_cast_curved.h"
#include "core/geometry/convex_hull.h"
#include "core/query/touch.h"

namespace cdlab {

namespace {

using Kind = QueryShape::Kind;

// The exponent k with 2^k · m in [0.5, 1) (0 for m = 0).
int exponentOf(double m) {
    int e = 0;
    if (m > 0 && std::isfinite(m)) std::frexp(m, &e);
    return -e;
}

struct CastAnswer {
    bool hit = false, inside = false;
    double t = 0;
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
};

// The plane n·x = d as a two-sided surface: crossed where the signed distance changes sign.
CastAnswer rayPlane(const Vec3& o, const Vec3& d, const QueryShape& plane, double maxT, RayCastQueryTrace* trace) {
    const auto [n, offset] = unitPlane(plane);
    const double s0 = n.dot(o) - offset, slope = n.dot(d);
    CastAnswer ans;
    if (trace) {
        trace->algorithm = RayCastQueryTrace::Algorithm::RayPlane;
        trace->signedDistance = s0;
        trace->slope = slope;
    }
    if (std::abs(s0) <= planeTouchTolerance(offset, o.cwiseAbs().maxCoeff())) {
        ans.hit = ans.inside = true;
        ans.point = o;
        return ans;
    }
    if (slope == 0 || (s0 > 0) == (slope > 0)) return ans;  // parallel, or moving away
    const double t = -s0 / slope;
    if (!(t <= maxT)) return ans;
    ans.hit = true;
    ans.t = t;
    ans.point = o + t * d;
    ans.normal = s0 > 0 ? n : Vec3(-n);  // the side the ray comes from
    return ans;
}

// A cylinder or cone in its own frame (core/cast/ray_cast_curved.h): t is the same there.
CastAnswer rayCurved(const Vec3& o, const Vec3& d, const QueryShape& shape, double maxT, double touch,
                     RayCastQueryTrace* trace) {
    const CurvedSolid& c = shape.curved;
    const Ray local{c.rotation.transpose() * (o - c.center), c.rotation.transpose() * d};
    ConvexCastOptions options;
    options.maxT = maxT;
    options.touchTolerance = touch;
    const ConvexCastHit h = c.cone ? castRayCone(local, c.halfHeight, c.radius, options)
                                   : castRayCylinder(local, c.halfHeight, c.radius, options);
    CastAnswer ans{h.hit, h.inside, h.t, o + h.t * d, c.rotation * h.normal};
    if (h.inside) ans.point = o;
    if (trace) trace->algorithm = c.cone ? RayCastQueryTrace::Algorithm::RayCone : RayCastQueryTrace::Algorithm::RayCylinder;
    return ans;
}

// A plane and a bounded shape: the shape's span of signed distances moves at the rate n̂·(m_s − m_p).
TimeOfImpactResult planeImpact(const QueryShape& plane, const Vec3& planeMotion, const QueryShape& s, const Vec3& motion,
                               ImpactQueryTrace* trace) {
    const PlaneSpan span = planeSpan(plane, s);
    const Vec3 n = unitPlane(plane).n;
    const double rate = n.dot(motion - planeMotion);
    TimeOfImpactResult res;
    if (trace) {
        trace->algorithm = ImpactQueryTrace::Algorithm::PlaneSpan;
        trace->low = span.lo;
        trace->high = span.hi;
        trace->rate = rate;
    }
    if (span.lo <= span.touch && span.hi >= -span.touch) {
        res.hit = res.initiallyOverlapping = true;
        return res;
    }
    const bool above = span.lo > span.touch;
    const double gap = above ? span.lo : -span.hi;
    const double closing = above ? -rate : rate;
    if (!(closing > 0) || gap > closing) return res;  // never reached, or not before t = 1
    res.hit = true;
    res.t = gap / closing;
    res.normal = above ? n : Vec3(-n);  // from the plane toward the shape
    res.pointA = res.pointB = (above ? span.lowPoint : span.highPoint) + res.t * motion;
    return res;
}

// The shape's hull vertices (the Minkowski difference needs no interior points), with their indices
// into the shape's vertices; a flat or tiny shape keeps all its points.
std::vector<int> hullVertexIndices(const QueryShape& s) {
    std::vector<int> all(s.vertices.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    if (s.vertices.size() <= 8) return all;
    const HullResult hull = convexHull(s.vertices);
    if (hull.status != HullStatus::Ok) return all;
    std::vector<int> kept = hull.inputIndex;
    std::sort(kept.begin(), kept.end());
    return kept;
}

void boundedImpact(const QueryShape& a, const Vec3& ma, const QueryShape& b, const Vec3& mb, double maxT,
                   const ImpactQueryOptions& o, ImpactQueryResult& out, ImpactQueryTrace* trace) {
    const std::vector<int> ia = hullVertexIndices(a), ib = hullVertexIndices(b);
    out.hullA = ia.size();
    out.hullB = ib.size();
    if (double(ia.size()) * double(ib.size()) > double(o.maxDifferencePoints)) {
        out.status = PairStatus::WorkLimit;
        return;
    }
    std::vector<Vec3> pa, pb;
    for (int i : ia) pa.push_back(a.vertices[i]);
    for (int j : ib) pb.push_back(b.vertices[j]);
    TimeOfImpactOptions options;
    options.touchTolerance = touchTolerance(a, b);
    options.maxT = maxT;
    out.result = translationalTimeOfImpact(pa, a.radius, ma, pb, b.radius, mb, options, trace ? &trace->cast : nullptr);
    if (trace) {
        trace->algorithm = ImpactQueryTrace::Algorithm::RayCast;
        trace->pairedWith = int(b.vertices.size());
        // Difference point k is b's hull vertex k % |ib| minus a's k / |ib|: name them in the input's indices.
        for (ConvexCastCandidate& c : trace->cast.candidates)
            for (int i = 0; i < c.count; ++i)
                c.index[i] = ia[c.index[i] / int(ib.size())] * int(b.vertices.size()) + ib[c.index[i] % int(ib.size())];
    }
}

QueryShape translated(QueryShape s, const Vec3& offset) {
    for (Vec3& v : s.vertices) v += offset;
    s.curved.center += offset;
    return s;
}

// The distance of a and b moved by t·ma and t·mb (pairQuery without the depth).
PairResult movedPair(const QueryShape& a, const Vec3& ma, const QueryShape& b, const Vec3& mb, double t) {
    PairOptions o;
    o.depth = false;
    return pairQuery(translated(a, t * ma), translated(b, t * mb), o);
}

// Conservative advancement's step cap: a path that creeps toward contact stops here (measured: a few
// to ~60 steps on the query corpus; tests/app/query/query_curved_cast_test.cpp).
constexpr int kMaxAdvancementSteps = 500;

// A cylinder or cone moving against a bounded shape: conservative advancement (Mirtich 1996 §2.3;
// van den Bergen 2004 §4 for the translational case) on the distance of the two moved shapes,
// taken from the pair query (GJK and its polish). For translations the distance
// φ(t) = dist(t·(m_a − m_b), B − A) is convex in t, so the tangent step t += φ / (−φ') with
// φ' = n·(m_b − m_a) (n the unit axis from a toward b) never passes the first contact: it climbs to
// it from below, quadratically where the path crosses the surface, and a path that only comes
// near stops when φ' turns non-negative or t passes 1. Contact: φ at or below the touching rule.
void curvedImpact(const QueryShape& a, const Vec3& ma, const QueryShape& b, const Vec3& mb, double lengthScale,
                  ImpactQueryResult& out, ImpactQueryTrace* trace) {
    TimeOfImpactResult& res = out.result;
    if (trace) trace->algorithm = ImpactQueryTrace::Algorithm::ConservativeAdvancement;
    const auto failed = [&](PairStatus s) {
        out.status = s;
        out.pairFailed = true;
    };
    double t = 0, lastT = 0;
    PairResult last;  // the last separated state (its normal and points name the contact)
    for (int iteration = 0; iteration < kMaxAdvancementSteps; ++iteration) {
        const PairResult now = movedPair(a, ma, b, mb, t);
        if (now.status != PairStatus::Ok) return failed(now.status);
        if (trace) trace->steps.push_back({t, now.intersect ? 0.0 : now.distance * lengthScale});
        if (now.intersect) {
            res.hit = true;
            res.t = t;
            res.initiallyOverlapping = t == 0;
            if (res.initiallyOverlapping) break;
            // The touching points: the closest pair of a state just before t, moved on to t. The
            // last state may be a whole step back (one step reaches a flat face), and its points,
            // moved, drift apart by the step times the sideways motion; 1e-10 back, they do not.
            for (const double back : {1e-10, 1e-8, 1e-6, 1e-4}) {
                if (t - back <= lastT) break;
                const PairResult near = movedPair(a, ma, b, mb, t - back);
                if (near.status != PairStatus::Ok) return failed(near.status);
                if (!near.intersect) {
                    last = near, lastT = t - back;
                    break;
                }
            }
            res.normal = last.normal;
            res.pointA = last.pointA + (t - lastT) * ma;
            res.pointB = last.pointB + (t - lastT) * mb;
            break;
        }
        const double closing = now.normal.dot(ma - mb);
        if (!(closing > 0)) break;  // moving apart along the axis: the convex distance only grows
        const double next = t + now.distance / closing;
        last = now, lastT = t;
        if (!(next <= 1)) break;
        if (next <= t) {  // below the rounding of t: the contact is here
            res.hit = true;
            res.t = t;
            res.normal = now.normal;
            res.pointA = now.pointA;
            res.pointB = now.pointB;
            break;
        }
        t = next;
    }
}

}  // namespace

RayCastQueryResult rayCastQuery(const Vec3& origin, const Vec3& direction, QueryShape shape, double maxT,
                                RayCastQueryTrace* trace) {
    // Exact power-of-two scaling: d' = 2^e d has its largest coordinate in [0.5, 1), lengths are
    // multiplied by 2^k; the scaled ray o' + t' d' is 2^k (o + t d) for t = t' 2^(e-k).
    const int e = exponentOf(direction.cwiseAbs().maxCoeff());
    QueryShape o = QueryShape::point(origin);
    const int k = normalisingExponent(o, shape);
    scaleShape(o, k);
    scaleShape(shape, k);
    const Vec3 d = scaled(direction, e);
    const double scaledMaxT = std::ldexp(maxT, k - e);
    if (trace) {
        trace->tExponent = e - k;
        trace->lengthExponent = -k;
    }
    CastAnswer ans;
    if (shape.kind == Kind::Plane) {
        ans = rayPlane(o.vertices[0], d, shape, scaledMaxT, trace);
    } else if (shape.isCurved()) {
        ans = rayCurved(o.vertices[0], d, shape, scaledMaxT, touchTolerance(o, shape), trace);
    } else {
        ConvexCastOptions options;
        options.maxT = scaledMaxT;
        options.touchTolerance = touchTolerance(o, shape);
        const ConvexCastHit h = castRayRoundedHull(Ray{o.vertices[0], d}, shape.vertices, shape.radius, options,
                                                   trace ? &trace->cast : nullptr);
        ans = {h.hit, h.inside, h.t, h.point, h.normal};
        if (trace) trace->algorithm = RayCastQueryTrace::Algorithm::RayCast;
    }
    RayCastQueryResult out;
    out.hit = ans.hit;
    out.inside = ans.inside;
    if (!ans.hit) return out;
    if (ans.inside) {
        out.point = origin;
        return out;
    }
    out.t = std::ldexp(ans.t, e - k);
    out.point = scaled(ans.point, -k);
    out.normal = ans.normal;
    if (!std::isfinite(out.t) || !out.point.allFinite()) out.status = PairStatus::Overflow;
    return out;
}

ImpactQueryResult timeOfImpactQuery(QueryShape a, const Vec3& ma, QueryShape b, const Vec3& mb,
                                    const ImpactQueryOptions& options, ImpactQueryTrace* trace) {
    // Exact powers of two: the shapes by 2^ks (size ~1), the motions by 2^km with km = min(ks, the
    // motions' own exponent), so neither the shapes nor the motions leave the range where their
    // digits are kept. A motion far larger than the shapes is scaled to ~1 and the shapes are not
    // shrunk along with it (they were, to ~1e-81 at |motion| / size = 1e81, and the cast's products
    // lost them: wrong touching points, then t = 0, then a false initial overlap;
    // tests/core/cast/time_of_impact_scale_test.cpp). The scaled problem's t' = 2^(ks − km) t, cast
    // up to 2^(ks − km); ks = km (the motions no larger than the shapes) is the former scaling.
    const int ks = normalisingExponent(a, b);
    const int km = std::min(ks, exponentOf(std::max(ma.cwiseAbs().maxCoeff(), mb.cwiseAbs().maxCoeff())));
    const bool bounded = a.kind != Kind::Plane && b.kind != Kind::Plane && !a.isCurved() && !b.isCurved();
    const int k = bounded ? ks : km;  // planes and curved shapes: one power of two for all (t unchanged)
    scaleShape(a, k);
    scaleShape(b, k);
    const Vec3 sma = scaled(ma, km), smb = scaled(mb, km);
    if (trace) trace->lengthExponent = -k;
    ImpactQueryResult out;
    if (a.kind == Kind::Plane) out.result = planeImpact(a, sma, b, smb, trace);
    else if (b.kind == Kind::Plane) {
        out.result = planeImpact(b, smb, a, sma, trace);
        out.result.normal = -out.result.normal;  // from a (the shape) toward b (the plane)
    } else if (a.isCurved() || b.isCurved()) {
        curvedImpact(a, sma, b, smb, std::ldexp(1.0, -k), out, trace);
    } else {
        if (trace) trace->tExponent = km - ks;
        boundedImpact(a, sma, b, smb, std::ldexp(1.0, ks - km), options, out, trace);
        out.result.t = std::ldexp(out.result.t, km - ks);
    }
    if (out.status != PairStatus::Ok) return out;
    TimeOfImpactResult& res = out.result;
    if (res.hit && !res.initiallyOverlapping) {
        res.pointA = scaled(res.pointA, -k);
        res.pointB = scaled(res.pointB, -k);
        if (!res.pointA.allFinite() || !res.pointB.allFinite()) out.status = PairStatus::Overflow;
    }
    return out;
}

}  // namespace cdlab
