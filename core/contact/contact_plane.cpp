#include "core/contact/contact_plane.h"

#include "core/base/tolerances.h"
#include "core/contact/contact_stages.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace cdlab {

const char* nameOf(PlaneContactStatus status) {
    switch (status) {
        case PlaneContactStatus::Separated: return "Separated";
        case PlaneContactStatus::Touching: return "Touching";
        case PlaneContactStatus::Penetrating: return "Penetrating";
        case PlaneContactStatus::InvalidInput: return "InvalidInput";
    }
    return "InvalidInput";
}

namespace {

bool adjacent(const ConvexPolyhedron& body, int u, int v, int& edge) {
    bool found = false;
    body.forEachVertexHalfEdge(u, [&](int h) {
        if (!found && body.halfEdgeDestination(h) == v) {
            found = true;
            edge = body.halfEdge(h).edge;
        }
    });
    return found;
}

// 2D cross product of (a - o) and (b - o) in the plane basis.
double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain (Andrew 1979; de Berg et al. §1.1): indices of the strict convex hull,
// counter-clockwise. Collinear and duplicate points are dropped; 1 or 2 points come back as is.
std::vector<int> hull2d(const std::vector<Vec2>& p) {
    const int n = static_cast<int>(p.size());
    std::vector<int> idx(n);
    for (int i = 0; i < n; ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(), [&](int a, int b) {
        return p[a].x() < p[b].x() ||
               (p[a].x() == p[b].x() && (p[a].y() < p[b].y() || (p[a].y() == p[b].y() && a < b)));
    });
    idx.erase(std::unique(idx.begin(), idx.end(), [&](int a, int b) { return p[a] == p[b]; }), idx.end());
    if (idx.size() <= 2) return idx;
    std::vector<int> h(2 * idx.size());
    int k = 0;
    for (int i : idx) {  // lower chain
        while (k >= 2 && cross2(p[h[k - 2]], p[h[k - 1]], p[i]) <= 0) --k;
        h[k++] = i;
    }
    const int lower = k + 1;
    for (int j = static_cast<int>(idx.size()) - 2; j >= 0; --j) {  // upper chain
        const int i = idx[j];
        while (k >= lower && cross2(p[h[k - 2]], p[h[k - 1]], p[i]) <= 0) --k;
        h[k++] = i;
    }
    h.resize(k - 1);  // the last point repeats the first
    return h;
}

// The body in world space: vertices x_i and their signed plane distances s_i, the lowest one.
struct PosedVertices {
    std::vector<Vec3> x;
    std::vector<double> s;
    int low = 0;
};

// Closest / deepest feature: the vertices within tol of s_min (returned), as a vertex, an edge or
// the face of the support set of -n̂.
std::vector<int> closestFeature(const ConvexPolyhedron& body, const Transform& pose, const Vec3& n,
                                const PosedVertices& pv, double tol, PlaneContactResult& r) {
    const std::vector<Vec3>& x = pv.x;
    const std::vector<double>& s = pv.s;
    const int nv = static_cast<int>(x.size());
    const int low = pv.low;
    std::vector<int> near;
    for (int i = 0; i < nv; ++i)
        if (s[i] <= s[low] + tol) near.push_back(i);
    const auto inNear = [&](int v) { return std::find(near.begin(), near.end(), v) != near.end(); };
    int edge = -1;
    if (near.size() == 1) {
        r.feature = {FeatureType::Vertex, low};
        r.featurePoints = {x[low]};
    } else if (near.size() == 2 && adjacent(body, near[0], near[1], edge)) {
        r.feature = {FeatureType::Edge, edge};
        r.featurePoints = {x[near[0]], x[near[1]]};
    } else {
        // The support set of -n̂ is a face: one around the lowest vertex holds every near vertex.
        // If tolerance noise leaves none holding all (e.g. two opposite vertices of a nearly
        // face-on quad), take the face around it whose normal is most opposite n̂.
        int face = -1, fallback = -1;
        double bestAlign = INFINITY;
        for (int f : body.vertexFaces(low)) {
            const std::vector<int> fv = body.faceVertices(f);
            int held = 0;
            for (int v : near) held += std::find(fv.begin(), fv.end(), v) != fv.end();
            if (held == static_cast<int>(near.size()) && face < 0) face = f;
            const double align = pose.rotate(body.face(f).normal).dot(n);
            if (align < bestAlign) bestAlign = align, fallback = f;
        }
        if (face < 0) face = fallback;
        r.feature = {FeatureType::Face, face};
        for (int v : body.faceVertices(face))
            if (inNear(v)) r.featurePoints.push_back(x[v]);
    }
    return near;
}

// Contact candidates: submerged (s_i <= tol) vertices and the edge crossings, each with its
// projection on the plane and its depth; candVertex names the vertex (-1 for a crossing).
void contactCandidates(const ConvexPolyhedron& body, const Vec3& n, double d, const PosedVertices& pv, double tol,
                       std::vector<ContactPoint>& cand, std::vector<int>& candVertex, PlaneContactTrace* trace) {
    const std::vector<Vec3>& x = pv.x;
    const std::vector<double>& s = pv.s;
    const int nv = static_cast<int>(x.size());
    for (int i = 0; i < nv; ++i) {
        if (s[i] > tol) continue;
        cand.push_back({x[i], x[i] - s[i] * n, std::max(0.0, -s[i])});
        candVertex.push_back(i);
    }
    for (int e = 0; e < body.edgeCount(); ++e) {
        auto [u, v] = body.edgeVertices(e);
        if (s[u] > s[v]) std::swap(u, v);
        if (!(s[u] < -tol && s[v] > tol)) continue;
        // s(t) = s_u + t (s_v - s_u) = 0; both sides are beyond tol, so the division is safe.
        const double t = s[u] / (s[u] - s[v]);
        const Vec3 p = x[u] + t * (x[v] - x[u]);
        cand.push_back({p, p - (n.dot(p) - d) * n, 0.0});
        candVertex.push_back(-1);
        if (trace) trace->crossings.push_back({e, u, v, t, p});
    }
}

// The contact polygon (2D hull of the candidates on the plane) and the manifold: every candidate
// reduced to options.maxPoints, or the hull plus the deepest point. Returns the hull.
std::vector<int> contactManifold(const std::vector<ContactPoint>& cand, const Vec3& n,
                                 const PlaneContactOptions& options, PlaneContactResult& r,
                                 std::vector<ManifoldReductionStep>& steps, bool traced) {
    // Plane basis (u, w) with u x w = n̂, coordinates relative to the deepest projection (small
    // numbers at large offsets).
    const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
    std::vector<Vec2> p2(cand.size());
    const Vec3 origin = cand.empty() ? Vec3::Zero() : cand[0].pointB;
    for (size_t i = 0; i < cand.size(); ++i) {
        const Vec3 q = cand[i].pointB - origin;
        p2[i] = Vec2(u.dot(q), w.dot(q));
    }
    const std::vector<int> hull = hull2d(p2);
    for (int i : hull) r.polygon.push_back(cand[i]);

    // Reduction over every candidate, not just the hull: the deepest point may project inside
    // the footprint (a corner pushed into the ground between its edge crossings) and must be kept.
    int deepest = 0;
    for (size_t i = 1; i < cand.size(); ++i)
        if (cand[i].depth > cand[deepest].depth) deepest = static_cast<int>(i);
    if (options.maxPoints > 0 || hull.size() >= size_t(kMaxContactPoints)) {
        for (int i : reduceContactPolygon(cand, n, options.maxPoints, traced ? &steps : nullptr))
            r.manifold.push_back(cand[i]);
    } else {
        for (int i : hull) r.manifold.push_back(cand[i]);
        if (std::find(hull.begin(), hull.end(), deepest) == hull.end()) r.manifold.push_back(cand[deepest]);
    }

    return hull;
}

}  // namespace

bool intersectPolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane) {
    const double s = signedDistancePolyhedronPlane(body, pose, plane);
    return s <= 0.0;  // NaN: false
}

bool intersectPolytopePlane(const PolytopeShape& body, const Transform& pose, const Plane& plane, int* hint) {
    Vec3 n;
    double d;
    if (body.vertexCount() == 0 || *detail::unitPlane(plane, n, d) || *detail::poseProblem(pose)) return false;
    const Vec3 dir = pose.rotateInverse(-n);  // body-frame direction of the lowest point
    const int i = hint ? body.supportIndex(dir, *hint) : body.supportIndex(dir);
    if (hint) *hint = i;
    return n.dot(pose.apply(body.vertex(i))) - d <= 0.0;
}

double signedDistancePolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane) {
    Vec3 n;
    double d;
    if (body.empty() || *detail::unitPlane(plane, n, d) || *detail::poseProblem(pose)) return NAN;
    double s = INFINITY;
    for (const auto& v : body.vertices()) s = std::min(s, n.dot(pose.apply(v.position)) - d);
    return s;
}

PlaneContactResult contactPolyhedronPlane(const ConvexPolyhedron& body, const Transform& pose, const Plane& plane,
                                          const PlaneContactOptions& options, PlaneContactTrace* trace) {
    PlaneContactResult r;
    Vec3 n;
    double d = 0.0;
    r.message = body.empty() ? "empty polyhedron" : detail::unitPlane(plane, n, d);
    if (r.message.empty()) r.message = detail::poseProblem(pose);
    if (r.message.empty() && options.tolerance && !std::isfinite(*options.tolerance))
        r.message = "tolerance is not finite";
    if (!r.message.empty()) {
        r.status = PlaneContactStatus::InvalidInput;
        r.signedDistance = NAN;
        return r;
    }
    r.normal = -n;

    // Signed vertex distances s_i.
    const int nv = body.vertexCount();
    PosedVertices pv{std::vector<Vec3>(nv), std::vector<double>(nv), 0};
    double maxCoord = std::abs(d);
    for (int i = 0; i < nv; ++i) {
        pv.x[i] = pose.apply(body.position(i));
        pv.s[i] = n.dot(pv.x[i]) - d;
        maxCoord = std::max(maxCoord, pv.x[i].cwiseAbs().maxCoeff());
        if (pv.s[i] < pv.s[pv.low]) pv.low = i;
    }
    // Tolerance: the caller's, else relative to the size plus 64 ulps of the coordinates (s_i is
    // n̂ · x - d̂ rounded: ~4 ulps of |x| + |d|; the margin keeps coplanar vertices of a face-on
    // body together at offsets 1e6 x its size).
    const double diag = (body.boundsMax() - body.boundsMin()).norm();
    r.tolerance = options.tolerance && *options.tolerance >= 0.0
                      ? *options.tolerance
                      : options.relativeTolerance * diag + ulps(64, maxCoord);
    const double tol = r.tolerance;
    const double sLow = pv.s[pv.low];
    r.deepestVertex = pv.low;
    r.signedDistance = sLow;
    r.depth = std::max(0.0, -sLow);
    r.status = sLow > tol     ? PlaneContactStatus::Separated
               : sLow >= -tol ? PlaneContactStatus::Touching
                              : PlaneContactStatus::Penetrating;

    const std::vector<int> near = closestFeature(body, pose, n, pv, tol, r);
    for (const Vec3& p : r.featurePoints) r.featurePointsOnPlane.push_back(p - (n.dot(p) - d) * n);
    if (trace) {
        *trace = PlaneContactTrace{};
        trace->unitNormal = n;
        trace->unitOffset = d;
        trace->worldVertices = pv.x;
        trace->vertexDistances = pv.s;
        trace->featureVertices = near;
    }
    if (!r.colliding()) return r;

    std::vector<ContactPoint> cand;
    std::vector<int> candVertex;
    contactCandidates(body, n, d, pv, tol, cand, candVertex, trace);
    std::vector<ManifoldReductionStep> steps;
    const std::vector<int> hull = contactManifold(cand, n, options, r, steps, trace != nullptr);
    if (trace) {
        trace->candidates = cand;
        trace->candidateVertex = candVertex;
        trace->hull = hull;
        trace->reduction = steps;
    }
    return r;
}

}  // namespace cdlab
