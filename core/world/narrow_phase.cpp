#include "core/world/narrow_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/contact/contact_box.h"
#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/query/contact.h"
#include "core/query/shape.h"

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

bool polytopePair(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                  PairManifold& out) {
    SatContactOptions o;
    o.tolerance = margin;
    o.maxPoints = kWorldManifoldPoints;
    const bool boxes = a.kind == WorldShape::Kind::Box && b.kind == WorldShape::Kind::Box;
    const SatContactResult r =
        boxes ? contactBoxBox(a.halfExtents, ta, b.halfExtents, tb, o) : contactPolyhedra(a.hull, ta, b.hull, tb, o);
    if (!r.colliding()) return false;
    out.method = boxes ? NarrowMethod::BoxBox : NarrowMethod::HullHull;
    out.normal = r.normal;
    out.featureKey = featureKeyOf(r.axisKind, r.featureA, r.featureB);
    for (const ContactPoint& p : r.manifold) addPoint(out, a, ta, b, tb, p.pointA, p.pointB);
    return !out.points.empty();
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
    out.featureKey = 1;  // the plane's pair has one configuration: its points' ids tell them apart
    for (const ContactPoint& p : *manifold) {
        // A point within the band above the plane has pointA − pointB = depth · normal with depth
        // < 0; a point beyond the margin is none (the reduction may keep a far crossing otherwise).
        if ((p.pointB - p.pointA).dot(out.normal) > margin) continue;
        addPoint(out, a, ta, plane, tp, p.pointA, p.pointB);
    }
    return !out.points.empty();
}

QueryShape queryShapeOf(const WorldShape& s, const Transform& t, double inflate) {
    switch (s.kind) {
        case WorldShape::Kind::Sphere: return QueryShape::sphere(t.position, s.radius + inflate);
        case WorldShape::Kind::Capsule: {
            const Vec3 axis = t.rotation * Vec3(0.0, s.halfHeight, 0.0);
            return QueryShape::capsule(t.position - axis, t.position + axis, s.radius + inflate);
        }
        case WorldShape::Kind::Box:
            return QueryShape::obb(t.position, s.halfExtents, t.rotation.toRotationMatrix());
        case WorldShape::Kind::Hull:
            return QueryShape::polytope(s.hull.positions(), t.rotation.toRotationMatrix(), t.position);
        case WorldShape::Kind::Plane: return QueryShape::plane(s.plane.normal, s.plane.offset);
    }
    return {};
}

// A sphere or capsule against anything: contactQuery with the rounded shape (A's if A is rounded)
// grown by margin, its points moved back onto its real surface.
bool roundedPair(const WorldShape& a, const Transform& ta, const WorldShape& b, const Transform& tb, double margin,
                 PairManifold& out) {
    const bool growA = a.rounded();
    const QueryShape qa = queryShapeOf(a, ta, growA ? margin : 0.0);
    const QueryShape qb = queryShapeOf(b, tb, growA ? 0.0 : margin);
    ContactOptions o;
    o.maxPoints = kWorldManifoldPoints;
    const ContactResult r = contactQuery(qa, qb, o);
    if (r.status != ContactStatus::Ok || !r.colliding) return false;
    out.method = NarrowMethod::Rounded;
    out.normal = r.normal;
    out.featureKey = 2;
    for (const ContactPoint& p : r.points) {
        // The grown shape's point sits margin beyond its real surface along the normal (A's point
        // is deepest along +n, B's along −n).
        const Vec3 pa = growA ? Vec3(p.pointA - margin * r.normal) : p.pointA;
        const Vec3 pb = growA ? p.pointB : Vec3(p.pointB + margin * r.normal);
        if (out.points.size() == kWorldManifoldPoints) break;
        addPoint(out, a, ta, b, tb, pa, pb);
    }
    return !out.points.empty();
}

void flip(PairManifold& m) {
    m.normal = -m.normal;
    for (WorldContactPoint& p : m.points) {
        std::swap(p.pointA, p.pointB);
        p.id = (p.id >> 16) | ((p.id & 0xFFFFu) << 16);
    }
}

}  // namespace

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
    if (a.rounded() || b.rounded()) return roundedPair(a, ta, b, tb, margin, out);
    if (b.kind == K::Plane) return polytopePlane(a, ta, b, tb, margin, out);
    return polytopePair(a, ta, b, tb, margin, out);
}

}  // namespace cdlab
