#include "demos/gjk/gjk_closest_set_frame.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/canvas.h"

namespace cdlab::demos {

using namespace render;

ClosestSet gjkClosestSet(const PairScene& pair, const GjkResult& r) {
    if (!pair.a.isPolytope() || !pair.b.isPolytope() || r.status != GjkStatus::Separated || !(r.distance > 0)) return {};
    const std::vector<Vec3> a = pair.a.worldVertices(), b = pair.b.worldVertices();
    double size = 0;
    for (const Vec3& p : a) size = std::max(size, p.norm());
    for (const Vec3& p : b) size = std::max(size, p.norm());
    return closestSetOfPolytopes(a, b, r.separatingAxis, r.distance, 1e-9 * (1 + size), r.pointA);
}

Json closestSetJson(const ClosestSet& set) {
    Json pts = Json::array();
    for (const Vec3& p : set.onA) pts.push_back(vec3Json(p));
    return {{"on_a", pts}, {"offset", vec3Json(set.offset)}};
}

Image drawClosestSet(GlContext& gl, const SceneCommon& common, int scale, const PairScene& pair, const PairDrawing& d,
                     const GjkResult& r, const ClosestSet& set) {
    const TwoPanelLayout layout = twoPanelLayout(common.image.width, common.image.height, common.caption);
    const CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), scale);
    const bool labels = common.hasLayer("labels");
    // Left: the pair, the set on both, pairs joined. Right: the same seen along the axis (the set's
    // true shape on A's face).
    Image panels[2];
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : set.onA) centroid += p;
    centroid /= double(set.onA.size());
    std::vector<Vec3> onB;
    for (const Vec3& p : set.onA) onB.push_back(p + set.offset);
    for (int k = 0; k < 2; ++k) {
        // Right: A alone seen from B's side along the axis, the set in its true shape on A's face.
        const Vec3 view = k == 0 ? pair.view : r.separatingAxis;
        Canvas c(gl, po, panelCamera(d.planar, k == 0 ? d.wCenter : centroid, k == 0 ? d.wRadius : 0.75 * d.a.radius, view, layout));
        if (k == 0) drawPairBodies(c, d, 0.25f, false, labels, true);
        else drawBody(c, d.a, roleColor(Role::ShapeA), 0.25f, roleColor(Role::ShapeA).scaled(0.6f), 2.0f);
        for (const std::vector<Vec3>* s : std::initializer_list<const std::vector<Vec3>*>{&set.onA, &onB}) {
            if (k == 1 && s == &onB) continue;
            if (s->size() >= 3) c.drawPolygon(*s, roleColor(Role::Result).withAlpha(0.75f));
            if (s->size() >= 2) c.drawPolyline(*s, s->size() >= 3, lineStyle(Role::Result, 4.0f, false, true));
        }
        if (k == 0)
            for (std::size_t i = 0; i < set.onA.size(); ++i) c.drawLine(set.onA[i], onB[i], lineStyle(Role::Ink, 1.5f, true, true));
        c.drawPoint(r.pointA, 10.0f, roleColor(Role::Support), true, 2.0f, roleColor(Role::Ink));
        if (k == 0) c.drawPoint(r.pointB, 10.0f, roleColor(Role::Support), true, 2.0f, roleColor(Role::Ink));
        if (labels) {
            drawLabelAway(c, r.pointA, k == 0 ? d.a.center : centroid, "GJK's p_A", labelStyle(Role::Ink, 16.0f), 10.0);
            if (k == 0) drawLabelAway(c, r.pointB, d.b.center, "p_B", labelStyle(Role::Ink, 16.0f), 10.0);
        }
        drawPanelHeading(c, k == 0 ? "World space" : "A's face seen from B along the axis (B not drawn)",
                         k == 0 ? "every closest pair: a point of the set on A and its translate on B"
                                : "the set in its true shape; GJK's p_A is one of its points");
        panels[k] = c.readPixels();
    }
    const std::string shape = set.onA.size() >= 3 ? "a polygon of " + std::to_string(set.onA.size()) + " corners"
                              : set.onA.size() == 2 ? "a segment of length " + formatNumber((set.onA[1] - set.onA[0]).norm())
                                                    : "one point";
    double area = 0;
    for (std::size_t i = 1; i + 1 < set.onA.size(); ++i)
        area += 0.5 * (set.onA[i] - set.onA[0]).cross(set.onA[i + 1] - set.onA[0]).norm();
    std::vector<std::string> lines;
    lines.push_back("The closest pairs (p, p + d n), d = " + formatNumber(r.distance) + ", n = " + formatPoint(r.separatingAxis) +
                    ": p over " + shape + (set.onA.size() >= 3 ? " of area " + formatNumber(area) : "") + " on A");
    lines.push_back("GJK returns one of them: p_A = " + formatPoint(r.pointA) + ", p_B = " + formatPoint(r.pointB) +
                    " — any other point of the set is as right");
    return composeTwoPanel(gl, layout, scale, common.title + ": the closest points are not unique", common.caption, panels[0],
                           panels[1], lines);
}

}  // namespace cdlab::demos
