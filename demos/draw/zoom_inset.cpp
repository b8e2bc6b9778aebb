#include "demos/draw/zoom_inset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/legibility.h"

namespace cdlab::demos {

using namespace render;

Camera zoomedCamera(const Camera& camera, const Vec3& mid, double radius) {
    if (camera.projection == Camera::Projection::TwoD) return Camera::twoD(mid.x(), mid.y(), 2.0 * radius);
    Camera c = camera;
    const Vec3 back = (camera.eye - camera.target).normalized();
    c.target = mid;
    c.viewHeight = 2.0 * radius;
    const double distance = camera.projection == Camera::Projection::Perspective
                                ? radius / std::tan(camera.fovYDegrees * M_PI / 360.0)
                                : (camera.eye - camera.target).norm();
    c.eye = mid + back * distance;
    if (camera.projection == Camera::Projection::Perspective) {
        c.nearPlane = 0.01 * distance;
        c.farPlane = 100.0 * distance + 1e3 * radius;
    }
    return c;
}

namespace {

// World units per output pixel at `mid`, across the view (where the projection is a similarity);
// 0 when it cannot be measured. The right and up unit vectors of the camera come with it.
double unitsPerPx(const Canvas& canvas, const Vec3& mid, double probe, Vec3& right, Vec3& up) {
    const Camera& cam = canvas.camera();
    const Vec3 forward = (cam.target - cam.eye).normalized();
    right = cam.projection == Camera::Projection::TwoD ? Vec3::UnitX() : Vec3(forward.cross(cam.up).normalized());
    up = cam.projection == Camera::Projection::TwoD ? Vec3::UnitY() : Vec3(right.cross(forward));
    Eigen::Vector2d m, r;
    if (!canvas.project(mid, m) || !canvas.project(mid + probe * right, r) || !((r - m).norm() > 0)) return 0.0;
    return probe / (r - m).norm();
}

// How much of the drawing a box at `area` hides: label and marker area, and for each stroke it
// cuts 20 px² per px of the stroke's width (a body's 1.5-px edge 30, an 8-px interval bar 160).
double hiddenCost(const FigureLayout& layout, const Box& area) {
    double cost = 0;
    for (const LayoutLabel& l : layout.labels) cost += area.overlapArea(l.box);
    for (const LayoutMarker& m : layout.markers) cost += area.overlapArea(m.box);
    for (const LayoutStroke& s : layout.strokes) {
        double t0 = 0, t1 = 0;
        if (area.clip(s.a, s.b, t0, t1) && t1 > t0) cost += 20.0 * s.width;
    }
    return cost;
}

// The inset's border and the rule under its heading, painted and recorded as strokes (a label of
// the picture that the inset half hides crosses them).
void paintBorder(Image& image, const Box& b, const Color& ink) {
    const int x = int(b.x0), y = int(b.y0), w = int(b.width()), h = int(b.height());
    paintRect(image, x, y, w, 2, ink);
    paintRect(image, x, y + h - 2, w, 2, ink);
    paintRect(image, x, y, 2, h, ink);
    paintRect(image, x + w - 2, y, 2, h, ink);
    paintRect(image, x, y + kZoomHeadingPx - 1, w, 1, ink);
    const double s = image.scale;
    const Eigen::Vector2d c[4] = {{b.x0 + 1, b.y0 + 1}, {b.x1 - 1, b.y0 + 1}, {b.x1 - 1, b.y1 - 1}, {b.x0 + 1, b.y1 - 1}};
    for (int i = 0; i < 4; ++i) image.layout.strokes.push_back({s * c[i], s * c[(i + 1) % 4], 2.0 * s});
}

}  // namespace

Image readPixelsZoomed(GlContext& gl, Canvas& canvas, int scale, const ZoomTarget& target, const Box& within) {
    Eigen::Vector2d pp, qq;
    const double length = (target.p - target.q).norm();
    if (!(length > 0) || !canvas.project(target.p, pp) || !canvas.project(target.q, qq) ||
        !((pp - qq).norm() < kMinQuantityPx))
        return canvas.readPixels();
    // A picture too small for an inset with a heading and a picture under it is left as it is
    // (tests/fuzz: scenes drawn at a few dozen pixels).
    if (!(0.25 * within.width() >= 60.0 && 0.25 * within.height() >= kZoomHeadingPx + 30.0)) return canvas.readPixels();
    const Vec3 mid = 0.5 * (target.p + target.q);
    Vec3 right, up;
    const double worldUnits = unitsPerPx(canvas, mid, 3e-3 * length, right, up);
    if (!(worldUnits > 0)) return canvas.readPixels();
    // The quantity as the picture shows it spans a sixth of the inset's height: a segment seen
    // foreshortened (EPA's gap along n, the view turned towards n) is zoomed further, up to 4×
    // (the review: the gap hid under the w marker at the zoom of its true length).
    const double radius = 3.0 * std::max((pp - qq).norm() * worldUnits, 0.25 * length);
    Eigen::Vector2d m;
    canvas.project(mid, m);
    // The source square: what the inset shows (2 radius across), at least 12 px so it is seen.
    const double half = std::max(6.0, radius / worldUnits);
    const Box source{m.x() - half, m.y() - half, m.x() + half, m.y() + half};

    // The corner of `within` and the size (9/20 of it each way down to 1/4, wide enough for the
    // heading) whose inset hides least of what the picture draws (its layout), each step smaller
    // costing as much as hiding two edges; the largest one, if none is wide enough.
    const FigureLayout drawn = canvas.layout();
    const TextStyle headStyle{18.0f, roleColor(Role::Ink), Anchor::Left, true, true};
    const double headWidth = canvas.measureText("zoom ×000: " + target.heading, headStyle).x() + 16.0;
    Box area;
    double best = std::numeric_limits<double>::infinity();
    for (int step = 0; step < 5; ++step) {
        const double fraction = 0.45 - 0.05 * step;
        const double w = std::round(fraction * within.width()), h = std::round(fraction * within.height());
        if (w < headWidth && step > 0) continue;
        for (const auto& [cx, cy] : std::array<std::array<double, 2>, 4>{
                 {{within.x1 - w, within.y1 - h}, {within.x0, within.y1 - h}, {within.x1 - w, within.y0}, {within.x0, within.y0}}}) {
            const Box b{std::round(cx), std::round(cy), std::round(cx) + w, std::round(cy) + h};
            const double cost = hiddenCost(drawn, b) + 60.0 * step + (b.overlapArea(source) > 0 ? 1e12 : 0.0);
            if (cost < best) best = cost, area = b;
        }
    }
    const int w = int(area.width()), h = int(area.height());

    // On the picture: the source square and a connector from its nearest corner to the inset.
    const auto at = [&](const Eigen::Vector2d& px) {
        return Vec3(mid + worldUnits * ((px.x() - m.x()) * right - (px.y() - m.y()) * up));
    };
    const LineStyle ink = lineStyle(Role::Ink, 1.5f, false, true);
    canvas.drawPolyline({at({source.x0, source.y0}), at({source.x1, source.y0}), at({source.x1, source.y1}),
                         at({source.x0, source.y1})},
                        true, ink);
    const Eigen::Vector2d corner(area.center().x() > m.x() ? source.x1 : source.x0,
                                 area.center().y() > m.y() ? source.y1 : source.y0);
    const Eigen::Vector2d end = area.nearest(corner);
    if ((end - corner).norm() > 4) canvas.drawLine(at(corner), at(end), ink);
    Image image = canvas.readPixels();
    image.layout.cover(area.scaled(image.scale));

    // The inset: the picture's camera moved onto the quantity, under a heading strip.
    const int pictureH = h - kZoomHeadingPx;
    Canvas c(gl, canvasOptions(w, pictureH, scale), zoomedCamera(canvas.camera(), mid, radius));
    // The quantity itself in ink under what the scene draws (5 px: a line the scene draws along it
    // shows inside), and over it a tick across each end.
    c.drawLine(target.p, target.q, lineStyle(Role::Ink, 5.0f, false, true));
    target.draw(c);
    Vec3 insetRight, insetUp;  // the picture's own: the camera only moved
    const double insetUnits = unitsPerPx(c, mid, 1e-3 * radius, insetRight, insetUp);
    Eigen::Vector2d p2, q2;
    if (c.project(target.p, p2) && c.project(target.q, q2) && (q2 - p2).norm() > 0) {
        const Eigen::Vector2d across = Eigen::Vector2d(-(q2 - p2).y(), (q2 - p2).x()).normalized() * 9.0;
        const Vec3 tick = insetUnits * (across.x() * right - across.y() * up);
        for (const Vec3& end : {target.p, target.q})
            c.drawLine(end - tick, end + tick, lineStyle(Role::Ink, 3.0f, false, true));
    }
    c.noteQuantity(target.name, target.p, target.q);
    const double zoom = insetUnits > 0 ? worldUnits / insetUnits : 0.0;
    char head[160];
    std::snprintf(head, sizeof head, zoom < 100 ? "zoom ×%.2g: %s" : "zoom ×%.0f: %s", zoom, target.heading.c_str());
    Canvas strip(gl, canvasOptions(w, kZoomHeadingPx, scale), Camera::pixels(w, kZoomHeadingPx));
    strip.drawTextPx(8, 0.5 * kZoomHeadingPx + 1, head, headStyle);
    blit(image, strip.readPixels(), int(area.x0), int(area.y0));
    Image picture = c.readPixels();
    picture.layout.bodies.clear();  // a zoomed view cuts its bodies by design
    blit(image, picture, int(area.x0), int(area.y0) + kZoomHeadingPx);
    paintBorder(image, area, roleColor(Role::Ink));
    return image;
}

}  // namespace cdlab::demos
