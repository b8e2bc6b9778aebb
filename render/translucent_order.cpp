#include "render/translucent_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include <Eigen/Geometry>

namespace cdlab::render {

using Eigen::Vector3d;

namespace {

struct Plane {
    Vector3d n;  // unit
    double d;    // n . x = d on the plane
    double distance(const Vector3d& x) const { return n.dot(x) - d; }
};

// A convex planar piece of an input triangle on its way down the partition.
struct Piece {
    std::vector<Vector3d> corners;
    Plane plane;  // of the input triangle; pointing out of the body for a piece of a convex mesh
    int item = 0;
    int mesh = 0, triangle = 0;
};

enum class Side { Front, Back, On, Spanning };

// Side of `plane` a piece lies on; corners within eps count as on it.
Side classify(const Piece& piece, const Plane& plane, double eps) {
    bool front = false, back = false;
    for (const Vector3d& c : piece.corners) {
        const double t = plane.distance(c);
        if (t > eps) front = true;
        else if (t < -eps) back = true;
    }
    if (front && back) return Side::Spanning;
    if (front) return Side::Front;
    if (back) return Side::Back;
    return Side::On;
}

// Sutherland–Hodgman against one plane: corners within eps go to both halves, and each crossing
// point is computed once and given to both, so the two pieces meet without a crack.
std::pair<Piece, Piece> split(const Piece& piece, const Plane& plane, double eps) {
    Piece front = piece, back = piece;
    front.corners.clear();
    back.corners.clear();
    const std::size_t n = piece.corners.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vector3d& a = piece.corners[i];
        const Vector3d& b = piece.corners[(i + 1) % n];
        const double da = plane.distance(a), db = plane.distance(b);
        if (da >= -eps) front.corners.push_back(a);
        if (da <= eps) back.corners.push_back(a);
        if ((da > eps && db < -eps) || (da < -eps && db > eps)) {
            // From the lexicographically smaller end, so the two triangles sharing this edge (which
            // run it in opposite directions) get the same point: no crack between their pieces.
            const bool fromA = std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
            const Vector3d x = fromA ? Vector3d(a + (b - a) * (da / (da - db))) : Vector3d(b + (a - b) * (db / (db - da)));
            front.corners.push_back(x);
            back.corners.push_back(x);
        }
    }
    return {std::move(front), std::move(back)};
}

// One item's bounding box and piece count (axisGap).
struct ItemBounds {
    Vector3d lo, hi;
    int pieces = 0;
};

class Orderer {
public:
    Orderer(const Viewer& viewer, std::vector<bool> convex, double eps, int cutBudget,
            std::vector<OrderedPiece>& out, TranslucentOrderStats& stats)
        : viewer_(viewer), convex_(std::move(convex)), eps_(eps), cutBudget_(cutBudget),
          workBudget_(64 * std::size_t(cutBudget) + 4000000), out_(out), stats_(stats) {}

    // Pieces of one item are consecutive and items ascend along `pieces`: the input is in item
    // order and every partition below keeps the order. The partition is walked with an explicit
    // stack (a convex item peeled against another takes one level per face: thousands of levels,
    // too deep for the call stack of a sanitizer build).
    void order(std::vector<Piece> pieces) {
        std::vector<Task> stack;
        stack.push_back({std::move(pieces), false});
        while (!stack.empty()) {
            Task task = std::move(stack.back());
            stack.pop_back();
            if (task.emitOnly) {
                for (Piece& p : task.pieces) emit(p);
            } else {
                node(std::move(task.pieces), stack);
            }
        }
    }

private:
    struct Task {
        std::vector<Piece> pieces;
        bool emitOnly;  // the pieces in a splitting plane, drawn between its far and near sides
    };
    // Where a splitting plane comes from: a piece's own triangle (its pieces are in the plane
    // whatever the rounding of their corners), or none (an axis or median plane).
    struct Splitter {
        Plane plane;
        int mesh = -1, triangle = -1;
    };

    void node(std::vector<Piece> pieces, std::vector<Task>& stack) {
        if (pieces.empty()) return;
        if (pieces.front().item == pieces.back().item) return emitItem(pieces);
        // Budgets for pathological input (many large triangles through each other): past them, the
        // rest of this subtree is ordered by depth alone.
        work_ += pieces.size();
        if (stats_.cuts > cutBudget_ || work_ > workBudget_) {
            stats_.budgetHit = true;
            return emitByDepth(pieces);
        }
        const std::optional<Plane> gap = axisGap(pieces);
        const Splitter splitter = gap ? Splitter{*gap} : faceSplitter(pieces);
        const Plane& plane = splitter.plane;
        std::vector<Piece> front, back, on;
        for (Piece& p : pieces) {
            const bool own = p.mesh == splitter.mesh && p.triangle == splitter.triangle;
            switch (own ? Side::On : classify(p, plane, eps_)) {
                case Side::Front: front.push_back(std::move(p)); break;
                case Side::Back: back.push_back(std::move(p)); break;
                case Side::On: on.push_back(std::move(p)); break;
                case Side::Spanning: {
                    auto [f, b] = split(p, plane, eps_);
                    front.push_back(std::move(f));
                    back.push_back(std::move(b));
                    ++stats_.cuts;
                    break;
                }
            }
        }
        // The far side first, then the plane's own pieces, then the near side (pushed in reverse).
        const bool eyeInFront = facesViewer(plane, plane.n * plane.d);
        stack.push_back({std::move(eyeInFront ? front : back), false});
        stack.push_back({std::move(on), true});
        stack.push_back({std::move(eyeInFront ? back : front), false});
    }

    // Whether the viewer is on the side `plane.n` points to (x: a point of the plane).
    bool facesViewer(const Plane& plane, const Vector3d& x) const {
        return viewer_.orthographic ? plane.n.dot(viewer_.towardsEye) > 0 : plane.n.dot(viewer_.eye - x) > 0;
    }

    void emit(Piece& p) { out_.push_back({std::move(p.corners), p.mesh, p.triangle}); }

    // One item: a convex surface is drawn faces turned away first (seen through the faces in front
    // of them), then faces turned towards the viewer; neither group overlaps itself on screen. A
    // piece of a non-convex mesh is one triangle, or pieces of it that lie side by side.
    void emitItem(std::vector<Piece>& pieces) {
        if (convex_[std::size_t(pieces.front().item)]) {
            std::stable_partition(pieces.begin(), pieces.end(),
                                  [&](const Piece& p) { return !facesViewer(p.plane, p.corners.front()); });
        }
        for (Piece& p : pieces) emit(p);
    }

    // Past a budget (a pathological input): the painter's order by centroid depth.
    void emitByDepth(std::vector<Piece>& pieces) {
        const auto depth = [&](const Piece& p) {
            Vector3d c = Vector3d::Zero();
            for (const Vector3d& x : p.corners) c += x;
            c /= double(p.corners.size());
            return viewer_.orthographic ? -c.dot(viewer_.towardsEye) : (c - viewer_.eye).norm();
        };
        std::vector<std::pair<double, std::size_t>> keyed;
        for (std::size_t i = 0; i < pieces.size(); ++i) keyed.emplace_back(depth(pieces[i]), i);
        std::stable_sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
        for (const auto& [key, i] : keyed) emit(pieces[i]);
    }

    // A plane between the items' bounding boxes along x, y or z, the one that splits the pieces
    // most evenly: it orders whole groups of items without cutting anything.
    std::optional<Plane> axisGap(const std::vector<Piece>& pieces) const {
        std::vector<ItemBounds> boxes;
        for (std::size_t i = 0; i < pieces.size(); ++i) {
            if (i == 0 || pieces[i].item != pieces[i - 1].item)
                boxes.push_back({Vector3d::Constant(INFINITY), Vector3d::Constant(-INFINITY), 0});
            ItemBounds& b = boxes.back();
            for (const Vector3d& c : pieces[i].corners) b.lo = b.lo.cwiseMin(c), b.hi = b.hi.cwiseMax(c);
            ++b.pieces;
        }
        std::optional<Plane> best;
        std::size_t bestImbalance = pieces.size();
        for (int axis = 0; axis < 3; ++axis) {
            std::sort(boxes.begin(), boxes.end(), [axis](const ItemBounds& x, const ItemBounds& y) { return x.lo[axis] < y.lo[axis]; });
            double reach = -INFINITY;
            std::size_t below = 0;
            for (std::size_t i = 0; i + 1 < boxes.size(); ++i) {
                reach = std::max(reach, boxes[i].hi[axis]);
                below += std::size_t(boxes[i].pieces);
                const double next = boxes[i + 1].lo[axis];
                if (!(reach < next - 2 * eps_)) continue;
                const std::size_t above = pieces.size() - below;
                const std::size_t imbalance = below > above ? below - above : above - below;
                if (imbalance < bestImbalance || !best) {
                    bestImbalance = imbalance;
                    best = Plane{Vector3d::Unit(axis), 0.5 * (reach + next)};
                }
            }
        }
        return best;
    }

    // The plane of a face of the item with the fewest pieces: a convex item stays wholly behind
    // its own faces, so only the others are cut, and once the small item's faces are used up the
    // rest is ordered. Among single-triangle items (a non-convex mesh), the one of a few evenly
    // spread candidates that cuts the fewest of a sample of the others (the usual BSP heuristic).
    Splitter faceSplitter(const std::vector<Piece>& pieces) const {
        std::vector<std::pair<std::size_t, std::size_t>> items;  // first piece, count
        for (std::size_t i = 0, start = 0; i < pieces.size(); ++i)
            if (i + 1 == pieces.size() || pieces[i + 1].item != pieces[i].item) {
                items.emplace_back(start, i + 1 - start);
                start = i + 1;
            }
        std::size_t fewest = pieces.size();
        for (const auto& [start, count] : items) fewest = std::min(fewest, count);
        std::vector<std::size_t> candidates;  // first pieces of the smallest items
        for (const auto& [start, count] : items)
            if (count == fewest) candidates.push_back(start);
        // A face of the smallest item when it is one of several pieces (a convex item: its own
        // plane has the rest of it behind), else the best of a few evenly spread candidates.
        if (fewest > 1) candidates.resize(1);
        constexpr std::size_t kCandidates = 8, kSample = 96;
        const std::size_t step = std::max<std::size_t>(1, candidates.size() / kCandidates);
        const std::size_t sampleStep = std::max<std::size_t>(1, pieces.size() / kSample);
        const auto score = [&](const Plane& plane, bool& divides) {
            long cuts = 0, front = 0, back = 0;
            for (std::size_t s = 0; s < pieces.size(); s += sampleStep) {
                const Side side = classify(pieces[s], plane, eps_);
                cuts += side == Side::Spanning, front += side == Side::Front, back += side == Side::Back;
            }
            divides = cuts > 0 || (front > 0 && back > 0);
            return 8 * cuts + std::labs(front - back);
        };
        std::size_t best = candidates.front();
        long bestScore = -1;
        bool bestDivides = false;
        for (std::size_t k = 0; k < candidates.size(); k += step) {
            bool divides = false;
            const long sc = score(pieces[candidates[k]].plane, divides);
            if (bestScore < 0 || sc < bestScore) bestScore = sc, best = candidates[k], bestDivides = divides;
        }
        // The face plane leaves the rest on one side, uncut (a curved sheet, or tiles of one: each
        // level would peel one face): a plane across the middle, if it does better.
        if (!bestDivides || fewest == 1) {
            if (const auto median = medianPlane(pieces)) {
                bool divides = false;
                if (score(*median, divides) < bestScore) return Splitter{*median};
            }
        }
        return Splitter{pieces[best].plane, pieces[best].mesh, pieces[best].triangle};
    }

    // The plane across the longest axis of the pieces' bounding box at the median of their first
    // corners, if it leaves some piece wholly on each side (so both halves are smaller than the
    // whole and the partition ends); any plane is a valid splitter, not only a face's.
    std::optional<Plane> medianPlane(const std::vector<Piece>& pieces) const {
        Vector3d lo = Vector3d::Constant(INFINITY), hi = Vector3d::Constant(-INFINITY);
        for (const Piece& p : pieces)
            for (const Vector3d& c : p.corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
        int axis = 0;
        (hi - lo).maxCoeff(&axis);
        std::vector<double> firsts;
        for (const Piece& p : pieces) firsts.push_back(p.corners.front()[axis]);
        std::nth_element(firsts.begin(), firsts.begin() + std::ptrdiff_t(firsts.size() / 2), firsts.end());
        const Plane plane{Vector3d::Unit(axis), firsts[firsts.size() / 2]};
        bool front = false, back = false;
        for (const Piece& p : pieces) {
            const Side side = classify(p, plane, eps_);
            front = front || side == Side::Front;
            back = back || side == Side::Back;
            if (front && back) return plane;
        }
        return std::nullopt;
    }

    const Viewer& viewer_;
    std::vector<bool> convex_;
    double eps_;
    int cutBudget_;
    std::size_t workBudget_ = 0, work_ = 0;  // pieces classified, summed over the nodes
    std::vector<OrderedPiece>& out_;
    TranslucentOrderStats& stats_;
};

// Unit normal of a triangle, or nothing for a degenerate one.
std::optional<Vector3d> unitNormal(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    const Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    // A needle (width under 1e-7 of its length, e.g. a fan triangle over a polygon corner that lies
    // on an edge) draws nothing, and rounding tilts its normal by ~1e-16 of its length over its
    // width: its own corners would leave the eps band of its plane.
    if (!(len > 1e-7 * longest) || !std::isfinite(len)) return std::nullopt;
    return n / len;
}

Vector3d centroidOf(const TranslucentMesh& mesh) {
    Vector3d sum = Vector3d::Zero();
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) sum += mesh.vertices[std::size_t(t[k])];
    return sum / double(3 * mesh.triangles.size());
}

}  // namespace

bool isConvexSurface(const TranslucentMesh& mesh) {
    if (mesh.triangles.empty()) return true;
    const Vector3d center = centroidOf(mesh);
    // Rounding of the coordinates, relative to the mesh's size (a tessellated sphere's faces fold by
    // far more, a flat polygon's fan triangles by nothing) and to their magnitude (far from the origin).
    double radius = 0, magnitude = 0;
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vector3d& x = mesh.vertices[std::size_t(t[k])];
            radius = std::max(radius, (x - center).norm());
            magnitude = std::max(magnitude, x.cwiseAbs().maxCoeff());
        }
    const double eps = std::max(1e-9 * radius + 1e-14 * magnitude, 1e-300);
    const auto vertex = [&](int i) -> const Vector3d& { return mesh.vertices[std::size_t(i)]; };

    // Flat: every corner in the plane of the first proper triangle.
    std::optional<Vector3d> first;
    const Eigen::Vector3i* firstTri = nullptr;
    for (const Eigen::Vector3i& t : mesh.triangles)
        if ((first = unitNormal(vertex(t[0]), vertex(t[1]), vertex(t[2])))) {
            firstTri = &t;
            break;
        }
    if (!first) return true;
    bool flat = true;
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3 && flat; ++k) flat = std::abs(first->dot(vertex(t[k]) - vertex((*firstTri)[0]))) <= eps;
    if (flat) return true;

    // Weld corners by position, snapped to a grid of eps: a mesh may repeat a vertex per face, or
    // a pole per segment with coordinates that differ by a rounding (sin pi is not 0).
    using Key = std::array<long long, 3>;
    std::vector<std::pair<Key, int>> keyed;
    bool snappable = true;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        Key key{};
        for (int k = 0; k < 3; ++k) {
            const double q = std::round(mesh.vertices[i][k] / eps);
            snappable = snappable && std::abs(q) < 1e18;
            key[std::size_t(k)] = snappable ? static_cast<long long>(q) : 0;
        }
        keyed.emplace_back(key, int(i));
    }
    std::vector<int> weld(mesh.vertices.size());
    for (std::size_t i = 0; i < weld.size(); ++i) weld[i] = int(i);
    if (snappable) {  // else (coordinates 1e9 times the mesh's size) every vertex stands alone
        std::sort(keyed.begin(), keyed.end());
        for (std::size_t i = 1; i < keyed.size(); ++i)
            if (keyed[i].first == keyed[i - 1].first) weld[std::size_t(keyed[i].second)] = weld[std::size_t(keyed[i - 1].second)];
    }

    std::vector<Plane> planes(mesh.triangles.size());
    std::vector<bool> proper(mesh.triangles.size(), false);
    struct EdgeUse {
        int lo, hi, triangle, opposite;
    };
    std::vector<EdgeUse> edges;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const Eigen::Vector3i& t = mesh.triangles[i];
        const auto n = unitNormal(vertex(t[0]), vertex(t[1]), vertex(t[2]));
        if (!n) continue;  // zero area: draws nothing
        // Outward: away from the centre, which lies strictly inside a convex body with volume.
        Plane p{*n, n->dot(vertex(t[0]))};
        const double s = p.distance(center);
        if (std::abs(s) <= eps) return false;
        if (s > 0) p = Plane{-p.n, -p.d};
        planes[i] = p;
        proper[i] = true;
        for (int k = 0; k < 3; ++k) {
            const int a = weld[std::size_t(t[k])], b = weld[std::size_t(t[(k + 1) % 3])];
            edges.push_back({std::min(a, b), std::max(a, b), int(i), t[(k + 2) % 3]});
        }
    }
    std::sort(edges.begin(), edges.end(),
              [](const EdgeUse& x, const EdgeUse& y) { return std::tie(x.lo, x.hi) < std::tie(y.lo, y.hi); });
    // Triangles joined across shared edges (union-find), to tell a closed connected surface.
    std::vector<int> parent(mesh.triangles.size());
    for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = int(i);
    const auto root = [&](int x) {
        while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
        return x;
    };
    bool closed = true;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
        if (j - i > 2) return false;  // three faces on one edge: not the surface of a convex body
        if (j - i == 1) closed = false;
        if (j - i == 2) {
            // Each face's opposite corner lies on or behind the other face: the edge folds outwards.
            const EdgeUse &e = edges[i], &f = edges[i + 1];
            if (planes[std::size_t(e.triangle)].distance(vertex(f.opposite)) > eps) return false;
            if (planes[std::size_t(f.triangle)].distance(vertex(e.opposite)) > eps) return false;
            parent[std::size_t(root(e.triangle))] = root(f.triangle);
        }
        i = j;
    }
    int components = 0;
    for (std::size_t i = 0; i < parent.size(); ++i) components += proper[i] && root(int(i)) == int(i) ? 1 : 0;
    // Closed, connected and folding outwards at every edge: the boundary of a convex body
    // (van Heijenoort, "On locally convex manifolds", 1952).
    if (closed && components == 1) return true;
    // Open or in parts (an open box, a few faces, a triangle soup): every corner behind every
    // face, when that is cheap; a large open mesh is treated as not convex (drawn right, cut more).
    constexpr std::size_t kMaxWork = 200000;
    if (mesh.triangles.size() * mesh.vertices.size() > kMaxWork) return false;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (!proper[i]) continue;
        for (const Eigen::Vector3i& t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
                if (planes[i].distance(vertex(t[k])) > eps) return false;
    }
    return true;
}

std::vector<OrderedPiece> backToFront(std::span<const TranslucentMesh> meshes, const Viewer& viewer,
                                      TranslucentOrderStats* stats) {
    TranslucentOrderStats local;
    TranslucentOrderStats& st = stats ? *stats : local;
    st = {};
    std::vector<Piece> pieces;
    std::vector<bool> convex;
    double extent = 0;  // the largest coordinate
    Vector3d lo = Vector3d::Constant(INFINITY), hi = Vector3d::Constant(-INFINITY);  // the scene's box
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const TranslucentMesh& mesh = meshes[m];
        if (mesh.triangles.empty()) continue;
        const bool isConvex = isConvexSurface(mesh);
        const Vector3d center = centroidOf(mesh);
        st.convexMeshes += isConvex ? 1 : 0;
        if (isConvex) convex.push_back(true);
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
            const Eigen::Vector3i& t = mesh.triangles[i];
            const Vector3d &a = mesh.vertices[std::size_t(t[0])], &b = mesh.vertices[std::size_t(t[1])],
                           &c = mesh.vertices[std::size_t(t[2])];
            const auto n = unitNormal(a, b, c);
            if (!n) continue;  // zero area: draws nothing
            Piece p;
            p.corners = {a, b, c};
            p.mesh = int(m);
            p.triangle = int(i);
            p.plane = Plane{*n, n->dot(a)};
            if (isConvex && p.plane.distance(center) > 0) p.plane = Plane{-p.plane.n, -p.plane.d};
            if (!isConvex) convex.push_back(false);
            p.item = int(convex.size()) - 1;
            for (const Vector3d& x : p.corners) {
                extent = std::max(extent, x.cwiseAbs().maxCoeff());
                lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
            }
            pieces.push_back(std::move(p));
        }
    }
    st.items = int(convex.size());
    // A corner this close to a plane is on it: 1e-9 of the scene's size, far below anything a figure
    // shows, plus the rounding of coordinates of size `extent` (a scene far from the origin).
    const double eps = pieces.empty() ? 1.0 : std::max(1e-9 * (hi - lo).maxCoeff() + 1e-14 * extent, 1e-300);
    const int budget = 16 * int(pieces.size()) + 4096;
    std::vector<OrderedPiece> out;
    out.reserve(pieces.size());
    Orderer(viewer, std::move(convex), eps, budget, out, st).order(std::move(pieces));
    return out;
}

}  // namespace cdlab::render
