#include "demos/draw/pair_figure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"

namespace cdlab::demos {

using namespace render;

Camera panelCamera(bool planar, const Vec3& center, double radius, const Vec3& view, const TwoPanelLayout& layout) {
    if (planar) {
        const double aspect = double(layout.panelWidth()) / layout.panelHeight();
        // Fit the circle in the shorter side with a margin for labels, and leave room for the heading.
        const double height = std::max(2.0 * radius, 2.0 * radius / aspect) * 1.3;
        return Camera::twoD(center.x(), center.y() + 0.04 * height, height);
    }
    return framingCamera(center, radius * 1.05, view, Vec3::UnitY(), true);
}

void drawPanelHeading(Canvas& canvas, const std::string& heading, const std::string& sub) {
    canvas.drawTextPx(14, 10, heading, TextStyle{20.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    if (!sub.empty())
        canvas.drawTextPx(14, 38, sub,
                          TextStyle{17.0f, roleColor(Role::Highlight).scaled(0.8f), Anchor::TopLeft, true, true});
}

TwoPanelLayout twoPanelLayout(int width, int height, const std::string& sceneCaption) {
    TwoPanelLayout layout{width, height};
    if (!sceneCaption.empty()) layout.captionBand += 25;
    return layout;
}

Image composeTwoPanel(GlContext& gl, const TwoPanelLayout& layout, int scale, const std::string& title,
                      const std::string& sceneCaption, const Image& left, const Image& right,
                      const std::vector<std::string>& captionLines) {
    Canvas canvas(gl, canvasOptions(layout.width, layout.height, scale), Camera::twoD(0, 0, 1));
    canvas.drawTextPx(18, 10, title, TextStyle{24.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    const double lineH = 25.0;
    double y = layout.height - layout.captionBand + 8;
    if (!sceneCaption.empty()) {  // the scene's caption first, in a quieter ink, as on every frame
        canvas.drawTextPx(18, y, sceneCaption,
                          TextStyle{17.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f), Anchor::TopLeft,
                                    false, false});
        y += lineH;
    }
    for (const std::string& line : captionLines) {
        canvas.drawTextPx(18, y, line, TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += lineH;
    }
    Image frame = canvas.readPixels();
    blit(frame, left, 0, layout.titleBand);
    blit(frame, right, layout.panelWidth(), layout.titleBand);
    // A 2-pixel rule between the panels.
    paintRect(frame, layout.panelWidth() - 1, layout.titleBand, 2, layout.panelHeight(), roleColor(Role::Muted));
    return frame;
}

PairDrawing makePairDrawing(const PairScene& pair, bool drawMinkowski, std::vector<Vec3> csPoints,
                            std::vector<std::string>& skipped) {
    PairDrawing d;
    d.planar = pair.dimension == 2;
    d.a = shapeDrawable(pair.a);
    d.b = shapeDrawable(pair.b);
    if (drawMinkowski) d.c = minkowskiDrawable(pair.a, pair.b, &d.exact);
    else skipped.push_back("Minkowski difference hull (no 'minkowski' layer)");
    if (d.c.valid) csPoints.insert(csPoints.end(), d.c.vertices.begin(), d.c.vertices.end());
    csPoints.push_back(Vec3::Zero());
    boundingSphere(csPoints, d.cCenter, d.cRadius);
    std::vector<Vec3> wpts = d.a.vertices;
    wpts.insert(wpts.end(), d.b.vertices.begin(), d.b.vertices.end());
    boundingSphere(wpts, d.wCenter, d.wRadius);
    return d;
}

void drawPairBodies(Canvas& world, const PairDrawing& d, float alpha3d, bool colliding, bool labels) {
    const float alpha = d.planar ? 0.35f : alpha3d;
    for (const auto& [body, role] : {std::pair{&d.a, Role::ShapeA}, std::pair{&d.b, Role::ShapeB}}) {
        world.setStrokeOwner(bodyOwner(role == Role::ShapeA ? "A" : "B"));
        drawBody(world, *body, roleColor(role), alpha,
                 colliding ? roleColor(Role::Colliding) : roleColor(role).scaled(0.6f), colliding ? 3.5f : 2.0f);
    }
    world.setStrokeOwner(0);
    if (!labels) return;
    const auto [nameA, nameB] = bodyNamePoints(d.a, d.b);
    drawBodyName(world, nameA, "A", Role::ShapeA);
    drawBodyName(world, nameB, "B", Role::ShapeB);
    // The key only where outlines are drawn (polytopes, 2D shapes; curved 3D bodies have none).
    if (colliding && (d.planar || !d.a.edges.empty() || !d.b.edges.empty()))
        drawKey(world, 14, 64, {{roleColor(Role::Colliding), "colliding: A and B intersect"}});
}

bool drawGapInset(GlContext& gl, const Canvas& world, Image& panel, int scale, const TwoPanelLayout& layout,
                  const PairDrawing& d, const Vec3& view, const Vec3& pa, const Vec3& pb) {
    const double gap = (pa - pb).norm();
    if (!(gap > 0.0) || gap >= 0.03 * d.wRadius) return false;
    const int w = layout.panelWidth() * 2 / 5, h = layout.panelHeight() * 2 / 5;
    // Corners, bottom right first; the top ones start below the panel heading's two lines.
    const int right = layout.panelWidth() - w - 14, bottom = layout.panelHeight() - h - 14;
    const std::array<std::array<int, 2>, 4> corners{{{right, bottom}, {14, bottom}, {right, 70}, {14, 70}}};
    const auto covered = [&](int cx, int cy) {
        int count = 0;
        const auto inside = [&](const Vec3& p) {
            Eigen::Vector2d px;
            return world.project(p, px) && px.x() >= cx && px.x() <= cx + w && px.y() >= cy && px.y() <= cy + h;
        };
        for (const ConvexDrawable* body : {&d.a, &d.b})
            for (const Vec3& v : body->vertices) count += inside(v);
        return count + 1000 * (inside(pa) + inside(pb));
    };
    int x = corners[0][0], y = corners[0][1], best = covered(x, y);
    for (const auto& [cx, cy] : corners) {
        const int c = covered(cx, cy);
        if (c < best) best = c, x = cx, y = cy;
    }
    const Vec3 mid = 0.5 * (pa + pb);
    const double radius = 3.0 * gap;  // the gap spans a sixth of the inset's height
    const Camera cam = d.planar ? Camera::twoD(mid.x(), mid.y(), 2.0 * radius)
                                : framingCamera(mid, radius, view, Vec3::UnitY(), true);
    Canvas c(gl, canvasOptions(w, h, scale), cam);
    drawPairBodies(c, d, 0.45f, false, false);
    c.drawLine(pa, pb, lineStyle(Role::Result, 3.0f, false, true));
    c.drawPoint(pa, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
    c.drawPoint(pb, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
    const TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    // The bodies' centres lie far outside the inset: each name points away from the other point.
    drawLabelAway(c, pa, pb, "p_A", ts);
    drawLabelAway(c, pb, pa, "p_B", ts);
    // Zoom: the panel frames ~2.1 world radii in its height, the inset 2 x 3 gaps in its height.
    const double zoom = (h / (2.0 * radius)) / (layout.panelHeight() / (2.1 * d.wRadius));
    char head[96];
    std::snprintf(head, sizeof head, zoom < 100 ? "zoom ×%.2g: gap %.3g" : "zoom ×%.0f: gap %.3g", zoom, gap);
    c.drawTextPx(8, 6, head, TextStyle{15.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    blit(panel, c.readPixels(), x, y);
    const Color ink = roleColor(Role::Ink);
    paintRect(panel, x, y, w, 2, ink);
    paintRect(panel, x, y + h - 2, w, 2, ink);
    paintRect(panel, x, y, 2, h, ink);
    paintRect(panel, x + w - 2, y, 2, h, ink);
    return true;
}

}  // namespace cdlab::demos
