#include "core/closest/feature_distance.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/closest/closest_point.h"

namespace cdlab {

const char* nameOf(ContactType type) {
    switch (type) {
        case ContactType::VV: return "V-V";
        case ContactType::VE: return "V-E";
        case ContactType::VF: return "V-F";
        case ContactType::EE: return "E-E";
        case ContactType::EF: return "E-F";
        case ContactType::FF: return "F-F";
    }
    return "V-V";
}

namespace {

// Newell normal of a polygon (Newell 1972; Ericson §12.1.1): robust for any planar polygon,
// length = twice the area. Relative to the first point for accuracy at large offsets.
Vec3 newellNormal(const std::vector<Vec3>& poly) {
    Vec3 n = Vec3::Zero();
    const size_t k = poly.size();
    for (size_t i = 0; i < k; ++i) {
        const Vec3 a = poly[i] - poly[0], b = poly[(i + 1) % k] - poly[0];
        n += a.cross(b);
    }
    return n;
}

double featureScale(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    Vec3 lo = a[0], hi = a[0];
    for (const auto* v : {&a, &b})
        for (const Vec3& p : *v) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return (hi - lo).norm();
}

// The polygon's unit normal (Newell's), or nothing for a zero-area polygon.
std::optional<Vec3> polygonUnitNormal(const std::vector<Vec3>& poly) {
    const Vec3 nn = newellNormal(poly);
    const double len = nn.norm();
    if (!(len > 0.0)) return std::nullopt;
    return Vec3(nn / len);
}

// The sub-feature of `f` that holds its closest point p, seen along `toOther` (the unit direction
// from p to the other feature's closest point; zero when they meet): a face counts only when
// toOther is along its normal (else p is on its boundary: that edge or corner), an edge only when
// toOther is across it (else p is an endpoint: that vertex). This also keeps the features of a
// parallel pair, whose closest points are one of many. `tol`: length below rounding (1e-12 of the
// pair's size); `slope`: the sine below which two directions count as parallel.
FeatureGeometry realizedFeature(const FeatureGeometry& f, const Vec3& p, const Vec3& toOther, double tol,
                                double slope) {
    if (f.type == FeatureType::Vertex) return f;
    const bool meet = toOther.isZero(0.0);
    if (f.type == FeatureType::Edge) {
        const Vec3 u = (f.points[1] - f.points[0]).normalized();
        if (!meet && std::abs(u.dot(toOther)) <= slope) return f;  // across the edge
        for (const Vec3& q : f.points)
            if ((p - q).norm() <= tol) return {FeatureType::Vertex, {q}};
        return f;
    }
    const std::optional<Vec3> n = polygonUnitNormal(f.points);
    if (n && !meet && (toOther - n->dot(toOther) * *n).norm() <= slope) return f;  // along the normal
    for (const Vec3& q : f.points)
        if ((p - q).norm() <= tol) return {FeatureType::Vertex, {q}};
    for (size_t i = 0; i < f.points.size(); ++i) {
        const Segment side{f.points[i], f.points[(i + 1) % f.points.size()]};
        if (closestPointOnSegment(p, side).distanceSquared <= tol * tol) {
            const FeatureGeometry edge{FeatureType::Edge, {side.a, side.b}};
            return realizedFeature(edge, p, toOther, tol, slope);
        }
    }
    return f;  // the features meet inside the face
}

// 1 for a vertex, 2 for an edge, 3 for a face: its point count, except that a face has >= 3.
int featureDimension(FeatureType t) { return t == FeatureType::Vertex ? 1 : t == FeatureType::Edge ? 2 : 3; }

ContactType contactType(FeatureType a, FeatureType b) {
    const int lo = std::min(featureDimension(a), featureDimension(b));
    const int hi = std::max(featureDimension(a), featureDimension(b));
    return lo == 1   ? (hi == 1 ? ContactType::VV : hi == 2 ? ContactType::VE : ContactType::VF)
           : lo == 2 ? (hi == 2 ? ContactType::EE : ContactType::EF)
                     : ContactType::FF;
}

}  // namespace

PointPolygonResult closestPointOnPolygon(const Vec3& p, const std::vector<Vec3>& poly) {
    PointPolygonResult r;
    if (const std::optional<Vec3> unitNormal = polygonUnitNormal(poly)) {
        const Vec3& n = *unitNormal;
        const Vec3 q = p - n.dot(p - poly[0]) * n;  // projection onto the plane
        bool inside = true;
        const size_t k = poly.size();
        for (size_t i = 0; i < k && inside; ++i)
            inside = (poly[(i + 1) % k] - poly[i]).cross(q - poly[i]).dot(n) >= 0.0;
        if (inside) {
            r.point = q;
            r.distanceSquared = (p - q).squaredNorm();
            r.interior = true;
            return r;
        }
    }
    // Outside (or a zero-area polygon): the nearest boundary point.
    r.distanceSquared = INFINITY;
    for (size_t i = 0; i < poly.size(); ++i) {
        const ClosestPointOnSegmentResult c = closestPointOnSegment(p, Segment{poly[i], poly[(i + 1) % poly.size()]});
        if (c.distanceSquared < r.distanceSquared) r.point = c.point, r.distanceSquared = c.distanceSquared;
    }
    return r;
}

FeaturePairPoints closestPointsSegmentPolygon(const Segment& s, const std::vector<Vec3>& poly) {
    FeaturePairPoints r;
    if (const std::optional<Vec3> unitNormal = polygonUnitNormal(poly)) {
        const Vec3& n = *unitNormal;
        const double sa = n.dot(s.a - poly[0]), sb = n.dot(s.b - poly[0]);
        // Plane crossing inside the polygon: distance 0 (both sides strictly, else an endpoint
        // on the plane is handled by the endpoint candidates below).
        if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) {
            const double t = sa / (sa - sb);
            const Vec3 x = s.a + t * (s.b - s.a);
            const PointPolygonResult c = closestPointOnPolygon(x, poly);
            if (c.interior) {
                r.pointA = x;
                r.pointB = c.point;
                r.distanceSquared = (x - c.point).squaredNorm();
                return r;
            }
        }
        // Parallel to the plane (to rounding): a continuum of closest pairs when the projection
        // overlaps the polygon.
        const double d = (s.b - s.a).norm();
        r.parallel = d > 0.0 && std::abs(sa - sb) <= kFeatureParallelRelative * d;
    }
    r.distanceSquared = INFINITY;
    for (const Vec3& e : {s.a, s.b}) {
        const PointPolygonResult c = closestPointOnPolygon(e, poly);
        if (c.distanceSquared < r.distanceSquared)
            r.pointA = e, r.pointB = c.point, r.distanceSquared = c.distanceSquared;
    }
    for (size_t i = 0; i < poly.size(); ++i) {
        const SegmentSegmentResult c = closestPointsSegmentSegment(s, Segment{poly[i], poly[(i + 1) % poly.size()]});
        if (c.distanceSquared < r.distanceSquared) {
            r.pointA = c.pointOnFirst, r.pointB = c.pointOnSecond, r.distanceSquared = c.distanceSquared;
            r.parallel = r.parallel || c.parallel;
        }
    }
    return r;
}

FeaturePairPoints closestPointsPolygonPolygon(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    FeaturePairPoints r;
    r.distanceSquared = INFINITY;
    for (size_t i = 0; i < a.size(); ++i) {
        const FeaturePairPoints c = closestPointsSegmentPolygon(Segment{a[i], a[(i + 1) % a.size()]}, b);
        if (c.distanceSquared < r.distanceSquared) r = c;
        if (r.distanceSquared == 0.0) return r;
    }
    for (size_t i = 0; i < b.size(); ++i) {
        FeaturePairPoints c = closestPointsSegmentPolygon(Segment{b[i], b[(i + 1) % b.size()]}, a);
        std::swap(c.pointA, c.pointB);
        if (c.distanceSquared < r.distanceSquared) r = c;
    }
    // Parallel planes: a face-on pair has a continuum of closest pairs.
    const Vec3 na = newellNormal(a), nb = newellNormal(b);
    r.parallel = na.cross(nb).norm() <= kFeatureParallelRelative * na.norm() * nb.norm();
    return r;
}

FeatureDistanceResult featureDistance(const FeatureGeometry& a, const FeatureGeometry& b) {
    FeatureDistanceResult r;
    for (const FeatureGeometry* f : {&a, &b}) {
        if (f->type == FeatureType::None) r.message = "feature type None";
        else if (f->type == FeatureType::Face ? f->points.size() < 3 : f->points.size() != size_t(featureDimension(f->type)))
            r.message = std::string("wrong point count for a ") + nameOf(f->type);
        else
            for (const Vec3& p : f->points)
                if (!p.allFinite()) r.message = "non-finite feature point";
        if (!r.message.empty()) return r;
    }
    r.valid = true;
    const int da = featureDimension(a.type), db = featureDimension(b.type);

    // Closest points: dispatch on (dim A, dim B), swapping the roles back when B is the lower one.
    FeaturePairPoints c;
    const auto flip = [](FeaturePairPoints x) {
        std::swap(x.pointA, x.pointB);
        return x;
    };
    const auto pointVs = [](const Vec3& p, const FeatureGeometry& f) {
        FeaturePairPoints x;
        x.pointA = p;
        if (f.type == FeatureType::Vertex) x.pointB = f.points[0];
        else if (f.type == FeatureType::Edge)
            x.pointB = closestPointOnSegment(p, Segment{f.points[0], f.points[1]}).point;
        else x.pointB = closestPointOnPolygon(p, f.points).point;
        x.distanceSquared = (x.pointA - x.pointB).squaredNorm();
        return x;
    };
    const auto segmentVs = [](const Segment& s, const FeatureGeometry& f) {
        if (f.type == FeatureType::Edge) {
            const SegmentSegmentResult ss = closestPointsSegmentSegment(s, Segment{f.points[0], f.points[1]});
            return FeaturePairPoints{ss.pointOnFirst, ss.pointOnSecond, ss.distanceSquared, ss.parallel};
        }
        return closestPointsSegmentPolygon(s, f.points);
    };
    if (da == 1) c = pointVs(a.points[0], b);
    else if (db == 1) c = flip(pointVs(b.points[0], a));
    else if (da == 2) c = segmentVs(Segment{a.points[0], a.points[1]}, b);
    else if (db == 2) c = flip(segmentVs(Segment{b.points[0], b.points[1]}, a));
    else c = closestPointsPolygonPolygon(a.points, b.points);
    r.pointA = c.pointA;
    r.pointB = c.pointB;
    r.distance = (c.pointB - c.pointA).norm();
    r.parallel = c.parallel;
    const double size = featureScale(a.points, b.points);

    // The features that hold the closest points (the pair type is decided by where the closest
    // points lie, not by the features asked about): kFeatureSnapRelative of the size.
    const Vec3 toB = r.distance > 0.0 ? Vec3((r.pointB - r.pointA) / r.distance) : Vec3::Zero();
    const double tol = kFeatureSnapRelative * size;
    const double slope =
        kFeatureDirectionSlope + (r.distance > 0.0 ? tol / r.distance : 0.0);  // the direction's own rounding
    const FeatureGeometry fa = realizedFeature(a, r.pointA, toB, tol, slope);
    const FeatureGeometry fb = realizedFeature(b, r.pointB, -toB, tol, slope);
    r.realizedA = fa.type;
    r.realizedB = fb.type;
    r.type = contactType(fa.type, fb.type);

    // Contact normal rule.
    if (fa.type == FeatureType::Face) {
        r.normal = newellNormal(fa.points).normalized();  // A's outward normal points toward B
        r.normalRule = "face A";
        r.normalDefined = true;
        return r;
    }
    if (fb.type == FeatureType::Face) {
        r.normal = -newellNormal(fb.points).normalized();  // B's outward normal points toward A
        r.normalRule = "face B";
        r.normalDefined = true;
        return r;
    }
    // V–V, V–E, E–E: the closest-point line, flagged unstable below kUnstableNormalRelative of the size.
    r.normalUnstable = r.distance <= kUnstableNormalRelative * size;
    if (r.distance > 0.0) {
        r.normal = (r.pointB - r.pointA) / r.distance;
        r.normalRule = "closest points";
        r.normalDefined = true;
        return r;
    }
    if (r.type == ContactType::EE) {
        const Vec3 x = (fa.points[1] - fa.points[0]).cross(fb.points[1] - fb.points[0]);
        if (x.norm() > 0.0) {
            const Vec3 toB = 0.5 * (fb.points[0] + fb.points[1]) - 0.5 * (fa.points[0] + fa.points[1]);
            r.normal = (x.dot(toB) < 0.0 ? Vec3(-x) : x).normalized();
            r.normalRule = "edge cross product";
            r.normalDefined = true;
            return r;
        }
    }
    r.normalRule = "none";
    r.normal = Vec3::Zero();
    return r;
}

}  // namespace cdlab
