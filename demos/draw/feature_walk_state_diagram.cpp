// V-Clip demo: the five-state diagram (Mirtich 1998, Fig. 6: V-V, V-E, V-F, E-E, E-F with the
// update transitions; F-F is never entered) and the small plots of the right column, drawn in
// pixel space with the 2D canvas.
#include <algorithm>
#include <cmath>

#include "demos/draw/feature_walk_figure.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/plot.h"

namespace cdlab::demos::walkfigure {

using namespace render;

namespace {

// Node centres (x right, y down, px of a 384-wide panel) ordered by VClipState: columns by the
// summed feature dimension (0: V-V, 1: V-E, 2: V-F over E-E, 3: E-F), so every update that raises
// a dimension points right.
struct NodePos {
    double x, y;
};
constexpr NodePos kNode[5] = {{48, 0.56}, {138, 0.56}, {236, 0.34}, {236, 0.80}, {330, 0.56}};
const char* kStateName[5] = {"V-V", "V-E", "V-F", "E-E", "E-F"};
// The transitions of the walk: each pair both ways (an update raises or lowers one dimension).
constexpr int kPairs[5][2] = {{0, 1}, {1, 2}, {1, 3}, {2, 4}, {3, 4}};
constexpr double kNodeRadius = 25;

}  // namespace

Image drawStateDiagram(GlContext& gl, int W, int H, int ss, const DiagramInput& in) {
    Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
    const double top = 44;  // below the heading
    auto P = [&](double x, double yDown) { return Vec3(x * W / 384.0, H - yDown, 0); };
    auto node = [&](int s) { return P(kNode[s].x, top + kNode[s].y * (H - top)); };
    const Color ink = roleColor(Role::Ink), lit = roleColor(Role::Highlight);

    auto arrowBetween = [&](int a, int b, double side, bool on) {
        const Vec3 pa = node(a), pb = node(b);
        const Vec3 d = (pb - pa).normalized();
        const Vec3 n(-d.y(), d.x(), 0);
        const Vec3 p = pa + d * (kNodeRadius + 3) + n * side, q = pb - d * (kNodeRadius + 4) + n * side;
        LineStyle ls = lineStyle(on ? Role::Highlight : Role::Muted, on ? 4.0f : 1.8f);
        c.drawArrow(p, q, ls);
    };
    bool drawnTaken = in.from < 0 || in.to < 0;
    for (const auto& pr : kPairs) {
        for (int dir = 0; dir < 2; ++dir) {
            const int a = dir == 0 ? pr[0] : pr[1], b = dir == 0 ? pr[1] : pr[0];
            const bool on = a == in.from && b == in.to;
            drawnTaken = drawnTaken || on;
            arrowBetween(a, b, 5.0, on);
        }
    }
    // handleLocalMin: V-F -> V-F (the face is replaced by another face), a loop over the node.
    {
        const bool on = in.from == 2 && in.to == 2;
        drawnTaken = drawnTaken || on;
        const Vec3 cen = node(2);
        std::vector<Vec3> arc;  // world y is up: a circle sitting on top of the node
        const Vec3 loopCentre = cen + Vec3(0, kNodeRadius + 7, 0);
        for (int k = 0; k <= 16; ++k) {
            const double t = (-50.0 + 280.0 * k / 16.0) * M_PI / 180.0;
            arc.push_back(loopCentre + 12.0 * Vec3(std::cos(t), std::sin(t), 0));
        }
        LineStyle ls = lineStyle(on ? Role::Highlight : Role::Muted, on ? 4.0f : 1.8f);
        c.drawPolyline(std::vector<Vec3>(arc.begin(), arc.end() - 1), false, ls);
        c.drawArrow(arc[arc.size() - 2], arc.back(), ls);
        c.drawText(cen + Vec3(30, kNodeRadius + 18, 0), "local min",
                   TextStyle{13.0f, ink.mixed(roleColor(Role::Muted), 0.3f), Anchor::Left, true, false});
    }
    // A transition outside the paper's diagram (should not happen): drawn straight so it is seen.
    if (!drawnTaken) {
        const Vec3 pa = node(in.from), pb = node(in.to);
        c.drawArrow(pa, pb, lineStyle(Role::Highlight, 3.0f, true));
    }
    for (int s = 0; s < 5; ++s) {
        const bool cur = s == in.current;
        const Color fill = cur                ? lit
                           : in.visits[s] > 0 ? lit.mixed(roleColor(Role::Background), 0.78f)
                                              : roleColor(Role::Background);
        c.drawPoint(node(s), float(kNodeRadius), fill, true, cur ? 3.0f : 1.8f, ink);
        const Color text = cur ? roleColor(Role::Background) : ink;
        const bool counted = in.visits[s] > 0;
        c.drawText(node(s) + Vec3(0, counted ? 5 : 0, 0), kStateName[s],
                   TextStyle{16.0f, text, Anchor::Center, false, true});
        if (counted)
            c.drawText(node(s) + Vec3(0, -10, 0), "×" + std::to_string(in.visits[s]),
                       TextStyle{13.0f, text, Anchor::Center, false, false});
    }
    c.drawTextPx(12, 8, in.heading, TextStyle{18.0f, ink, Anchor::TopLeft, true, true});
    if (!in.terminal.empty())
        c.drawTextPx(12, 30, in.terminal, TextStyle{15.0f, lit.scaled(0.8f), Anchor::TopLeft, true, true});
    return c.readPixels();
}

Image drawPlot(GlContext& gl, int W, int H, int ss, const PlotInput& in) {
    Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
    auto P = [&](double x, double yDown) { return Vec3(x, H - yDown, 0); };
    const double x0 = 62, x1 = W - 18, yTop = 40 + 18.0 * ((in.legend.size() + 1) / 2), yBot = H - 40;
    double xmin = INFINITY, xmax = -INFINITY, ymin = 0, ymax = -INFINITY;
    for (const auto& s : in.series)
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            xmin = std::min(xmin, s.x[i]);
            xmax = std::max(xmax, s.x[i]);
            ymin = std::min(ymin, s.y[i]);
            ymax = std::max(ymax, s.y[i]);
        }
    if (!(xmax > xmin)) xmax = xmin + 1;
    if (!std::isfinite(xmin)) xmin = 0, xmax = 1;
    if (!(ymax > ymin)) ymax = ymin + 1;
    if (in.integerY) ymax = std::ceil(ymax);
    ymax += 0.06 * (ymax - ymin);
    const bool anyBars = std::any_of(in.series.begin(), in.series.end(), [](const PlotSeries& s) { return s.bars; });
    const double xpad = anyBars ? 0.5 : 0.0;
    auto X = [&](double x) { return x0 + (x - xmin + xpad) / (xmax - xmin + 2 * xpad) * (x1 - x0); };
    auto Y = [&](double y) { return yBot - (y - ymin) / (ymax - ymin) * (yBot - yTop); };
    const Color ink = roleColor(Role::Ink);
    const LineStyle axis = lineStyle(Role::Ink, 1.5f);
    c.drawLine(P(x0, yBot), P(x1, yBot), axis);
    c.drawLine(P(x0, yBot), P(x0, yTop), axis);
    TextStyle tick{13.0f, ink, Anchor::Top, false, false};
    const int nx = int(std::lround(xmax - xmin));
    const int xStep = std::max(1, (nx + 9) / 10);
    for (int i = int(std::ceil(xmin)); i <= int(std::floor(xmax)); i += xStep) {
        c.drawLine(P(X(i), yBot), P(X(i), yBot + 4), axis);
        c.drawText(P(X(i), yBot + 6), std::to_string(i), tick);
    }
    TextStyle ytick{13.0f, ink, Anchor::Right, false, false};
    const double step = std::max(in.integerY ? 1.0 : 0.0, roundTickStep(ymax - ymin, 4));
    for (double v = std::ceil(ymin / step) * step; v <= ymax + 1e-9 * step; v += step) {
        if (std::abs(v) < 1e-9 * step) v = 0;
        if (v > ymin) c.drawLine(P(x0, Y(v)), P(x1, Y(v)), lineStyle(Role::Muted, 0.8f, true));
        c.drawText(P(x0 - 6, Y(v)), formatNumber(v), ytick);
    }
    if (in.marker >= 0)
        c.drawLine(P(X(in.marker), yBot), P(X(in.marker), yTop), lineStyle(Role::Highlight, 1.5f, true));
    for (const auto& s : in.series) {
        std::vector<Vec3> pts;
        for (std::size_t i = 0; i < s.x.size(); ++i) pts.push_back(P(X(s.x[i]), Y(s.y[i])));
        if (s.bars) {
            const double bw = std::max(2.0, 0.6 * (X(1) - X(0)));
            for (std::size_t i = 0; i < pts.size(); ++i) {
                const double cx = pts[i].x();
                c.drawPolygon({P(cx - bw / 2, yBot), P(cx + bw / 2, yBot), Vec3(cx + bw / 2, pts[i].y(), 0),
                               Vec3(cx - bw / 2, pts[i].y(), 0)},
                              i < s.pointColors.size() ? s.pointColors[i] : s.lineColor);
            }
            continue;
        }
        LineStyle ls = lineStyle(Role::Ink, 2.5f);
        ls.color = s.lineColor;
        if (pts.size() > 1) c.drawPolyline(pts, false, ls);
        for (std::size_t i = 0; i < pts.size(); ++i)
            c.drawPoint(pts[i], 4.5f, i < s.pointColors.size() ? s.pointColors[i] : s.lineColor, true, 1.0f, ink);
    }
    c.drawTextPx(12, 8, in.heading, TextStyle{18.0f, ink, Anchor::TopLeft, true, true});
    c.drawText(P(0.5 * (x0 + x1), H - 6), in.xLabel, TextStyle{14.0f, ink, Anchor::Bottom, false, false});
    for (std::size_t i = 0; i < in.legend.size(); ++i) {
        const double lx = 14 + (i % 2) * 180, ly = 40 + 18.0 * (i / 2);
        c.drawPoint(P(lx + 5, ly), 5.0f, in.legend[i].first, true, 1.0f, ink);
        c.drawText(P(lx + 14, ly), in.legend[i].second, TextStyle{13.0f, ink, Anchor::Left, false, false});
    }
    return c.readPixels();
}

}  // namespace cdlab::demos::walkfigure
