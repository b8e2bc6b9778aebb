// BVH demo: drawing pieces (boxes, meshes, the tree diagram, legends, the panel grid).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>

#include "demos/bvh/bvh_draw.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"

namespace cdlab::demos::bvhdemo {

using namespace render;

std::array<Vec3, 8> boxCorners(const Obb& b) {
    std::array<Vec3, 8> c;
    for (int k = 0; k < 8; ++k) {
        Vec3 p = b.center;
        for (int i = 0; i < 3; ++i) p += ((k >> i) & 1 ? 1.0 : -1.0) * b.halfExtents[i] * b.axes.col(i);
        c[k] = p;
    }
    return c;
}

Obb obbFromAabb(const Aabb& box) {
    Obb o;
    o.center = 0.5 * (box.min + box.max);
    o.halfExtents = 0.5 * (box.max - box.min);
    o.axes = Mat3::Identity();
    return o;
}

Color levelColor(int depth) {
    // Okabe–Ito without the blue of the mesh: vermillion, green, purple, orange, sky blue, yellow.
    static const Color kLevel[6] = {{0.84f, 0.37f, 0.0f, 1}, {0.0f, 0.62f, 0.45f, 1},  {0.80f, 0.47f, 0.65f, 1},
                                    {0.90f, 0.62f, 0.0f, 1}, {0.34f, 0.71f, 0.91f, 1}, {0.75f, 0.70f, 0.10f, 1}};
    return kLevel[((depth % 6) + 6) % 6];
}

namespace {
// Box edges: corner pairs differing in one bit.
constexpr int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                               {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
// Box faces (quads) as corner indices.
constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
}  // namespace

void drawBoxWire(Canvas& canvas, const Obb& box, const LineStyle& style) {
    const auto c = boxCorners(box);
    for (const auto& e : kEdges) canvas.drawLine(c[e[0]], c[e[1]], style);
}

void drawBoxFill(Canvas& canvas, const Obb& box, const Color& color) {
    const auto c = boxCorners(box);
    std::vector<Vec3> v(c.begin(), c.end());
    std::vector<Eigen::Vector3i> t;
    for (const auto& f : kFaces) {
        t.emplace_back(f[0], f[1], f[2]);
        t.emplace_back(f[0], f[2], f[3]);
    }
    canvas.drawMesh(v, t, color, false);
}

void drawMesh(Canvas& canvas, const MeshView& mesh, const Color& fill, float edgeWidth, const Color& edge) {
    canvas.drawMesh(mesh.vertices, mesh.triangles, fill, true);
    if (edgeWidth <= 0) return;
    LineStyle s;
    s.widthPx = edgeWidth;
    s.color = edge;
    // Each undirected edge once.
    std::vector<std::pair<int, int>> edges;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& e : edges) canvas.drawLine(mesh.vertices[e.first], mesh.vertices[e.second], s);
}

void drawTriangleSubset(Canvas& canvas, const MeshView& mesh, const std::vector<int>& which, const Color& fill,
                        const Color& outline, float outlineWidth, bool lit) {
    std::vector<Vec3> v;
    std::vector<Eigen::Vector3i> t;
    for (int i : which) {
        const auto& tri = mesh.triangles[i];
        const int base = int(v.size());
        for (int k = 0; k < 3; ++k) v.push_back(mesh.vertices[tri[k]]);
        t.emplace_back(base, base + 1, base + 2);
    }
    if (!t.empty()) canvas.drawMesh(v, t, fill, lit);
    LineStyle s;
    s.widthPx = outlineWidth;
    s.color = outline;
    s.onTop = true;
    for (std::size_t k = 0; k + 2 < v.size(); k += 3) canvas.drawPolyline({v[k], v[k + 1], v[k + 2]}, true, s);
}

void meshSphere(const std::vector<const MeshView*>& meshes, Vec3& center, double& radius,
                const std::vector<Vec3>& extra) {
    std::vector<const Vec3*> pts;
    for (const MeshView* m : meshes)
        for (const Vec3& p : m->vertices) pts.push_back(&p);
    for (const Vec3& p : extra) pts.push_back(&p);
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Vec3* p : pts) {
        lo = lo.cwiseMin(*p);
        hi = hi.cwiseMax(*p);
    }
    center = 0.5 * (lo + hi);
    radius = 0;
    for (const Vec3* p : pts) radius = std::max(radius, (*p - center).norm());
    if (radius <= 0) radius = 1;
}

// ---- tree diagram

Image drawTreeDiagram(GlContext& gl, int W, int H, int ss, const TreeDiagramInput& in) {
    Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
    auto P = [&](double x, double yDown) { return Vec3(x, H - yDown, 0); };
    drawHeading(c, in.heading, in.sub);
    const int n = int(in.children.size());
    if (n == 0) return c.readPixels();

    // Slots: each drawn leaf (or cut-off node at maxDepth) takes one; a parent sits over the middle
    // of its children.
    std::vector<double> slot(n, 0.0);
    std::vector<int> depth(n, -1);
    int slots = 0;
    std::function<void(int, int)> place = [&](int i, int d) {
        depth[i] = d;
        const auto& ch = in.children[i];
        if (d == in.maxDepth || ch[0] < 0) {
            slot[i] = slots++;
            return;
        }
        place(ch[0], d + 1);
        place(ch[1], d + 1);
        slot[i] = 0.5 * (slot[ch[0]] + slot[ch[1]]);
    };
    place(0, 0);
    int deepest = 0;
    for (int i = 0; i < n; ++i) deepest = std::max(deepest, depth[i]);

    const double left = in.levelLabels ? 64.0 : 16.0, right = 14.0, top = in.sub.empty() ? 48.0 : 70.0, bottom = 22.0;
    const double dx = slots > 1 ? (W - left - right) / double(slots - 1) : 0.0;
    const double dy = deepest > 0 ? (H - top - bottom) / double(deepest + 0.4) : 0.0;
    auto pos = [&](int i) {
        const double x = slots > 1 ? left + slot[i] * dx : 0.5 * (W + left - right);
        return P(x, top + depth[i] * dy);
    };
    auto lookOf = [&](int i) {
        if (i < int(in.look.size())) return in.look[i];
        return TreeNodeLook{roleColor(Role::Muted), 3.0f, false};
    };
    if (in.levelLabels)
        for (int d = 0; d <= deepest; ++d) {
            const bool lit = std::find(in.litLevels.begin(), in.litLevels.end(), d) != in.litLevels.end();
            c.drawTextPx(10, top + d * dy, "level " + std::to_string(d),
                         TextStyle{13.0f, lit ? roleColor(Role::Ink) : roleColor(Role::Muted).scaled(0.8f),
                                   Anchor::Left, true, lit});
        }
    const LineStyle edge = lineStyle(Role::Muted, 1.2f);
    std::vector<char> litEdge(n, 0);
    for (int i : in.litEdges)
        if (i >= 0 && i < n) litEdge[i] = 1;
    for (int i = 0; i < n; ++i) {
        if (depth[i] < 0) continue;
        const auto& ch = in.children[i];
        if (ch[0] < 0) continue;
        if (depth[i] == in.maxDepth) {
            // Stub: the subtree goes on below.
            c.drawLine(pos(i), pos(i) - Vec3(0, 0.28 * dy, 0), lineStyle(Role::Muted, 1.0f, true));
            continue;
        }
        for (int k = 0; k < 2; ++k) {
            LineStyle s = edge;
            if (litEdge[ch[k]]) {
                s.widthPx = 3.0f;
                s.color = lookOf(ch[k]).color;
            }
            c.drawLine(pos(i), pos(ch[k]), s);
        }
    }
    // Nodes, lit ones last so they sit on top.
    for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < n; ++i) {
            if (depth[i] < 0) continue;
            const TreeNodeLook l = lookOf(i);
            if ((l.ring || l.radius > 4.5f) != (pass == 1)) continue;
            c.drawPoint(pos(i), l.radius, l.color, true, l.ring ? 2.5f : 0.8f, roleColor(Role::Ink));
        }
    for (int i = 0; i < n && i < int(in.names.size()); ++i)
        if (depth[i] >= 0 && !in.names[std::size_t(i)].empty())
            c.drawTextPx(pos(i).x(), H - pos(i).y() + lookOf(i).radius + 4.0, in.names[std::size_t(i)],
                         TextStyle{16.0f, roleColor(Role::Ink), Anchor::Top, true, true});
    return c.readPixels();
}

// ---- legends and frames

void drawHeading(Canvas& canvas, const std::string& heading, const std::string& sub) {
    if (!heading.empty())
        canvas.drawTextPx(12, 8, heading, TextStyle{18.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    if (!sub.empty())
        canvas.drawTextPx(
            12, 33, sub,
            TextStyle{15.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.3f), Anchor::TopLeft, true, false});
}

void drawFooter(Canvas& canvas, const std::vector<std::string>& lines, const Color& color) {
    double y = canvas.height() - 8.0 - 19.0 * (double(lines.size()) - 1.0);
    for (const std::string& s : lines) {
        canvas.drawTextPx(12, y, s, TextStyle{15.0f, color, Anchor::BottomLeft, true, false});
        y += 19.0;
    }
}

Camera sphereCamera(const Vec3& center, double radius, const Vec3& view, int width, int height) {
    const Vec3 up = std::abs(view.normalized().z()) > 0.95 ? Vec3::UnitY() : Vec3::UnitZ();
    // framingCamera fits the sphere vertically; a panel narrower than tall needs it to fit across.
    // The sphere is framed a little larger and lower than the panel's centre: the heading lines
    // take the top ~60 pixels.
    const double aspect = double(width) / double(height);
    const double r = (aspect < 1.0 ? radius / aspect : radius) * 1.12;
    Camera cam = framingCamera(center, r, view, up);
    const Vec3 forward = (cam.target - cam.eye).normalized();
    const Vec3 screenUp = forward.cross(up).cross(forward).normalized();
    const Vec3 shift = screenUp * (0.10 * r);
    cam.target += shift;
    cam.eye += shift;
    return cam;
}

Image composeGrid(GlContext& gl, const GridLayout& L, int ss, const std::string& title,
                  const std::vector<Image>& panels, const std::vector<LegendItem>& legend,
                  const std::vector<std::string>& captionLines) {
    Canvas c(gl, canvasOptions(L.width, L.height, ss), Camera::pixels(L.width, L.height));
    auto P = [&](double x, double yDown) { return Vec3(x, L.height - yDown, 0); };
    c.drawTextPx(16, 9, title, TextStyle{23.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    const double gridBottom = L.titleBand + L.rows * L.panelHeight();
    if (L.legendBand > 0 && !legend.empty()) {
        double x = 18;
        const double y = gridBottom + L.legendBand / 2.0 + 1;
        const TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::Left, false, false};
        for (const LegendItem& it : legend) {
            switch (it.swatch) {
                case LegendItem::Swatch::Line:
                case LegendItem::Swatch::Dashed: {
                    LineStyle s;
                    s.widthPx = 3.0f;
                    s.color = it.color;
                    s.dashPx = it.swatch == LegendItem::Swatch::Dashed ? 5.0f : 0.0f;
                    c.drawLine(P(x, y), P(x + 24, y), s);
                    break;
                }
                case LegendItem::Swatch::Dot:
                    c.drawPoint(P(x + 12, y), 5.0f, it.color, true, 1.0f, roleColor(Role::Ink));
                    break;
                case LegendItem::Swatch::Fill:
                    c.drawPolygon({P(x + 3, y - 7), P(x + 21, y - 7), P(x + 21, y + 7), P(x + 3, y + 7)}, it.color);
                    break;
            }
            c.drawTextPx(x + 30, y, it.text, ts);
            x += 30 + c.measureText(it.text, ts).x() + 22;
        }
    }
    double y = gridBottom + L.legendBand + 6;
    for (const std::string& line : captionLines) {
        c.drawTextPx(16, y, line, TextStyle{16.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += 22.0;
    }
    Image frame = c.readPixels();
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const int col = int(k) % L.columns, row = int(k) / L.columns;
        blit(frame, panels[k], L.columnX(col), L.titleBand + row * L.panelHeight());
    }
    // 1-pixel rules between panels.
    const Color m = roleColor(Role::Muted);
    for (int col = 1; col < L.columns; ++col)
        paintRect(frame, L.columnX(col) - 1, L.titleBand, 1, int(gridBottom) - L.titleBand, m);
    for (int row = 1; row < L.rows; ++row)
        paintRect(frame, 0, L.titleBand + row * L.panelHeight() - 1, L.columnX(L.columns), 1, m);
    return frame;
}

}  // namespace cdlab::demos::bvhdemo

namespace cdlab::demos::bvhdemo {

using namespace render;

Image drawBarChart(GlContext& gl, int W, int H, int ss, const BarChartInput& in) {
    Canvas c(gl, canvasOptions(W, H, ss), Camera::pixels(W, H));
    auto P = [&](double x, double yDown) { return Vec3(x, H - yDown, 0); };
    drawHeading(c, in.heading, in.sub);
    // Without a number on each bar a linear chart gets a value axis on the left.
    const bool valueAxis = in.valueFormat.empty() && !in.logY;
    const double left = valueAxis || in.logY ? 56 : 24, right = 16, legendTop = in.sub.empty() ? 40 : 62, bottom = 40;
    const double top = legendTop + 18.0 * double(in.series.size()) + 22;
    const int groups = int(in.groups.size()), ns = int(in.series.size());
    if (groups == 0 || ns == 0) return c.readPixels();
    double hi = 0, lo = 1e300;
    for (const BarSeries& s : in.series)
        for (double v : s.values)
            if (v > 0) {
                hi = std::max(hi, v);
                lo = std::min(lo, v);
            }
    if (hi <= 0) hi = 1, lo = 1;
    // Bar height in [0, 1] of the plot height: linear from 0, or log from a decade below the least value.
    const double logLo = std::floor(std::log10(lo)) - 0.3, logHi = std::log10(hi);
    auto frac = [&](double v) {
        if (!in.logY) return std::max(0.0, v / hi);
        if (v <= 0) return 0.0;
        return std::clamp((std::log10(v) - logLo) / std::max(1e-12, logHi - logLo), 0.0, 1.0);
    };
    const double plotH = H - top - bottom, groupW = (W - left - right) / groups, barW = 0.8 * groupW / ns;
    c.drawLine(P(left - 4, H - bottom), P(W - right, H - bottom), lineStyle(Role::Ink, 1.5f));
    // The value axis: a linear one ticked at 2, 5 or 10 x 10^k (at most five, with grid lines); a
    // log scale at its decades, ticks only, the values sitting on the bars (the review: 389
    // against 10000 read as 1 : 2 on bars with no axis).
    std::vector<std::pair<double, std::string>> ticks;
    char buf[32];
    if (valueAxis) {
        const double raw = hi / 4, decade = std::pow(10.0, std::floor(std::log10(raw)));
        const double tickStep = raw / decade < 2 ? 2 * decade : raw / decade < 5 ? 5 * decade : 10 * decade;
        for (double v = 0; v <= hi * (1 + 1e-9); v += tickStep) {
            std::snprintf(buf, sizeof buf, "%g", v);
            ticks.emplace_back(v, buf);
        }
    } else if (in.logY) {
        for (int e = int(std::ceil(logLo)); e <= int(std::floor(logHi)); ++e) {
            if (e >= 0 && e <= 4) std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, e));
            else std::snprintf(buf, sizeof buf, "1e%d", e);
            ticks.emplace_back(std::pow(10.0, e), buf);
        }
    }
    if (valueAxis || in.logY) {
        c.drawLine(P(left - 4, H - bottom), P(left - 4, top), lineStyle(Role::Ink, 1.5f));
        c.noteAxis(P(left - 4, H - bottom), P(left - 4, top), in.logY);  // LogAxisWithoutValues
    }
    for (const auto& [v, text] : ticks) {
        const double y = H - bottom - frac(v) * plotH;
        c.drawLine(P(left - 8, y), P(left - 4, y), lineStyle(Role::Ink, 1.5f));
        if (valueAxis) c.drawLine(P(left - 4, y), P(W - right, y), lineStyle(Role::Muted, 1.0f, true));
        c.drawTextPx(left - 11, y, text, TextStyle{13.0f, roleColor(Role::Ink), Anchor::Right, true, false});
    }
    const TextStyle value{13.0f, roleColor(Role::Ink), Anchor::Bottom, true, false};
    for (int g = 0; g < groups; ++g) {
        const double gx = left + g * groupW + 0.1 * groupW;
        for (int s = 0; s < ns; ++s) {
            if (g >= int(in.series[s].values.size())) continue;
            const double v = in.series[s].values[g];
            const double x0 = gx + s * barW, x1 = x0 + barW * 0.9, h = frac(v) * plotH;
            const double yb = H - bottom;
            c.drawPolygon({P(x0, yb), P(x1, yb), P(x1, yb - h), P(x0, yb - h)}, in.series[s].color);
            if (!in.valueFormat.empty()) {
                char buf[32];
                std::snprintf(buf, sizeof buf, in.valueFormat.c_str(), v);
                c.drawTextPx(0.5 * (x0 + x1), yb - h - 2, buf, value);
            }
        }
        c.drawTextPx(left + (g + 0.5) * groupW, H - bottom + 6, in.groups[g],
                     TextStyle{13.0f, roleColor(Role::Ink), Anchor::Top, true, false});
    }
    // Legend: one row per series under the heading, right-aligned.
    double ly = legendTop + 9;
    for (int s = 0; s < ns; ++s) {
        const TextStyle ts{13.0f, roleColor(Role::Ink), Anchor::Right, true, false};
        const double tw = c.measureText(in.series[s].label, ts).x();
        const double x = W - right;
        c.drawTextPx(x, ly, in.series[s].label, ts);
        c.noteSeries(in.series[s].label, in.series[s].color, P(x - tw - 13, ly));  // SeriesShareColour
        c.drawPolygon({P(x - tw - 20, ly - 6), P(x - tw - 6, ly - 6), P(x - tw - 6, ly + 6), P(x - tw - 20, ly + 6)},
                      in.series[s].color);
        ly += 18;
    }
    return c.readPixels();
}

}  // namespace cdlab::demos::bvhdemo
