#include "demos/draw/figure_style.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/scene/demo.h"
#include "render/legibility.h"

namespace cdlab::demos {

using namespace render;

void drawTitleAndCaption(Canvas& canvas, const std::string& title, const std::string& caption) {
    const double margin = 18;
    if (!title.empty())
        canvas.drawTextPx(margin, margin, title, TextStyle{26.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    if (!caption.empty())
        canvas.drawTextPx(margin, canvas.height() - margin, caption,
                          TextStyle{19.0f, roleColor(Role::Ink), Anchor::BottomLeft, true, false});
}

Frame finishedFrame(Canvas& canvas, const std::string& title, const std::string& caption, const std::string& name,
                    const std::string& frameCaption) {
    drawTitleAndCaption(canvas, title, caption);
    Frame f;
    f.name = name;
    f.caption = frameCaption;
    f.image = canvas.readPixels();
    return f;
}

LineStyle lineStyle(Role role, float widthPx, bool dashed, bool onTop) {
    LineStyle s;
    s.widthPx = widthPx;
    s.color = roleColor(role);
    s.dashPx = dashed ? 3.0f * widthPx + 4.0f : 0.0f;
    s.onTop = onTop;
    return s;
}

TextStyle labelStyle(Role role, float sizePx, bool bold) {
    return TextStyle{sizePx, roleColor(role), Anchor::Center, true, bold};
}

std::string formatNumber(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x == 0 ? 0.0 : x);  // no "-0"
    return buf;
}

std::string formatPoint(const Vec3& p) {
    return "(" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + ", " + formatNumber(p.z()) + ")";
}

Camera framingCamera(const Vec3& center, double radius, const Vec3& viewDirection, const Vec3& up, bool perspective) {
    Camera cam;
    cam.projection = perspective ? Camera::Projection::Perspective : Camera::Projection::Orthographic;
    cam.fovYDegrees = 30.0;
    const double halfFov = cam.fovYDegrees * M_PI / 360.0;
    const double distance = radius / std::sin(halfFov) * 1.08;
    cam.target = center;
    cam.eye = center + viewDirection.normalized() * distance;
    cam.up = up;
    cam.viewHeight = 2.3 * radius;
    cam.nearPlane = distance * 0.01;
    cam.farPlane = distance * 10 + radius * 4;
    return cam;
}

void drawKey(Canvas& canvas, double x, double y, const std::vector<KeyItem>& items, float sizePx) {
    const TextStyle text{sizePx, roleColor(Role::Ink), Anchor::TopLeft, true, false};
    for (const KeyItem& item : items) {
        const TextStyle swatch{sizePx * 1.2f, item.color.withAlpha(1.0f), Anchor::TopLeft, false, false};
        canvas.drawTextPx(x, y - 0.15 * sizePx, item.swatch, swatch);
        // The swatch is a label of the key too: a space's width to its text (render/legibility.h).
        x += canvas.measureText(item.swatch, swatch).x() + std::max(5.0, render::kMinGapFraction * sizePx);
        canvas.drawTextPx(x, y, item.text, text);
        x += canvas.measureText(item.text, text).x() + 16;
    }
}

std::vector<std::string> wrapPieces(const Canvas& measure, const std::vector<std::string>& pieces,
                                    const std::string& separator, const TextStyle& style, double width, bool cutWide) {
    const auto wider = [&](const std::string& text) { return measure.measureText(text, style).x() > width; };
    std::vector<std::string> lines;
    std::string line;
    for (const std::string& piece : pieces) {
        const std::string longer = line.empty() ? piece : line + separator + piece;
        if (line.empty() || !wider(longer)) {
            line = longer;
            if (!(cutWide && wider(line))) continue;
        } else {
            lines.push_back(line);
            line = piece;
            if (!(cutWide && wider(line))) continue;
        }
        // A piece wider than the line: cut between UTF-8 characters (never inside one).
        const std::string wide = line;
        line.clear();
        for (std::size_t c = 0; c < wide.size();) {
            std::size_t n = 1;
            while (c + n < wide.size() && (static_cast<unsigned char>(wide[c + n]) & 0xC0) == 0x80) ++n;
            const std::string character = wide.substr(c, n);
            if (!line.empty() && wider(line + character)) lines.push_back(line), line.clear();
            line += character;
            c += n;
        }
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

std::vector<std::string> wrapAtSeparator(const Canvas& measure, const std::string& line, const std::string& separator,
                                         const TextStyle& style, double width, bool cutWide) {
    std::vector<std::string> pieces;
    std::size_t start = 0;
    for (std::size_t at; (at = line.find(separator, start)) != std::string::npos; start = at + separator.size())
        pieces.push_back(line.substr(start, at - start));
    pieces.push_back(line.substr(start));
    return wrapPieces(measure, pieces, separator, style, width, cutWide);
}

render::Color triangleRegionColor(int regionIndex) {
    static constexpr int kHue[7] = {0, 3, 2, 1, 6, 4, 5};  // orange, yellow, green, sky, purple, blue, vermillion
    return render::categorical(kHue[std::clamp(regionIndex, 0, 6)]);
}

render::Color featureDimensionColor(int dimension) {
    static constexpr int kColor[4] = {0, 4, 2, 6};  // orange, blue, bluish green, reddish purple
    return render::categorical(kColor[std::clamp(dimension, 0, 3)]);
}

Vec3 viewTowards(const Vec3& view, const Vec3& normal, double minCos) {
    const Vec3 v0 = view.normalized(), n = normal.normalized();
    if (!v0.allFinite() || !n.allFinite() || n.dot(v0) >= minCos) return view;
    const double flat = std::sqrt(1 - 0.95 * 0.95);  // the horizontal part at 72° from the vertical
    Vec3 v = v0;
    for (int k = 1; k <= 40 && n.dot(v) < minCos; ++k) {
        const double t = k / 40.0;
        v = ((1 - t) * v0 + t * n).normalized();
        if (const double h = std::hypot(v.x(), v.z()); std::abs(v.y()) > 0.95 && h > 1e-9)
            v = Vec3(v.x() / h * flat, std::copysign(0.95, v.y()), v.z() / h * flat);
    }
    return v * view.norm();
}

}  // namespace cdlab::demos
