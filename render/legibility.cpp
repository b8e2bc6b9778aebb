#include "render/legibility.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/label_placement.h"

namespace cdlab::render {

const char* nameOf(LegibilityKind kind) {
    switch (kind) {
        case LegibilityKind::LabelsOverlap: return "labels overlap";
        case LegibilityKind::LabelsRunTogether: return "labels run together";
        case LegibilityKind::LabelOnMarker: return "label on a marker it does not name";
        case LegibilityKind::LabelOutsidePanel: return "label outside its panel";
        case LegibilityKind::TextTooSmall: return "text too small";
        case LegibilityKind::Unplaced: return "label could not be placed";
        case LegibilityKind::LabelOnStroke: return "label crosses a stroke";
        case LegibilityKind::LabelNearerOther: return "label nearer another anchor than its own";
        case LegibilityKind::FontBelowTarget: return "font below the 1.6 % target";
        case LegibilityKind::QuantityTooSmall: return "quantity drawn too small";
        case LegibilityKind::BodyCutByPanel: return "body cut by its panel's edge";
        case LegibilityKind::SeparatedBodiesOverlap: return "separated bodies overlap on the picture";
        case LegibilityKind::FeatureEdgeOn: return "highlighted feature seen edge-on";
        case LegibilityKind::FeatureFromBehind: return "the step's feature seen from behind";
        case LegibilityKind::HiddenFilled: return "hidden feature drawn filled";
        case LegibilityKind::LogAxisWithoutValues: return "log axis without values";
        case LegibilityKind::SeriesShareColour: return "two series share a colour";
        case LegibilityKind::StepFeatureFaded: return "the step's feature does not show its colour";
    }
    return "?";
}

namespace {

std::string boxText(const Box& b) {
    char s[96];
    std::snprintf(s, sizeof s, "[%.0f, %.0f, %.0f, %.0f]", b.x0, b.y0, b.x1, b.y1);
    return s;
}

// The panel a point belongs to: the smallest one holding it (null: none).
const Box* homePanel(const FigureLayout& layout, const Eigen::Vector2d& p) {
    const Box* best = nullptr;
    for (const Box& panel : layout.panels)
        if (panel.contains(p) && (!best || panel.width() * panel.height() < best->width() * best->height()))
            best = &panel;
    return best;
}

// The panel a label belongs to: its anchor's (or its box centre's).
const Box* homePanel(const FigureLayout& layout, const LayoutLabel& label) {
    return homePanel(layout, label.anchor ? *label.anchor : label.box.center());
}

// How far `inner` sticks out of `outer`, px (0 when inside).
double outside(const Box& outer, const Box& inner) {
    return std::max({0.0, outer.x0 - inner.x0, outer.y0 - inner.y0, inner.x1 - outer.x1, inner.y1 - outer.y1});
}

// Length of segment ab inside box (Liang–Barsky clipping), px.
double lengthInside(const Box& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    double t0, t1;
    if (!box.clip(a, b, t0, t1)) return 0;
    // A zero-length stroke (a dot) inside the box counts as its width.
    const double len = (b - a).norm();
    return len > 0 ? (t1 - t0) * len : 1.0;
}

// Labels crossing strokes, and labels nearer another anchor than their own.
void strokeAndAnchorRules(const FigureLayout& layout, std::vector<LegibilityProblem>& out) {
    const std::vector<LayoutLabel>& labels = layout.labels;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        const Box& b = labels[i].box;
        double worst = 0;
        const LayoutStroke* hit = nullptr;
        for (const LayoutStroke& k : layout.strokes) {
            // Its own leader, its own body's outline; a band at least as wide as the text is a fill
            // behind it (a table's highlighted row).
            if (k.leaderOf == int(i) || k.outlineOf == int(i) || k.width >= labels[i].lineHeight) continue;
            // The stroke's centre line against the box grown by its half width, less the graze margin.
            const double h = 0.5 * k.width - kStrokeGrazePx;
            const double inside = lengthInside(Box{b.x0 - h, b.y0 - h, b.x1 + h, b.y1 + h}, k.a, k.b);
            if (inside > worst) worst = inside, hit = &k;
        }
        if (hit && worst >= 1.0) {  // under a pixel: the stroke only nicks the box's corner
            char s[128];
            std::snprintf(s, sizeof s, "stroke (%.0f, %.0f)-(%.0f, %.0f) %.1f px wide, %.0f px inside its box",
                          hit->a.x(), hit->a.y(), hit->b.x(), hit->b.y(), hit->width, worst);
            out.push_back({LegibilityKind::LabelOnStroke, labels[i].text, s, worst});
        }
        if (!labels[i].anchor) continue;
        const double own = b.distanceTo(*labels[i].anchor);
        // Only the points of its own panel compete: a panel's border separates what it names from
        // another panel's points (a 3D view's label is not read as a plot's tick).
        const Box* home = homePanel(layout, labels[i]);
        for (std::size_t j = 0; j < labels.size(); ++j) {
            if (j == i || !labels[j].anchor || (*labels[j].anchor - *labels[i].anchor).norm() < 1.0) continue;
            if (homePanel(layout, labels[j]) != home) continue;
            const double other = b.distanceTo(*labels[j].anchor);
            if (other + 0.5 < own) {
                char s[128];
                std::snprintf(s, sizeof s, "%.1f px from \"%s\"'s anchor, %.1f px from its own", other,
                              labels[j].text.c_str(), own);
                out.push_back({LegibilityKind::LabelNearerOther, labels[i].text, s, own - other, labels[j].text});
                break;
            }
        }
    }
}

// A body cut by the edge of its panel (the smallest holding its outline's centre).
void bodyRules(const FigureLayout& layout, std::vector<LegibilityProblem>& out) {
    const auto bounds = [](const LayoutBody& b) {
        Box box{INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (const Eigen::Vector2d& p : b.outline)
            box = {std::min(box.x0, p.x()), std::min(box.y0, p.y()), std::max(box.x1, p.x()), std::max(box.y1, p.y())};
        return box;
    };
    for (const LayoutBody& b : layout.bodies) {
        if (b.outline.empty()) continue;
        const Box box = bounds(b);
        const Box* home = homePanel(layout, box.center());
        if (!home) continue;
        const double off = outside(*home, box);
        if (off > kBodySlackPx)
            out.push_back({LegibilityKind::BodyCutByPanel, b.name,
                           "outline " + boxText(box) + " vs panel " + boxText(*home), off});
    }
}

// How deep two convex outlines overlap, px: the least overlap of their projections on any edge
// normal of either (separating axis theorem; <= 0: a gap). Fewer than 3 points: no area, 0.
double overlapDepth(const std::vector<Eigen::Vector2d>& p, const std::vector<Eigen::Vector2d>& q) {
    if (p.size() < 3 || q.size() < 3) return 0;
    double depth = INFINITY;
    for (const std::vector<Eigen::Vector2d>* poly : {&p, &q})
        for (std::size_t i = 0; i < poly->size(); ++i) {
            const Eigen::Vector2d e = (*poly)[(i + 1) % poly->size()] - (*poly)[i];
            if (e.norm() == 0) continue;
            const Eigen::Vector2d n = Eigen::Vector2d(-e.y(), e.x()).normalized();
            double pl = INFINITY, ph = -INFINITY, ql = INFINITY, qh = -INFINITY;
            for (const Eigen::Vector2d& v : p) pl = std::min(pl, n.dot(v)), ph = std::max(ph, n.dot(v));
            for (const Eigen::Vector2d& v : q) ql = std::min(ql, n.dot(v)), qh = std::max(qh, n.dot(v));
            depth = std::min(depth, std::min(ph, qh) - std::max(pl, ql));
        }
    return depth;
}

// Bodies the trace says are apart, overlapping on the picture (their panel's two outlines).
void separationRules(const FigureLayout& layout, std::vector<LegibilityProblem>& out) {
    for (const LayoutBody& a : layout.bodies) {
        if (a.apartFrom.empty() || a.outline.empty()) continue;
        const Box* home = homePanel(layout, a.outline.front());
        for (const LayoutBody& b : layout.bodies) {
            if (b.name != a.apartFrom || b.outline.empty() || homePanel(layout, b.outline.front()) != home) continue;
            const double depth = overlapDepth(a.outline, b.outline);
            if (depth > kBodySlackPx) {
                char s[96];
                std::snprintf(s, sizeof s, "and \"%s\" overlap %.1f px deep", b.name.c_str(), depth);
                out.push_back({LegibilityKind::SeparatedBodiesOverlap, a.name, s, depth});
            }
        }
    }
}

// Highlighted features against the camera: edge-on, the step's from behind, hidden ones filled.
void viewRules(const FigureLayout& layout, std::vector<LegibilityProblem>& out) {
    for (const LayoutFeature& f : layout.features) {
        char s[128];
        if (f.step && f.dimension > 0 && f.foreshortening < kEdgeOnFraction) {
            std::snprintf(s, sizeof s, "%s at %.0f deg to the view (under %.0f%% of it shows)",
                          f.dimension == 2 ? "normal" : "direction",
                          std::acos(std::clamp(f.dimension == 2 ? f.foreshortening
                                                                : std::sqrt(1 - f.foreshortening * f.foreshortening),
                                               0.0, 1.0)) * 180 / M_PI,
                          100 * kEdgeOnFraction);
            out.push_back({LegibilityKind::FeatureEdgeOn, f.name, s, kEdgeOnFraction - f.foreshortening});
        }
        if (f.facing >= 0) continue;
        std::snprintf(s, sizeof s, "every face holding it turned away (cos %.2f)", f.facing);
        if (f.step) out.push_back({LegibilityKind::FeatureFromBehind, f.name, s, -f.facing});
        if (f.filled) out.push_back({LegibilityKind::HiddenFilled, f.name, s, -f.facing});
    }
}

// Plots: a log axis carries its values; two series apart by name are apart by colour.
void plotRules(const FigureLayout& layout, std::vector<LegibilityProblem>& out) {
    for (const LayoutAxis& axis : layout.axes) {
        if (!axis.log) continue;
        const Eigen::Vector2d d = axis.b - axis.a;
        int values = 0;
        for (const LayoutLabel& l : layout.labels) {
            if (l.text.find_first_of("0123456789") == std::string::npos) continue;
            // Beside the axis: near it, and level with some point of it.
            const double t = d.squaredNorm() > 0 ? (l.box.center() - axis.a).dot(d) / d.squaredNorm() : 0;
            if (t < -0.02 || t > 1.02) continue;
            double t0, t1;
            const Box reach{l.box.x0 - kAxisValueReachPx, l.box.y0 - kAxisValueReachPx,
                            l.box.x1 + kAxisValueReachPx, l.box.y1 + kAxisValueReachPx};
            if (reach.clip(axis.a, axis.b, t0, t1)) ++values;
        }
        if (values < kMinLogAxisValues) {
            char s[128];
            std::snprintf(s, sizeof s, "(%.0f, %.0f)-(%.0f, %.0f): %d numbers beside it", axis.a.x(), axis.a.y(),
                          axis.b.x(), axis.b.y(), values);
            out.push_back({LegibilityKind::LogAxisWithoutValues, "axis", s, double(kMinLogAxisValues - values)});
        }
    }
    const auto channel = [](unsigned rgb, int shift) { return int((rgb >> shift) & 0xFF); };
    const std::vector<LayoutSeries>& k = layout.series;
    for (std::size_t i = 0; i < k.size(); ++i)
        for (std::size_t j = i + 1; j < k.size(); ++j) {
            if (k[i].name == k[j].name || homePanel(layout, k[i].at) != homePanel(layout, k[j].at)) continue;
            int delta = 0;
            for (const int shift : {0, 8, 16})
                delta = std::max(delta, std::abs(channel(k[i].rgb, shift) - channel(k[j].rgb, shift)));
            if (delta <= int(kSameColourDelta)) {
                char s[96];
                std::snprintf(s, sizeof s, "and \"%s\" both #%06X", k[j].name.c_str(), k[i].rgb);
                out.push_back({LegibilityKind::SeriesShareColour, k[i].name, s, double(kSameColourDelta + 1 - delta)});
            }
        }
}

}  // namespace

std::string describe(const LegibilityProblem& p) {
    return std::string(nameOf(p.kind)) + ": \"" + p.text + "\" " + p.detail;
}

std::vector<LegibilityProblem> checkLegibility(const FigureLayout& layout, int width, int height) {
    std::vector<LegibilityProblem> out;
    const std::vector<LayoutLabel>& labels = layout.labels;
    for (std::size_t i = 0; i < labels.size(); ++i)
        for (std::size_t j = i + 1; j < labels.size(); ++j) {
            const Box &a = labels[i].box, &b = labels[j].box;
            const double area = a.overlapArea(b);
            if (area > kOverlapSlackArea) {
                out.push_back({LegibilityKind::LabelsOverlap, labels[i].text, "\"" + labels[j].text + "\"", area});
                continue;
            }
            // Side by side on one line (sharing half the lower height) with less than a space between.
            const double shared = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
            const double line = std::min(labels[i].lineHeight, labels[j].lineHeight);
            const double gap = std::max(a.x0, b.x0) - std::min(a.x1, b.x1);
            if (shared >= 0.5 * std::min(a.height(), b.height()) && gap < kMinGapFraction * line) {
                char s[64];
                std::snprintf(s, sizeof s, " %.1f px apart < %.1f px", gap, kMinGapFraction * line);
                out.push_back({LegibilityKind::LabelsRunTogether, labels[i].text, "\"" + labels[j].text + "\"" + s,
                               kMinGapFraction * line - gap});
            }
        }
    for (const LayoutMarker& m : layout.markers)
        for (std::size_t i = 0; i < labels.size(); ++i) {
            // Every label whose point is on the marker is about it (a node's name and its count).
            if (m.label == int(i) || (labels[i].anchor && m.box.contains(*labels[i].anchor))) continue;
            const double area = labels[i].box.overlapArea(m.box);
            if (area > kOverlapSlackArea)
                out.push_back({LegibilityKind::LabelOnMarker, labels[i].text,
                               "marker " + boxText(m.box) +
                                   (m.label >= 0 ? " (named \"" + labels[std::size_t(m.label)].text + "\")" : ""),
                               area});
        }
    const Box image{0, 0, double(width), double(height)};
    for (const LayoutLabel& l : labels) {
        const Box* panel = homePanel(layout, l);
        const Box& home = panel ? *panel : image;
        const double off = std::max(outside(home, l.box), outside(image, l.box));
        if (off > 0.5)
            out.push_back({LegibilityKind::LabelOutsidePanel, l.text,
                           "box " + boxText(l.box) + " vs panel " + boxText(home), off});
        const double minimum = kMinLineHeightFraction * height;
        if (l.lineHeight < minimum) {
            char s[96];
            std::snprintf(s, sizeof s, "font size %.1f px < %.1f px", l.lineHeight, minimum);
            out.push_back({LegibilityKind::TextTooSmall, l.text, s, minimum - l.lineHeight});
        } else if (l.lineHeight < kTargetFontFraction * height) {
            char s[96];
            std::snprintf(s, sizeof s, "font size %.1f px < %.1f px", l.lineHeight, kTargetFontFraction * height);
            out.push_back({LegibilityKind::FontBelowTarget, l.text, s, kTargetFontFraction * height - l.lineHeight});
        }
    }
    strokeAndAnchorRules(layout, out);
    // Each named quantity at its longest (an inset that zooms on it draws it again, larger).
    std::vector<std::pair<std::string, double>> longest;
    for (const LayoutQuantity& q : layout.quantities) {
        auto it = std::find_if(longest.begin(), longest.end(), [&](const auto& e) { return e.first == q.name; });
        if (it == longest.end()) longest.emplace_back(q.name, q.px);
        else it->second = std::max(it->second, q.px);
    }
    for (const auto& [name, px] : longest)
        if (!(px >= kMinQuantityPx)) {
            char s[96];
            std::snprintf(s, sizeof s, "drawn %.1f px long < %.0f px (no inset draws it larger)", px, kMinQuantityPx);
            out.push_back({LegibilityKind::QuantityTooSmall, name, s, kMinQuantityPx - px});
        }
    bodyRules(layout, out);
    separationRules(layout, out);
    viewRules(layout, out);
    plotRules(layout, out);
    for (const std::string& t : layout.unplaced)
        out.push_back({LegibilityKind::Unplaced, t, "no free position around its anchor", 1e9});
    std::stable_sort(out.begin(), out.end(),
                     [](const LegibilityProblem& a, const LegibilityProblem& b) { return a.severity > b.severity; });
    return out;
}

namespace {

// Whether a sample of a feature can be judged: no label or marker drawn over it and, inside a face,
// no stroke (an arrow or a leader crossing it); an edge's or a vertex's samples are its own stroke.
bool judgeable(const FigureLayout& layout, const LayoutFeature& f, const Eigen::Vector2d& p) {
    for (const LayoutLabel& l : layout.labels)  // with its halo
        if (Box{l.box.x0 - 3, l.box.y0 - 3, l.box.x1 + 3, l.box.y1 + 3}.contains(p)) return false;
    for (const LayoutMarker& m : layout.markers)
        if (m.box.contains(p)) return false;
    if (f.dimension == 1) return true;
    for (const LayoutStroke& k : layout.strokes)
        if (pointSegmentDistance(p, k.a, k.b) <= 0.5 * k.width + 1.5) return false;
    return true;
}

}  // namespace

std::vector<LegibilityProblem> checkFigure(const Image& image) {
    std::vector<LegibilityProblem> out = checkLegibility(image.layout, image.width, image.height);
    const FigureLayout& layout = image.layout;
    std::vector<std::string> shownSomewhere;  // a feature a zoomed inset shows in its colour
    std::vector<LegibilityProblem> faded;
    for (const LayoutFeature& f : layout.features) {
        // A vertex is a marker drawn over everything, its colour a ring round whatever point sits on it.
        if (!f.step || f.rgb < 0 || f.facing < 0 || f.dimension == 0 || (f.dimension == 2 && !f.filled)) continue;
        int judged = 0, shown = 0, worst = 0;
        unsigned seen = 0;
        for (const Eigen::Vector2d& p : f.samples) {
            const int x = int(std::floor(p.x() * image.scale)), y = int(std::floor(p.y() * image.scale));
            if (x < 0 || y < 0 || x >= image.width || y >= image.height || !judgeable(layout, f, p)) continue;
            const std::uint8_t* px = &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
            int delta = 0;
            for (int c = 0; c < 3; ++c) delta = std::max(delta, std::abs(int(px[c]) - ((f.rgb >> (16 - 8 * c)) & 0xFF)));
            ++judged;
            if (delta <= int(kHighlightDelta)) ++shown;
            else if (delta > worst) worst = delta, seen = unsigned(px[0]) << 16 | unsigned(px[1]) << 8 | px[2];
        }
        if (judged == 0) continue;
        if (2 * shown >= judged) {
            shownSomewhere.push_back(f.name);
            continue;
        }
        char s[128];
        std::snprintf(s, sizeof s, "drawn #%06X, %d of %d points show it (one shows #%06X, %d off)", unsigned(f.rgb),
                      shown, judged, seen, worst);
        faded.push_back({LegibilityKind::StepFeatureFaded, f.name, s, double(worst)});
    }
    for (LegibilityProblem& p : faded)
        if (std::find(shownSomewhere.begin(), shownSomewhere.end(), p.text) == shownSomewhere.end())
            out.push_back(std::move(p));
    std::stable_sort(out.begin(), out.end(), [](const LegibilityProblem& a, const LegibilityProblem& b) {
        return a.severity > b.severity;
    });
    return out;
}

}  // namespace cdlab::render
