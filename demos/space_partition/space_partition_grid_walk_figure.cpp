// The space_partition demo's grid_walk figure (demos/space_partition/space_partition_scene.h): a
// segment walking a uniform grid cell by cell (core's UniformGrid::cellsAlongSegment, the 3D DDA of
// Amanatides and Woo in the plane z = 0), the cells numbered in the order visited, the boxes entered
// in those cells — the only candidates a ray query tests — and those the segment hits
// (intersectSegmentAabb). Test: tests/demos/space_partition/grid_walk_test.cpp.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/overlap/intersect_ray.h"
#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos::spacefig {

DemoOutput SpaceScene::runGridWalk(const RunContext& ctx) const {
    DemoOutput out;
    const double h = gridCell;
    const std::vector<UniformGrid::RayCell> cells = UniformGrid::cellsAlongSegment(segment.a, segment.b, h, 10000);
    // The candidates: boxes entered in a visited cell (a box enters every cell its closed extent touches).
    std::vector<int> candidates, hits;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const auto lo = UniformGrid::cellOf(boxes[i].min, h), hi = UniformGrid::cellOf(boxes[i].max, h);
        const bool entered = std::any_of(cells.begin(), cells.end(), [&](const UniformGrid::RayCell& c) {
            return c.cell[0] >= lo[0] && c.cell[0] <= hi[0] && c.cell[1] >= lo[1] && c.cell[1] <= hi[1];
        });
        if (!entered) continue;
        candidates.push_back(int(i));
        if (intersectSegmentAabb(segment, boxes[i]).hit) hits.push_back(int(i));
    }
    Json cs = Json::array();
    for (const auto& c : cells) cs.push_back({{"cell", {c.cell[0], c.cell[1]}}, {"t_enter", c.tEnter}});
    Json list = Json::array();
    for (const Aabb& b : boxes) list.push_back({b.min.x(), b.min.y(), b.max.x(), b.max.y()});
    out.trace["cell_size"] = h;
    out.trace["segment"] = {vec2Json(segment.a), vec2Json(segment.b)};
    out.trace["box_list"] = list;
    out.trace["cells"] = cs;
    out.trace["candidates"] = candidates;
    out.trace["hits"] = hits;
    if (numericOnly(ctx, out)) return out;
    Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
    const Aabb& fr = region;
    const double W = std::max(fr.max.x() - fr.min.x(), fr.max.y() - fr.min.y());
    const Vec3 c = 0.5 * (fr.min + fr.max);
    const double aspect = double(common_.image.width) / double(common_.image.height);
    canvas.setCamera(Camera::twoD(c.x() + 0.05 * W, c.y() + 0.04 * W, std::max(W * 1.42, W * 1.5 / aspect)));
    // Visited cells shaded, the grid lines, the boxes (candidates filled, the rest faint), the segment.
    for (const auto& cell : cells) {
        const Aabb sq{P(double(cell.cell[0]) * h, double(cell.cell[1]) * h), P(double(cell.cell[0] + 1) * h, double(cell.cell[1] + 1) * h)};
        fillRect(canvas, sq, Vec3::Zero(), roleColor(Role::Highlight).withAlpha(0.18f));
    }
    const LineStyle gridLine = lineStyle(Role::Muted, 1.0f);
    for (double x = std::floor(fr.min.x() / h) * h; x <= fr.max.x() + 1e-9; x += h) canvas.drawLine(P(x, fr.min.y()), P(x, fr.max.y()), gridLine);
    for (double y = std::floor(fr.min.y() / h) * h; y <= fr.max.y() + 1e-9; y += h) canvas.drawLine(P(fr.min.x(), y), P(fr.max.x(), y), gridLine);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const bool cand = std::count(candidates.begin(), candidates.end(), int(i)) > 0;
        const bool hit = std::count(hits.begin(), hits.end(), int(i)) > 0;
        fillRect(canvas, boxes[i], Vec3::Zero(), roleColor(Role::ShapeA).withAlpha(cand ? 0.6f : 0.15f));
        outlineRect(canvas, boxes[i], Vec3::Zero(),
                    hit ? lineStyle(Role::Highlight, 3.0f, false, true) : lineStyle(Role::ShapeA, cand ? 1.5f : 0.8f));
    }
    canvas.drawArrow(segment.a, segment.b, lineStyle(Role::Ink, 2.5f, false, true));
    if (common_.hasLayer("labels"))
        for (std::size_t k = 0; k < cells.size() && k < 60; ++k) {
            const Vec3 centre = P((double(cells[k].cell[0]) + 0.5) * h, (double(cells[k].cell[1]) + 0.5) * h);
            TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::Center, true, true};
            ts.place = true;  // in its cell off the segment and the boxes' outlines where it can be
            canvas.drawText(centre, std::to_string(k + 1), ts);
        }
    heading(canvas, P(fr.min.x(), fr.max.y()), "A segment walking the grid (cell size " + formatNumber(h) + ")",
            std::to_string(cells.size()) + " cells visited in order; " + std::to_string(candidates.size()) +
                " boxes in them tested, " + std::to_string(hits.size()) + " hit; " + std::to_string(boxes.size()) +
                " boxes in all");
    keyBelow(canvas, fr.min,
             {{roleColor(Role::Highlight).withAlpha(0.5f), "cell visited (numbered in order)"},
              {roleColor(Role::ShapeA), "box in a visited cell: tested"},
              {roleColor(Role::Highlight), "box hit (outlined)"}});
    out.frames.push_back(titledFrame(canvas, "walk"));
    return out;
}

}  // namespace cdlab::demos::spacefig
