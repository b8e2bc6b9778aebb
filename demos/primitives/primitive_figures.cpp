#include "demos/primitives/primitive_figures.h"

#include <cmath>

#include "demos/draw/figure_style.h"

namespace cdlab::demos {

using namespace render;

Camera viewAbove(const std::vector<Vec3>& points, const Vec3& viewDirection, const Vec3& up, double fraction,
                 int width, int height) {
    constexpr double kTitleBand = 64;  // pixels: the title's line and a gap under it
    const Vec3 back = viewDirection.normalized();
    Vec3 screenUp = up - up.dot(back) * back;
    screenUp = screenUp.norm() > 1e-12 ? Vec3(screenUp.normalized()) : back.unitOrthogonal();
    const Vec3 right = screenUp.cross(back);
    // The points' extents on the screen axes (and along the view, for the clipping planes).
    Eigen::AlignedBox3d box;
    for (const Vec3& p : points) box.extend(Vec3(p.dot(right), p.dot(screenUp), p.dot(back)));
    const Vec3 size = box.sizes().cwiseMax(Vec3::Constant(1e-6 * (1.0 + box.sizes().maxCoeff())));
    const Vec3 mid = box.center();
    const Vec3 center = mid.x() * right + mid.y() * screenUp + mid.z() * back;
    Camera cam = framingCamera(center, 0.5 * size.norm(), back, screenUp, false);
    // The band for the points: from under the title to `fraction` of the height, with a margin of 10%
    // above and below (17% left and right: labels run sideways) for the labels and the arrow heads.
    const double band = std::max(fraction * height - kTitleBand, 0.3 * height);
    cam.viewHeight = std::max(1.2 * size.y() * height / band, 1.35 * size.x() * height / width);
    // The points' centre sits in the middle of the band: the view's centre (pixel row height / 2) lies below it.
    const double bandMiddle = kTitleBand + 0.5 * band;
    const Vec3 shift = screenUp * (0.5 * height - bandMiddle) / height * cam.viewHeight;
    cam.target -= shift;
    cam.eye -= shift;
    return cam;
}

Vec3 viewAcross(const Vec3& preferred, const Vec3& line) {
    if (!(line.norm() > 0)) return preferred;
    const Vec3 u = line.normalized();
    const Vec3 across = preferred - preferred.dot(u) * u;
    const Vec3 v = across.norm() > 0.3 * preferred.norm() ? across : Vec3(u.unitOrthogonal());
    // The highest view across the line: +y with the line's part taken out.
    const Vec3 up = Vec3::UnitY() - u.y() * u;
    if (v.normalized().y() >= 0.3 || up.norm() < 1e-9) return v;
    const Vec3 a = v.normalized(), b = up.normalized();
    for (int k = 1; k <= 20; ++k) {  // from a towards b, in the plane across the line
        const Vec3 w = ((1 - k / 20.0) * a + (k / 20.0) * b).normalized();
        if (w.y() >= 0.3) return w * v.norm();
    }
    return b * v.norm();
}

double drawNumberBlock(Canvas& canvas, const std::vector<std::string>& lines, double bottomMargin) {
    const TextStyle ts{kNumberTextPx, roleColor(Role::Ink), Anchor::TopLeft, true, false};
    std::vector<std::string> wrapped;  // a line breaks only between its ";  "-separated phrases
    for (const std::string& l : lines)
        for (const std::string& w : wrapAtSeparator(canvas, l, ";  ", ts, canvas.width() - 40)) wrapped.push_back(w);
    double y = canvas.height() - bottomMargin - kNumberLineHeight * double(wrapped.size());
    const double top = y;
    for (const std::string& l : wrapped) {
        canvas.drawTextPx(20, y, l, ts);
        y += kNumberLineHeight;
    }
    return top;
}

Json finiteOrNull(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

}  // namespace cdlab::demos
