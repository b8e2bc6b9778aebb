#include "core/query/feature_walk.h"

#include <cmath>
#include <utility>
#include <vector>

namespace cdlab {

WalkBody walkBodyOf(const QueryShape& s, int k) {
    using Kind = QueryShape::Kind;
    WalkBody out;
    if (s.kind != Kind::Polytope && s.kind != Kind::Aabb && s.kind != Kind::Obb) {
        out.status = WalkBody::Status::NotPolyhedron;
        return out;
    }
    std::vector<Vec3> points;
    points.reserve(s.vertices.size());
    const Vec3 origin = scaled(s.vertices.front(), k);
    out.pose.position = origin;
    for (const Vec3& v : s.vertices) points.push_back(scaled(v, k) - origin);
    const HullResult hull = convexHull(points);
    if (!hull.ok()) {
        out.status = WalkBody::Status::DegenerateHull;
        out.hullStatus = hull.status;
        out.message = hull.message;
        return out;
    }
    VClipBuild built = buildVClipPolyhedron(hull.polyhedron);
    if (!built.ok()) {
        out.status = WalkBody::Status::BuildFailed;
        out.message = built.message;
        return out;
    }
    out.polyhedron = std::move(built.polyhedron);
    return out;
}

namespace {

// The answer of either walk (VClipResult or LinCannyResult: the same fields), scaled back by 2^-k.
// A walk that ends at a distance within the touching rule reports touching, as every pair query does.
template <class Result>
void walkAnswer(const Result& r, int k, double touch, WalkPairResult& out) {
    const auto unscale = [k](double x) { return std::ldexp(x, -k); };
    if (r.intersect || r.distance <= touch) {  // the walk finds that the bodies meet, not a depth
        out.intersect = true;
        return;
    }
    out.distance = unscale(r.distance);
    out.pointA = r.pointA.unaryExpr(unscale);
    out.pointB = r.pointB.unaryExpr(unscale);
    out.normal = r.normal;
    if (!std::isfinite(out.distance) || !out.pointA.allFinite() || !out.pointB.allFinite()) out.status = PairStatus::Overflow;
}

}  // namespace

WalkPairResult walkPair(const WalkBody& a, const WalkBody& b, int k, double touch, bool linCanny, VClipTrace* vclipTrace,
                        LinCannyTrace* linCannyTrace) {
    WalkPairResult out;
    if (linCanny) {
        const LinCannyResult r = cdlab::linCanny(a.polyhedron, a.pose, b.polyhedron, b.pose, nullptr, {}, linCannyTrace);
        if (r.status != LinCannyStatus::Separated && r.status != LinCannyStatus::Penetrating) {
            out.status = PairStatus::InvalidInput;
            out.cycle = r.status == LinCannyStatus::CycleDetected;
            out.walkStatus = nameOf(r.status);
            out.message = r.message;
            return out;
        }
        walkAnswer(r, k, touch, out);
    } else {
        const VClipResult r = vclip(a.polyhedron, a.pose, b.polyhedron, b.pose, nullptr, {}, vclipTrace);
        if (r.status != VClipStatus::Separated && r.status != VClipStatus::Penetrating) {
            out.status = PairStatus::InvalidInput;
            out.walkStatus = nameOf(r.status);
            out.message = r.message;
            return out;
        }
        walkAnswer(r, k, touch, out);
    }
    return out;
}

}  // namespace cdlab
