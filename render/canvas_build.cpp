// Canvas vertices: every recorded command expanded into triangles of the shared program, in
// drawing order: meshes (opaque, then translucent back to front), lines / points / arrows with the
// leader lines of placed labels, then glyph quads grouped by atlas texture.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "render/canvas_internal.h"
#include "render/translucent_order.h"

namespace cdlab::render {

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

}  // namespace cdlab::render
