// Canvas: records draw commands, renders them into a multisampled FBO in a fixed order and
// reads the picture back. Geometry is projected on the CPU in double precision; wide lines,
// points, arrow heads and glyphs are expanded into screen-space quads on the CPU (a core
// profile has no wide lines), and one small shader (gl_context.cpp) shades them.
#include "render/canvas.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <variant>

#include <Eigen/Geometry>

#include "render/gl_internal.h"
#include "render/label_placement.h"
#include "render/pixel_budget.h"
#include "render/legibility.h"
#include "render/translucent_order.h"

namespace cdlab::render {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector4d;

/// One vertex of the shared program: 5 x vec4 (layout set in GlContext::Impl::ensureDrawResources).
struct Vertex {
    float pos[4];     // clip space
    float color[4];   // fill
    float color2[4];  // disc outline
    float local[4];   // mode-specific, interpolated without perspective
    float param[4];   // mode, then mode-specific constants
};
static_assert(sizeof(Vertex) == 20 * sizeof(float));

enum Mode { kFlat = 0, kCapsule = 1, kDisc = 2, kGlyph = 3 };

void set4(float* dst, double a, double b, double c, double d) {
    dst[0] = float(a), dst[1] = float(b), dst[2] = float(c), dst[3] = float(d);
}
void setColor(float* dst, const Color& c) { dst[0] = c.r, dst[1] = c.g, dst[2] = c.b, dst[3] = c.a; }

struct MeshCmd {
    std::vector<Vector3d> vertices;
    std::vector<Eigen::Vector3i> triangles;
    Color color;
    bool lit;
};
struct LineCmd {
    std::vector<Vector3d> points;  // closed polylines repeat the first point at the end
    LineStyle style;
    bool arrow;
    bool pixelSpace = false;  // points are output pixels (x, y, 0): leader lines of placed labels
};
struct PointCmd {
    Vector3d p;
    float radiusPx;
    Color color;
    bool onTop;
    float outlinePx;
    Color outline;
};
struct TextCmd {
    bool world;
    Vector3d at;  // world
    Vector2d px;  // output pixels
    std::string text;
    TextStyle style;
};

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

/// A laid-out line of glyphs: code points (already mapped to what the atlas has) and pen x.
struct TextLayout {
    struct Line {
        std::vector<std::uint32_t> codepoints;
        std::vector<double> penX;  // relative to the line start, px
        double width = 0;
    };
    std::vector<Line> lines;
    double width = 0, height = 0;  // box, px
    double ascent = 0, lineHeight = 0;
};

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

}  // namespace

struct Canvas::Impl {
    GlContext& context;
    CanvasOptions options;
    Camera camera;
    Color background = roleColor(Role::Background);
    std::vector<MeshCmd> meshes;
    std::vector<std::variant<LineCmd, PointCmd>> overlays;
    std::vector<TextCmd> texts;
    // Per frame, from layoutTexts(): where each text goes (its offset after placement; none: not
    // drawn) and the leader lines of labels moved away from their points.
    std::vector<std::optional<Vector2d>> textOffsets;
    std::vector<LineCmd> leaders;
    RenderTarget target;
    bool haveTarget = false;
    int samples = 1;

    // Per frame.
    int rw = 0, rh = 0, ss = 1;  // render size and supersampling factor
    Eigen::Matrix4d viewProjection;

    Impl(GlContext& c, const CanvasOptions& o) : context(c), options(o) {}

    /// Clip-space position of a world point with the frame's matrix.
    Vector4d clip(const Vector3d& p) const { return viewProjection * Vector4d(p.x(), p.y(), p.z(), 1.0); }
    /// Render-pixel position (x right, y down) and NDC depth of a clip-space point (w > 0).
    Vector3d screen(const Vector4d& c) const {
        return {(c.x() / c.w() + 1.0) * 0.5 * rw, (1.0 - c.y() / c.w()) * 0.5 * rh, c.z() / c.w()};
    }
    /// Clip-space vertex for a render-pixel position and NDC depth.
    void pixelVertex(Vertex& v, double x, double y, double z) const {
        set4(v.pos, 2.0 * x / rw - 1.0, 1.0 - 2.0 * y / rh, std::clamp(z, -1.0, 1.0), 1.0);
    }
    bool is3D() const { return camera.projection != Camera::Projection::TwoD; }

    /// Clips segment ab (clip space) to the near plane z >= -w; false if nothing is left.
    static bool clipNear(Vector4d& a, Vector4d& b) {
        const double da = a.z() + a.w(), db = b.z() + b.w();
        if (!(da >= 0) && !(db >= 0)) return false;  // also rejects NaN
        if (da < 0) a = a + (b - a) * (da / (da - db));
        if (db < 0) b = b + (a - b) * (db / (db - da));
        return std::isfinite(a.squaredNorm()) && std::isfinite(b.squaredNorm()) && a.w() > 0 && b.w() > 0;
    }

    /// Output-pixel position of a world point; false behind the eye.
    bool toPixels(const Vector3d& p, Vector2d& px) const {
        const Vector4d c = clip(p);
        if (!(c.w() > 0) || !(c.z() >= -c.w()) || !c.allFinite()) return false;
        px = screen(c).head<2>() / ss;
        return px.allFinite();
    }
    FigureLayout layoutTexts();
    void buildMeshes(std::vector<Vertex>& opaque, std::vector<Vertex>& translucent);
    void addCapsule(std::vector<Vertex>& out, const Vector3d& a, const Vector3d& b, double halfW, double dash,
                    double phase, const Color& color);
    void buildOverlays(std::vector<Vertex>& out);  // lines, points, then the leader lines
    void buildLine(std::vector<Vertex>& out, const LineCmd& line);
    void buildPoint(std::vector<Vertex>& out, const PointCmd& point);
    void buildText(std::vector<Vertex>& out, std::vector<std::pair<GLuint, std::pair<int, int>>>& runs, int base);
};

// ---------------------------------------------------------------------------------------------

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
            if (line.style.widthPx < 3.0f) continue;  // thin lines: a label may cross them (halo)
            for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
                Vector2d a, b;
                if (toPixels(line.points[i], a) && toPixels(line.points[i + 1], b))
                    obstacles.lines.push_back({a, b, 0.5 * line.style.widthPx});
            }
        }
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
        // Kept a space's width clear on either side, so the next label cannot run into it
        // (the legibility check's rule, render/legibility.h).
        const double space = kMinGapFraction * asked[i].lineHeight;
        obstacles.boxes.push_back(Box{box.x0 - space, box.y0, box.x1 + space, box.y1});
    };
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
        if (p.leader) {  // from the point to the nearest point of the box, stopping 2 px short
            const Vector2d near(std::clamp(request.anchor.x(), p.box.x0, p.box.x1),
                                std::clamp(request.anchor.y(), p.box.y0, p.box.y1));
            const Vector2d d = near - request.anchor;
            const Vector2d end = d.norm() > 4 ? Vector2d(near - 2.0 * d.normalized()) : near;
            LineStyle style{1.5f, t.style.color.withAlpha(0.8f), 0.0f, true};
            leaders.push_back(
                LineCmd{{Vector3d(request.anchor.x(), request.anchor.y(), 0), Vector3d(end.x(), end.y(), 0)},
                        style,
                        false,
                        true});
        }
    }
    // A marker is named by the label whose point is inside it (the nearest to its centre).
    for (LayoutMarker& m : layout.markers) {
        double best = INFINITY;
        for (std::size_t i = 0; i < layout.labels.size(); ++i) {
            const auto& a = layout.labels[i].anchor;
            if (!a || !m.box.contains(*a)) continue;
            const double d = (*a - m.box.center()).norm();
            if (d < best) best = d, m.label = int(i);
        }
    }
    return layout;
}

void Canvas::Impl::buildMeshes(std::vector<Vertex>& opaque, std::vector<Vertex>& translucent) {
    // Camera frame for the light: a key light from the upper left, in front of the scene, so
    // faces turned towards the viewer are bright and neighbouring faces differ.
    const Vector3d back = camera.viewDirection();  // towards the eye
    Vector3d right = camera.up.cross(back);
    if (!(right.norm() > 1e-12)) right = back.unitOrthogonal();
    right.normalize();
    const Vector3d upCam = back.cross(right);
    const Vector3d light = (0.6 * back + 0.65 * upCam - 0.45 * right).normalized();

    const auto vertex = [&](const Vector3d& p, const Color& shade) {
        Vertex v;
        const Vector4d c = clip(p);
        set4(v.pos, c.x(), c.y(), c.z(), c.w());
        setColor(v.color, shade);
        set4(v.color2, 0, 0, 0, 0);
        set4(v.local, 0, 0, 0, 0);
        set4(v.param, kFlat, 0, 0, 0);
        return v;
    };
    // Translucent meshes: their finite triangles and each one's shade, ordered below.
    std::vector<std::vector<Eigen::Vector3i>> kept;
    std::vector<std::vector<Color>> shades;
    std::vector<const MeshCmd*> sources;
    for (const MeshCmd& m : meshes) {
        const bool isTranslucent = m.color.a < 1.0f;
        if (isTranslucent) {
            kept.emplace_back();
            shades.emplace_back();
            sources.push_back(&m);
        }
        for (const Eigen::Vector3i& t : m.triangles) {
            const Vector3d& a = m.vertices[std::size_t(t[0])];
            const Vector3d& b = m.vertices[std::size_t(t[1])];
            const Vector3d& c = m.vertices[std::size_t(t[2])];
            if (!a.allFinite() || !b.allFinite() || !c.allFinite()) continue;  // NaN geometry: skip the face
            Color shade = m.color;
            if (m.lit) {
                const Vector3d n = (b - a).cross(c - a);
                const double len = n.norm();
                // Both sides lit: |n . l|. Ambient 0.45 keeps faces turned away readable.
                const double k = len > 0 ? 0.45 + 0.55 * std::abs(n.dot(light) / len) : 1.0;
                shade = m.color.scaled(float(k));
            }
            if (isTranslucent) {
                kept.back().push_back(t);
                shades.back().push_back(shade);
            } else {
                for (const Vector3d* p : {&a, &b, &c}) opaque.push_back(vertex(*p, shade));
            }
        }
    }
    if (!is3D()) {
        // 2D: no depth; translucent regions blend in the order they were drawn.
        for (std::size_t m = 0; m < kept.size(); ++m)
            for (std::size_t i = 0; i < kept[m].size(); ++i)
                for (int k = 0; k < 3; ++k)
                    translucent.push_back(vertex(sources[m]->vertices[std::size_t(kept[m][i][k])], shades[m][i]));
        return;
    }
    // 3D: back to front for this camera, faces that cross each other cut along the crossing.
    std::vector<TranslucentMesh> input;
    for (std::size_t m = 0; m < kept.size(); ++m) input.push_back({sources[m]->vertices, kept[m]});
    const Viewer viewer{camera.eye, back, camera.projection == Camera::Projection::Orthographic};
    for (const OrderedPiece& piece : backToFront(input, viewer)) {
        const Color& shade = shades[std::size_t(piece.mesh)][std::size_t(piece.triangle)];
        // A convex piece as a fan around its first corner.
        for (std::size_t k = 1; k + 1 < piece.corners.size(); ++k)
            for (const Vector3d* p : {&piece.corners[0], &piece.corners[k], &piece.corners[k + 1]})
                translucent.push_back(vertex(*p, shade));
    }
}

/// Thick line from a to b (render pixels + NDC depth) as one quad: a capsule (round caps)
/// with a 1 px anti-aliasing ramp, optionally dashed with the dash pattern starting at `phase`.
void Canvas::Impl::addCapsule(std::vector<Vertex>& out, const Vector3d& a, const Vector3d& b, double halfW, double dash,
                              double phase, const Color& color) {
    Vector2d d(b.x() - a.x(), b.y() - a.y());
    const double len = d.norm();
    d = len > 1e-9 ? Vector2d(d / len) : Vector2d(1, 0);  // zero length: a round dot
    const Vector2d n(-d.y(), d.x());
    const double ext = halfW + 1.0;  // quad margin: the cap plus the AA ramp
    const double us[2] = {-ext, len + ext}, vs[2] = {-ext, ext};
    Vertex corner[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            Vertex& v = corner[i][j];
            const double t = len > 1e-9 ? us[i] / len : 0.0;
            const Vector2d p = Vector2d(a.x(), a.y()) + d * us[i] + n * vs[j];
            pixelVertex(v, p.x(), p.y(), a.z() + (b.z() - a.z()) * t);
            setColor(v.color, color);
            set4(v.color2, 0, 0, 0, 0);
            set4(v.local, us[i], vs[j], phase, 0);
            set4(v.param, kCapsule, halfW, len, dash);
        }
    const Vertex quad[6] = {corner[0][0], corner[1][0], corner[1][1], corner[0][0], corner[1][1], corner[0][1]};
    out.insert(out.end(), quad, quad + 6);
}

void Canvas::Impl::buildOverlays(std::vector<Vertex>& out) {
    for (const auto& item : overlays) {
        if (const auto* line = std::get_if<LineCmd>(&item)) buildLine(out, *line);
        else buildPoint(out, std::get<PointCmd>(item));
    }
    for (const LineCmd& leader : leaders) buildLine(out, leader);
}

void Canvas::Impl::buildLine(std::vector<Vertex>& out, const LineCmd& line) {
    const double s = ss;
    const LineStyle& st = line.style;
    const double halfW = 0.5 * std::max(0.0f, st.widthPx) * s;
    const double dash = std::max(0.0f, st.dashPx) * s;
    if (halfW <= 0) return;
    double phase = 0;
    const std::size_t nSeg = line.points.size() < 2 ? 0 : line.points.size() - 1;
    for (std::size_t i = 0; i < nSeg; ++i) {
        Vector3d a, b;
        if (line.pixelSpace) {
            a = Vector3d(line.points[i].x() * s, line.points[i].y() * s, -1.0);
            b = Vector3d(line.points[i + 1].x() * s, line.points[i + 1].y() * s, -1.0);
        } else {
            Vector4d ca = clip(line.points[i]), cb = clip(line.points[i + 1]);
            if (!clipNear(ca, cb)) continue;
            a = screen(ca), b = screen(cb);
        }
        if (st.onTop || !is3D()) a.z() = b.z() = -1.0;  // nearest depth: always passes
        const bool isHead = line.arrow && i + 1 == nSeg;
        if (!isHead) {
            addCapsule(out, a, b, halfW, dash, phase, st.color);
            phase += (b - a).head<2>().norm();
            continue;
        }
        // Arrow: the shaft stops inside the head; the head is a triangle in screen space
        // sized from the line width (output px: length 4w + 6, width 2.5w + 5).
        Vector2d d = (b - a).head<2>();
        const double len = d.norm();
        if (!(len > 1e-9)) continue;  // no direction: nothing meaningful to draw
        d /= len;
        double headLen = (4.0 * st.widthPx + 6.0) * s, headHalf = 0.5 * (2.5 * st.widthPx + 5.0) * s;
        if (headLen > 0.6 * len) {  // short arrow: shrink the head, keep its shape
            const double k = 0.6 * len / headLen;
            headLen *= k, headHalf *= k;
        }
        const double shaftLen = len - 0.7 * headLen;
        const Vector3d shaftEnd = a + (b - a) * (shaftLen / len);
        addCapsule(out, a, shaftEnd, halfW, dash, phase, st.color);
        const Vector2d n(-d.y(), d.x());
        const Vector2d tip = b.head<2>(), base = tip - d * headLen;
        const double zBase = b.z() + (a.z() - b.z()) * (headLen / len);
        const Vector2d pts[3] = {tip, base + n * headHalf, base - n * headHalf};
        for (int k = 0; k < 3; ++k) {
            Vertex v;
            pixelVertex(v, pts[k].x(), pts[k].y(), k == 0 ? b.z() : zBase);
            setColor(v.color, st.color);
            set4(v.color2, 0, 0, 0, 0);
            set4(v.local, 0, 0, 0, 0);
            set4(v.param, kFlat, 0, 0, 0);
            out.push_back(v);
        }
    }
}

void Canvas::Impl::buildPoint(std::vector<Vertex>& out, const PointCmd& pt) {
    const double s = ss;
    const Vector4d c = clip(pt.p);
    if (!(c.w() > 0) || !(c.z() >= -c.w()) || !c.allFinite()) return;  // behind the eye
    Vector3d p = screen(c);
    if (pt.onTop || !is3D()) p.z() = -1.0;
    const double radius = std::max(0.0f, pt.radiusPx) * s, outline = std::max(0.0f, pt.outlinePx) * s;
    if (radius <= 0) return;
    const double e = radius + 1.0;
    const double cs[4][2] = {{-e, -e}, {e, -e}, {e, e}, {-e, e}};
    Vertex q[4];
    for (int k = 0; k < 4; ++k) {
        pixelVertex(q[k], p.x() + cs[k][0], p.y() + cs[k][1], p.z());
        setColor(q[k].color, pt.color);
        setColor(q[k].color2, pt.outline);
        set4(q[k].local, cs[k][0], cs[k][1], 0, 0);
        set4(q[k].param, kDisc, radius, std::min(outline, radius), 0);
    }
    const Vertex quad[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
    out.insert(out.end(), quad, quad + 6);
}

void Canvas::Impl::buildText(std::vector<Vertex>& out, std::vector<std::pair<GLuint, std::pair<int, int>>>& runs,
                             int base) {
    GlContext::Impl& gl = context.impl();
    for (std::size_t ti = 0; ti < texts.size(); ++ti) {
        const TextCmd& t = texts[ti];
        if (!textOffsets[ti]) continue;  // a label the placement step could not place
        Vector2d at;
        if (t.world) {
            const Vector4d c = clip(t.at);
            if (!(c.w() > 0) || !(c.z() >= -c.w()) || !c.allFinite()) continue;
            at = screen(c).head<2>();
        } else {
            at = t.px * ss;
        }
        at += *textOffsets[ti] * ss;
        if (!at.allFinite() || !(t.style.sizePx > 0)) continue;
        const int pixelSize = std::max(1, int(std::lround(t.style.sizePx * ss)));
        GlyphAtlas& atlas = gl.atlas(t.style.bold, pixelSize);
        const FontFace& face = gl.font(t.style.bold);
        const TextLayout L = layoutText(face, t.text, pixelSize);
        double align = 0;
        const Vector2d origin =
            boxOrigin(t.style.place ? Anchor::Center : t.style.anchor, at.x(), at.y(), L.width, L.height, align);

        const int first = int(out.size());
        auto emitGlyphs = [&](double dx, double dy, const Color& color) {
            for (std::size_t li = 0; li < L.lines.size(); ++li) {
                const TextLayout::Line& line = L.lines[li];
                // Integer pen start and baseline: glyph texels map 1:1 to pixels (crisp text).
                const double x0 = std::round(origin.x() + align * (L.width - line.width)) + dx;
                const double baseline = std::round(origin.y() + L.ascent + double(li) * L.lineHeight) + dy;
                for (std::size_t g = 0; g < line.codepoints.size(); ++g) {
                    const auto it = atlas.glyphs.find(line.codepoints[g]);
                    if (it == atlas.glyphs.end()) continue;
                    const stbtt_packedchar& pc = it->second;
                    if (pc.x1 <= pc.x0 || pc.y1 <= pc.y0) continue;  // space
                    const double gx = std::floor(x0 + line.penX[g] + pc.xoff + 0.5);
                    const double gy = std::floor(baseline + pc.yoff + 0.5);
                    const double gw = pc.x1 - pc.x0, gh = pc.y1 - pc.y0;
                    const double u0 = pc.x0 / double(atlas.width), u1 = pc.x1 / double(atlas.width);
                    const double v0 = pc.y0 / double(atlas.height), v1 = pc.y1 / double(atlas.height);
                    const double cs[4][4] = {
                        {gx, gy, u0, v0}, {gx + gw, gy, u1, v0}, {gx + gw, gy + gh, u1, v1}, {gx, gy + gh, u0, v1}};
                    Vertex q[4];
                    for (int k = 0; k < 4; ++k) {
                        pixelVertex(q[k], cs[k][0], cs[k][1], -1.0);
                        setColor(q[k].color, color);
                        set4(q[k].color2, 0, 0, 0, 0);
                        set4(q[k].local, cs[k][2], cs[k][3], 0, 0);
                        set4(q[k].param, kGlyph, 0, 0, 0);
                    }
                    const Vertex quad[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
                    out.insert(out.end(), quad, quad + 6);
                }
            }
        };
        if (t.style.halo) {
            // Halo: the glyphs stamped in the background colour around a circle (12 directions
            // at the full radius, 6 at half), then the text itself on top.
            const double r = std::max(1.0, 0.09 * t.style.sizePx) * ss;
            for (int k = 0; k < 12; ++k)
                emitGlyphs(r * std::cos(k * M_PI / 6), r * std::sin(k * M_PI / 6), background.withAlpha(1.0f));
            for (int k = 0; k < 6; ++k)
                emitGlyphs(0.5 * r * std::cos(k * M_PI / 3 + 0.5), 0.5 * r * std::sin(k * M_PI / 3 + 0.5),
                           background.withAlpha(1.0f));
        }
        emitGlyphs(0, 0, t.style.color);
        const int count = int(out.size()) - first;
        if (count == 0) continue;
        if (!runs.empty() && runs.back().first == atlas.texture) runs.back().second.second += count;
        else runs.push_back({atlas.texture, {base + first, count}});
    }
}

// ---------------------------------------------------------------------------------------------

Canvas::Canvas(GlContext& context, const CanvasOptions& options) : impl_(nullptr) {
    if (options.width <= 0 || options.height <= 0)
        throw std::invalid_argument("Canvas: size must be positive, got " + std::to_string(options.width) + "x" +
                                    std::to_string(options.height));
    if (options.supersample < 1 || options.supersample > 16)
        throw std::invalid_argument("Canvas: supersample must be 1..16, got " + std::to_string(options.supersample));
    if (options.scale < 1 || options.scale > 16)
        throw std::invalid_argument("Canvas: scale must be 1..16, got " + std::to_string(options.scale));
    impl_ = new Impl(context, options);
    impl_->samples = std::clamp(options.msaaSamples, 1, std::max(1, context.maxSamples()));
}

Canvas::Canvas(GlContext& context, const CanvasOptions& options, const Camera& camera) : Canvas(context, options) {
    setCamera(camera);
}

Canvas::~Canvas() {
    if (impl_->haveTarget) {
        try {
            impl_->context.makeCurrent();
            impl_->context.impl().releaseTarget(impl_->target);
        } catch (...) {  // destructor: never throw; the context frees the FBO with itself
        }
    }
    delete impl_;
}

void Canvas::setCamera(const Camera& camera) { impl_->camera = camera; }
const Camera& Canvas::camera() const { return impl_->camera; }
void Canvas::setBackground(const Color& color) { impl_->background = color; }
int Canvas::width() const { return impl_->options.width; }
int Canvas::height() const { return impl_->options.height; }
int Canvas::samples() const { return impl_->samples; }

bool Canvas::project(const Eigen::Vector3d& p, Eigen::Vector2d& pixel) const {
    const Eigen::Matrix4d vp = impl_->camera.viewProjection(double(width()) / height());
    const Vector4d c = vp * Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (!(c.w() > 0) || !c.allFinite()) return false;
    pixel = {(c.x() / c.w() + 1.0) * 0.5 * width(), (1.0 - c.y() / c.w()) * 0.5 * height()};
    return true;
}

void Canvas::drawMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
                      const Color& color, bool lit) {
    for (const Eigen::Vector3i& t : triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || std::size_t(t[k]) >= vertices.size())
                throw std::out_of_range("Canvas::drawMesh: triangle index " + std::to_string(t[k]) + " outside 0.." +
                                        std::to_string(int(vertices.size()) - 1));
    impl_->meshes.push_back({vertices, triangles, color, lit});
}

void Canvas::drawPolygon(const std::vector<Eigen::Vector3d>& corners, const Color& color, bool lit) {
    if (corners.size() < 3) return;
    std::vector<Eigen::Vector3i> fan;
    for (int i = 1; i + 1 < int(corners.size()); ++i) fan.emplace_back(0, i, i + 1);
    impl_->meshes.push_back({corners, std::move(fan), color, lit});
}

void Canvas::drawLine(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style) {
    impl_->overlays.emplace_back(LineCmd{{p, q}, style, false});
}

void Canvas::drawPolyline(const std::vector<Eigen::Vector3d>& points, bool closed, const LineStyle& style) {
    if (points.size() < 2) return;
    LineCmd cmd{points, style, false};
    if (closed) cmd.points.push_back(points.front());
    impl_->overlays.emplace_back(std::move(cmd));
}

void Canvas::drawPoint(const Eigen::Vector3d& p, float radiusPx, const Color& color, bool onTop, float outlinePx,
                       const Color& outline) {
    impl_->overlays.emplace_back(PointCmd{p, radiusPx, color, onTop, outlinePx, outline});
}

void Canvas::drawArrow(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style) {
    impl_->overlays.emplace_back(LineCmd{{p, q}, style, true});
}

void Canvas::drawText(const Eigen::Vector3d& at, const std::string& text, const TextStyle& style) {
    drawnTextLog().push_back(text);
    impl_->texts.push_back({true, at, Vector2d::Zero(), text, style});
}

void Canvas::drawTextPx(double x, double y, const std::string& text, const TextStyle& style) {
    drawnTextLog().push_back(text);
    impl_->texts.push_back({false, Vector3d::Zero(), Vector2d(x, y), text, style});
}

Eigen::Vector2d Canvas::measureText(const std::string& text, const TextStyle& style) const {
    if (!(style.sizePx > 0)) return {0, 0};
    const FontFace& face = impl_->context.impl().font(style.bold);  // metrics only: no GL
    const TextLayout L = layoutText(face, text, style.sizePx);
    return {L.width, L.height};
}

void Canvas::clearCommands() {
    impl_->meshes.clear();
    impl_->overlays.clear();
    impl_->texts.clear();
}

RenderStats& renderStats() {
    thread_local RenderStats stats;  // per thread: `cdlab figures` draws on several
    return stats;
}

std::vector<std::string>& drawnTextLog() {
    thread_local std::vector<std::string> log;
    return log;
}

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

thread_local PixelBudget* g_budget = nullptr;  // the innermost budget of this thread
}  // namespace

PixelBudget::PixelBudget(double limit) : limit_(limit), outer_(g_budget) { g_budget = this; }

PixelBudget::~PixelBudget() { g_budget = outer_; }

void PixelBudget::spend(double pixels) {
    PixelBudget* b = g_budget;
    if (!b) return;
    if (b->used_ + pixels > b->limit_)
        throw ImageError("the frames drawn take more than " + std::to_string(static_cast<long long>(b->limit_)) +
                         " rendered pixels together, the limit for one scene (fewer steps, views or queries, or a "
                         "smaller image)");
    b->used_ += pixels;
}

Image Canvas::readPixels() {
    Impl& m = *impl_;
    // The rendered size, counted before anything is drawn or read back (m.rw, m.rh are set below).
    const double ss = double(m.options.supersample) * double(m.options.scale);
    PixelBudget::spend(double(m.options.width) * ss * double(m.options.height) * ss);
    RenderStats& stats = renderStats();
    auto t0 = std::chrono::steady_clock::now();
    GlContext::Impl& gl = m.context.impl();
    gl.makeCurrent();
    gl.ensureDrawResources();
    m.ss = m.options.supersample * m.options.scale;  // every pixel size is multiplied by this
    m.rw = m.options.width * m.ss;
    m.rh = m.options.height * m.ss;
    const int requested = std::clamp(m.options.msaaSamples, 1, std::max(1, gl.maxSamples));
    if (!m.haveTarget || m.target.width != m.rw || m.target.height != m.rh || m.target.requestedSamples != requested) {
        if (m.haveTarget) gl.releaseTarget(m.target);
        m.haveTarget = false;
        m.target = gl.acquireTarget(m.rw, m.rh, requested);
        m.haveTarget = true;
    }
    m.samples = m.target.samples;
    m.viewProjection = m.camera.viewProjection(double(m.options.width) / m.options.height);
    FigureLayout layout = m.layoutTexts();  // places the point labels: before any vertex is built

    // Build every vertex for the frame, in drawing order.
    std::vector<Vertex> opaque, translucent, overlay, text;
    m.buildMeshes(opaque, translucent);
    m.buildOverlays(overlay);
    std::vector<std::pair<GLuint, std::pair<int, int>>> textRuns;
    const int textBase = int(opaque.size() + translucent.size() + overlay.size());
    m.buildText(text, textRuns, textBase);  // may bake atlases (binds textures): before the draw state
    std::vector<Vertex> all;
    all.reserve(std::size_t(textBase) + text.size());
    for (auto* part : {&opaque, &translucent, &overlay, &text}) all.insert(all.end(), part->begin(), part->end());

    stats.buildSeconds += secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    const GLuint drawFbo = m.target.samples > 1 ? m.target.msaaFbo : m.target.resolveFbo;
    glBindFramebuffer(GL_FRAMEBUFFER, drawFbo);
    glViewport(0, 0, m.rw, m.rh);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_MULTISAMPLE);
    glDepthMask(GL_TRUE);
    glClearColor(m.background.r, m.background.g, m.background.b, m.background.a);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    glUseProgram(gl.program);
    glUniform1i(gl.uniformAtlas, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl.whiteTexture);
    glBindVertexArray(gl.vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl.vbo);
    const std::size_t bytes = all.size() * sizeof(Vertex);
    if (bytes > gl.vboCapacity) {
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_DRAW);
        gl.vboCapacity = bytes;
    }
    if (bytes) glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes), all.data());

    auto draw = [](std::size_t first, std::size_t count) {
        if (count) glDrawArrays(GL_TRIANGLES, GLint(first), GLsizei(count));
    };
    // 1. Opaque meshes: depth test + write. Polygon offset pushes faces back a little so lines
    //    drawn along their edges win the depth test.
    if (m.is3D()) glEnable(GL_DEPTH_TEST);
    else glDisable(GL_DEPTH_TEST);  // 2D: painter's order
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    draw(0, opaque.size());
    // 2. Translucent meshes back to front: tested against the opaque depth, not written. Pushed back
    //    one depth unit more than the opaque faces, so a translucent face in the plane of an opaque
    //    one (a highlighted triangle over its mesh) stays behind it everywhere: the pieces it was cut
    //    into (render/translucent_order.h) have new corners whose depth, rounded to float, may
    //    otherwise fall either side of the opaque face's, in stripes. The cost: a translucent face
    //    less than ~1 depth unit in front of an opaque one (1e-4 world units at 5 units from an eye
    //    with near plane 0.01) is hidden there.
    glPolygonOffset(1.0f, 2.0f);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    draw(opaque.size(), translucent.size());
    // 3. Lines, points, arrows in call order; depth-tested (onTop ones sit at the near plane).
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(GL_LEQUAL);
    draw(opaque.size() + translucent.size(), overlay.size());
    // 4. Text on top of everything.
    glDisable(GL_DEPTH_TEST);
    for (const auto& [texture, range] : textRuns) {
        glBindTexture(GL_TEXTURE_2D, texture);
        draw(std::size_t(range.first), std::size_t(range.second));
    }
    glBindTexture(GL_TEXTURE_2D, gl.whiteTexture);
    glDepthMask(GL_TRUE);

    if (stats.profiling) glFinish();
    stats.drawSeconds += secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    // Resolve MSAA, read back bottom-up, flip to top-first.
    if (m.target.samples > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, m.target.msaaFbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.target.resolveFbo);
        glBlitFramebuffer(0, 0, m.rw, m.rh, 0, 0, m.rw, m.rh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m.target.resolveFbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    Image raw(m.rw, m.rh);
    std::vector<std::uint8_t> rows(raw.rgba.size());
    glReadPixels(0, 0, m.rw, m.rh, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("rendering and reading back the canvas");
    const std::size_t stride = std::size_t(m.rw) * 4;
    for (int y = 0; y < m.rh; ++y)
        std::copy_n(rows.data() + std::size_t(m.rh - 1 - y) * stride, stride,
                    raw.rgba.data() + std::size_t(y) * stride);
    const int resolve = m.options.supersample;
    Image out = resolve > 1 ? downsample(raw, resolve) : std::move(raw);
    out.layout = m.options.scale > 1 ? layout.scaled(m.options.scale) : std::move(layout);  // in output pixels
    out.scale = m.options.scale;
    stats.readbackSeconds += secondsSince(t0);
    ++stats.frames;
    return out;
}

}  // namespace cdlab::render
