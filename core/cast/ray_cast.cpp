#include "core/cast/ray_cast.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/base/accurate_cross.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "core/overlap/intersect_ray.h"

namespace cdlab {

const char* nameOf(CastFeature feature) {
    switch (feature) {
        case CastFeature::None: return "none";
        case CastFeature::Face: return "face";
        case CastFeature::Edge: return "edge";
        case CastFeature::Vertex: return "vertex";
    }
    return "?";
}

namespace {

// The core conv(P) as boundary pieces, indices into P. Faces are triangles (a hull face fanned);
// for a flat core they are two-sided.
struct CoreBoundary {
    int dimension = -1;
    std::vector<std::array<int, 3>> faces;
    std::vector<Vec3> faceNormals;  // unit; outward for dimension 3, one side of the plane for 2
    std::vector<std::array<int, 2>> edges;
    std::vector<int> vertices;
};

Vec3 unitNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = accurateCross(a, b, c);
    const double m = n.stableNorm();
    return m > 0 ? Vec3(n / m) : Vec3::Zero();
}

// Andrew's monotone chain (de Berg et al. §1.1) on the points projected to the plane of the flat
// core; returns the hull loop, counter-clockwise about n.
std::vector<int> planarHullLoop(std::span<const Vec3> p, const Vec3& origin, const Vec3& u, const Vec3& v) {
    std::vector<int> order(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) order[i] = int(i);
    const auto uv = [&](int i) { return std::array<double, 2>{u.dot(p[i] - origin), v.dot(p[i] - origin)}; };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return uv(a) < uv(b); });
    const auto turn = [&](int o, int a, int b) {
        const auto po = uv(o), pa = uv(a), pb = uv(b);
        return (pa[0] - po[0]) * (pb[1] - po[1]) - (pa[1] - po[1]) * (pb[0] - po[0]);
    };
    std::vector<int> loop(2 * order.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {  // lower chain
        while (k >= 2 && turn(loop[k - 2], loop[k - 1], order[i]) <= 0) --k;
        loop[k++] = order[i];
    }
    for (std::size_t i = order.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
        while (k >= lower && turn(loop[k - 2], loop[k - 1], order[i]) <= 0) --k;
        loop[k++] = order[i];
    }
    loop.resize(k > 1 ? k - 1 : k);
    return loop;
}

void addPolygon(CoreBoundary& core, const std::vector<int>& loop, std::span<const Vec3> p, const Vec3* normal) {
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
        core.faces.push_back({loop[0], loop[i], loop[i + 1]});
        core.faceNormals.push_back(normal ? *normal : unitNormal(p[loop[0]], p[loop[i]], p[loop[i + 1]]));
    }
}

CoreBoundary flatCore(std::span<const Vec3> p) {
    // The plane through p0, the point p1 farthest from it and the point p2 farthest from line p0p1.
    std::size_t i1 = 0, i2 = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if ((p[i] - p[0]).squaredNorm() > (p[i1] - p[0]).squaredNorm()) i1 = i;
    const Vec3 u = (p[i1] - p[0]).normalized();
    for (std::size_t i = 0; i < p.size(); ++i)
        if (u.cross(p[i] - p[0]).squaredNorm() > u.cross(p[i2] - p[0]).squaredNorm()) i2 = i;
    const Vec3 n = unitNormal(p[0], p[i1], p[i2]);
    CoreBoundary core;
    core.dimension = 2;
    const std::vector<int> loop = planarHullLoop(p, p[0], u, n.cross(u));
    addPolygon(core, loop, p, &n);
    for (std::size_t i = 0; i < loop.size(); ++i) core.edges.push_back({loop[i], loop[(i + 1) % loop.size()]});
    core.vertices = loop;
    return core;
}

CoreBoundary collinearCore(std::span<const Vec3> p) {
    std::size_t far = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if ((p[i] - p[0]).squaredNorm() > (p[far] - p[0]).squaredNorm()) far = i;
    const Vec3 axis = p[far] - p[0];
    int lo = 0, hi = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (axis.dot(p[i] - p[0]) < axis.dot(p[lo] - p[0])) lo = int(i);
        if (axis.dot(p[i] - p[0]) > axis.dot(p[hi] - p[0])) hi = int(i);
    }
    CoreBoundary core;
    core.dimension = 1;
    core.edges.push_back({lo, hi});
    core.vertices = {lo, hi};
    return core;
}

CoreBoundary coreBoundary(std::span<const Vec3> p) {
    HullOptions options;
    options.mergeCoplanarFaces = false;
    const HullResult hull = convexHull(p, options);
    switch (hull.status) {
        case HullStatus::Ok: break;
        case HullStatus::AllCoplanar: return flatCore(p);
        case HullStatus::AllCollinear: return collinearCore(p);
        case HullStatus::AllCoincident: {
            CoreBoundary core;
            core.dimension = 0;
            core.vertices = {0};
            return core;
        }
        default: return {};
    }
    const ConvexPolyhedron& poly = hull.polyhedron;
    CoreBoundary core;
    core.dimension = 3;
    for (int f = 0; f < poly.faceCount(); ++f) {
        std::vector<int> loop = poly.faceVertices(f);
        for (int& v : loop) v = hull.inputIndex[v];
        addPolygon(core, loop, p, nullptr);  // counter-clockwise from outside: outward normals
    }
    for (int e = 0; e < poly.edgeCount(); ++e) {
        const auto [a, b] = poly.edgeVertices(e);
        core.edges.push_back({hull.inputIndex[a], hull.inputIndex[b]});
    }
    for (int v = 0; v < poly.vertexCount(); ++v) core.vertices.push_back(hull.inputIndex[v]);
    return core;
}

// The roots of A t² + 2 B t + C = 0 in increasing order, computed without cancellation
// (Numerical Recipes §5.6), given its discriminant disc = B² − A C computed by the caller without
// cancellation; false when there are none.
bool quadraticRoots(double A, double B, double C, double disc, double& t0, double& t1) {
    if (!(A > 0) || !(disc >= 0)) return false;
    const double q = -(B + std::copysign(std::sqrt(disc), B));
    t0 = q / A;
    t1 = q != 0 ? C / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

// (b − a) × v with b − a taken exactly (core/base/accurate_cross.h): the plain product beyond the
// error-free split's range (~2^996).
Vec3 offsetCross(const Vec3& a, const Vec3& b, const Vec3& v) {
    const Vec3 w = accurateOffsetCross(a, b, v);
    return w.allFinite() ? w : Vec3((b - a).cross(v));
}

// First t >= 0 of the ray on the sphere |x − c| = r (Ericson §5.3.2). The discriminant
// B² − A C = |d|² r² − |e × d|² (Lagrange's identity; |e × d| / |d| is the line's distance from c,
// from the exact e): its error is relative to r², where B² − A C lost r² to the rounding of |e|²
// far from c (a unit sphere at 1e9 was hit at its centre; tests/core/cast/ray_cast_far_test.cpp).
bool raySphereSurface(const Ray& ray, const Vec3& c, double r, double& t) {
    const Vec3 e = ray.origin - c;
    const double A = ray.direction.squaredNorm();
    const double disc = A * (r * r) - offsetCross(c, ray.origin, ray.direction).squaredNorm();
    double t0, t1;
    if (!quadraticRoots(A, e.dot(ray.direction), e.squaredNorm() - r * r, disc, t0, t1)) return false;
    t = t0 >= 0 ? t0 : t1;
    return t >= 0;
}

// First t >= 0 of the ray on the side of the cylinder of radius r around segment ab (Ericson
// §5.3.7 without the caps, which the end spheres cover); s returns the axial weight of b.
// With L = b − a, P = L × (o − a) and Q = L × d (|P| / |L| is the origin's distance from the axis
// line, P + t Q the ray across it, scaled by |L|), the side is |P + t Q|² = |L|² r², divided by |L|²:
// A = |Q|² / |L|², B = P·Q / |L|², C = |P|² / |L|² − r², and (Lagrange, and (L × e) × (L × d) =
// [L, e, d] L) B² − A C = A r² − [L, e, d]² / |L|², the triple product [L, e, d] = L · (e × d)
// from the exact e = o − a. Its error is relative to r times the distance from the axis, where
// B² − A C lost r² to the rounding of |e⊥|² (and the projection e⊥ erred relative to the axial
// offset) far from the axis (tests/core/cast/ray_cast_far_test.cpp).
bool rayCylinderSide(const Ray& ray, const Vec3& a, const Vec3& b, double r, double& t, double& s) {
    const Vec3 axis = b - a;
    const double length2 = axis.squaredNorm();
    if (!(length2 > 0)) return false;
    const Vec3 e = ray.origin - a;
    const Vec3 P = -offsetCross(a, ray.origin, axis);  // axis × (o − a)
    const Vec3 Q = axis.cross(ray.direction);
    const double across = axis.dot(offsetCross(a, ray.origin, ray.direction)) / std::sqrt(length2);
    const double A = Q.squaredNorm() / length2;
    const double disc = A * (r * r) - across * across;
    double t0, t1;
    if (!quadraticRoots(A, P.dot(Q) / length2, P.squaredNorm() / length2 - r * r, disc, t0, t1)) return false;
    for (double root : {t0, t1}) {
        if (root < 0) continue;
        s = (e + root * ray.direction).dot(axis) / length2;
        if (s >= 0 && s <= 1) {
            t = root;
            return true;
        }
    }
    return false;
}

// A ray in the plane of a flat core enters through the polygon's rim: its normal there is the rim
// edge's outward normal in the plane, (b − a) × n for the counter-clockwise loop about n (among
// the edges through the entry point, the one facing the ray most squarely).
Vec3 rimNormal(const Ray& ray, std::span<const Vec3> p, const CoreBoundary& core, const Vec3& n, const Vec3& at) {
    Vec3 best = Vec3::Zero();
    double bestDistance = std::numeric_limits<double>::infinity(), bestFacing = 0;
    for (const auto& [i, j] : core.edges) {
        const Vec3 e = p[j] - p[i];
        const double s = std::clamp(e.dot(at - p[i]) / e.squaredNorm(), 0.0, 1.0);
        const double distance = (p[i] + s * e - at).norm();
        const Vec3 out = e.cross(n).normalized();
        const double facing = out.dot(ray.direction);
        const double tie = 1e-12 * (e.norm() + at.cwiseAbs().maxCoeff());
        if (distance < bestDistance - tie || (distance <= bestDistance + tie && facing < bestFacing))
            best = out, bestDistance = std::min(distance, bestDistance), bestFacing = facing;
    }
    return best;
}

struct Piece {
    ConvexCastCandidate where;
    Vec3 normal = Vec3::Zero();
    double weight[3] = {0.0, 0.0, 0.0};
};

// The pieces of ∂S the ray meets (step 2), the first one in `best`.
bool firstPiece(const Ray& ray, std::span<const Vec3> p, double r, const CoreBoundary& core, Piece& best,
                ConvexCastTrace* trace) {
    std::vector<Piece> met;
    const auto consider = [&](const Piece& piece) {
        if (trace) trace->candidates.push_back(piece.where);
        met.push_back(piece);
    };
    const int sides = core.dimension == 2 ? 2 : 1;  // a flat core's faces are pushed out on both sides
    for (std::size_t f = 0; f < core.faces.size(); ++f) {
        const auto [i, j, k] = core.faces[f];
        for (int side = 0; side < sides; ++side) {
            Vec3 n = side ? Vec3(-core.faceNormals[f]) : core.faceNormals[f];
            const Vec3 lift = r * n;
            const RayTriangleHit h = intersectRayTriangle(ray, Triangle{p[i] + lift, p[j] + lift, p[k] + lift});
            if (!h.hit) continue;
            if (r == 0 && sides == 2 && h.coplanar) n = rimNormal(ray, p, core, n, h.point);
            else if (r == 0 && sides == 2 && ray.direction.dot(n) > 0) n = -n;  // an unrounded flat face: facing the ray
            Piece piece{{CastFeature::Face, 3, {i, j, k}, h.t}, n, {h.barycentric[0], h.barycentric[1], h.barycentric[2]}};
            consider(piece);
            if (r == 0 && sides == 2) break;  // both sides are the same triangle
        }
    }
    if (r > 0) {
        for (const auto& [i, j] : core.edges) {
            double t, s;
            if (!rayCylinderSide(ray, p[i], p[j], r, t, s)) continue;
            const Vec3 axisPoint = p[i] + s * (p[j] - p[i]);
            const Vec3 n = (ray.origin + t * ray.direction - axisPoint).normalized();
            consider(Piece{{CastFeature::Edge, 2, {i, j, -1}, t}, n, {1 - s, s, 0.0}});
        }
        for (int i : core.vertices) {
            double t;
            if (!raySphereSurface(ray, p[i], r, t)) continue;
            const Vec3 n = (ray.origin + t * ray.direction - p[i]).normalized();
            consider(Piece{{CastFeature::Vertex, 1, {i, -1, -1}, t}, n, {1.0, 0.0, 0.0}});
        }
    }
    if (trace)
        std::sort(trace->candidates.begin(), trace->candidates.end(),
                  [](const ConvexCastCandidate& x, const ConvexCastCandidate& y) { return x.t < y.t; });
    if (met.empty()) return false;
    // Through an edge or a vertex several pieces are met at the same t up to rounding; each normal is
    // in the normal cone there, and the one facing the ray most squarely is the one the ray hits
    // (a ray sliding along a face and into the next gets the next face's normal, not the slid one).
    double tFirst = met[0].where.t;
    for (const Piece& p : met) tFirst = std::min(tFirst, p.where.t);
    const double window = 1e-12 * tFirst;  // ~4500 ulps: rounding of the piece tests, far below a feature
    const Vec3 d = ray.direction.normalized();
    const Piece* chosen = nullptr;
    for (const Piece& p : met)
        if (p.where.t <= tFirst + window && (!chosen || p.normal.dot(d) < chosen->normal.dot(d))) chosen = &p;
    best = *chosen;
    best.where.t = tFirst;
    return best.normal.allFinite() && best.normal.squaredNorm() > 0.5;
}

// Step 3: the normal of a hit that no piece saw. The closest points of the verdict give it when they
// are apart; touching, the face whose plane is nearest the hit point (a normal of the face or edge
// it grazes), or for a segment / point core the direction back along the ray, projected off the segment.
Vec3 fallbackNormal(const Ray& ray, const GjkResult& g, const Vec3& hitPoint, std::span<const Vec3> p,
                    const CoreBoundary& core) {
    if (g.distance > 0 && g.separatingAxis.squaredNorm() > 0.5) return -g.separatingAxis;
    Vec3 back = -ray.direction.normalized();
    if (core.dimension == 3 || core.dimension == 2) {
        int bestFace = -1;
        double bestSide = -std::numeric_limits<double>::infinity();
        for (std::size_t f = 0; f < core.faces.size(); ++f) {
            double side = core.faceNormals[f].dot(hitPoint - p[core.faces[f][0]]);
            if (core.dimension == 2) side = std::abs(side);
            if (side > bestSide) bestSide = side, bestFace = int(f);
        }
        if (bestFace >= 0) {
            const Vec3 n = core.faceNormals[bestFace];
            return core.dimension == 2 && n.dot(back) < 0 ? Vec3(-n) : n;
        }
    }
    if (core.dimension == 1) {
        const Vec3 axis = (p[core.edges[0][1]] - p[core.edges[0][0]]).normalized();
        const Vec3 off = back - back.dot(axis) * axis;
        if (off.squaredNorm() > 1e-24) return off.normalized();
    }
    return back;
}

// The parameters between which the ray can touch S: before `first` every point of S is still
// ahead of the ray point, after `last` every one is behind. The verdict tests only that piece of the
// ray: a segment as long as S is wide, so GJK's rounding is relative to S, not to a far origin (a
// segment from 1e9 through a unit box made GJK stop 0.7 short).
struct RayWindow {
    double first, last;
};
RayWindow rayWindow(const Ray& ray, std::span<const Vec3> p, double r) {
    const double dd = ray.direction.squaredNorm();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : p) {
        const double t = ray.direction.dot(v - ray.origin) / dd;
        lo = std::min(lo, t), hi = std::max(hi, t);
    }
    const double pad = r / std::sqrt(dd);
    lo -= pad, hi += pad;
    // Rounding of the projections: never cut a contact at either end.
    const double slack = ulps(64, std::max(std::abs(lo), std::abs(hi)));
    return {std::max(0.0, lo - slack), hi + slack};
}

bool validInput(const Ray& ray, std::span<const Vec3> points, double radius) {
    if (points.empty() || !(radius >= 0) || !std::isfinite(radius)) return false;
    if (!ray.origin.allFinite() || !ray.direction.allFinite() || ray.direction.isZero(0.0)) return false;
    return std::all_of(points.begin(), points.end(), [](const Vec3& v) { return v.allFinite(); });
}

}  // namespace

ConvexCastHit castRayRoundedHull(const Ray& ray, std::span<const Vec3> points, double radius,
                                 const ConvexCastOptions& options, ConvexCastTrace* trace) {
    ConvexCastHit out;
    if (!validInput(ray, points, radius) || !(options.maxT >= 0)) return out;
    const PolytopeShape shape(std::vector<Vec3>(points.begin(), points.end()));
    const double reach = radius + options.touchTolerance;

    // 1. The verdict: origin inside, then the ray segment that can hold the first contact.
    const GjkResult atOrigin = gjkDistance(PolytopeShape({ray.origin}), shape);
    if (atOrigin.status == GjkStatus::InvalidInput) return out;
    if (trace) trace->gap = atOrigin.distance - radius;
    if (atOrigin.distance <= reach) {
        out.hit = out.inside = true;
        out.point = ray.origin;
        return out;
    }
    const RayWindow window = rayWindow(ray, points, radius);
    const double tEnd = std::min(options.maxT, window.last);
    if (trace) trace->tEnd = tEnd;
    if (!(tEnd >= window.first)) return out;
    const GjkResult verdict = gjkDistance(PolytopeShape({ray.at(window.first), ray.at(tEnd)}), shape);
    if (trace) trace->gap = verdict.distance - radius;
    if (verdict.status == GjkStatus::InvalidInput || verdict.distance > reach) return out;
    out.hit = true;

    // 2. The first boundary piece the ray meets.
    const CoreBoundary core = coreBoundary(points);
    if (trace) trace->coreDimension = core.dimension, trace->coreVertices = int(core.vertices.size());
    Piece first;
    if (firstPiece(ray, points, radius, core, first, trace) && first.where.t <= tEnd) {
        out.t = first.where.t;
        out.normal = first.normal;
        out.feature = first.where.feature;
        out.count = first.where.count;
        for (int i = 0; i < 3; ++i) out.index[i] = first.where.index[i], out.weight[i] = first.weight[i];
        out.point = ray.at(out.t);
        return out;
    }

    // 3. A graze below rounding, or a segment / point core: the verdict's closest point on the ray.
    const double dd = ray.direction.squaredNorm();
    double t = std::clamp(ray.direction.dot(verdict.pointA - ray.origin) / dd, window.first, tEnd);
    // A polytope core (radius 0, a face or solid core): the piece tests are exact, so no piece met
    // means the ray never goes in, only comes within the touch tolerance, and it may do so over a whole
    // stretch: a ray sliding along a face within rounding. The verdict's common point is any point of
    // that stretch, not its start (t = 0.494 for a first touch at 0.4327;
    // tests/core/cast/time_of_impact_scale_test.cpp). The t within reach are an interval (the distance
    // is convex along the ray): bisect down to its start, between window.first and a t within reach.
    // (Rounded cores keep the verdict's point: their quadratic tests can miss a real crossing by
    // rounding, where the verdict's point is a good one and reach would move it early.)
    if (radius == 0 && core.dimension >= 2 && t > window.first) {
        const auto within = [&](double s) { return gjkDistance(PolytopeShape({ray.at(s)}), shape).distance <= reach; };
        if (within(t)) {
            double lo = window.first, hi = t;
            if (within(lo)) hi = lo;
            for (int i = 0; i < 1100; ++i) {
                const double mid = lo + 0.5 * (hi - lo);
                if (!(mid > lo && mid < hi)) break;
                (within(mid) ? hi : lo) = mid;
            }
            t = hi;
        }
    }
    if (core.dimension == 1 && radius == 0) {
        // A ray along the segment meets it first at its nearer end, not where GJK's common point is.
        const Vec3 a = points[core.edges[0][0]], b = points[core.edges[0][1]];
        const Vec3 axis = b - a;
        if (axis.cross(ray.direction).squaredNorm() <= 1e-24 * axis.squaredNorm() * dd)
            t = std::clamp(std::min(ray.direction.dot(a - ray.origin), ray.direction.dot(b - ray.origin)) / dd, 0.0, tEnd);
    }
    out.t = t;
    out.point = ray.at(t);
    out.normal = fallbackNormal(ray, verdict, out.point, points, core);
    return out;
}

}  // namespace cdlab
