#include "render/figure_layout.h"

#include <algorithm>
#include <cmath>

namespace cdlab::render {

double Box::overlapArea(const Box& o) const {
    const double w = std::min(x1, o.x1) - std::max(x0, o.x0);
    const double h = std::min(y1, o.y1) - std::max(y0, o.y0);
    return w > 0 && h > 0 ? w * h : 0.0;
}

bool Box::contains(const Box& o, double slack) const {
    return o.x0 >= x0 - slack && o.y0 >= y0 - slack && o.x1 <= x1 + slack && o.y1 <= y1 + slack;
}

void FigureLayout::append(const FigureLayout& other, double dx, double dy) {
    const int base = int(labels.size());
    for (const Box& p : other.panels) panels.push_back(p.translated(dx, dy));
    for (const LayoutLabel& l : other.labels) {
        LayoutLabel moved = l;
        moved.box = l.box.translated(dx, dy);
        if (l.anchor) moved.anchor = *l.anchor + Eigen::Vector2d(dx, dy);
        labels.push_back(std::move(moved));
    }
    for (const LayoutMarker& m : other.markers)
        markers.push_back({m.box.translated(dx, dy), m.label >= 0 ? m.label + base : -1});
    const Eigen::Vector2d d(dx, dy);
    for (const LayoutStroke& k : other.strokes)
        strokes.push_back({k.a + d, k.b + d, k.width, k.leaderOf >= 0 ? k.leaderOf + base : -1,
                           k.outlineOf >= 0 ? k.outlineOf + base : -1});
    quantities.insert(quantities.end(), other.quantities.begin(), other.quantities.end());
    for (LayoutBody b : other.bodies) {
        for (Eigen::Vector2d& p : b.outline) p += d;
        bodies.push_back(std::move(b));
    }
    for (LayoutFeature f : other.features) {
        f.at += d;
        for (Eigen::Vector2d& p : f.samples) p += d;
        features.push_back(std::move(f));
    }
    for (const LayoutAxis& a : other.axes) axes.push_back({a.a + d, a.b + d, a.log});
    for (LayoutSeries k : other.series) series.push_back((k.at += d, k));
    unplaced.insert(unplaced.end(), other.unplaced.begin(), other.unplaced.end());
}

void FigureLayout::cover(const Box& area) {
    std::vector<int> newIndex(labels.size(), -1);
    std::vector<LayoutLabel> keptLabels;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (area.contains(labels[i].box)) continue;
        newIndex[i] = int(keptLabels.size());
        keptLabels.push_back(std::move(labels[i]));
    }
    labels = std::move(keptLabels);
    const auto remap = [&](int i) { return i >= 0 ? newIndex[std::size_t(i)] : -1; };
    std::vector<LayoutMarker> keptMarkers;
    for (const LayoutMarker& m : markers)
        if (!area.contains(m.box)) keptMarkers.push_back({m.box, remap(m.label)});
    markers = std::move(keptMarkers);
    std::vector<LayoutStroke> keptStrokes;
    for (const LayoutStroke& k : strokes) {
        LayoutStroke s = k;
        s.leaderOf = remap(k.leaderOf), s.outlineOf = remap(k.outlineOf);
        double t0 = 0, t1 = 0;
        if (!area.clip(k.a, k.b, t0, t1) || t1 <= t0) {
            keptStrokes.push_back(s);
            continue;
        }
        const Eigen::Vector2d d = k.b - k.a;
        if (t0 > 0) {
            LayoutStroke before = s;
            before.b = k.a + t0 * d;
            keptStrokes.push_back(before);
        }
        if (t1 < 1) {
            LayoutStroke after = s;
            after.a = k.a + t1 * d;
            keptStrokes.push_back(after);
        }
    }
    strokes = std::move(keptStrokes);
    // What the picture pasted over it hides is not seen from the camera's side any more.
    std::erase_if(features, [&](const LayoutFeature& f) { return area.contains(f.at); });
    for (LayoutFeature& f : features)
        std::erase_if(f.samples, [&](const Eigen::Vector2d& p) { return area.contains(p); });
    std::erase_if(axes, [&](const LayoutAxis& a) { return area.contains(a.a) && area.contains(a.b); });
    std::erase_if(series, [&](const LayoutSeries& k) { return area.contains(k.at); });
}

Eigen::Vector2d Box::nearest(const Eigen::Vector2d& p) const {
    return {std::clamp(p.x(), x0, x1), std::clamp(p.y(), y0, y1)};
}

double Box::distanceTo(const Eigen::Vector2d& p) const {
    const double dx = std::max({x0 - p.x(), 0.0, p.x() - x1});
    const double dy = std::max({y0 - p.y(), 0.0, p.y() - y1});
    return std::hypot(dx, dy);
}

bool Box::clip(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double& t0, double& t1) const {
    t0 = 0, t1 = 1;
    const Eigen::Vector2d d = b - a;
    const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
    const double q[4] = {a.x() - x0, x1 - a.x(), a.y() - y0, y1 - a.y()};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

FigureLayout FigureLayout::scaled(double s) const {
    FigureLayout out = *this;
    for (Box& p : out.panels) p = p.scaled(s);
    for (LayoutLabel& l : out.labels) {
        l.box = l.box.scaled(s);
        if (l.anchor) l.anchor = *l.anchor * s;
        l.lineHeight *= s;
    }
    for (LayoutMarker& m : out.markers) m.box = m.box.scaled(s);
    for (LayoutStroke& k : out.strokes) k.a *= s, k.b *= s, k.width *= s;
    for (LayoutQuantity& q : out.quantities) q.px *= s;
    for (LayoutBody& b : out.bodies)
        for (Eigen::Vector2d& p : b.outline) p *= s;
    for (LayoutFeature& f : out.features) {
        f.at *= s;
        for (Eigen::Vector2d& p : f.samples) p *= s;
    }
    for (LayoutAxis& a : out.axes) a.a *= s, a.b *= s;
    for (LayoutSeries& k : out.series) k.at *= s;
    return out;
}

}  // namespace cdlab::render
