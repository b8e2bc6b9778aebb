#include "core/spatial/convex_decomposition.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

namespace {

using Polygon = std::vector<Vec3>;
using Cell = std::vector<Polygon>;  // a convex polyhedron: its faces, counter-clockwise from outside

// The box [lo, hi] as six outward faces.
Cell boxCell(const Vec3& lo, const Vec3& hi) {
    const auto p = [&](int x, int y, int z) { return Vec3(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z()); };
    return {{p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0)}, {p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)},
            {p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)}, {p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0)},
            {p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)}, {p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)}};
}

// Orders the points where a plane (unit normal n) cuts a convex cell into the cap polygon,
// counter-clockwise seen from the side n points to; near-duplicates (within eps) are merged.
Polygon capPolygon(std::vector<Vec3> points, const Vec3& n, double eps) {
    Polygon unique;
    for (const Vec3& p : points)
        if (std::none_of(unique.begin(), unique.end(), [&](const Vec3& q) { return (p - q).norm() <= eps; }))
            unique.push_back(p);
    if (unique.size() < 3) return {};
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : unique) centre += p;
    centre /= double(unique.size());
    const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
    std::sort(unique.begin(), unique.end(), [&](const Vec3& a, const Vec3& b) {
        return std::atan2((a - centre).dot(w), (a - centre).dot(u)) < std::atan2((b - centre).dot(w), (b - centre).dot(u));
    });
    return unique;
}

// Splits a convex cell by the plane n·x = d into its parts behind (n·x − d <= 0) and in front:
// Sutherland–Hodgman on every face (vertices within eps of the plane go to both sides, a crossing
// edge adds its intersection point, always computed from the front end so that the two faces
// sharing the edge get the same point), and each part closed by the cap polygon on the plane.
void splitCell(const Cell& cell, const Vec3& n, double d, double eps, Cell& back, Cell& front) {
    back.clear();
    front.clear();
    double lo = INFINITY, hi = -INFINITY;
    for (const Polygon& f : cell)
        for (const Vec3& v : f) {
            const double s = n.dot(v) - d;
            lo = std::min(lo, s), hi = std::max(hi, s);
        }
    if (hi <= eps) {  // the whole cell behind (or on) the plane
        back = cell;
        return;
    }
    if (lo >= -eps) {
        front = cell;
        return;
    }
    std::vector<Vec3> cut;
    for (const Polygon& f : cell) {
        const std::size_t count = f.size();
        std::vector<double> s(count);
        for (std::size_t i = 0; i < count; ++i) s[i] = n.dot(f[i]) - d;
        const auto side = [&](std::size_t i) { return s[i] > eps ? 1 : s[i] < -eps ? -1 : 0; };
        Polygon b, fr;
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t j = (i + 1) % count;
            const int si = side(i), sj = side(j);
            if (si <= 0) b.push_back(f[i]);
            if (si >= 0) fr.push_back(f[i]);
            if (si == 0) cut.push_back(f[i]);
            if (si * sj < 0) {
                const std::size_t fi = si > 0 ? i : j, bi = si > 0 ? j : i;
                const double t = s[fi] / (s[fi] - s[bi]);
                const Vec3 x = f[fi] + t * (f[bi] - f[fi]);
                b.push_back(x);
                fr.push_back(x);
                cut.push_back(x);
            }
        }
        // A face lying within eps of the plane (all its vertices ON) belongs to neither part:
        // the cap replaces it.
        const bool allOn = std::all_of(s.begin(), s.end(), [eps](double x) { return std::abs(x) <= eps; });
        if (allOn) continue;
        if (b.size() >= 3) back.push_back(std::move(b));
        if (fr.size() >= 3) front.push_back(std::move(fr));
    }
    Polygon cap = capPolygon(std::move(cut), n, eps);
    if (cap.empty()) return;
    back.push_back(cap);  // the back part's outward normal is +n
    std::reverse(cap.begin(), cap.end());
    front.push_back(std::move(cap));
}

// Volume and surface area of a closed convex cell (faces counter-clockwise from outside).
void volumeAndArea(const Cell& cell, double& volume, double& area) {
    Vec3 ref = Vec3::Zero();
    int count = 0;
    for (const Polygon& f : cell)
        for (const Vec3& v : f) ref += v, ++count;
    ref /= double(std::max(count, 1));
    volume = 0, area = 0;
    for (const Polygon& f : cell)
        for (std::size_t i = 1; i + 1 < f.size(); ++i) {
            const Vec3 c = (f[i] - f[0]).cross(f[i + 1] - f[0]);
            area += 0.5 * c.norm();
            volume += (f[0] - ref).dot((f[i] - ref).cross(f[i + 1] - ref)) / 6.0;
        }
}

struct Walk {
    const BspTree* tree = nullptr;
    Vec3 centre = Vec3::Zero();          // cells are kept relative to it
    std::vector<Vec3> sortedVertices;    // mesh vertices (relative), sorted by x, to snap to
    double eps = 0;
    ConvexDecomposition* out = nullptr;
    DecompositionTrace* trace = nullptr;
};

// The mesh vertex within eps of p, if any (else p).
Vec3 snapped(const Walk& w, const Vec3& p) {
    auto it = std::lower_bound(w.sortedVertices.begin(), w.sortedVertices.end(), p.x() - w.eps,
                               [](const Vec3& v, double x) { return v.x() < x; });
    Vec3 best = p;
    double bestDistance = w.eps;
    for (; it != w.sortedVertices.end() && it->x() <= p.x() + w.eps; ++it) {
        const double dist = (*it - p).norm();
        if (dist <= bestDistance) bestDistance = dist, best = *it;
    }
    return best;
}

void emitPiece(Walk& w, const Cell& cell) {
    double volume = 0, area = 0;
    volumeAndArea(cell, volume, area);
    if (!(volume > w.eps * area)) {  // thinner than the thick planes: no volume of its own
        ++w.out->droppedSlivers;
        return;
    }
    std::vector<Vec3> corners;
    for (const Polygon& f : cell)
        for (const Vec3& v : f) {
            const Vec3 p = snapped(w, v);
            if (std::none_of(corners.begin(), corners.end(), [&](const Vec3& q) { return (p - q).norm() <= w.eps; }))
                corners.push_back(p);
        }
    for (Vec3& c : corners) c += w.centre;
    w.out->pieces.push_back(std::move(corners));
}

void walk(Walk& w, int nodeId, const Cell& cell) {
    const BspNode& node = w.tree->nodes()[std::size_t(nodeId)];
    if (w.trace) {
        DecompositionStep st{nodeId, node.parent, node.depth, node.kind, node.plane, {}, -1, 0.0};
        double area = 0;
        volumeAndArea(cell, st.volume, area);
        for (const Polygon& f : cell)
            for (const Vec3& v : f)
                if (std::none_of(st.cell.begin(), st.cell.end(), [&](const Vec3& q) { return (q - (v + w.centre)).norm() <= w.eps; }))
                    st.cell.push_back(v + w.centre);
        if (node.kind == BspNodeKind::SolidLeaf) {
            const std::size_t before = w.out->pieces.size();
            emitPiece(w, cell);
            if (w.out->pieces.size() > before) st.piece = int(before);
        }
        w.trace->steps.push_back(std::move(st));
        if (node.kind == BspNodeKind::SolidLeaf) return;
    }
    if (node.kind == BspNodeKind::SolidLeaf) return emitPiece(w, cell);
    if (node.kind == BspNodeKind::EmptyLeaf) return;
    const Vec3& n = node.plane.normal;
    const double d = node.plane.offset - n.dot(w.centre);
    Cell back, front;
    splitCell(cell, n, d, w.eps, back, front);
    if (!front.empty()) walk(w, node.front, front);
    if (!back.empty()) walk(w, node.back, back);
}

}  // namespace

ConvexDecomposition decomposeIntoConvexPieces(const TriangleMesh& mesh, const BspOptions& options,
                                              DecompositionTrace* trace) {
    ConvexDecomposition out;
    std::vector<BspPolygon> polygons;
    polygons.reserve(mesh.triangles.size());
    for (int t = 0; t < mesh.triangleCount(); ++t) {
        const Triangle tri = mesh.triangle(t);
        polygons.push_back(BspPolygon{{tri.a, tri.b, tri.c}});
    }
    BspTree tree;
    tree.build(polygons, options);
    out.status = tree.status();
    out.treeNodes = int(tree.nodes().size());
    if (tree.nodes().empty() || mesh.vertices.empty()) return out;

    Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    Walk w;
    w.tree = &tree;
    w.centre = 0.5 * (lo + hi);
    w.eps = tree.thickness();
    w.out = &out;
    w.trace = trace;
    for (const Vec3& v : mesh.vertices) w.sortedVertices.push_back(v - w.centre);
    std::sort(w.sortedVertices.begin(), w.sortedVertices.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
    // The starting cell: the bounds grown by 1 % of their size (and by the thickness), so that no
    // face of the mesh lies on the box.
    const Vec3 grow = Vec3::Constant(0.01 * (hi - lo).maxCoeff() + 4 * w.eps);
    walk(w, 0, boxCell(lo - w.centre - grow, hi - w.centre + grow));
    return out;
}

}  // namespace cdlab
