#include "demos/draw/plot.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "app/scene/scene.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

PlotOptions scenePlotOptions(const SceneCommon& scene, int scale) {
    PlotOptions o;
    o.title = scene.title;
    o.width = scene.image.width;
    o.height = scene.image.height;
    o.scale = scale;
    return o;
}

using render::Anchor;
using render::Canvas;
using render::Color;
using render::LineStyle;
using render::Role;
using render::roleColor;
using render::TextStyle;

namespace {

/// A decade's tick label, 10^k, drawn as "10" and its exponent raised, each a text of its own so the
/// legibility gate sees the exponent's size: a Unicode superscript ("10⁻¹²") drew it at about 9 px
/// inside a 15-px label (the review: tick exponents ~5 px). `anchor` as the tick's TextStyle: Top
/// (x the centre, y the exponent's top) or Right (x the right end, y the middle). The exponent's size is the
/// 1.6 % target of the picture's height, at least.
void drawDecadeLabel(Canvas& c, double x, double y, int k, const TextStyle& style, int pictureHeight) {
    if (k == 0 || k == 1) {  // on the baseline of the labels with exponents beside it
        c.drawTextPx(x, y + (style.anchor == Anchor::Right ? 0.24 : 0.5) * style.sizePx, k == 0 ? "1" : "10", style);
        return;
    }
    TextStyle base = style, exponent = style;
    exponent.sizePx = std::max(0.8f * style.sizePx, float(std::ceil(0.0165 * pictureHeight * 10) / 10));
    const std::string e = (k < 0 ? "−" : "") + std::to_string(std::abs(k));
    const double wBase = c.measureText("10", base).x(), wExp = c.measureText(e, exponent).x();
    const double width = wBase + 1.0 + wExp;
    const double left = style.anchor == Anchor::Right ? x - width : x - 0.5 * width;
    // Under an x axis the exponent's top, not the base's, is at y (clear of the tick marks above).
    // Beside a y axis the base and its raised exponent together are centred on y.
    const double middle = style.anchor == Anchor::Right ? y + 0.24 * style.sizePx : y + style.sizePx;
    base.anchor = exponent.anchor = Anchor::Left;
    c.drawTextPx(left, middle, "10", base);
    // Raised by 0.55 of the base size: the two boxes share under half a line (not run together).
    c.drawTextPx(left + wBase + 1.0, middle - 0.55 * style.sizePx, e, exponent);
}

struct Axis {
    double lo = 0, hi = 1;  // in axis units (log10 for log axes)
    bool log = true;
    double floor = 0;
    double unit(double v) const { return log ? std::log10(std::max(v, floor)) : v; }
};

/// Pixel frame of the plot area (y down) and the mapping from data.
struct PlotArea {
    double x0, x1, y0, y1;  // left, right, top, bottom pixels
    Axis ax, ay;
    double px(double x) const { return x0 + (ax.unit(x) - ax.lo) / (ax.hi - ax.lo) * (x1 - x0); }
    double py(double y) const { return y1 - (ay.unit(y) - ay.lo) / (ay.hi - ay.lo) * (y1 - y0); }
};

Axis fitAxis(std::vector<double> values, bool log, double floor) {
    Axis a;
    a.log = log;
    a.floor = floor;
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        const double u = a.unit(v);
        lo = std::min(lo, u);
        hi = std::max(hi, u);
    }
    if (!(hi >= lo)) lo = 0, hi = 1;
    if (log) {
        // Whole decades, with at least 0.3 decade free above and below the data (a point or a
        // reference line on the frame would hide under it).
        a.lo = std::floor(lo - 0.3);
        a.hi = std::ceil(hi + 0.3);
        if (a.hi <= a.lo) a.hi = a.lo + 1;
    } else {
        const double pad = hi > lo ? 0.05 * (hi - lo) : 0.5;
        a.lo = lo >= 0 && lo - pad < 0 ? 0.0 : lo - pad;
        a.hi = hi + pad;
    }
    return a;
}

/// Vertices of marker `shape` (0 disc: none, 1 square, 2 triangle, 3 diamond) of radius r at (x, y).
std::vector<Eigen::Vector3d> markerPolygon(int shape, double x, double y, double r) {
    std::vector<Eigen::Vector3d> v;
    if (shape == 1) {
        const double s = 0.85 * r;
        v = {{x - s, y - s, 0}, {x + s, y - s, 0}, {x + s, y + s, 0}, {x - s, y + s, 0}};
    } else if (shape == 2) {
        v = {{x, y + 1.15 * r, 0}, {x - r, y - 0.6 * r, 0}, {x + r, y - 0.6 * r, 0}};
    } else {
        v = {{x, y + 1.2 * r, 0}, {x + r, y, 0}, {x, y - 1.2 * r, 0}, {x - r, y, 0}};
    }
    return v;
}

class PlotCanvas {
public:
    PlotCanvas(render::GlContext& gl, const PlotOptions& o)
        : o_(o), c_(gl, canvasOptions(o.width, o.height, o.scale), render::Camera::pixels(o.width, o.height)) {}
    // Pixel (x right, y down) to the 2D camera's world (y up).
    Eigen::Vector3d P(double x, double y) const { return {x, o_.height - y, 0}; }
    /// A text size: `base`, or the 1.6 % of the height the legibility gate asks of taller plots.
    float textPx(float base) const { return std::max(base, float(std::ceil(0.0165 * o_.height * 10) / 10)); }
    Canvas& canvas() { return c_; }

    void marker(int style, double x, double y, double r, float alpha) {
        const Color color = render::categorical(style).withAlpha(alpha);
        const int shape = style % 4;
        if (shape == 0) {
            c_.drawPoint(P(x, y), static_cast<float>(r), color, true, 0.8f, roleColor(Role::Ink).withAlpha(alpha));
            return;
        }
        std::vector<Eigen::Vector3d> v = markerPolygon(shape, x, o_.height - y, r);
        c_.drawPolygon(v, color);
        LineStyle edge;
        edge.widthPx = 1.0f;
        edge.color = roleColor(Role::Ink).withAlpha(alpha);
        edge.onTop = true;
        c_.drawPolyline(v, true, edge);
    }

    /// Axes, ticks, tick labels, axis labels, title, subtitle.
    void axes(const PlotArea& f) {
        const LineStyle axis = lineStyle(Role::Ink, 1.5f, false, true);
        const LineStyle grid = lineStyle(Role::Muted, 1.0f, true, false);
        LineStyle faint = grid;
        faint.color = roleColor(Role::Muted).withAlpha(0.35f);
        faint.dashPx = 0;
        const TextStyle xtick{textPx(15.0f), roleColor(Role::Ink), Anchor::Top, false, false};
        const TextStyle ytick{textPx(15.0f), roleColor(Role::Ink), Anchor::Right, false, false};
        auto ticks = [&](const Axis& a, bool isX) {
            const double span = a.hi - a.lo;
            if (a.log) {
                const int step = span > 14 ? 3 : span > 8 ? 2 : 1;
                for (int k = static_cast<int>(a.lo); k <= static_cast<int>(a.hi); ++k) {
                    const double u = (k - a.lo) / span;
                    const bool labelled = (k - static_cast<int>(a.lo)) % step == 0;
                    if (isX) {
                        const double x = f.x0 + u * (f.x1 - f.x0);
                        c_.drawLine(P(x, f.y0), P(x, f.y1), labelled ? grid : faint);
                        c_.drawLine(P(x, f.y1), P(x, f.y1 + 6), axis);
                        if (labelled) drawDecadeLabel(c_, x, f.y1 + 9, k, xtick, o_.height);
                    } else {
                        const double y = f.y1 - u * (f.y1 - f.y0);
                        c_.drawLine(P(f.x0, y), P(f.x1, y), labelled ? grid : faint);
                        c_.drawLine(P(f.x0 - 6, y), P(f.x0, y), axis);
                        if (labelled) drawDecadeLabel(c_, f.x0 - 9, y, k, ytick, o_.height);
                    }
                }
            } else {
                // Linear: 5 intervals at a round step.
                const double raw = span / 5;
                const double mag = std::pow(10.0, std::floor(std::log10(raw)));
                const double step = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
                for (double v = std::ceil(a.lo / step) * step; v <= a.hi + 1e-12 * span; v += step) {
                    const double u = (v - a.lo) / span;
                    char buf[32];
                    std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 * span ? 0.0 : v);
                    if (isX) {
                        const double x = f.x0 + u * (f.x1 - f.x0);
                        c_.drawLine(P(x, f.y0), P(x, f.y1), grid);
                        c_.drawTextPx(x, f.y1 + 9, buf, xtick);
                    } else {
                        const double y = f.y1 - u * (f.y1 - f.y0);
                        c_.drawLine(P(f.x0, y), P(f.x1, y), grid);
                        c_.drawLine(P(f.x0 - 6, y), P(f.x0, y), axis);
                        c_.drawTextPx(f.x0 - 9, y, buf, ytick);
                    }
                }
            }
        };
        ticks(f.ax, true);
        ticks(f.ay, false);
        // The value axes, for the rule that a log axis carries its values (LogAxisWithoutValues).
        c_.noteAxis(P(f.x0, f.y1), P(f.x1, f.y1), f.ax.log);
        c_.noteAxis(P(f.x0, f.y1), P(f.x0, f.y0), f.ay.log);
        c_.drawPolyline({P(f.x0, f.y0), P(f.x1, f.y0), P(f.x1, f.y1), P(f.x0, f.y1)}, true, axis);
        const TextStyle label{17.0f, roleColor(Role::Ink), Anchor::Top, false, true};
        c_.drawTextPx(0.5 * (f.x0 + f.x1), f.y1 + 36, o_.xLabel, label);
        c_.drawTextPx(f.x0 + 2, f.y0 - 10, o_.yLabel,  // right of the axis: clear of the top tick's exponent
                      TextStyle{17.0f, roleColor(Role::Ink), Anchor::BottomLeft, false, true});
        drawTitleAndCaption(c_, o_.title, o_.subtitle);
    }

    /// Legend box in the upper right corner of the plot area.
    /// What a legend row shows: the series' colour (style) with its marker and/or its line.
    struct LegendEntry {
        std::string label;
        int style = 0;
        bool line = false, markers = true;
    };
    void legend(const PlotArea& f, const std::vector<LegendEntry>& entries, bool steps) {
        if (entries.empty()) return;
        const TextStyle text{textPx(15.0f), roleColor(Role::Ink), Anchor::Left, false, false};
        double w = 0;
        for (const auto& e : entries) w = std::max(w, c_.measureText(e.label, text).x());
        const double rowH = 24, boxW = std::min(w + 58, o_.width - f.x1 - 24), boxH = rowH * entries.size() + 12;
        const double bx = f.x1 + 16, by = f.y0;
        // Opaque: a translucent box is drawn after every opaque mesh and would cover the swatches.
        c_.drawPolygon({P(bx, by), P(bx + boxW, by), P(bx + boxW, by + boxH), P(bx, by + boxH)},
                       roleColor(Role::Background));
        c_.drawPolyline({P(bx, by), P(bx + boxW, by), P(bx + boxW, by + boxH), P(bx, by + boxH)}, true,
                        lineStyle(Role::Muted, 1.0f, false, true));
        for (size_t i = 0; i < entries.size(); ++i) {
            const double y = by + 6 + rowH * (i + 0.5);
            const LegendEntry& e = entries[i];
            if (steps || e.line) {  // the series is drawn as a line: so is its swatch
                LineStyle s;
                s.widthPx = steps ? 3.0f : 2.0f;
                s.color = render::categorical(e.style);
                s.onTop = true;
                c_.drawLine(P(bx + 10, y), P(bx + 40, y), s);
            }
            if (!steps && e.markers) marker(e.style, bx + 25, y, 6.0, 1.0f);
            c_.drawTextPx(bx + 50, y, e.label, text);
        }
    }

    render::Image image() { return c_.readPixels(); }

private:
    const PlotOptions& o_;
    Canvas c_;
};

/// Plot area: room on the left for tick labels, on the right for the legend (outside the data).
PlotArea plotArea(const PlotOptions& o) {
    PlotArea f;
    f.x0 = 100;
    f.x1 = o.width - o.legendWidth - 40;
    f.y0 = 92;
    f.y1 = o.height - 100;
    return f;
}

}  // namespace

render::Image drawLogLogPlot(render::GlContext& gl, const PlotOptions& o, const std::vector<PlotSeries>& series) {
    PlotCanvas pc(gl, o);
    PlotArea f = plotArea(o);
    std::vector<double> xs, ys;
    for (const PlotSeries& s : series)
        for (const auto& [x, y] : s.points) xs.push_back(x), ys.push_back(y);
    for (const auto& h : o.hLines) ys.push_back(h.first);
    f.ax = fitAxis(xs, o.logX, o.xFloor);
    f.ay = fitAxis(ys, o.logY, o.yFloor);
    pc.axes(f);
    Canvas& c = pc.canvas();
    for (std::size_t i = 0; i < o.hLines.size(); ++i) {
        const auto& [value, text] = o.hLines[i];
        const double y = f.py(value);
        // Reference lines in ink and grey, never a series' colour, each its own (figure review
        // 2026-11-29: two orange lines beside an orange series); beyond two they repeat grey.
        const Color color = i == 0 ? roleColor(Role::Ink) : roleColor(Role::Muted).scaled(0.75f);
        // 3 px: thick enough to be an obstacle to the placement step, so its name stays off it.
        LineStyle ls = lineStyle(Role::Ink, 3.0f, true, false);
        ls.color = color;
        c.drawLine(pc.P(f.x0, y), pc.P(f.x1, y), ls);
        c.noteSeries(text, color, pc.P(f.x0, y));
        // Named just past the line's right end, in the margin outside the data (inside the axes
        // it sat among the series: the re-render review of 2026-11-29 found "u = 1.1e-16" crossed
        // twice by a median line), or where the placement step finds room.
        TextStyle ts{16.0f, color, Anchor::Center, true, false};
        ts.place = true;
        ts.offsetPx = Eigen::Vector2d(10, 0);
        c.drawText(pc.P(f.x1, y), text, ts);
    }
    // Many points: smaller, translucent markers so that dense clouds stay readable.
    size_t total = 0;
    for (const PlotSeries& s : series) total += s.points.size();
    const double r = total > 2000 ? 3.0 : total > 300 ? 4.5 : 7.0;
    const float alpha = total > 2000 ? 0.55f : 0.9f;
    std::vector<PlotCanvas::LegendEntry> entries;
    // A marker on an earlier series' marker is drawn a size smaller, so a value two series share
    // shows both, one inside the other (the review: Johnson's median hidden under the signed
    // volumes' at 0 error); a point alone keeps the full size.
    std::vector<Eigen::Vector3d> drawnMarkers;  // x, y, radius
    for (const PlotSeries& s : series) {
        entries.push_back({s.label, s.style, s.line && s.points.size() > 1, s.markers});
        if (!s.points.empty())
            c.noteSeries(s.label, render::categorical(s.style),
                         pc.P(f.px(s.points[0].first), f.py(s.points[0].second)));
        if (s.line && s.points.size() > 1) {
            std::vector<Eigen::Vector3d> line;
            for (const auto& [x, y] : s.points) line.push_back(pc.P(f.px(x), f.py(y)));
            LineStyle ls;
            ls.widthPx = 2.0f;
            ls.color = render::categorical(s.style);
            c.drawPolyline(line, false, ls);
        }
        if (!s.markers) continue;
        for (size_t i = 0; i < s.points.size(); ++i) {
            const double x = f.px(s.points[i].first), y = f.py(s.points[i].second);
            double radius = r;
            for (const Eigen::Vector3d& m : drawnMarkers)
                if (std::hypot(m.x() - x, m.y() - y) < 0.5 * r) radius = std::min(radius, m.z() - 0.15 * r);
            radius = std::max(radius, 0.45 * r);
            pc.marker(s.style, x, y, radius, alpha);
            drawnMarkers.emplace_back(x, y, radius);
            if (i < s.pointLabels.size() && !s.pointLabels[i].empty())
                c.drawTextPx(x + radius + 3, y - radius - 1, s.pointLabels[i],
                             TextStyle{pc.textPx(12.0f), roleColor(Role::Ink), Anchor::BottomLeft, true, false});
        }
    }
    pc.legend(f, entries, false);
    return pc.image();
}

render::Image drawDecadeHistogram(render::GlContext& gl, const PlotOptions& o,
                                  const std::vector<std::pair<std::string, std::vector<double>>>& series) {
    PlotCanvas pc(gl, o);
    PlotArea f = plotArea(o);
    double maxValue = o.xFloor * 10;
    for (const auto& s : series)
        for (double v : s.second)
            if (std::isfinite(v)) maxValue = std::max(maxValue, v);
    const int k0 = static_cast<int>(std::floor(std::log10(o.xFloor)));
    const int k1 = std::max(k0 + 1, static_cast<int>(std::ceil(std::log10(maxValue))));
    f.ax.log = true;
    f.ax.floor = o.xFloor;
    f.ax.lo = k0;
    f.ax.hi = k1;
    // Fractions per bin [10^k, 10^(k+1)); the first bin also holds everything <= floor.
    std::vector<std::vector<double>> frac;
    double top = 0;
    for (const auto& s : series) {
        std::vector<double> h(k1 - k0, 0.0);
        for (double v : s.second) {
            int k = std::isfinite(v) && v > o.xFloor ? static_cast<int>(std::floor(std::log10(v))) : k0;
            k = std::clamp(k, k0, k1 - 1);
            h[k - k0] += 1.0;
        }
        for (double& x : h) {
            x /= std::max<size_t>(1, s.second.size());
            top = std::max(top, x);
        }
        frac.push_back(h);
    }
    f.ay.log = false;
    f.ay.lo = 0;
    f.ay.hi = std::max(0.05, std::min(1.0, top * 1.15));
    pc.axes(f);
    Canvas& c = pc.canvas();
    std::vector<PlotCanvas::LegendEntry> entries;
    for (size_t si = 0; si < series.size(); ++si) {
        const int style = static_cast<int>(si);
        entries.push_back({series[si].first, style, true, false});
        c.noteSeries(series[si].first, render::categorical(style), pc.P(0.5 * (f.x0 + f.x1), f.y1));
        // Step outlines only, slightly offset per series so equal bins stay visible: three
        // translucent fills over one bin mixed into a grey-green no legend names (the review).
        const double dx = 2.0 * si;
        std::vector<Eigen::Vector3d> outline;
        for (int k = k0; k < k1; ++k) {
            const double xa = f.px(std::pow(10.0, k)) + dx, xb = f.px(std::pow(10.0, k + 1)) + dx;
            const double y = f.py(frac[si][k - k0]);
            outline.push_back(pc.P(xa, y));
            outline.push_back(pc.P(xb, y));
        }
        LineStyle ls;
        ls.widthPx = 2.5f;
        ls.color = render::categorical(style);
        ls.onTop = true;
        c.drawPolyline(outline, false, ls);
    }
    pc.legend(f, entries, true);
    return pc.image();
}

double roundTickStep(double span, int intervals) {
    const double raw = span / intervals;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    return raw / mag <= 1.0 ? mag : raw / mag <= 2.0 ? 2 * mag : raw / mag <= 5.0 ? 5 * mag : 10 * mag;
}

render::Image drawBoundsPlot(render::GlContext& gl, int width, int height, int scale, const BoundsPlot& plot) {
    using render::Canvas, render::TextStyle, render::Anchor, render::Camera;
    const int W = width, H = height;
    Canvas c(gl, canvasOptions(W, H, scale), Camera::pixels(W, H));  // world = pixels, y up
    const double x0 = 110, x1 = W - 60, y0 = 125, y1 = H - 100;
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < plot.iterations.size(); ++i) {
        lo = std::min({lo, plot.lower[i], plot.upper[i]});
        hi = std::max({hi, plot.lower[i], plot.upper[i]});
    }
    if (!(hi > lo)) hi = lo + 1e-9 + std::abs(lo) * 1e-6;
    // The axis from a round tick below the data to one above, so its base is labelled (the
    // review: a base of 0.03 unlabelled read as 0).
    const double step = roundTickStep(hi - lo, 5);
    lo = std::floor(lo / step) * step;
    hi = std::ceil(hi / step) * step;
    const int n = int(plot.iterations.size());
    auto X = [&](double it) { return n > 1 ? x0 + (it - 1) / (n - 1) * (x1 - x0) : 0.5 * (x0 + x1); };
    auto Y = [&](double v) { return y0 + (v - lo) / (hi - lo) * (y1 - y0); };
    auto P = [](double x, double y) { return Eigen::Vector3d(x, y, 0); };
    const LineStyle axis = lineStyle(Role::Ink, 2.0f);
    c.drawLine(P(x0, y0), P(x1, y0), axis);
    c.drawLine(P(x0, y0), P(x0, y1), axis);
    // Tick labels at 15 px, or the 1.6 % of the height the legibility gate asks of taller frames.
    const float tickPx = std::max(15.0f, float(std::ceil(0.0165 * H * 10) / 10));
    TextStyle tick{tickPx, roleColor(Role::Ink), Anchor::Top, false, false};
    const int xStep = std::max(1, n / 12);
    for (int i = 1; i <= n; i += xStep) {
        c.drawLine(P(X(i), y0), P(X(i), y0 - 6), axis);
        c.drawText(P(X(i), y0 - 10), std::to_string(i), tick);
    }
    TextStyle ytick{tickPx, roleColor(Role::Ink), Anchor::Right, false, false};
    // Round values (the review: ticks at −0.1522, 0.4556, ... read as data).
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) {
        if (std::abs(v) < 1e-9 * step) v = 0;
        c.drawLine(P(x0, Y(v)), P(x1, Y(v)), lineStyle(Role::Muted, 1.0f, true));
        c.drawText(P(x0 - 10, Y(v)), formatNumber(v), ytick);
    }
    c.drawText(P(0.5 * (x0 + x1), y0 - 40), plot.xLabel, TextStyle{17.0f, roleColor(Role::Ink), Anchor::Top, false, true});
    c.drawText(P(x0, y1 + 14), plot.yLabel, TextStyle{17.0f, roleColor(Role::Ink), Anchor::BottomLeft, false, true});
    std::vector<Eigen::Vector3d> lower, upper;
    for (std::size_t i = 0; i < plot.iterations.size(); ++i) {
        lower.push_back(P(X(plot.iterations[i]), Y(plot.lower[i])));
        upper.push_back(P(X(plot.iterations[i]), Y(plot.upper[i])));
    }
    c.drawPolyline(upper, false, lineStyle(Role::ShapeB, 3.0f));
    c.drawPolyline(lower, false, lineStyle(Role::ShapeA, 3.0f));
    for (const Eigen::Vector3d& p : upper) c.drawPoint(p, 5.0f, roleColor(Role::ShapeB));
    for (const Eigen::Vector3d& p : lower) c.drawPoint(p, 5.0f, roleColor(Role::ShapeA));
    // Legend, top right.
    const double lx = x1 - 330, ly = y1 - 10;
    c.drawLine(P(lx, ly), P(lx + 40, ly), lineStyle(Role::ShapeB, 3.0f));
    c.drawText(P(lx + 50, ly), plot.upperName, TextStyle{std::max(16.0f, tickPx), roleColor(Role::Ink), Anchor::Left, true, false});
    c.drawLine(P(lx, ly - 28), P(lx + 40, ly - 28), lineStyle(Role::ShapeA, 3.0f));
    c.drawText(P(lx + 50, ly - 28), plot.lowerName, TextStyle{std::max(16.0f, tickPx), roleColor(Role::Ink), Anchor::Left, true, false});
    drawTitleAndCaption(c, plot.title, plot.caption);
    return c.readPixels();
}

}  // namespace cdlab::demos
