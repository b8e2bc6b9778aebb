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
        drawKey(world, 14, 64, {{roleColor(Role::Colliding), "colliding: A and B share a point"}});  // touching too
}

GapInset planGapInset(const Canvas& world, const TwoPanelLayout& layout, const PairDrawing& d, const Vec3& pa,
                      const Vec3& pb) {
    GapInset g;
    const double gap = (pa - pb).norm();
    if (!(gap > 0.0) || gap >= 0.03 * d.wRadius) return g;
    g.w = layout.panelWidth() * 2 / 5, g.h = layout.panelHeight() * 2 / 5;
    // Corners, bottom right first; the top ones start below the panel heading's two lines, and
    // leave a line for the inset's heading (drawn above a bottom inset, below a top one).
    const int right = layout.panelWidth() - g.w - 14, bottom = layout.panelHeight() - g.h - 14;
    const std::array<std::array<int, 2>, 4> corners{{{right, bottom}, {14, bottom}, {right, 70}, {14, 70}}};
    const auto covered = [&](int cx, int cy) {
        int count = 0;
        const auto inside = [&](const Vec3& p) {
            Eigen::Vector2d px;
            return world.project(p, px) && px.x() >= cx && px.x() <= cx + g.w && px.y() >= cy - 26 &&
                   px.y() <= cy + g.h + 26;
        };
        for (const ConvexDrawable* body : {&d.a, &d.b})
            for (const Vec3& v : body->vertices) count += inside(v);
        return count + 1000 * (inside(pa) + inside(pb));
    };
    g.x = corners[0][0], g.y = corners[0][1];
    int best = covered(g.x, g.y);
    for (const auto& [cx, cy] : corners) {
        const int c = covered(cx, cy);
        if (c < best) best = c, g.x = cx, g.y = cy;
    }
    g.shown = true;
    g.radius = 3.0 * gap;  // the gap spans a sixth of the inset's height
    // Zoom: the panel frames ~2.1 world radii in its height, the inset 2 x 3 gaps in its height.
    g.zoom = ((g.h - GapInset::kHeading) / (2.0 * g.radius)) / (layout.panelHeight() / (2.1 * d.wRadius));
    return g;
}

void markGapInset(Canvas& world, const GapInset& g, const Vec3& pa, const Vec3& pb) {
    if (!g.shown) return;
    const Vec3 mid = 0.5 * (pa + pb);
    Eigen::Vector2d m;
    if (!world.project(mid, m)) return;
    // Pixel offsets as world points in the plane through mid facing the camera, where the
    // projection is a similarity: (dx, dy) px from mid's pixel.
    const Camera& cam = world.camera();
    const Vec3 forward = (cam.target - cam.eye).normalized();
    const Vec3 right = forward.cross(cam.up).normalized(), up = right.cross(forward);
    Eigen::Vector2d r1;
    const double probe = 1e-3 * std::max(g.radius, 1e-300) + 1e-12;
    if (!world.project(mid + probe * right, r1) || !((r1 - m).norm() > 0)) return;
    const double unitsPerPx = probe / (r1 - m).norm();
    const auto at = [&](double dx, double dy) { return Vec3(mid + unitsPerPx * (dx * right - dy * up)); };
    // The source square: what the inset shows (2 radius across), at least 12 px so it is seen.
    const double half = std::max(6.0, g.radius / unitsPerPx);
    const LineStyle ink = lineStyle(Role::Ink, 1.5f, false, true);
    world.drawPolyline({at(-half, -half), at(half, -half), at(half, half), at(-half, half)}, true, ink);
    // A connector from the square's nearest corner to the inset's nearest point on its border.
    const Eigen::Vector2d c(m.x() + (g.x + 0.5 * g.w > m.x() ? half : -half),
                            m.y() + (g.y + 0.5 * g.h > m.y() ? half : -half));
    const Eigen::Vector2d e = g.area().nearest(c);
    if ((e - c).norm() > 4) world.drawLine(at(c.x() - m.x(), c.y() - m.y()), at(e.x() - m.x(), e.y() - m.y()), ink);
}

void drawGapInset(GlContext& gl, Image& panel, int scale, const GapInset& g, const PairDrawing& d, const Vec3& view,
                  const Vec3& pa, const Vec3& pb) {
    if (!g.shown) return;
    const Vec3 mid = 0.5 * (pa + pb);
    const Camera cam = d.planar ? Camera::twoD(mid.x(), mid.y(), 2.0 * g.radius)
                                : framingCamera(mid, g.radius, view, Vec3::UnitY(), true);
    // What the inset covers is hidden: the world panel's strokes and labels there are not seen.
    panel.layout.cover(g.area().scaled(panel.scale));
    // The heading in a strip of its own above the picture, so no stroke runs under it.
    {
        Canvas strip(gl, canvasOptions(g.w, GapInset::kHeading, scale), Camera::pixels(g.w, GapInset::kHeading));
        char head[96];
        const double gap = (pa - pb).norm();
        std::snprintf(head, sizeof head, g.zoom < 100 ? "zoom ×%.2g: gap %.3g" : "zoom ×%.0f: gap %.3g", g.zoom, gap);
        strip.drawTextPx(8, 0.5 * GapInset::kHeading + 1, head,
                         TextStyle{15.0f, roleColor(Role::Ink), Anchor::Left, true, true});
        blit(panel, strip.readPixels(), g.x, g.y);
    }
    Canvas c(gl, canvasOptions(g.w, g.h - GapInset::kHeading, scale), cam);
    drawPairBodies(c, d, 0.45f, false, false);
    c.drawLine(pa, pb, lineStyle(Role::Result, 3.0f, false, true));
    c.noteQuantity(kDistanceQuantity, pa, pb);
    c.drawPoint(pa, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
    c.drawPoint(pb, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
    const TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    // The bodies' centres lie far outside the inset: each name points away from the other point.
    drawLabelAway(c, pa, pb, "p_A", ts);
    drawLabelAway(c, pb, pa, "p_B", ts);
    blit(panel, c.readPixels(), g.x, g.y + GapInset::kHeading);
    const Color ink = roleColor(Role::Ink);
    paintRect(panel, g.x, g.y, g.w, 2, ink);
    paintRect(panel, g.x, g.y + g.h - 2, g.w, 2, ink);
    paintRect(panel, g.x, g.y, 2, g.h, ink);
    paintRect(panel, g.x + g.w - 2, g.y, 2, g.h, ink);
    paintRect(panel, g.x, g.y + GapInset::kHeading - 1, g.w, 1, ink);
}

}  // namespace cdlab::demos
