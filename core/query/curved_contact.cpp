// Contact points of a cylinder or cone on a reference face, and the feature holding them
// (core/query/curved_contact.h). Moved from app/query (`cdlab query`'s contact op) unchanged: the
// same samples, crossings, order of candidates and reduction, so every answer keeps its bits.
#include "core/query/curved_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "core/contact/contact_manifold.h"

namespace cdlab {

namespace {

// Azimuths sampled on each rim circle (the first at the deepest one).
constexpr int kRimSamples = 32;
// The side has a deepest generator when −n leans off the axis by more than this (|−n in the rim's
// plane| > 1e-9); else a cap faces the face and no generator is lowest.
constexpr double kGeneratorTiltMin = 1e-9;
// The rims' samples start at the deepest azimuth when −n in the rim's plane is longer than this;
// else (a cap facing the face) at azimuth 0.
constexpr double kDeepestAzimuthMin = 1e-12;
// A cap lies flat on the face when |n · axis| >= 1 − kCapFlatSlack.
constexpr double kCapFlatSlack = 1e-9;
// curvedFeature: a point is on an end, the rim or the apex within kFeatureRelative of the solid's
// size (its half height or radius, at least kFeatureSizeFloor).
constexpr double kFeatureRelative = 1e-9, kFeatureSizeFloor = 1e-300;

struct Rim {
    Vec3 center, e1, e2;  // the circle center + r (cos φ e1 + sin φ e2)
    double radius;
    Vec3 at(double phi) const { return center + radius * (std::cos(phi) * e1 + std::sin(phi) * e2); }
};

std::vector<Rim> rimsOf(const CurvedSolid& s) {
    const Vec3 u = s.axis(), e1 = u.unitOrthogonal(), e2 = u.cross(e1);
    std::vector<Rim> rims = {{s.center - s.halfHeight * u, e1, e2, s.radius}};
    if (!s.cone) rims.push_back({s.center + s.halfHeight * u, e1, e2, s.radius});
    return rims;
}

// The angles φ at which a cos φ + b sin φ = c (none, one or two).
std::vector<double> solveCircle(double a, double b, double c) {
    const double m = std::hypot(a, b);
    if (!(m > 0.0) || std::abs(c) > m) return {};
    const double base = std::atan2(b, a), spread = std::acos(std::clamp(c / m, -1.0, 1.0));
    if (spread == 0.0) return {base};
    return {base - spread, base + spread};
}

struct Candidates {
    const ReferenceFace& face;
    double touch;
    std::vector<CurvedContactPoint> points;

    double depthOf(const Vec3& x) const { return face.offset - face.normal.dot(x); }
    // Outward in the face's plane across corner edge k (counter-clockwise seen from outside).
    Vec3 side(std::size_t k) const {
        const Vec3 &v = face.corners[k], &w = face.corners[(k + 1) % face.corners.size()];
        return (w - v).cross(face.normal);
    }
    bool insideFace(const Vec3& x, std::size_t skip = SIZE_MAX) const {
        for (std::size_t k = 0; k < face.corners.size(); ++k)
            if (k != skip && side(k).dot(x - face.corners[k]) > touch * side(k).norm()) return false;
        return true;
    }
    void add(const Vec3& x, bool crossing = false) {
        const double depth = crossing ? 0.0 : depthOf(x);
        if (depth < -touch || !insideFace(x)) return;
        points.push_back({x, x + depth * face.normal, std::max(depth, 0.0)});
    }
};

// The side's deepest generator: the line of the side surface lowest along −n, from the first rim's
// deepest point to the second's (a cone: to its apex). A cylinder lying on the face touches along it;
// where it leaves the face across a side plane (at its own depth there: a cylinder overhanging an
// edge keeps that end), or rises through the face's plane, is a corner of the contact region that no
// rim holds. None when the axis is along n (a cap faces the face).
void addDeepestGenerator(const CurvedSolid& s, Candidates& c) {
    const std::vector<Rim> rims = rimsOf(s);
    const Rim& rim = rims.front();
    const Vec3& n = c.face.normal;
    const double w1 = -n.dot(rim.e1), w2 = -n.dot(rim.e2);
    if (!(std::hypot(w1, w2) > kGeneratorTiltMin) || !(rim.radius > 0.0)) return;
    const double deepest = std::atan2(w2, w1);
    const Vec3 p0 = rim.at(deepest);
    const Vec3 p1 = s.cone ? Vec3(s.center + s.halfHeight * s.axis()) : rims[1].at(deepest);
    const auto crossing = [&](double f0, double f1) { return Vec3(p0 + f0 / (f0 - f1) * (p1 - p0)); };
    for (std::size_t k = 0; k < c.face.corners.size(); ++k) {
        const Vec3 side = c.side(k);
        const double f0 = side.dot(p0 - c.face.corners[k]), f1 = side.dot(p1 - c.face.corners[k]);
        if ((f0 < 0) == (f1 < 0)) continue;
        const Vec3 x = crossing(f0, f1);
        const double depth = c.depthOf(x);
        if (depth >= -c.touch && c.insideFace(x, k)) c.points.push_back({x, x + depth * n, std::max(depth, 0.0)});
    }
    const double g0 = c.depthOf(p0), g1 = c.depthOf(p1);
    if ((g0 < 0) != (g1 < 0)) c.add(crossing(g0, g1), true);
}

}  // namespace

std::vector<CurvedContactPoint> curvedOnFace(const CurvedSolid& s, const ReferenceFace& face, int maxPoints, double touch) {
    Candidates c{face, touch, {}};
    const Vec3& n = face.normal;
    for (const Rim& rim : rimsOf(s)) {
        if (!(rim.radius > 0.0)) {
            c.add(rim.center);
            continue;
        }
        // Samples from the deepest azimuth: the direction of −n in the rim's plane.
        const double w1 = -n.dot(rim.e1), w2 = -n.dot(rim.e2);
        const double deepest = std::hypot(w1, w2) > kDeepestAzimuthMin ? std::atan2(w2, w1) : 0.0;
        for (int k = 0; k < kRimSamples; ++k) c.add(rim.at(deepest + 2 * std::numbers::pi * k / kRimSamples));
        // Where the circle crosses the face's plane (depth 0) ...
        for (double phi : solveCircle(rim.radius * n.dot(rim.e1), rim.radius * n.dot(rim.e2), face.offset - n.dot(rim.center)))
            c.add(rim.at(phi), true);
        // ... and the face's side planes.
        for (std::size_t k = 0; k < face.corners.size(); ++k) {
            const Vec3 side = c.side(k);
            for (double phi : solveCircle(rim.radius * side.dot(rim.e1), rim.radius * side.dot(rim.e2),
                                          side.dot(face.corners[k] - rim.center))) {
                const Vec3 x = rim.at(phi);
                const double depth = c.depthOf(x);
                if (depth >= -touch && c.insideFace(x, k)) c.points.push_back({x, x + depth * n, std::max(depth, 0.0)});
            }
        }
    }
    if (s.cone) c.add(s.center + s.halfHeight * s.axis());
    addDeepestGenerator(s, c);
    // A cap lying flat on the face: the face's corners over the disc touch it too.
    const double along = n.dot(s.axis());
    if (std::abs(along) >= 1 - kCapFlatSlack && !(s.cone && along < 0)) {
        const Vec3 cap = s.center - (along > 0 ? 1.0 : -1.0) * s.halfHeight * s.axis();  // the cap facing the face
        for (const Vec3& q : face.corners) {
            const Vec3 onCap = q + (cap - q).dot(n) * n;
            if ((onCap - cap).norm() <= s.radius) {
                const double depth = c.depthOf(onCap);
                if (depth >= -touch) c.points.push_back({onCap, onCap + depth * n, std::max(depth, 0.0)});
            }
        }
    }
    std::vector<ContactPoint> polygon;
    for (const CurvedContactPoint& p : c.points) polygon.push_back({p.onSolid, p.onFace, p.depth});
    std::vector<CurvedContactPoint> kept;
    for (int i : reduceContactPolygon(polygon, n, maxPoints)) kept.push_back(c.points[std::size_t(i)]);
    return kept;
}

const char* nameOf(CurvedFeature::Type type) {
    switch (type) {
        case CurvedFeature::Type::Cap: return "cap";
        case CurvedFeature::Type::Side: return "side";
        case CurvedFeature::Type::Rim: return "rim";
        case CurvedFeature::Type::Apex: return "apex";
    }
    return "side";
}

const char* nameOf(CurvedFeature::End end) {
    switch (end) {
        case CurvedFeature::End::None: return "";
        case CurvedFeature::End::Top: return "top";
        case CurvedFeature::End::Bottom: return "bottom";
    }
    return "";
}

CurvedFeature curvedFeature(const CurvedSolid& s, const std::vector<Vec3>& points) {
    using Type = CurvedFeature::Type;
    using End = CurvedFeature::End;
    const Vec3 u = s.axis();
    const double tol = kFeatureRelative * std::max({s.halfHeight, s.radius, kFeatureSizeFloor});
    int top = 0, bottom = 0, apex = 0, onRim = 0;
    for (const Vec3& p : points) {
        const double y = (p - s.center).dot(u);
        const double radial = (p - s.center - y * u).norm();
        if (s.cone && (p - (s.center + s.halfHeight * u)).norm() <= tol) ++apex;
        else if (std::abs(y + s.halfHeight) <= tol) ++bottom;
        else if (!s.cone && std::abs(y - s.halfHeight) <= tol) ++top;
        if (std::abs(radial - s.radius) <= tol) ++onRim;
    }
    const int count = static_cast<int>(points.size());
    if (apex == count) return {Type::Apex, End::None};
    // On one end: its rim when one or two points all lie on the circle, else its cap (three or
    // more points, or a point inside the disc: a sphere resting on the middle of the cap).
    for (const auto& [onEnd, end] : {std::pair{top, End::Top}, std::pair{bottom, End::Bottom}})
        if (onEnd == count) return {count < 3 && onRim == count ? Type::Rim : Type::Cap, end};
    return {Type::Side, End::None};
}

}  // namespace cdlab
