#include "core/bounding/swept_sphere_overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/closest/closest_point.h"

namespace cdlab {

namespace {

bool validRectangle(const Rss& r) {
    return r.center.allFinite() && r.axes.allFinite() && r.halfLengths.allFinite() &&
           (r.halfLengths.array() >= 0.0).all();
}

std::array<Vec3, 4> corners(const Rss& r) {
    const Vec3 u = r.axes.col(0) * r.halfLengths.x(), v = r.axes.col(1) * r.halfLengths.y();
    return {r.center - u - v, r.center + u - v, r.center + u + v, r.center - u + v};
}

// Closest point of the solid rectangle to p: clamp the in-plane coordinates.
Vec3 closestOnRectangle(const Rss& r, const Vec3& p) {
    const Vec3 local = r.axes.transpose() * (p - r.center);
    const double x = std::clamp(local.x(), -r.halfLengths.x(), r.halfLengths.x());
    const double y = std::clamp(local.y(), -r.halfLengths.y(), r.halfLengths.y());
    return r.center + r.axes.col(0) * x + r.axes.col(1) * y;
}

// Does segment pq pierce the rectangle (cross or touch its plane inside it)? Coplanar segments
// are left to the edge-edge and corner tests.
bool segmentPierces(const Vec3& p, const Vec3& q, const Rss& r, Vec3& at) {
    const Vec3 n = r.axes.col(2);
    const double dp = n.dot(p - r.center), dq = n.dot(q - r.center);
    if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq) return false;
    const double t = dp / (dp - dq);
    at = p + t * (q - p);
    const Vec3 local = r.axes.transpose() * (at - r.center);
    return std::abs(local.x()) <= r.halfLengths.x() && std::abs(local.y()) <= r.halfLengths.y();
}

SweptSphereOverlapResult invalidResult() {
    SweptSphereOverlapResult r;
    r.coreDistance = r.separation = kNaN;
    return r;
}

SweptSphereOverlapResult fromCoreDistance(double d, double ra, double rb, const Vec3& pa, const Vec3& pb) {
    SweptSphereOverlapResult r;
    r.coreDistance = d;
    r.separation = d - (ra + rb);
    r.hit = d <= ra + rb;
    r.pointOnA = pa;
    r.pointOnB = pb;
    return r;
}

}  // namespace

const char* nameOf(RectangleFeaturePair pair) {
    switch (pair) {
        case RectangleFeaturePair::EdgeEdge: return "EdgeEdge";
        case RectangleFeaturePair::VertexFace: return "VertexFace";
        case RectangleFeaturePair::FaceVertex: return "FaceVertex";
        case RectangleFeaturePair::EdgeCrossesB: return "EdgeCrossesB";
        case RectangleFeaturePair::EdgeCrossesA: return "EdgeCrossesA";
        case RectangleFeaturePair::Invalid: return "Invalid";
    }
    return "?";
}

RectangleDistanceResult distanceRectangleRectangle(const Rss& a, const Rss& b) {
    RectangleDistanceResult best;
    if (!validRectangle(a) || !validRectangle(b)) {
        best.distance = kNaN;
        best.pointOnA = best.pointOnB = Vec3::Constant(kNaN);
        return best;
    }
    const auto ca = corners(a), cb = corners(b);
    // An edge of one piercing the other: they cross, distance 0.
    Vec3 at;
    for (int i = 0; i < 4; ++i) {
        if (segmentPierces(ca[i], ca[(i + 1) % 4], b, at)) {
            return {0.0, at, at, RectangleFeaturePair::EdgeCrossesB, i, -1};
        }
        if (segmentPierces(cb[i], cb[(i + 1) % 4], a, at)) {
            return {0.0, at, at, RectangleFeaturePair::EdgeCrossesA, -1, i};
        }
    }
    double best2 = std::numeric_limits<double>::infinity();
    auto consider = [&](double d2, const Vec3& pa, const Vec3& pb, RectangleFeaturePair f, int fa, int fb) {
        if (d2 < best2) {
            best2 = d2;
            best = {0.0, pa, pb, f, fa, fb};
        }
    };
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const SegmentSegmentResult s =
                closestPointsSegmentSegment(Segment{ca[i], ca[(i + 1) % 4]}, Segment{cb[j], cb[(j + 1) % 4]});
            consider(s.distanceSquared, s.pointOnFirst, s.pointOnSecond, RectangleFeaturePair::EdgeEdge, i, j);
        }
    for (int i = 0; i < 4; ++i) {
        const Vec3 qb = closestOnRectangle(b, ca[i]);
        consider((ca[i] - qb).squaredNorm(), ca[i], qb, RectangleFeaturePair::VertexFace, i, -1);
        const Vec3 qa = closestOnRectangle(a, cb[i]);
        consider((cb[i] - qa).squaredNorm(), qa, cb[i], RectangleFeaturePair::FaceVertex, -1, i);
    }
    best.distance = std::sqrt(best2);
    return best;
}

SweptSphereOverlapResult testPssPss(const Sphere& a, const Sphere& b) {
    if (!a.center.allFinite() || !b.center.allFinite() || !(a.radius >= 0.0) || !(b.radius >= 0.0) ||
        !std::isfinite(a.radius) || !std::isfinite(b.radius))
        return invalidResult();
    return fromCoreDistance((b.center - a.center).norm(), a.radius, b.radius, a.center, b.center);
}

SweptSphereOverlapResult testLssLss(const Capsule& a, const Capsule& b) {
    if (!a.a.allFinite() || !a.b.allFinite() || !b.a.allFinite() || !b.b.allFinite() || !(a.radius >= 0.0) ||
        !(b.radius >= 0.0) || !std::isfinite(a.radius) || !std::isfinite(b.radius))
        return invalidResult();
    const SegmentSegmentResult s = closestPointsSegmentSegment(Segment{a.a, a.b}, Segment{b.a, b.b});
    return fromCoreDistance(std::sqrt(s.distanceSquared), a.radius, b.radius, s.pointOnFirst, s.pointOnSecond);
}

SweptSphereOverlapResult testRssRss(const Rss& a, const Rss& b) {
    if (!(a.radius >= 0.0) || !(b.radius >= 0.0) || !std::isfinite(a.radius) || !std::isfinite(b.radius))
        return invalidResult();
    const RectangleDistanceResult d = distanceRectangleRectangle(a, b);
    if (std::isnan(d.distance)) return invalidResult();
    return fromCoreDistance(d.distance, a.radius, b.radius, d.pointOnA, d.pointOnB);
}

}  // namespace cdlab
