#include "demos/draw/pair_figure.h"

#include <algorithm>
#include <cmath>

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
        canvas.drawTextPx(14, 38, sub, TextStyle{17.0f, roleColor(Role::Highlight).scaled(0.8f), Anchor::TopLeft, true, true});
}

Image composeTwoPanel(GlContext& gl, const TwoPanelLayout& layout, int supersample, const std::string& title,
                      const Image& left, const Image& right, const std::vector<std::string>& captionLines) {
    CanvasOptions o;
    o.width = layout.width;
    o.height = layout.height;
    o.supersample = supersample;
    Canvas canvas(gl, o);
    canvas.setBackground(roleColor(Role::Background));
    canvas.setCamera(Camera::twoD(0, 0, 1));
    canvas.drawTextPx(18, 10, title, TextStyle{24.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    const double lineH = 25.0;
    double y = layout.height - layout.captionBand + 8;
    for (const std::string& line : captionLines) {
        canvas.drawTextPx(18, y, line, TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += lineH;
    }
    Image frame = canvas.readPixels();
    blit(frame, left, 0, layout.titleBand);
    blit(frame, right, layout.panelWidth(), layout.titleBand);
    // A 2-pixel rule between the panels.
    const Color m = roleColor(Role::Muted);
    for (int yy = layout.titleBand; yy < layout.titleBand + layout.panelHeight(); ++yy)
        for (int xx = layout.panelWidth() - 1; xx <= layout.panelWidth(); ++xx) {
            std::uint8_t* p = frame.pixel(xx, yy);
            p[0] = std::uint8_t(std::lround(std::clamp(m.r, 0.0f, 1.0f) * 255));
            p[1] = std::uint8_t(std::lround(std::clamp(m.g, 0.0f, 1.0f) * 255));
            p[2] = std::uint8_t(std::lround(std::clamp(m.b, 0.0f, 1.0f) * 255));
            p[3] = 255;
        }
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

}  // namespace cdlab::demos
