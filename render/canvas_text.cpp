// Canvas text: UTF-8 decoding, line layout and anchoring (one code path for measuring and
// drawing), and the per-frame placement of every text box and point label (layoutTexts).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "render/canvas_internal.h"
#include "render/label_placement.h"
#include "render/legibility.h"

namespace cdlab::render {

namespace canvas_detail {

/// UTF-8 to code points; malformed bytes become U+FFFD (drawn as '?').
std::vector<std::uint32_t> decodeUtf8(const std::string& s) {
    std::vector<std::uint32_t> out;
    std::size_t i = 0;
    while (i < s.size()) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        const int extra = c < 0x80 ? 0 : (c & 0xE0) == 0xC0 ? 1 : (c & 0xF0) == 0xE0 ? 2 : (c & 0xF8) == 0xF0 ? 3 : -1;
        std::uint32_t cp = extra == 0 ? c : extra == 1 ? (c & 0x1Fu) : extra == 2 ? (c & 0x0Fu) : (c & 0x07u);
        bool ok = extra >= 0 && i + std::size_t(extra) < s.size();
        for (int k = 1; ok && k <= extra; ++k) {
            const unsigned char cc = static_cast<unsigned char>(s[i + std::size_t(k)]);
            ok = (cc & 0xC0) == 0x80;
            cp = (cp << 6) | (cc & 0x3Fu);
        }
        if (!ok) {  // bad lead byte, truncated or broken sequence: one replacement, resync at the next byte
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        out.push_back(cp);
        i += std::size_t(extra) + 1;
    }
    return out;
}

/// Layout at `sizePx` (stb "pixel height": ascent - descent). The same code measures (output
/// pixels) and draws (render pixels), so the measured box is the drawn box.
TextLayout layoutText(const FontFace& face, const std::string& text, double sizePx) {
    TextLayout L;
    const double scale = sizePx / double(face.ascent - face.descent);
    L.ascent = face.ascent * scale;
    L.lineHeight = (face.ascent - face.descent + face.lineGap) * scale;
    L.lines.emplace_back();
    std::uint32_t previous = 0;
    for (std::uint32_t cp : decodeUtf8(text)) {
        if (cp == '\n') {
            L.lines.emplace_back();
            previous = 0;
            continue;
        }
        if (cp == '\t') cp = ' ';
        if (!face.available.count(cp)) cp = '?';
        TextLayout::Line& line = L.lines.back();
        if (previous) line.width += scale * stbtt_GetCodepointKernAdvance(&face.info, int(previous), int(cp));
        int advance = 0, lsb = 0;
        stbtt_GetCodepointHMetrics(&face.info, int(cp), &advance, &lsb);
        line.codepoints.push_back(cp);
        line.penX.push_back(line.width);
        line.width += scale * advance;
        previous = cp;
    }
    for (const auto& line : L.lines) L.width = std::max(L.width, line.width);
    L.height = sizePx + double(L.lines.size() - 1) * L.lineHeight;
    return L;
}

/// Top-left of the text box whose `anchor` point sits at (x, y); horizontal alignment of lines.
Vector2d boxOrigin(Anchor anchor, double x, double y, double w, double h, double& align) {
    double fx = 0.5, fy = 0.5;  // fraction of the box left of / above the anchor point
    switch (anchor) {
        case Anchor::Center: break;
        case Anchor::Left: fx = 0; break;
        case Anchor::Right: fx = 1; break;
        case Anchor::Top: fy = 0; break;
        case Anchor::Bottom: fy = 1; break;
        case Anchor::TopLeft: fx = 0, fy = 0; break;
        case Anchor::TopRight: fx = 1, fy = 0; break;
        case Anchor::BottomLeft: fx = 0, fy = 1; break;
        case Anchor::BottomRight: fx = 1, fy = 1; break;
    }
    align = fx;
    return {x - fx * w, y - fy * h};
}

}  // namespace canvas_detail

// Clips segment ab to the box; false when nothing of it is inside.
static bool clipToBox(const Box& box, Vector2d& a, Vector2d& b) {
    double t0, t1;
    if (!box.clip(a, b, t0, t1)) return false;
    const Vector2d a0 = a, d = b - a;
    a = a0 + t0 * d;
    b = a0 + t1 * d;
    return true;
}

// Which label each stroke's body and each marker belong to: a stroke outlines the body its owner
// names (the first label with that id, setStrokeOwner / TextStyle::names); a marker is named by the
// label whose point is inside it (the nearest to its centre).
static void nameOutlinesAndMarkers(FigureLayout& layout, const std::vector<int>& strokeOwners,
                                   const std::vector<int>& labelNames) {
    for (std::size_t k = 0; k < strokeOwners.size(); ++k) {
        if (strokeOwners[k] == 0) continue;
        const auto it = std::find(labelNames.begin(), labelNames.end(), strokeOwners[k]);
        if (it != labelNames.end()) layout.strokes[k].outlineOf = int(it - labelNames.begin());
    }
    for (LayoutMarker& m : layout.markers) {
        double best = INFINITY;
        for (std::size_t i = 0; i < layout.labels.size(); ++i) {
            const auto& a = layout.labels[i].anchor;
            if (!a || !m.box.contains(*a)) continue;
            const double d = (*a - m.box.center()).norm();
            if (d < best) best = d, m.label = int(i);
        }
    }
}

// A placed label's leader line: from its point to the nearest point of its box, stopping 2 px
// short, in ink (not the label's colour: a brown leader among a brown body's edges was lost,
// figure review of 2026-11-29's re-render); the label's own stroke in the layout, and an obstacle
// the next labels keep off and their leaders do not cross.
static void addLeader(const Vector2d& anchor, const Box& box, FigureLayout& layout, PlacementObstacles& obstacles,
                      std::vector<LineCmd>& leaders) {
    const Vector2d near = box.nearest(anchor);
    const Vector2d d = near - anchor;
    const Vector2d end = d.norm() > 4 ? Vector2d(near - 2.0 * d.normalized()) : near;
    LineStyle style{1.5f, roleColor(Role::Ink).withAlpha(0.85f), 0.0f, true};
    layout.strokes.push_back({anchor, end, style.widthPx, int(layout.labels.size()) - 1});
    obstacles.lines.push_back({anchor, end, 0.5 * style.widthPx, true, 0});
    leaders.push_back(LineCmd{{Vector3d(anchor.x(), anchor.y(), 0), Vector3d(end.x(), end.y(), 0)}, style, false, true});
}

// Every text's box in output pixels: fixed texts where they were asked for, point labels
// (TextStyle::place) through placeLabel around their points, in drawing order, each one an
// obstacle for the next. Fills textOffsets and leaders for the build steps.
FigureLayout Canvas::Impl::layoutTexts() {
    FigureLayout layout;
    const Box panel{0, 0, double(options.width), double(options.height)};
    layout.panels.push_back(panel);
    textOffsets.assign(texts.size(), std::nullopt);
    leaders.clear();

    PlacementObstacles obstacles;
    obstacles.panel = panel;
    std::vector<int> strokeOwners, labelNames;  // parallel to layout.strokes / layout.labels
    for (const auto& item : overlays) {
        if (const auto* pt = std::get_if<PointCmd>(&item)) {
            Vector2d c;
            const double r = std::max(0.0f, pt->radiusPx);
            if (r <= 0 || !toPixels(pt->p, c)) continue;
            const Box box{c.x() - r, c.y() - r, c.x() + r, c.y() + r};
            layout.markers.push_back({box, -1});
            obstacles.boxes.push_back(box);
        } else {
            const LineCmd& line = std::get<LineCmd>(item);
            for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
                Vector2d a, b;
                if (!toPixels(line.points[i], a) || !toPixels(line.points[i + 1], b)) continue;
                // Only the part inside the picture is seen (a ground line running past the canvas
                // edge was recorded across the neighbouring panel it is blitted beside).
                if (!clipToBox(panel, a, b)) continue;
                layout.strokes.push_back({a, b, line.style.widthPx, -1});
                strokeOwners.push_back(line.owner);
                // Thin lines: avoided where there is room, else crossed (halo); the review rule
                // LabelOnStroke reports it (render/legibility.h).
                obstacles.lines.push_back({a, b, 0.5 * line.style.widthPx, line.style.widthPx < 3.0f, line.owner});
            }
        }
    }
    for (const QuantityCmd& q : quantities) {
        Vector2d a, b;
        if (toPixels(q.p, a) && toPixels(q.q, b)) layout.quantities.push_back({q.name, (b - a).norm()});
    }
    if (!options.text) {  // a thumbnail: no text, no leaders (CanvasOptions::text)
        nameOutlinesAndMarkers(layout, strokeOwners, labelNames);
        return layout;
    }
    // Where a text is asked to be: its anchor point (output px) and its box's size.
    struct Asked {
        bool visible = false;
        Vector2d anchor, size;
        double lineHeight = 0;
    };
    std::vector<Asked> asked(texts.size());
    for (std::size_t i = 0; i < texts.size(); ++i) {
        const TextCmd& t = texts[i];
        Asked& a = asked[i];
        if (!(t.style.sizePx > 0) || t.text.empty()) continue;
        if (t.world) a.visible = toPixels(t.at, a.anchor);
        else a.anchor = t.px, a.visible = t.px.allFinite();
        const TextLayout L = layoutText(context.impl().font(t.style.bold), t.text, t.style.sizePx);
        a.size = Vector2d(L.width, L.height);
        a.lineHeight = t.style.sizePx;
    }
    const auto record = [&](std::size_t i, const Box& box) {
        const TextCmd& t = texts[i];
        std::optional<Vector2d> anchor;
        if (t.world) anchor = asked[i].anchor;
        layout.labels.push_back({t.text, box, anchor, asked[i].lineHeight});
        labelNames.push_back(t.style.names);
        // Kept a space's width clear on either side, so the next label cannot run into it
        // (the legibility check's rule, render/legibility.h).
        const double space = kMinGapFraction * asked[i].lineHeight;
        obstacles.boxes.push_back(Box{box.x0 - space, box.y0, box.x1 + space, box.y1});
    };
    for (std::size_t i = 0; i < texts.size(); ++i)
        if (texts[i].world && asked[i].visible) obstacles.anchors.push_back(asked[i].anchor);
    for (std::size_t i = 0; i < texts.size(); ++i) {  // fixed texts first: the labels go around them
        if (texts[i].style.place) continue;
        textOffsets[i] = texts[i].style.offsetPx;
        if (!asked[i].visible) continue;
        const Vector2d at = asked[i].anchor + texts[i].style.offsetPx;
        double align = 0;
        const Vector2d o =
            boxOrigin(texts[i].style.anchor, at.x(), at.y(), asked[i].size.x(), asked[i].size.y(), align);
        record(i, Box{o.x(), o.y(), o.x() + asked[i].size.x(), o.y() + asked[i].size.y()});
    }
    for (std::size_t i = 0; i < texts.size(); ++i) {
        const TextCmd& t = texts[i];
        if (!t.style.place || !asked[i].visible) continue;
        PlacementRequest request;
        request.anchor = asked[i].anchor;
        request.size = asked[i].size;
        request.preferred = t.style.offsetPx;
        request.names = t.style.names;
        const Vector2d dir = t.style.offsetPx.norm() > 0 ? Vector2d(t.style.offsetPx.normalized()) : Vector2d(0, 0);
        const double halfAlong =
            0.5 * std::abs(dir.x()) * request.size.x() + 0.5 * std::abs(dir.y()) * request.size.y();
        request.gap = std::max(4.0, t.style.offsetPx.norm() - halfAlong);
        const Placement p = placeLabel(request, obstacles);
        if (!p.placed) {
            layout.unplaced.push_back(t.text);
            continue;
        }
        textOffsets[i] = p.box.center() - request.anchor;
        record(i, p.box);
        if (p.leader) addLeader(request.anchor, p.box, layout, obstacles, leaders);
    }
    nameOutlinesAndMarkers(layout, strokeOwners, labelNames);
    return layout;
}

}  // namespace cdlab::render
