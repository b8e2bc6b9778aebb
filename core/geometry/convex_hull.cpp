#include "core/geometry/convex_hull.h"

#include "core/base/tolerances.h"
#include "core/geometry/convex_hull_internal.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <unordered_set>

namespace cdlab {

namespace {

using hull_internal::AliveTriangles;
using hull_internal::aliveTriangles;
using hull_internal::FaceGroups;
using hull_internal::facePolygons;
using hull_internal::FacePolygons;
using hull_internal::groupCoplanar;
using hull_internal::mergeFolds;
using hull_internal::removeCollinear;
using hull_internal::Tri;

std::string fmtNumber(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// splitmix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014):
// same sequence on every platform, unlike std::shuffle + std:: distributions.
std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Frame of the explicit depth-first search over visible triangles (Lloyd's quickhull3d
// "calculateHorizon", iterative to survive very large visible regions).
struct DfsFrame {
    int face;
    int firstEdge;  // edge the search entered through (root: 0)
    int k;          // next offset to examine (root starts at 0, others at 1: skip the entry edge)
};

// Cone triangles whose apex is closer than kThin * eps to their base edge are not built (see insert).
// 4: at 1 the tilt error of such slivers reaches 1 rad and noise of 2-3 eps broke convexity.
constexpr double kThin = 4.0;

class HullBuilder {
public:
    HullBuilder(const std::vector<Vec3>& local, std::span<const Vec3> original, double eps, HullTrace* trace)
        : P_(local), original_(original), eps_(eps), trace_(trace) {
        pointFaces_.resize(P_.size());
        tris_.reserve(8 + 4 * P_.size());  // ~2 live + ~2 dead faces per inserted point on average
        done_.assign(P_.size(), 0);
        pointMark_.assign(P_.size(), -1);
        vertexStamp_.assign(P_.size(), -1);
    }

    double dist(int q, int f) const { return tris_[f].n.dot(P_[q]) - tris_[f].d; }

    void setPlane(Tri& t) const {
        const Vec3& a = P_[t.v[0]];
        const Vec3& b = P_[t.v[1]];
        const Vec3& c = P_[t.v[2]];
        const Vec3 n = accurateCross(a, b, c);  // slivers too get an accurate plane
        const double len = n.norm();
        // A new cone triangle has its apex > eps above the visible face it replaces, so it never
        // has zero area; the guard only keeps NaN out of the planes.
        t.n = len > 0.0 ? Vec3(n / len) : Vec3::UnitZ();
        t.d = t.n.dot((a + b + c) / 3.0);
    }

    Triangle triangleOf(int f) const {
        const Tri& t = tris_[f];
        return Triangle{original_[t.v[0]], original_[t.v[1]], original_[t.v[2]]};
    }

    void buildTetrahedron(const std::array<int, 4>& ids) {
        static const int kFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
        for (const auto& f : kFaces) {
            Tri t;
            t.v = {ids[f[0]], ids[f[1]], ids[f[2]]};
            setPlane(t);
            tris_.push_back(std::move(t));
        }
        for (int f = 0; f < 4; ++f) {
            for (int k = 0; k < 3; ++k) {
                const int a = tris_[f].v[k], b = tris_[f].v[(k + 1) % 3];
                for (int g = 0; g < 4; ++g) {
                    for (int j = 0; j < 3; ++j) {
                        if (tris_[g].v[j] == b && tris_[g].v[(j + 1) % 3] == a) tris_[f].adj[k] = g;
                    }
                }
            }
        }
        for (int i : ids) done_[i] = 1;
        interior_ = (P_[ids[0]] + P_[ids[1]] + P_[ids[2]] + P_[ids[3]]) / 4.0;
        for (int q = 0; q < static_cast<int>(P_.size()); ++q) {
            if (done_[q]) continue;
            for (int f = 0; f < 4; ++f) {
                if (dist(q, f) > eps_) {
                    tris_[f].conflicts.push_back(q);
                    pointFaces_[q].push_back(f);
                }
            }
        }
        aliveCount_ = 4;
        if (trace_) {
            trace_->initialIndices = ids;
            for (int f = 0; f < 4; ++f) trace_->initialFaces.push_back({f, triangleOf(f)});
        }
    }

    // Depth-first search of the faces r sees (by more than eps, or forced), from the eye face;
    // fills visible_ and the ordered horizon_ (Lloyd's quickhull3d "calculateHorizon", iterative).
    void findVisibleRegion(int r, int eye) {
        ++stamp_;
        faceStamp_.resize(tris_.size(), -1);
        visible_.clear();
        horizon_.clear();
        stack_.clear();
        faceStamp_[eye] = stamp_;
        visible_.push_back(eye);
        stack_.push_back({eye, 0, 0});
        while (!stack_.empty()) {
            DfsFrame& top = stack_.back();
            if (top.k == 3) {
                stack_.pop_back();
                continue;
            }
            const int f = top.face;
            const int e = (top.firstEdge + top.k) % 3;
            ++top.k;
            const int g = tris_[f].adj[e];
            if (faceStamp_[g] == stamp_) continue;  // already in the visible region
            if (forceMark_[g] == forceStamp_ || dist(r, g) > eps_) {
                faceStamp_[g] = stamp_;
                visible_.push_back(g);
                int back = 0;
                while (tris_[g].adj[back] != f || tris_[g].v[back] != tris_[f].v[(e + 1) % 3]) ++back;
                stack_.push_back({g, back, 1});  // invalidates `top`; not used below
            } else {
                horizon_.push_back({f, e});
            }
        }
    }

    // Inserts point r if it is outside the current hull by more than eps (de Berg §11.2): the
    // faces r sees, their horizon, and a cone of new faces from the horizon to r.
    void insert(int r) {
        double eyeDist = eps_;
        const int eye = eyeFace(r, eyeDist);
        std::vector<int>().swap(pointFaces_[r]);
        done_[r] = 1;
        if (eye < 0) return;  // inside or within eps of the hull: not a vertex
        const bool forcedAny = findVisibleRegionWithoutFolds(r, eye);
        const bool simple = horizonIsSimpleLoop();
        HullTraceStep* step = recordStep(r, eye, eyeDist);
        if (!simple) {
            ++dropped_;
            if (step) {
                step->skipped = true;
                step->visibleFaceIds.clear();
                step->hullFaceCount = aliveCount_;
            }
            return;
        }
        buildCone(r, forcedAny, step);
    }

    const std::vector<Tri>& tris() const { return tris_; }
    int dropped() const { return dropped_; }

private:
    // Eye face: the farthest alive conflict face of r by more than eyeDist (-1 when none).
    int eyeFace(int r, double& eyeDist) const {
        // Eye face: the farthest alive conflict face.
        int eye = -1;
        for (int f : pointFaces_[r]) {
            if (!tris_[f].alive) continue;
            const double dd = dist(r, f);
            if (dd > eyeDist) {
                eyeDist = dd;
                eye = f;
            }
        }
        return eye;
    }

    // Visible region: depth-first from the eye face over neighbours r sees by more than eps.
    // The depth-first order emits the horizon edges as a loop (each starts where the last ended).
    // Each cone triangle (a, b, r) must be convex with the kept neighbour g across a -> b: g's
    // third vertex c behind the triangle's plane. In exact arithmetic that follows from r being
    // behind g; when r is in front of g by at most eps (g not "visible"), a thin cone triangle
    // can fold under g with c far in front of it. Such neighbours are deleted too ("forced",
    // r is coplanar with them within eps) and the region is searched again; each round forces
    // at least one more face, so this terminates.
    // Returns whether any face was forced.
    bool findVisibleRegionWithoutFolds(int r, int eye) {
        ++forceStamp_;
        forceMark_.resize(tris_.size(), -1);
        bool forcedAny = false;
        for (;;) {
            findVisibleRegion(r, eye);
            bool retry = false;
            for (const auto& [f1, e] : horizon_) {
                const Tri& t = tris_[f1];
                const int ia = t.v[e], ib = t.v[(e + 1) % 3];
                const Tri& g = tris_[t.adj[e]];
                int c = g.v[0];
                for (int j = 0; j < 3; ++j) {
                    if (g.v[j] != ia && g.v[j] != ib) c = g.v[j];
                }
                const Vec3 n = accurateCross(P_[ia], P_[ib], P_[r]);
                const double len = n.norm();
                // Flat fold: r within eps of g's plane and on g's side of the line ab (the cone
                // triangle would overlap g, flipped). Steep fold: c in front of the cone triangle.
                // A thin cone triangle (r within kThin * eps of the line ab, so also of g's plane)
                // has a plane whose tilt is only known to ~eps / (distance of r from ab): a hull
                // that is eps-accurate would show up as vertices far in front of it. Force g.
                const Vec3 intoG = g.n.cross(P_[ia] - P_[ib]);  // in g's plane, from edge b -> a into g
                const bool flatFold = g.n.dot(P_[r]) - g.d >= -eps_ && intoG.dot(P_[r] - P_[ib]) > 0.0;
                const bool degenerate = !(len > kThin * eps_ * (P_[ib] - P_[ia]).norm());
                // Inside-out: the centroid of the initial tetrahedron is interior to every hull
                // (by at least the tetrahedron's inradius), so it must be behind every face. This
                // catches flat folds where r is more than eps behind g (input noise a few eps).
                const bool insideOut = !(n.dot(interior_ - P_[ia]) < 0.0);
                if (degenerate || flatFold || insideOut || n.dot(P_[c] - P_[ia]) / len > eps_) {
                    forceMark_[t.adj[e]] = forceStamp_;
                    retry = true;
                }
            }
            if (!retry) break;
            forcedAny = true;
        }

        return forcedAny;
    }

    // The horizon must be one simple loop. With tolerances a point within a few eps of the
    // hull can see a region with a hole or a pinch; such a point is dropped (the hull stays
    // valid and the point stays within a few eps of it).
    bool horizonIsSimpleLoop() {
        const int m = static_cast<int>(horizon_.size());
        bool simple = m >= 3;
        for (int i = 0; simple && i < m; ++i) {
            const Tri& t = tris_[horizon_[i].first];
            const Tri& u = tris_[horizon_[(i + 1) % m].first];
            const int a = t.v[horizon_[i].second];
            const int b = t.v[(horizon_[i].second + 1) % 3];
            if (b != u.v[horizon_[(i + 1) % m].second] || vertexStamp_[a] == stamp_) simple = false;
            vertexStamp_[a] = stamp_;
        }
        return simple;
    }

    // The trace step of inserting r (null without a trace).
    HullTraceStep* recordStep(int r, int eye, double eyeDist) {
        HullTraceStep* step = nullptr;
        if (trace_) {
            trace_->steps.emplace_back();
            step = &trace_->steps.back();
            step->pointIndex = r;
            step->point = original_[r];
            step->eyeFaceId = eye;
            step->eyeDistance = eyeDist;
            step->visibleFaceIds = visible_;
            for (const auto& [f, e] : horizon_) {
                step->horizon.push_back(Segment{original_[tris_[f].v[e]], original_[tris_[f].v[(e + 1) % 3]]});
            }
        }
        return step;
    }

    // Cone of new triangles (a, b, r), one per horizon edge a -> b, with their conflict lists;
    // the visible faces die.
    void buildCone(int r, bool forcedAny, HullTraceStep* step) {
        const int m = static_cast<int>(horizon_.size());
        const int base = static_cast<int>(tris_.size());
        pooled_.clear();
        if (forcedAny) {
            for (int f : visible_) {
                for (int q : tris_[f].conflicts) {
                    if (done_[q] || pointMark_[q] == -2 - r) continue;
                    pointMark_[q] = -2 - r;  // distinct from every face id
                    pooled_.push_back(q);
                }
            }
        }
        for (int i = 0; i < m; ++i) {
            const auto [f1, e] = horizon_[i];
            const int a = tris_[f1].v[e], b = tris_[f1].v[(e + 1) % 3];
            const int g = tris_[f1].adj[e];
            Tri t;
            t.v = {a, b, r};
            t.adj = {g, base + (i + 1) % m, base + (i + m - 1) % m};
            setPlane(t);
            for (int j = 0; j < 3; ++j) {
                if (tris_[g].v[j] == b && tris_[g].v[(j + 1) % 3] == a) tris_[g].adj[j] = base + i;
            }
            // Conflicts of the new face: only points that saw f1 or g can see it (de Berg lemma 11.6).
            // With forced (coplanar, not strictly visible) faces the lemma's premise fails, so then
            // every point that saw any deleted face is a candidate.
            const int id = base + i;
            // g survives: drop its points that were inserted or discarded meanwhile (lazy deletion),
            // or its list would be rescanned for every cone built against it.
            std::vector<int>& keep = tris_[g].conflicts;
            keep.erase(std::remove_if(keep.begin(), keep.end(), [&](int q) { return done_[q] != 0; }), keep.end());
            for (const std::vector<int>* src : {forcedAny ? &pooled_ : &tris_[f1].conflicts, &keep}) {
                for (int q : *src) {
                    if (done_[q] || pointMark_[q] == id) continue;
                    pointMark_[q] = id;
                    if (t.n.dot(P_[q]) - t.d > eps_) {
                        t.conflicts.push_back(q);
                        pointFaces_[q].push_back(id);
                    }
                }
            }
            tris_.push_back(std::move(t));
        }
        for (int f : visible_) {
            tris_[f].alive = false;
            std::vector<int>().swap(tris_[f].conflicts);
        }
        aliveCount_ += m - static_cast<int>(visible_.size());
        if (step) {
            for (int i = 0; i < m; ++i) step->newFaces.push_back({base + i, triangleOf(base + i)});
            step->hullFaceCount = aliveCount_;
        }
    }

    const std::vector<Vec3>& P_;
    std::span<const Vec3> original_;
    double eps_;
    HullTrace* trace_;
    std::vector<Tri> tris_;
    std::vector<std::vector<int>> pointFaces_;  // faces each point sees (may hold dead faces)
    std::vector<char> done_;                    // inserted, dropped, or part of the tetrahedron
    std::vector<int> pointMark_;                // dedup of candidate points per new face
    std::vector<int> vertexStamp_;              // horizon simplicity check
    std::vector<int> faceStamp_;                // visible-region membership
    std::vector<int> forceMark_;                // faces forced into the visible region
    int stamp_ = 0;
    int forceStamp_ = 0;
    int aliveCount_ = 0;
    int dropped_ = 0;
    std::vector<int> visible_;
    std::vector<std::pair<int, int>> horizon_;  // (visible face, edge index)
    std::vector<DfsFrame> stack_;
    std::vector<int> pooled_;       // conflicts of all deleted faces, when some were forced
    Vec3 interior_ = Vec3::Zero();  // centroid of the initial tetrahedron: inside every later hull
};

HullResult failure(HullStatus status, std::string message, int badIndex = -1) {
    HullResult r;
    r.status = status;
    r.message = std::move(message);
    r.badIndex = badIndex;
    return r;
}

// The input's frame: the tolerance eps (see the header), the merge tolerance and the points
// centred on their bounding box (centred coordinates keep the cross products small).
struct HullFrame {
    double eps = 0.0;
    double mergeTol = 0.0;
    std::vector<Vec3> P;
};

HullFrame hullFrame(std::span<const Vec3> points, const HullOptions& options) {
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double maxAbs = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    const double diagonal = (hi - lo).norm();
    HullFrame frame;
    frame.eps = options.absoluteEpsilon && *options.absoluteEpsilon > 0.0
                    ? *options.absoluteEpsilon
                    : options.epsilonFactor * kMachineEpsilon * (maxAbs + diagonal);
    frame.mergeTol = options.mergeFactor * frame.eps;
    const Vec3 center = 0.5 * (lo + hi);
    frame.P.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) frame.P[i] = points[i] - center;
    return frame;
}

// The initial tetrahedron from extreme points (i0 leftmost, i1 farthest from it, i2 farthest
// from their line, i3 farthest from their plane), oriented so that i3 is behind the plane of
// (i0, i1, i2); or the failure that says which degenerate input this is.
struct InitialTetrahedron {
    std::array<int, 4> vertex{};
    std::optional<HullResult> failure;
};

InitialTetrahedron initialTetrahedron(const std::vector<Vec3>& P, double eps) {
    const int n = static_cast<int>(P.size());
    InitialTetrahedron tet;
    int i0 = 0;
    for (int i = 1; i < n; ++i)
        if (P[i].x() < P[i0].x()) i0 = i;
    int i1 = i0;
    double best = 0.0;
    for (int i = 0; i < n; ++i) {
        const double d2 = (P[i] - P[i0]).squaredNorm();
        if (d2 > best) {
            best = d2;
            i1 = i;
        }
    }
    if (!(std::sqrt(best) > eps)) {
        tet.failure = failure(HullStatus::AllCoincident,
                              "all " + std::to_string(n) + " points coincide within eps = " + fmtNumber(eps));
        return tet;
    }
    const Vec3 u = (P[i1] - P[i0]).normalized();
    int i2 = i0;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1) continue;                       // rounding must never pick a chosen point again
        const double d2 = u.cross(P[i] - P[i0]).squaredNorm();  // squared distance from line p0 p1
        if (d2 > best) {
            best = d2;
            i2 = i;
        }
    }
    if (!(std::sqrt(best) > eps)) {
        tet.failure = failure(HullStatus::AllCollinear,
                              "all " + std::to_string(n) + " points lie on one line within eps = " + fmtNumber(eps));
        return tet;
    }
    // The plane of a needle triangle (p2 barely off the line p0 p1) is ill-conditioned: the plain
    // cross product's direction error is DBL_EPSILON * |p1 - p0| / dist(p2, line), enough to make
    // p2 itself look farthest from its own plane (found by `cdlab stress`, slivers and needles).
    // accurateCross is the exact cross product rounded, so the normal is right to ~DBL_EPSILON.
    const Vec3 nrm = accurateCross(P[i0], P[i1], P[i2]).normalized();
    int i3 = i0;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1 || i == i2) continue;
        const double d = std::abs(nrm.dot(P[i] - P[i0]));
        if (d > best) {
            best = d;
            i3 = i;
        }
    }
    if (!(best > eps)) {
        tet.failure = failure(HullStatus::AllCoplanar,
                              "all " + std::to_string(n) + " points lie in one plane within eps = " + fmtNumber(eps));
        return tet;
    }
    // Orient so that p3 is behind the plane of (p0, p1, p2) with its right-hand normal.
    if (nrm.dot(P[i3] - P[i0]) > 0.0) std::swap(i1, i2);

    tet.vertex = {i0, i1, i2, i3};
    return tet;
}

// Insertion order of the points not in the tetrahedron: input order, or a seeded shuffle.
std::vector<int> insertionOrder(int n, const std::array<int, 4>& tet, const HullOptions& options) {
    std::vector<int> order;
    order.reserve(n);
    for (int i = 0; i < n; ++i) {
        if (i != tet[0] && i != tet[1] && i != tet[2] && i != tet[3]) order.push_back(i);
    }
    if (options.shuffle) {
        std::uint64_t state = options.shuffleSeed;
        for (int i = static_cast<int>(order.size()) - 1; i > 0; --i) {
            const int j = static_cast<int>(splitmix64(state) % static_cast<std::uint64_t>(i + 1));
            std::swap(order[i], order[j]);
        }
    }
    return order;
}

// The polyhedron from the polygon loops, on the input points it uses (ascending input index).
HullResult hullResult(std::span<const Vec3> points, std::vector<std::vector<int>>& loops, const HullFrame& frame, int T,
                      int droppedPoints) {
    const int n = static_cast<int>(points.size());
    const double eps = frame.eps, mergeTol = frame.mergeTol;
    // Compact to the used input points (ascending input index) and build the mesh.
    std::vector<int> newIndex(n, -1);
    for (const auto& l : loops)
        for (int v : l) newIndex[v] = 0;
    HullResult result;
    for (int i = 0; i < n; ++i) {
        if (newIndex[i] == 0) {
            newIndex[i] = static_cast<int>(result.inputIndex.size());
            result.inputIndex.push_back(i);
        }
    }
    std::vector<Vec3> positions;
    positions.reserve(result.inputIndex.size());
    for (int i : result.inputIndex) positions.push_back(points[i]);
    for (auto& l : loops)
        for (int& v : l) v = newIndex[v];
    PolyhedronBuild build = ConvexPolyhedron::fromFaces(std::move(positions), loops);
    result.epsilon = eps;
    result.mergeTolerance = mergeTol;
    result.triangleCount = T;
    result.droppedPoints = droppedPoints;
    if (!build.ok()) {
        result.status = HullStatus::InternalError;
        result.message = "hull mesh failed its check: " + build.check.message;
        result.inputIndex.clear();
        return result;
    }
    result.status = HullStatus::Ok;
    result.polyhedron = std::move(build.polyhedron);
    return result;
}

}  // namespace

const char* nameOf(HullStatus status) {
    switch (status) {
        case HullStatus::Ok: return "Ok";
        case HullStatus::EmptyInput: return "EmptyInput";
        case HullStatus::NonFiniteInput: return "NonFiniteInput";
        case HullStatus::AllCoincident: return "AllCoincident";
        case HullStatus::AllCollinear: return "AllCollinear";
        case HullStatus::AllCoplanar: return "AllCoplanar";
        case HullStatus::InternalError: return "InternalError";
    }
    return "Unknown";
}

// Incremental hull (de Berg et al., "Computational Geometry", 3rd ed., ch. 11, with conflict
// lists), then the triangles merged into polygon faces within tolerance (see the header).
HullResult convexHull(std::span<const Vec3> points, const HullOptions& options, HullTrace* trace) {
    const int n = static_cast<int>(points.size());
    if (n == 0) return failure(HullStatus::EmptyInput, "no input points");
    for (int i = 0; i < n; ++i) {
        if (!points[i].allFinite()) {
            return failure(HullStatus::NonFiniteInput, "point " + std::to_string(i) + " has a non-finite coordinate",
                           i);
        }
    }
    const HullFrame frame = hullFrame(points, options);
    const InitialTetrahedron tet = initialTetrahedron(frame.P, frame.eps);
    if (tet.failure) return *tet.failure;

    HullBuilder builder(frame.P, points, frame.eps, trace);
    builder.buildTetrahedron(tet.vertex);
    for (int r : insertionOrder(n, tet.vertex, options)) builder.insert(r);

    const AliveTriangles at = aliveTriangles(builder.tris());
    const int T = static_cast<int>(at.alive.size());
    if (trace) {
        for (int t = 0; t < T; ++t) {
            const Tri& tri = at.tris[at.alive[t]];
            trace->finalTriangles.push_back(
                {at.alive[t], Triangle{points[tri.v[0]], points[tri.v[1]], points[tri.v[2]]}});
        }
    }
    FaceGroups groups = groupCoplanar(at, frame.P, frame.mergeTol, options);
    if (options.mergeCoplanarFaces) mergeFolds(at, frame.P, frame.mergeTol, groups);
    FacePolygons polygons = facePolygons(at, frame.P, frame.mergeTol, groups);
    int removedCollinear = 0;
    if (options.removeCollinearVertices) removedCollinear = removeCollinear(polygons.loops, frame.P, frame.mergeTol);
    if (trace) {
        trace->mergedGroups = polygons.mergedGroups;
        trace->rejectedMerges = polygons.rejected;
        trace->removedCollinearVertices = removedCollinear;
    }
    return hullResult(points, polygons.loops, frame, T, builder.dropped());
}

}  // namespace cdlab
