#include "demos/gjk/gjk_regions_frame.h"

#include <algorithm>
#include <cmath>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;
using Vec2d = Eigen::Vector2d;

/// a · p <= b.
struct HalfPlane {
    Vec2d a;
    double b;
};

std::vector<Vec2d> clip(std::vector<Vec2d> poly, const HalfPlane& h) {
    std::vector<Vec2d> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2d& p = poly[i];
        const Vec2d& q = poly[(i + 1) % poly.size()];
        const double sp = h.a.dot(p) - h.b, sq = h.a.dot(q) - h.b;
        if (sp <= 0) out.push_back(p);
        if ((sp <= 0) != (sq <= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    return out;
}

/// One Voronoi region of the simplex: its vertices (slot indices), and its half-planes.
struct Region {
    std::vector<int> slots;
    std::vector<HalfPlane> planes;
};

/// The simplex's points in its plane's coordinates and the origin's projection there.
struct PlaneFrame {
    std::vector<int> slots;      ///< the simplex's slots in order
    std::vector<Vec2d> points;   ///< the same order
    Vec2d origin = Vec2d::Zero();
    double offPlane = 0.0;       ///< the origin's distance from the triangle's plane (0 for a segment)
};

PlaneFrame planeFrame(const GjkTraceStep& s) {
    PlaneFrame f;
    std::vector<Vec3> w;
    for (int i = 0; i < s.simplexCount; ++i) f.slots.push_back(i), w.push_back(s.simplex[i].w);
    const Vec3 e1 = (w[1] - w[0]).normalized();
    Vec3 n = w.size() == 3 ? Vec3((w[1] - w[0]).cross(w[2] - w[0])) : Vec3(e1.cross(-w[0]));
    if (!(n.norm() > 0)) n = e1.unitOrthogonal();  // the origin on the segment's line
    n.normalize();
    const Vec3 e2 = n.cross(e1);
    for (const Vec3& p : w) f.points.emplace_back((p - w[0]).dot(e1), (p - w[0]).dot(e2));
    f.origin = Vec2d((-w[0]).dot(e1), (-w[0]).dot(e2));
    f.offPlane = w.size() == 3 ? std::abs(n.dot(-w[0])) : 0.0;
    double size = 0;
    for (const Vec3& p : w) size = std::max(size, p.norm());
    if (f.offPlane <= 1e-12 * size) f.offPlane = 0.0;  // in the plane up to rounding (a planar scene)
    return f;
}

/// Every region of a segment (3) or a triangle (7), by its half-planes in the plane.
std::vector<Region> regionsOf(const PlaneFrame& f) {
    const std::vector<Vec2d>& p = f.points;
    const int n = int(p.size());
    std::vector<Region> out;
    for (int i = 0; i < n; ++i) {  // vertex i: behind every edge's perpendicular at it
        Region r{{f.slots[i]}, {}};
        for (int j = 0; j < n; ++j)
            if (j != i) r.planes.push_back({p[j] - p[i], (p[j] - p[i]).dot(p[i])});
        out.push_back(r);
    }
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {  // edge ij: between the perpendiculars, outside the triangle
            if (n == 2 && !(i == 0 && j == 1)) continue;
            Region r{{f.slots[i], f.slots[j]}, {}};
            r.planes.push_back({-(p[j] - p[i]), -(p[j] - p[i]).dot(p[i])});
            r.planes.push_back({-(p[i] - p[j]), -(p[i] - p[j]).dot(p[j])});
            if (n == 3) {
                const int k = 3 - i - j;
                Vec2d out2(p[j].y() - p[i].y(), p[i].x() - p[j].x());
                if (out2.dot(p[k] - p[i]) > 0) out2 = -out2;  // away from the third vertex
                r.planes.push_back({-out2, -out2.dot(p[i])});
            }
            out.push_back(r);
        }
    if (n == 3) {  // the face: inside every edge
        Region r{{f.slots[0], f.slots[1], f.slots[2]}, {}};
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            Vec2d out2(p[j].y() - p[i].y(), p[i].x() - p[j].x());
            if (out2.dot(p[k] - p[i]) > 0) out2 = -out2;
            r.planes.push_back({out2, out2.dot(p[i])});
        }
        out.push_back(r);
    }
    return out;
}

std::string names(const std::vector<int>& slots) {
    std::string s;
    for (int i : slots) s += "w" + std::to_string(i);
    return s;
}

std::vector<int> keptOf(const GjkTraceStep& s) {
    std::vector<int> kept;
    for (int i = 0; i < s.simplexCount; ++i)
        if (s.keptSlots & (1u << i)) kept.push_back(i);
    return kept;
}

/// One sign test of the kept feature's region: its name, value and the sign it must have.
struct RegionTest {
    std::string name;
    double value;
    bool positive;
};

/// A vertex i: (O − wi)·(wj − wi) ≤ 0 for the other vertices j. An edge ij: (O − wi)·(wj − wi) ≥ 0
/// both ways and, in a triangle, n·(O − wi) ≥ 0 with n the edge's normal away from the third
/// vertex. The face: n·(O − wi) ≤ 0 for every edge (inside all three). Regions are closed: a
/// boundary point (golden gjk/touching: the origin on the edge's line) belongs to both sides.
std::vector<RegionTest> regionTests(const PlaneFrame& f, const std::vector<int>& kept) {
    const auto at = [&](int slot) { return int(std::find(f.slots.begin(), f.slots.end(), slot) - f.slots.begin()); };
    const auto w = [](int i) { return "w" + std::to_string(i); };
    const auto dot = [&](int i, int j) {
        return RegionTest{"(O − " + w(i) + ")·(" + w(j) + " − " + w(i) + ")",
                          (f.origin - f.points[at(i)]).dot(f.points[at(j)] - f.points[at(i)]), false};
    };
    const auto outward = [&](int i, int j, int k) {  // n·(O − wi) for edge ij, n away from wk
        const Vec2d a = f.points[at(i)], b = f.points[at(j)];
        Vec2d n(b.y() - a.y(), a.x() - b.x());
        if (n.dot(f.points[at(k)] - a) > 0) n = -n;
        return RegionTest{"n" + w(i) + w(j) + "·(O − " + w(i) + ")", n.dot(f.origin - a), true};
    };
    std::vector<RegionTest> out;
    if (kept.size() == 1) {
        for (int j : f.slots)
            if (j != kept[0]) out.push_back(dot(kept[0], j));
    } else if (kept.size() == 2) {
        RegionTest a = dot(kept[0], kept[1]), b = dot(kept[1], kept[0]);
        a.positive = b.positive = true;
        out.push_back(a), out.push_back(b);
        for (int k : f.slots)
            if (k != kept[0] && k != kept[1]) out.push_back(outward(kept[0], kept[1], k));
    } else {
        for (int i = 0; i < 3; ++i) {
            RegionTest t = outward(f.slots[i], f.slots[(i + 1) % 3], f.slots[(i + 2) % 3]);
            t.positive = false;
            out.push_back(t);
        }
    }
    return out;
}

}  // namespace

int firstDroppingStep(const std::vector<GjkTraceStep>& steps) {
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const GjkTraceStep& s = steps[i];
        if ((s.simplexCount == 2 || s.simplexCount == 3) && s.keptCount() < s.simplexCount && !s.terminated)
            return int(i);
    }
    return -1;
}

Json reductionRegionsJson(const GjkTraceStep& step) {
    const PlaneFrame f = planeFrame(step);
    const std::vector<int> kept = keptOf(step);
    Json tests = Json::array();
    for (const RegionTest& t : regionTests(f, kept))
        tests.push_back({{"test", t.name}, {"value", t.value}, {"sign", t.positive ? ">= 0" : "<= 0"}});
    Json dropped = Json::array();
    for (int i = 0; i < step.simplexCount; ++i)
        if (!(step.keptSlots & (1u << i))) dropped.push_back("w" + std::to_string(i));
    return {{"iteration", step.iteration}, {"kept", names(kept)}, {"dropped", dropped},
            {"origin_in_plane", {f.origin.x(), f.origin.y()}}, {"off_plane", f.offPlane}, {"tests", tests}};
}

Image drawReductionRegions(GlContext& gl, int width, int height, int scale, const std::string& title, const GjkTraceStep& step) {
    const PlaneFrame f = planeFrame(step);
    const std::vector<int> kept = keptOf(step);
    Canvas c(gl, canvasOptions(width, height, scale), Camera::pixels(width, height));
    // The plane's window: the simplex and the origin with a margin, mapped into the picture area.
    Vec2d lo = f.origin, hi = f.origin;
    for (const Vec2d& p : f.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec2d mid = 0.5 * (lo + hi);
    const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y()) * 1.9;
    const double top = 60, bottom = 110;
    const double box = std::min(width - 80.0, height - top - bottom);
    const double cx = 0.5 * width, cy = top + 0.5 * (height - top - bottom);
    const auto S = [&](const Vec2d& p) {
        return Vec3(cx + (p.x() - mid.x()) / span * box, height - (cy - (p.y() - mid.y()) / span * box), 0);
    };
    const std::vector<Vec2d> window = {mid + Vec2d(-0.5, -0.5) * span, mid + Vec2d(0.5, -0.5) * span,
                                       mid + Vec2d(0.5, 0.5) * span, mid + Vec2d(-0.5, 0.5) * span};
    const std::vector<Region> regions = regionsOf(f);
    for (const Region& r : regions) {
        std::vector<Vec2d> poly = window;
        for (const HalfPlane& h : r.planes) poly = clip(poly, h);
        if (poly.size() < 3) continue;
        const bool hot = r.slots == kept;
        std::vector<Vec3> px;
        for (const Vec2d& p : poly) px.push_back(S(p));
        const Color color = featureDimensionColor(int(r.slots.size()) - 1);
        c.drawPolygon(px, color.withAlpha(hot ? 0.55f : 0.16f));
        c.drawPolyline(px, true, LineStyle{1.0f, color.scaled(0.7f), 0.0f, false});
        Vec2d centre = Vec2d::Zero();
        for (const Vec2d& p : poly) centre += p;
        centre /= double(poly.size());
        TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, hot};
        ts.place = true;
        c.drawText(S(centre), names(r.slots) + (hot ? " (the origin's)" : ""), ts);
    }
    // The simplex, its vertices (dropped ones hollow), the origin.
    const int n = int(f.points.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) c.drawLine(S(f.points[i]), S(f.points[j]), lineStyle(Role::Simplex, 3.0f, false, true));
    for (int i = 0; i < n; ++i) {
        const bool keep = step.keptSlots & (1u << f.slots[i]);
        c.drawPoint(S(f.points[i]), 11.0f, keep ? roleColor(Role::Simplex) : roleColor(Role::Background), true, 2.0f,
                    roleColor(Role::Ink));
        TextStyle ts = labelStyle(Role::Ink, 18.0f);
        ts.place = true;
        const Vec2d away = (f.points[i] - mid).normalized();
        ts.offsetPx = Eigen::Vector2d(away.x(), -away.y()) * 22.0;
        c.drawText(S(f.points[i]), "w" + std::to_string(f.slots[i]) + (keep ? "" : " dropped"), ts);
    }
    c.drawPoint(S(f.origin), 9.0f, roleColor(Role::Ink), true);
    TextStyle os = labelStyle(Role::Ink, 18.0f);
    os.place = true;
    os.offsetPx = Eigen::Vector2d(16, -16);
    c.drawText(S(f.origin), "O", os);
    // The tests that place the origin in the kept feature's region.
    std::string tests;
    for (const RegionTest& t : regionTests(f, kept))
        tests += (tests.empty() ? "" : ",  ") + t.name + " = " + formatNumber(t.value) + (t.positive ? " ≥ 0" : " ≤ 0");
    std::vector<std::string> dropped;
    for (int i = 0; i < step.simplexCount; ++i)
        if (!(step.keptSlots & (1u << i))) dropped.push_back("w" + std::to_string(i));
    std::string droppedText;
    for (const std::string& d : dropped) droppedText += (droppedText.empty() ? "" : ", ") + d;
    const std::string kind = kept.size() == 1 ? "vertex" : kept.size() == 2 ? "edge" : "face";
    c.drawTextPx(20, height - 96,
                 "Iteration " + std::to_string(step.iteration) + ": the origin" +
                     (f.offPlane > 0 ? " (" + formatNumber(f.offPlane) + " off the plane, drawn projected)" : "") +
                     " lies in the Voronoi region of " + kind + " " + names(kept) + ": keep it, drop " + droppedText,
                 TextStyle{17.0f, roleColor(Role::Ink), Anchor::Left, false, true});
    c.drawTextPx(20, height - 70, tests, TextStyle{16.0f, roleColor(Role::Ink), Anchor::Left, false, false});
    drawTitleAndCaption(c, title + ": the simplex's Voronoi regions at a reduction",
                        "In the plane of the simplex: each region holds the points nearest one feature; the origin's names what GJK keeps");
    return c.readPixels();
}

}  // namespace cdlab::demos
