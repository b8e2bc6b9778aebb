#include "demos/nonconvex/decomposition_figure.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "app/scene/pair_scene.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

using namespace render;

namespace {

const char* kindName(BspNodeKind k) {
    return k == BspNodeKind::Inner ? "inner" : k == BspNodeKind::SolidLeaf ? "solid" : "empty";
}

ConvexDrawable cellDrawable(const std::vector<Vec3>& corners) {
    SceneShape s;
    s.kind = SceneShape::Kind::Polytope;
    s.polytope = PolytopeShape(corners);
    return shapeDrawable(s);
}

/// The polygon where the plane cuts the convex cell (its hull's edges crossing the plane), ordered
/// around its centre; empty when the plane misses the cell.
std::vector<Vec3> cutPolygon(const ConvexDrawable& cell, const Plane& plane) {
    std::vector<Vec3> pts;
    const auto side = [&](const Vec3& v) { return plane.normal.dot(v) - plane.offset; };
    for (const auto& [i, j] : cell.edges) {
        const Vec3 &a = cell.vertices[std::size_t(i)], &b = cell.vertices[std::size_t(j)];
        const double sa = side(a), sb = side(b);
        if ((sa < 0) != (sb < 0)) pts.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    if (pts.size() < 3) return {};
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : pts) c += p;
    c /= double(pts.size());
    const Vec3 u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
    std::sort(pts.begin(), pts.end(), [&](const Vec3& p, const Vec3& q) {
        return std::atan2((p - c).dot(v), (p - c).dot(u)) < std::atan2((q - c).dot(v), (q - c).dot(u));
    });
    return pts;
}

}  // namespace

Json decompositionJson(const DecompositionTrace& trace) {
    Json steps = Json::array();
    for (const DecompositionStep& s : trace.steps)
        steps.push_back({{"node", s.node}, {"parent", s.parent}, {"depth", s.depth}, {"kind", kindName(s.kind)},
                         {"piece", s.piece}, {"corners", s.cell.size()}, {"volume", s.volume},
                         {"normal", vec3Json(s.plane.normal)}, {"offset", s.plane.offset}});
    return steps;
}

Image drawDecomposition(GlContext& gl, int width, int height, int scale, const std::string& title, const std::string& bodyName,
                        const DecompositionTrace& trace, const TriangleMesh& mesh, const Vec3& view) {
    int maxDepth = 0;
    for (const DecompositionStep& s : trace.steps) maxDepth = std::max(maxDepth, s.depth);
    // The depths that cut (the deepest holds leaves only), then the pieces.
    const int panels = std::min(std::max(maxDepth, 1), 11) + 1;
    const int cols = 4, rows = (panels + cols - 1) / cols;
    Canvas c(gl, canvasOptions(width, height, scale), Camera::pixels(width, height));
    Image image = c.readPixels();  // background; panels are pasted in
    const int top = 56, bottom = 44, pw = width / cols, ph = (height - top - bottom) / rows;
    // One camera for every panel: the starting cell (the root's) framed.
    Vec3 centre;
    double radius;
    boundingSphere(trace.steps.front().cell, centre, radius);
    int piecesSoFar = 0;
    for (int k = 0; k < panels; ++k) {
        const bool last = k == panels - 1;
        const int depth = last ? maxDepth + 1 : k;
        Canvas p(gl, canvasOptions(pw, ph, scale));
        p.setCamera(framingCamera(centre, radius * 0.95, view, Vec3::UnitY(), true));
        int split = 0, kept = 0, outside = 0;
        for (const DecompositionStep& s : trace.steps) {
            const bool atDepth = s.depth == depth && s.kind == BspNodeKind::Inner;
            const bool leafAbove = s.depth <= depth && s.kind != BspNodeKind::Inner;
            if (s.cell.size() < 4 || !(atDepth || leafAbove)) continue;
            if (s.kind == BspNodeKind::Inner) {
                ++split;
                const ConvexDrawable cd = cellDrawable(s.cell);
                drawBody(p, cd, roleColor(Role::Muted), 0.12f, roleColor(Role::Ink).withAlpha(0.8f), 1.5f, false);
                // This node's plane where it cuts the cell: what the step does.
                const std::vector<Vec3> cut = cutPolygon(cd, s.plane);
                if (!cut.empty()) {
                    p.drawPolygon(cut, roleColor(Role::Support).withAlpha(0.55f));
                    p.drawPolyline(cut, true, lineStyle(Role::Support, 2.5f, false, true));
                }
            } else if (s.kind == BspNodeKind::SolidLeaf && s.piece >= 0) {
                ++kept;
                const Color col = categorical(s.piece % 7);
                drawBody(p, cellDrawable(s.cell), col, s.depth == depth ? 0.8f : 0.45f, col.scaled(0.6f), 1.5f, false);
            } else {
                ++outside;
            }
        }
        // The body's outline: its mesh's silhouette-free wireframe, faint.
        for (const auto& t : mesh.triangles)
            for (int e = 0; e < 3; ++e) {
                const Vec3& a = mesh.vertices[std::size_t(t[e])];
                const Vec3& b = mesh.vertices[std::size_t(t[(e + 1) % 3])];
                p.drawLine(a, b, LineStyle{1.0f, roleColor(Role::ShapeA).withAlpha(0.35f), 0.0f, false});
            }
        if (last) piecesSoFar = kept;
        const TextStyle head{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, true};
        const TextStyle sub{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false};
        p.drawTextPx(10, 6, last ? "the pieces: " + std::to_string(kept) : "depth " + std::to_string(depth), head);
        p.drawTextPx(10, 27,
                     last ? "convex, their union the solid"
                          : "cut " + std::to_string(split) + ", kept " + std::to_string(kept) + ", dropped " +
                                std::to_string(outside),
                     sub);
        blit(image, p.readPixels(), (k % cols) * pw * scale, (top + (k / cols) * ph) * scale);
    }
    Canvas t(gl, canvasOptions(width, height, scale), Camera::pixels(width, height));
    drawTitleAndCaption(t, title + ": how " + bodyName + " is cut into convex pieces",
                        "Each node's plane (vermillion) cuts its cell in two; a solid leaf keeps its cell as a piece, an "
                        "empty one drops it; " + std::to_string(piecesSoFar) + " pieces from " +
                            std::to_string(trace.steps.size()) + " nodes");
    // The title band and caption drawn over the pasted panels.
    const Image text = t.readPixels();
    const std::size_t row = std::size_t(image.width) * 4;
    for (int y = 0; y < image.height; ++y)
        if (y < top * scale || y >= (height - bottom) * scale)
            std::copy_n(text.rgba.begin() + std::ptrdiff_t(row * std::size_t(y)), row,
                        image.rgba.begin() + std::ptrdiff_t(row * std::size_t(y)));
    return image;
}

}  // namespace cdlab::demos
