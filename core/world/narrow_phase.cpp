#include "core/world/narrow_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/contact/contact_box.h"
#include "core/contact/contact_manifold.h"
#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/closest/closest_point.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab {

const char* nameOf(NarrowMethod method) {
    switch (method) {
        case NarrowMethod::None: return "none";
        case NarrowMethod::BoxBox: return "box-box";
        case NarrowMethod::BoxPlane: return "box-plane";
        case NarrowMethod::HullHull: return "hull-hull";
        case NarrowMethod::HullPlane: return "hull-plane";
        case NarrowMethod::Rounded: return "rounded";
    }
    return "?";
}

namespace {

// The vertex of the shape nearest to the world point p (its id part): a polytope's vertex by
// brute force over at most its vertex count, a capsule's nearer end (0: −y, 1: +y), else 0.
std::uint32_t nearestVertex(const WorldShape& s, const Transform& t, const Vec3& p) {
    if (s.kind == WorldShape::Kind::Capsule) return t.applyInverse(p).y() > 0 ? 1u : 0u;
    if (!s.polytope()) return 0u;
    const Vec3 local = t.applyInverse(p);
    std::uint32_t best = 0;
    double bestD = INFINITY;
    const auto& vs = s.hull.vertices();
    for (std::size_t i = 0; i < vs.size(); ++i) {
        const double d = (vs[i].position - local).squaredNorm();
        if (d < bestD) {
            bestD = d;
            best = static_cast<std::uint32_t>(i);
        }
    }
    return best & 0xFFFFu;
}

std::uint64_t featureKeyOf(SatAxisKind axis, const FeatureRef& fa, const FeatureRef& fb) {
    const auto part = [](const FeatureRef& f) {
        return (static_cast<std::uint64_t>(f.type) << 24) | (static_cast<std::uint64_t>(f.index) & 0xFFFFFFu);
    };
    return (static_cast<std::uint64_t>(axis) << 60) ^ (part(fa) << 30) ^ part(fb);
}

void addPoint(PairManifold& out, const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb,
              const Vec3& pa, const Vec3& pb) {
    WorldContactPoint c;
    c.pointA = pa;
    c.pointB = pb;
    c.separation = (pb - pa).dot(out.normal);
    c.id = (nearestVertex(a, ta, pa) << 16) | nearestVertex(b, tb, pb);
    out.points.push_back(c);
}

// A polytope's support in the world: the body-frame vertex extreme along Rᵀ d, rotated and moved.
struct PosedHull {
    const ConvexPolyhedron* hull = nullptr;
    Mat3 rotation = Mat3::Identity();
    Vec3 position = Vec3::Zero();
    Vec3 support(const Vec3& d) const {
        const Vec3 local = rotation.transpose() * d;
        const auto& vs = hull->vertices();
        std::size_t best = 0;
        double bestDot = -INFINITY;
        for (std::size_t i = 0; i < vs.size(); ++i) {
            const double x = vs[i].position.dot(local);
            if (x > bestDot) bestDot = x, best = i;
        }
        return rotation * vs[best].position + position;
    }
};

// The face of `hull` (at pose t) whose outward normal is nearest to the world direction d.
int faceAlong(const ConvexPolyhedron& hull, const Transform& t, const Vec3& d) {
    const Vec3 local = t.rotateInverse(d);
    int best = 0;
    double bestDot = -INFINITY;
    for (int f = 0; f < hull.faceCount(); ++f) {
        const double x = hull.face(f).normal.dot(local);
        if (x > bestDot) bestDot = x, best = f;
    }
    return best;
}

using Polygon = FixedCapacityVector<Vec3, 64>;

Polygon worldFace(const ConvexPolyhedron& hull, const Transform& t, int f) {
    Polygon p;
    for (int k = hull.faceVertexStart()[f]; k < hull.faceVertexStart()[f + 1]; ++k)
        p.push_back(t.apply(hull.position(hull.faceVertexIds()[k])));
    return p;
}

// Two polytopes apart by at most margin whose separating axis is a face normal: the incident face
// (the other body's face most anti-parallel to it) clipped by the reference face's side planes
// (Sutherland–Hodgman), each clipped point within margin of the reference plane a speculative
// point with its projection on it, reduced to 4 by core's area-keeping rules (Box2D v3's
// speculative manifold, in 3D). False when the axis is an edge pair's or the clip keeps nothing.
bool speculativeFaces(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb,
                      const SatContactResult& r, double margin, PairManifold& out) {
    if (r.axisKind == SatAxisKind::EdgeEdge) return false;
    const bool refA = r.axisKind == SatAxisKind::FaceA;
    const ConvexPolyhedron& rh = refA ? a.hull : b.hull;
    const ConvexPolyhedron& ih = refA ? b.hull : a.hull;
    const Transform& rt = refA ? ta : tb;
    const Transform& it = refA ? tb : ta;
    const Vec3 outward = refA ? r.normal : Vec3(-r.normal);  // the reference face's outward normal
    const int rf = faceAlong(rh, rt, outward);
    const Vec3 n = rt.rotate(rh.face(rf).normal);
    const Polygon ref = worldFace(rh, rt, rf);
    Polygon poly = worldFace(ih, it, faceAlong(ih, it, -n)), next;
    for (std::size_t i = 0; i < ref.size() && !poly.empty(); ++i) {
        const Vec3 side = (ref[(i + 1) % ref.size()] - ref[i]).cross(n);  // outward (counter-clockwise face)
        const double d = side.dot(ref[i]);
        next.clear();
        for (std::size_t k = 0; k < poly.size(); ++k) {
            const Vec3& p = poly[k];
            const Vec3& q = poly[(k + 1) % poly.size()];
            const double sp = side.dot(p) - d, sq = side.dot(q) - d;
            if (sp <= 0) next.push_back(p);
            if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) next.push_back(p + (sp / (sp - sq)) * (q - p));
        }
        std::swap(poly, next);
    }
    FixedCapacityVector<ContactPoint, kMaxContactPoints> kept;
    for (const Vec3& p : poly) {
        const double sep = n.dot(p - ref[0]);
        if (sep > margin) continue;
        const Vec3 onRef = p - sep * n;
        // pointA − pointB = depth · normal with depth = −sep (the generators' convention).
        kept.push_back(refA ? ContactPoint{onRef, p, -sep} : ContactPoint{p, onRef, -sep});
    }
    if (kept.empty()) return false;
    out.normal = r.normal;
    out.featureKey = featureKeyOf(r.axisKind, FeatureRef{FeatureType::Face, refA ? rf : -1},
                                  FeatureRef{FeatureType::Face, refA ? -1 : rf});
    out.normalBody = refA ? 0 : 1;
    for (int i : reduceContactPolygon(std::span<const ContactPoint>(kept.begin(), kept.end()), out.normal,
                                      kWorldManifoldPoints))
        addPoint(out, a, ta, b, tb, kept[i].pointA, kept[i].pointB);
    return !out.points.empty();
}

// Two polytopes. Overlapping or touching (core's automatic touching band): the SAT manifold. Apart
// by at most margin: the speculative face clip above, else (an edge axis) GJK's closest pair. (A
// SAT with the margin as its touching band would do the clip itself, but where its clip keeps
// nothing core computes an exact touching pair over the |A|·|B| vertex differences: 60 % of a
// 400-body pile's time.)
bool polytopePair(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                  PairManifold& out) {
    SatContactOptions o;
    o.maxPoints = kWorldManifoldPoints;
    const bool boxes = a.kind == WorldShape::Kind::Box && b.kind == WorldShape::Kind::Box;
    const SatContactResult r =
        boxes ? contactBoxBox(a.halfExtents, ta, b.halfExtents, tb, o) : contactPolyhedra(a.hull, ta, b.hull, tb, o);
    out.method = boxes ? NarrowMethod::BoxBox : NarrowMethod::HullHull;
    if (r.status == SatContactStatus::InvalidInput) return false;
    if (r.colliding()) {
        out.normal = r.normal;
        out.featureKey = featureKeyOf(r.axisKind, r.featureA, r.featureB);
        out.normalBody = r.axisKind == SatAxisKind::FaceB ? 1 : 0;
        for (const ContactPoint& p : r.manifold) addPoint(out, a, ta, b, tb, p.pointA, p.pointB);
        return !out.points.empty();
    }
    if (r.separation > margin) {  // the SAT's separation is a lower bound of the distance
        out.separatingAxis = r.normal;
        return false;
    }
    if (speculativeFaces(a, ta, b, tb, r, margin, out)) return true;
    const PosedHull ha{&a.hull, ta.rotation.toRotationMatrix(), ta.position};
    const PosedHull hb{&b.hull, tb.rotation.toRotationMatrix(), tb.position};
    const GjkResult g = gjkDistance(ha, hb);
    if (g.status != GjkStatus::Separated) return false;
    if (g.distance > margin) {
        out.separatingAxis = g.separatingAxis;
        return false;
    }
    out.normal = g.separatingAxis;
    out.featureKey = 3;
    addPoint(out, a, ta, b, tb, g.pointA, g.pointB);
    return true;
}

bool polytopePlane(const WorldShape& a, const Transform& ta, const WorldShape& plane, const Transform& tp,
                   double margin, PairManifold& out) {
    PlaneContactOptions o;
    o.tolerance = margin;
    o.maxPoints = kWorldManifoldPoints;
    const ContactManifold* manifold = nullptr;
    BoxPlaneContact box;
    PlaneContactResult hull;
    if (a.kind == WorldShape::Kind::Box) {
        box = contactBoxPlane(a.halfExtents, ta, plane.plane, o);
        if (!box.colliding()) return false;
        out.method = NarrowMethod::BoxPlane;
        out.normal = box.normal;
        manifold = &box.manifold;
    } else {
        hull = contactPolyhedronPlane(a.hull, ta, plane.plane, o);
        if (!hull.colliding()) return false;
        out.method = NarrowMethod::HullPlane;
        out.normal = hull.normal;
        manifold = &hull.manifold;
    }
    out.normalBody = 1;
    out.featureKey = 1;  // the plane's pair has one configuration: its points' ids tell them apart
    for (const ContactPoint& p : *manifold) {
        // A point within the band above the plane has pointA − pointB = depth · normal with depth
        // < 0; a point beyond the margin is none (the reduction may keep a far crossing otherwise).
        if ((p.pointB - p.pointA).dot(out.normal) > margin) continue;
        addPoint(out, a, ta, plane, tp, p.pointA, p.pointB);
    }
    return !out.points.empty();
}

// A sphere's or capsule's core (its centre, or its segment) in the world; the shape is core ⊕ ball(r).
struct RoundedCore {
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();
    double radius = 0.0;
    bool segment = false;
    Vec3 support(const Vec3& d) const { return d.dot(b - a) > 0 ? b : a; }
};

RoundedCore coreOf(const WorldShape& s, const Transform& t) {
    RoundedCore c;
    c.radius = s.radius;
    if (s.kind == WorldShape::Kind::Capsule) {
        const Vec3 axis = t.rotation * Vec3(0.0, s.halfHeight, 0.0);
        c.a = t.position - axis;
        c.b = t.position + axis;
        c.segment = s.halfHeight > 0;
    } else {
        c.a = c.b = t.position;
    }
    return c;
}

// The point pair of two cores' closest points pa, pb with radii ra, rb: surface points along the
// line between them (any perpendicular when the cores meet).
bool roundedPoint(PairManifold& out, const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb,
                  const Vec3& pa, double ra, const Vec3& pb, double rb, const Vec3& fallbackNormal, double margin,
                  bool setNormal) {
    const Vec3 d = pb - pa;
    const double len = d.norm();
    if (len - ra - rb > margin) return false;
    if (setNormal) out.normal = len > 1e-12 ? Vec3(d / len) : fallbackNormal;
    addPoint(out, a, ta, b, tb, pa + ra * out.normal, pb - rb * out.normal);
    return true;
}

// Sphere or capsule (A) against sphere or capsule (B): closest points of the cores; two nearly
// parallel capsules (|u_A · u_B| > 0.995) get a point at each end of their overlap along A.
bool roundedRounded(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                    PairManifold& out) {
    const RoundedCore ca = coreOf(a, ta), cb = coreOf(b, tb);
    Vec3 pa = ca.a, pb = cb.a;
    if (ca.segment && cb.segment) {
        const SegmentSegmentResult r = closestPointsSegmentSegment(Segment{ca.a, ca.b}, Segment{cb.a, cb.b});
        pa = r.pointOnFirst, pb = r.pointOnSecond;
    } else if (ca.segment) {
        pa = closestPointOnSegment(cb.a, Segment{ca.a, ca.b}).point;
    } else if (cb.segment) {
        pb = closestPointOnSegment(ca.a, Segment{cb.a, cb.b}).point;
    }
    const Vec3 up = ta.rotation * Vec3::UnitY();
    const Vec3 fallback = std::abs(up.z()) < 0.9 ? Vec3(up.cross(Vec3::UnitZ()).normalized()) : Vec3::UnitX();
    if (!roundedPoint(out, a, ta, b, tb, pa, ca.radius, pb, cb.radius, fallback, margin, true)) return false;
    if (ca.segment && cb.segment) {
        const Vec3 ua = (ca.b - ca.a).normalized(), ub = (cb.b - cb.a).normalized();
        if (std::abs(ua.dot(ub)) > 0.995) {
            // Overlap of B's projection on A's line, as parameters of A.
            const double len = (ca.b - ca.a).norm();
            double t0 = (cb.a - ca.a).dot(ua), t1 = (cb.b - ca.a).dot(ua);
            if (t0 > t1) std::swap(t0, t1);
            t0 = std::max(t0, 0.0), t1 = std::min(t1, len);
            if (t1 - t0 > 1e-3 * len) {
                out.points.clear();
                for (double t : {t0, t1}) {
                    const Vec3 p = ca.a + t * ua;
                    const Vec3 q = closestPointOnSegment(p, Segment{cb.a, cb.b}).point;
                    roundedPoint(out, a, ta, b, tb, p, ca.radius, q, cb.radius, out.normal, margin, false);
                }
                if (out.points.empty()) return false;
            }
        }
    }
    return true;
}

// Sphere or capsule (A) on the plane (B): each end of the core whose ball reaches within margin.
bool roundedPlane(const WorldShape& a, const Transform& ta, const WorldShape& plane, const Transform& tp, double margin,
                  PairManifold& out) {
    const RoundedCore c = coreOf(a, ta);
    const Vec3& n = plane.plane.normal;
    out.normal = -n;
    for (int end = 0; end < (c.segment ? 2 : 1); ++end) {
        const Vec3& p = end == 0 ? c.a : c.b;
        const Vec3 surface = p - c.radius * n;
        const double s = n.dot(surface) - plane.plane.offset;
        if (s > margin) continue;
        addPoint(out, a, ta, plane, tp, surface, Vec3(surface - s * n));
    }
    return !out.points.empty();
}

// A capsule (A) lying along the polytope face whose outward normal is closest to −normal: its segment
// clipped to the face's side planes, a point at each clipped end within margin (Box2D v3's
// capsule–polygon manifold, in 3D). False when the segment is not parallel to the face within
// sin 3° or the clip keeps less than 1e-3 of it.
bool capsuleOnFace(const RoundedCore& c, const WorldShape& a, const Transform& ta, const WorldShape& b,
                   const Transform& tb, const Vec3& normal, double margin, PairManifold& out) {
    const ConvexPolyhedron& hull = b.hull;
    const int face = faceAlong(hull, tb, -normal);
    const Vec3 nf = hull.face(face).normal;
    const Vec3 la = tb.applyInverse(c.a), lb = tb.applyInverse(c.b);
    const Vec3 u = lb - la;
    if (std::abs(u.normalized().dot(nf)) > 0.0523) return false;
    double t0 = 0.0, t1 = 1.0;
    const int start = hull.faceVertexStart()[face], end = hull.faceVertexStart()[face + 1];
    for (int k = start; k < end; ++k) {
        const Vec3& v0 = hull.position(hull.faceVertexIds()[k]);
        const Vec3& v1 = hull.position(hull.faceVertexIds()[k + 1 < end ? k + 1 : start]);
        const Vec3 side = (v1 - v0).cross(nf);  // outward from the face's prism (counter-clockwise face)
        const double da = side.dot(la - v0), du = side.dot(u);
        if (du == 0) {
            if (da > 0) return false;
            continue;
        }
        const double t = -da / du;
        if (du > 0) t1 = std::min(t1, t);
        else t0 = std::max(t0, t);
    }
    if (t1 - t0 < 1e-3) return false;
    const Vec3 v0 = hull.position(hull.faceVertexIds()[start]);
    const Vec3 n = tb.rotation * nf;
    PairManifold m;
    m.normal = -n;
    for (double t : {t0, t1}) {
        const Vec3 p = la + t * u;
        const double s = nf.dot(p - v0) - c.radius;
        if (s > margin) continue;
        const Vec3 surface = tb.apply(p) - c.radius * n;
        addPoint(m, a, ta, b, tb, surface, Vec3(surface - s * n));  // pointB: its projection on the face
    }
    if (m.points.size() < 2) return false;
    out.normal = m.normal;
    out.points = m.points;
    return true;
}

// Sphere or capsule (A) against a box or hull (B) by GJK on the core and the polytope: apart, the
// closest points (a capsule lying on a face: its clipped ends); the core inside the polytope, EPA's
// deepest points. Separation = core distance − r, or −(EPA depth + r).
bool roundedPolytope(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                     PairManifold& out) {
    const RoundedCore c = coreOf(a, ta);
    const PosedHull h{&b.hull, tb.rotation.toRotationMatrix(), tb.position};
    const GjkResult g = gjkDistance(c, h);
    if (g.status == GjkStatus::InvalidInput) return false;
    if (g.status == GjkStatus::Separated && g.distance > 0) {
        if (g.distance - c.radius > margin) {
            out.separatingAxis = g.separatingAxis;
            return false;
        }
        out.normal = g.separatingAxis;
        if (c.segment && capsuleOnFace(c, a, ta, b, tb, out.normal, margin, out)) return true;
        addPoint(out, a, ta, b, tb, g.pointA + c.radius * out.normal, g.pointB);
        return true;
    }
    const EpaResult e = penetration(c, h);
    if (e.status == EpaStatus::InvalidInput) return false;
    out.normal = e.normal;
    addPoint(out, a, ta, b, tb, e.pointA + c.radius * e.normal, e.pointB);
    return true;
}

// A sphere or capsule (A) against anything (B).
bool roundedPair(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                 PairManifold& out) {
    out.method = NarrowMethod::Rounded;
    out.featureKey = 2;
    out.normalBody = b.rounded() ? 2 : 1;
    if (b.rounded()) return roundedRounded(a, ta, b, tb, margin, out);
    if (b.kind == WorldShape::Kind::Plane) return roundedPlane(a, ta, b, tb, margin, out);
    return roundedPolytope(a, ta, b, tb, margin, out);
}

void flip(PairManifold& m) {
    m.normal = -m.normal;
    if (m.normalBody < 2) m.normalBody = 1 - m.normalBody;
    for (WorldContactPoint& p : m.points) {
        std::swap(p.pointA, p.pointB);
        p.id = (p.id >> 16) | ((p.id & 0xFFFFu) << 16);
    }
}

// The extent of a shape along the unit d: max over the solid of d·x.
double extentAlong(const WorldShape& s, const Transform& t, const Vec3& d) {
    switch (s.kind) {
        case WorldShape::Kind::Box:
        case WorldShape::Kind::Hull: {
            const Vec3 local = t.rotateInverse(d);
            double best = -INFINITY;
            for (const auto& v : s.hull.vertices()) best = std::max(best, v.position.dot(local));
            return best + d.dot(t.position);
        }
        case WorldShape::Kind::Sphere: return d.dot(t.position) + s.radius;
        case WorldShape::Kind::Capsule: {
            const Vec3 axis = t.rotation * Vec3(0.0, s.halfHeight, 0.0);
            return d.dot(t.position) + std::abs(d.dot(axis)) + s.radius;
        }
        case WorldShape::Kind::Plane: break;
    }
    return INFINITY;
}

}  // namespace

double separationAlong(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb,
                       const Vec3& d) {
    if (a.kind == WorldShape::Kind::Plane || b.kind == WorldShape::Kind::Plane) return -INFINITY;
    return -extentAlong(b, tb, -d) - extentAlong(a, ta, d);
}

bool collideShapes(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                   PairManifold& out) {
    out = PairManifold{};
    using K = WorldShape::Kind;
    if (a.kind == K::Plane && b.kind == K::Plane) return false;
    if (a.kind == K::Plane) {  // generators take the plane second
        if (!collideShapes(b, tb, a, ta, margin, out)) return false;
        flip(out);
        return true;
    }
    if (!a.rounded() && b.rounded()) {  // the rounded routines take the sphere or capsule first
        const bool hit = collideShapes(b, tb, a, ta, margin, out);
        out.separatingAxis = -out.separatingAxis;
        if (!hit) return false;
        flip(out);
        return true;
    }
    if (a.rounded()) return roundedPair(a, ta, b, tb, margin, out);
    if (b.kind == K::Plane) return polytopePlane(a, ta, b, tb, margin, out);
    return polytopePair(a, ta, b, tb, margin, out);
}

}  // namespace cdlab
