#include "core/spatial/bsp_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

enum class Side { Front, Back, Coplanar, Straddling };

struct Fragment {
    std::vector<Vec3> vertices;  // local frame (relative to the tree's origin)
    int source = -1;
    bool split = false;
};

}  // namespace

struct BspTree::Work {
    std::vector<Fragment> frags;
    std::vector<Vec3> normal;    // per input polygon: unit normal (local frame)
    std::vector<double> offset;  // per input polygon: normal . x = offset (local frame)
    double eps = 0.0;
};

namespace {

// Ericson §8.3.3 ClassifyPolygonToPlane with a thick plane: vertices within eps are ON.
Side classify(const Fragment& f, const Vec3& n, double d, double eps) {
    int front = 0, back = 0;
    for (const Vec3& v : f.vertices) {
        const double s = n.dot(v) - d;
        if (s > eps) ++front;
        else if (s < -eps) ++back;
    }
    if (front > 0 && back > 0) return Side::Straddling;
    if (front > 0) return Side::Front;
    if (back > 0) return Side::Back;
    return Side::Coplanar;
}

// Ericson §8.3.4 SplitPolygon: walk the edges a -> b; vertices ON the plane go to both sides,
// an edge from front to back (or back to front) adds its intersection point to both. The
// intersection is always computed from the front end towards the back end, so two polygons
// sharing the edge get bit-identical points (no cracks).
void splitPolygon(const Fragment& f, const Vec3& n, double d, double eps, Fragment& front, Fragment& back) {
    const std::size_t count = f.vertices.size();
    std::vector<double> s(count);
    for (std::size_t i = 0; i < count; ++i) s[i] = n.dot(f.vertices[i]) - d;
    auto side = [&](std::size_t i) { return s[i] > eps ? 1 : s[i] < -eps ? -1 : 0; };
    auto intersect = [&](std::size_t fi, std::size_t bi) {
        // Parameter of the plane crossing from the front vertex (s > eps) to the back one (s < -eps).
        const double t = s[fi] / (s[fi] - s[bi]);
        return Vec3(f.vertices[fi] + t * (f.vertices[bi] - f.vertices[fi]));
    };
    front.vertices.clear();
    back.vertices.clear();
    std::size_t a = count - 1;
    for (std::size_t b = 0; b < count; ++b) {
        const int sa = side(a), sb = side(b);
        if (sb > 0) {
            if (sa < 0) {
                const Vec3 i = intersect(b, a);
                front.vertices.push_back(i);
                back.vertices.push_back(i);
            }
            front.vertices.push_back(f.vertices[b]);
        } else if (sb < 0) {
            if (sa > 0) {
                const Vec3 i = intersect(a, b);
                front.vertices.push_back(i);
                back.vertices.push_back(i);
            } else if (sa == 0) {
                back.vertices.push_back(f.vertices[a]);
            }
            back.vertices.push_back(f.vertices[b]);
        } else {
            front.vertices.push_back(f.vertices[b]);
            if (sa < 0) back.vertices.push_back(f.vertices[b]);
        }
        a = b;
    }
    front.source = back.source = f.source;
    front.split = back.split = true;
}

}  // namespace

void BspTree::build(const std::vector<BspPolygon>& polygons, const BspOptions& options, BspTrace* trace) {
    options_ = options;
    if (!(options_.planeThickness >= 0.0)) options_.planeThickness = kBspPlaneThickness;
    options_.splitWeight = std::clamp(std::isfinite(options_.splitWeight) ? options_.splitWeight : 0.8, 0.0, 1.0);
    nodes_.clear();
    localOffset_.clear();
    fragments_.clear();
    stats_ = {};
    if (trace) trace->steps.clear();
    origin_ = Vec3::Zero();
    thickness_ = 0.0;

    auto emptyTree = [&](BspStatus status) {
        status_ = status;
        nodes_.push_back(BspNode{});
        localOffset_.push_back(0.0);
        stats_.nodeCount = 1;
        stats_.emptyLeaves = 1;
    };
    // Bounds, and NaN / inf check.
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const BspPolygon& p : polygons)
        for (const Vec3& v : p.vertices) {
            if (!v.allFinite()) return emptyTree(BspStatus::InvalidInput);
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    Work work;
    bool degenerate = false;
    if (lo.allFinite()) {
        origin_ = 0.5 * (lo + hi);
        const double size = (hi - lo).maxCoeff();
        // Relative part (see the header) plus 8 ulps of the largest coordinate: the input
        // vertices themselves are rounded to that, so a small polygon far from the origin is
        // non-planar by ~1 ulp (1e6 offset: 1e-10) whatever its size.
        const double maxAbs = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
        thickness_ = options_.planeThickness * size + ulps(8.0, maxAbs);
        work.eps = thickness_;
        for (std::size_t i = 0; i < polygons.size(); ++i) {
            Fragment f;
            f.source = int(i);
            for (const Vec3& v : polygons[i].vertices) f.vertices.push_back(v - origin_);
            // Newell normal about the centroid (twice the vector area): robust for any planar polygon.
            Vec3 c = Vec3::Zero();
            for (const Vec3& v : f.vertices) c += v;
            if (!f.vertices.empty()) c /= double(f.vertices.size());
            Vec3 nrm = Vec3::Zero();
            for (std::size_t k = 0; k < f.vertices.size(); ++k)
                nrm += (f.vertices[k] - c).cross(f.vertices[(k + 1) % f.vertices.size()] - c);
            // Zero-area threshold, relative to the input size squared: kBspDegenerateArea.
            const double len = nrm.norm();
            work.normal.push_back(len > 0 ? Vec3(nrm / len) : Vec3::UnitZ());
            work.offset.push_back(len > 0 ? work.normal.back().dot(c) : 0.0);
            if (f.vertices.size() < 3 || !(len > kBspDegenerateArea * size * size)) {
                degenerate = true;
                continue;
            }
            work.frags.push_back(std::move(f));
        }
    }
    if (work.frags.empty()) return emptyTree(degenerate ? BspStatus::SomeDegenerate : BspStatus::Empty);
    status_ = degenerate ? BspStatus::SomeDegenerate : BspStatus::Ok;
    std::vector<int> all(work.frags.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    buildNode(std::move(all), 0, -1, work, trace);

    for (const BspNode& n : nodes_) {
        ++stats_.nodeCount;
        stats_.depth = std::max(stats_.depth, n.depth);
        if (n.kind == BspNodeKind::Inner) ++stats_.innerCount;
        else if (n.kind == BspNodeKind::SolidLeaf) ++stats_.solidLeaves;
        else ++stats_.emptyLeaves;
    }
    stats_.fragmentCount = int(fragments_.size());
}

int BspTree::buildNode(std::vector<int> polys, int depth, int parent, Work& work, BspTrace* trace) {
    const int id = int(nodes_.size());
    nodes_.push_back(BspNode{});
    localOffset_.push_back(0.0);
    nodes_[std::size_t(id)].parent = parent;
    nodes_[std::size_t(id)].depth = depth;
    if (depth >= options_.maxDepth) {
        status_ = BspStatus::DepthLimit;
        return id;  // empty leaf: the polygons left here are dropped
    }
    BspSplitStep step;
    step.node = id;
    step.depth = depth;
    step.polygons = int(polys.size());
    const int splitter = pickSplitter(polys, work, step, trace != nullptr);
    std::vector<int> frontList, backList;
    partition(polys, id, work, step, frontList, backList);
    if (trace) trace->steps.push_back(step);
    const Vec3 n = work.normal[std::size_t(splitter)];
    const double d = work.offset[std::size_t(splitter)];
    {
        BspNode& node = nodes_[std::size_t(id)];
        node.kind = BspNodeKind::Inner;
        node.splitter = splitter;
        node.plane = Plane{n, d + n.dot(origin_)};
        localOffset_[std::size_t(id)] = d;
    }
    polys.clear();
    polys.shrink_to_fit();
    // Front: nothing left means outside (empty leaf); back: nothing left means solid.
    const int front = buildChild(std::move(frontList), BspNodeKind::EmptyLeaf, depth + 1, id, work, trace);
    const int back = buildChild(std::move(backList), BspNodeKind::SolidLeaf, depth + 1, id, work, trace);
    nodes_[std::size_t(id)].front = front;
    nodes_[std::size_t(id)].back = back;
    return id;
}

int BspTree::pickSplitter(const std::vector<int>& polys, const Work& work, BspSplitStep& step, bool record) const {
    // Score every candidate's plane against the node's polygons; coplanar polygons count as in
    // front, as in Ericson's code.
    const double K = options_.splitWeight;
    std::vector<int> candidates = polys;
    if (options_.maxCandidates > 0 && int(polys.size()) > options_.maxCandidates) {
        candidates.clear();
        for (int k = 0; k < options_.maxCandidates; ++k)
            candidates.push_back(
                polys[std::size_t(std::int64_t(k) * std::int64_t(polys.size()) / options_.maxCandidates)]);
    }
    int bestSource = -1;
    double bestScore = INFINITY;
    for (int c : candidates) {
        const int s = work.frags[std::size_t(c)].source;
        int nf = 0, nb = 0, ns = 0;
        for (int j : polys) {
            const Fragment& f = work.frags[std::size_t(j)];
            const Side side = f.source == s
                                  ? Side::Coplanar
                                  : classify(f, work.normal[std::size_t(s)], work.offset[std::size_t(s)], work.eps);
            if (side == Side::Front || side == Side::Coplanar) ++nf;
            else if (side == Side::Back) ++nb;
            else ++ns;
        }
        const double score = K * ns + (1.0 - K) * std::abs(nf - nb);
        if (record) step.scores.push_back(BspCandidateScore{s, nf, nb, ns, score});
        if (score < bestScore) {  // strict: the first of equal scores wins (deterministic)
            bestScore = score;
            bestSource = s;
        }
    }
    step.splitter = bestSource;
    step.candidates = int(candidates.size());
    step.score = bestScore;
    return bestSource;
}

void BspTree::partition(const std::vector<int>& polys, int id, Work& work, BspSplitStep& step,
                        std::vector<int>& frontList, std::vector<int>& backList) {
    const int bestSource = step.splitter;
    const Vec3 n = work.normal[std::size_t(bestSource)];
    const double d = work.offset[std::size_t(bestSource)];
    for (int j : polys) {
        Fragment& f = work.frags[std::size_t(j)];
        Side side = f.source == bestSource ? Side::Coplanar : classify(f, n, d, work.eps);
        if (side == Side::Coplanar && f.source != bestSource && work.normal[std::size_t(f.source)].dot(n) < 0)
            side = Side::Back;  // opposite facing: its solid is on our front side, handled behind (see header)
        switch (side) {
            case Side::Coplanar: {
                BspFragment out;
                for (const Vec3& v : f.vertices) out.vertices.push_back(v + origin_);
                out.source = f.source;
                out.split = f.split;
                out.node = id;
                nodes_[std::size_t(id)].fragments.push_back(int(fragments_.size()));
                fragments_.push_back(std::move(out));
                ++step.coplanar;
                break;
            }
            case Side::Front:
                frontList.push_back(j);
                ++step.front;
                break;
            case Side::Back:
                backList.push_back(j);
                ++step.back;
                break;
            case Side::Straddling: {
                Fragment fp, bp;
                splitPolygon(f, n, d, work.eps, fp, bp);
                ++step.straddling;
                ++stats_.splits;
                f = std::move(fp);  // reuse the slot for the front piece
                frontList.push_back(j);
                backList.push_back(int(work.frags.size()));
                work.frags.push_back(std::move(bp));
                break;
            }
        }
    }
}

int BspTree::buildChild(std::vector<int> polys, BspNodeKind leafKind, int depth, int parent, Work& work,
                        BspTrace* trace) {
    if (!polys.empty()) return buildNode(std::move(polys), depth, parent, work, trace);
    const int id = int(nodes_.size());
    BspNode leaf;
    leaf.kind = leafKind;
    leaf.parent = parent;
    leaf.depth = depth;
    nodes_.push_back(leaf);
    localOffset_.push_back(0.0);
    return id;
}

double BspTree::localDistance(const BspNode& n, const Vec3& local) const {
    return n.plane.normal.dot(local) - localOffset_[std::size_t(&n - nodes_.data())];
}

BspPointClass BspTree::classifyPoint(const Vec3& p) const {
    if (!p.allFinite() || nodes_.empty()) return BspPointClass::Outside;
    return classifyFrom(0, p - origin_);
}

// Ericson §8.4.1 PointInSolidSpace with thick planes.
BspPointClass BspTree::classifyFrom(int id, const Vec3& local) const {
    for (;;) {
        const BspNode& n = nodes_[std::size_t(id)];
        if (n.kind == BspNodeKind::SolidLeaf) return BspPointClass::Inside;
        if (n.kind == BspNodeKind::EmptyLeaf) return BspPointClass::Outside;
        const double s = localDistance(n, local);
        if (s > thickness_) id = n.front;
        else if (s < -thickness_) id = n.back;
        else {
            // On the thick plane: both sides; a disagreement means the point is on the boundary.
            const BspPointClass f = classifyFrom(n.front, local), b = classifyFrom(n.back, local);
            return f == b ? f : BspPointClass::OnBoundary;
        }
    }
}

// Ericson §8.4.2 RayIntersect, recursive, with thick planes: the part [t0, t1] of p + t d in
// node's region is cut into the sub-interval where it is on the front side (s >= -eps) and the
// one where it is on the back side (s <= eps); they overlap where the segment is within the
// thick plane, so a point on a face is tested on both sides (closed solid). The smallest t at
// which the segment is in a solid leaf wins.
bool BspTree::firstSolid(int id, const Vec3& p, const Vec3& d, double t0, double t1, double& tHit, int& leaf) const {
    const BspNode& n = nodes_[std::size_t(id)];
    if (n.kind != BspNodeKind::Inner) {
        if (n.kind == BspNodeKind::EmptyLeaf) return false;
        tHit = t0;
        leaf = id;
        return true;
    }
    const double dist = localDistance(n, p);  // signed distance at t = 0: s(t) = dist + t * denom
    const double denom = n.plane.normal.dot(d);
    const double eps = thickness_;
    double f0 = t0, f1 = t1, b0 = t0, b1 = t1;  // front part [f0, f1], back part [b0, b1]
    if (denom > 0.0) {
        f0 = std::max(t0, (-eps - dist) / denom);
        b1 = std::min(t1, (eps - dist) / denom);
    } else if (denom < 0.0) {
        f1 = std::min(t1, (-eps - dist) / denom);
        b0 = std::max(t0, (eps - dist) / denom);
    } else {
        if (dist < -eps) f1 = t0 - 1.0;  // parallel: entirely on one side, or in the thick plane
        if (dist > eps) b1 = t0 - 1.0;
    }
    double tf = 0, tb = 0;
    int lf = -1, lb = -1;
    // Visit the part that starts first; the other only if it could still give an earlier hit.
    const bool frontFirst = f0 <= b0;
    bool hf = false, hb = false;
    if (frontFirst) {
        hf = f0 <= f1 && firstSolid(n.front, p, d, f0, f1, tf, lf);
        if (b0 <= b1 && (!hf || b0 < tf)) hb = firstSolid(n.back, p, d, b0, b1, tb, lb);
    } else {
        hb = b0 <= b1 && firstSolid(n.back, p, d, b0, b1, tb, lb);
        if (f0 <= f1 && (!hb || f0 < tb)) hf = firstSolid(n.front, p, d, f0, f1, tf, lf);
    }
    if (!hf && !hb) return false;
    const bool useFront = hf && (!hb || tf <= tb);
    tHit = useFront ? tf : tb;
    leaf = useFront ? lf : lb;
    // A hit right where the part was widened by the thick plane is reported at the exact plane
    // crossing instead (otherwise every hit through a face would be thickness/|d| early).
    const double start = useFront ? f0 : b0, end = useFront ? f1 : b1;
    if (tHit == start && start > t0 && denom != 0.0) tHit = std::clamp(-dist / denom, start, end);
    return true;
}

BspRayResult BspTree::rayQuery(const Ray& ray, double tMax) const {
    BspRayResult r;
    if (nodes_.empty() || !ray.origin.allFinite() || !ray.direction.allFinite() || !(tMax >= 0.0)) return r;
    const Vec3 p = ray.origin - origin_;
    double t = 0.0;
    int leaf = -1;
    if (!firstSolid(0, p, ray.direction, 0.0, tMax, t, leaf)) return r;
    r.hit = true;
    r.t = t;
    r.point = ray.at(t);
    r.startsInside = t == 0.0;
    r.leaf = leaf;
    return r;
}

BspRayResult BspTree::segmentQuery(const Segment& segment) const {
    return rayQuery(Ray{segment.a, segment.b - segment.a}, 1.0);
}

}  // namespace cdlab
