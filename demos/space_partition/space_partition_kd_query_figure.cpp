// The space_partition demo's kd_query figure (demos/space_partition/space_partition_scene.h: SpaceScene
// and its helpers).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos::spacefig {

DemoOutput SpaceScene::runKdQuery(const RunContext& ctx) const {
    DemoOutput out;
    KdTree kt;
    kt.build(points, {kd.rule, kd.leaf});
    KdQueryTrace nt, rt;
    const KdNearestResult nearest = kt.nearest(query, &nt);
    const std::vector<int> hits = kt.rangeQuery(range, &rt);
    out.trace["points"] = int(points.size());
    out.trace["nodes"] = int(kt.nodes().size());
    out.trace["depth"] = kt.depth();
    out.trace["nearest"] = {{"query", vec2Json(query)},
                            {"index", nearest.index},
                            {"distance", std::sqrt(nearest.distanceSquared)},
                            {"distance_tests", nt.distanceTests},
                            {"nodes_visited", int(nt.visited.size())},
                            {"subtrees_pruned", int(nt.pruned.size())},
                            {"best_so_far", nt.bestSoFar}};
    out.trace["range"] = {{"box", {vec2Json(range.min), vec2Json(range.max)}},
                          {"hits", hits},
                          {"point_tests", rt.distanceTests},
                          {"nodes_visited", int(rt.visited.size())},
                          {"subtrees_pruned", int(rt.pruned.size())}};
    if (numericOnly(ctx, out)) return out;
    Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
    const Vec3 size = region.max - region.min;
    const double W = std::max(size.x(), size.y());
    const double gap = 0.12 * W;
    const Vec3 offsets[2] = {P(0, 0), P(W + gap, 0)};
    const Vec3 middle = region.min + P(0.5 * (2 * W + gap), 0.5 * W);
    const double aspect = double(common_.image.width) / double(common_.image.height);
    canvas.setCamera(
        Camera::twoD(middle.x(), middle.y() + 0.03 * W, std::max(W * 1.45, (2 * W + gap) * 1.05 / aspect)));
    const Aabb frame{region.min, region.min + P(W, W)};
    const auto& nodes = kt.nodes();

    auto cellOf = [&](int id) { return kdCellInFrame(kt, id, frame); };
    auto drawTree = [&](const Vec3& at, const KdQueryTrace& t) {
        if (common_.hasLayer("cells")) {
            for (int id : t.pruned) fillRect(canvas, cellOf(id), at, roleColor(Role::Muted).withAlpha(0.30f));
            for (int id : t.visited)
                if (nodes[std::size_t(id)].isLeaf())
                    fillRect(canvas, cellOf(id), at, roleColor(Role::Highlight).withAlpha(0.22f));
        }
        if (common_.hasLayer("splits"))
            for (std::size_t id = 0; id < nodes.size(); ++id) {
                const KdNode& node = nodes[id];
                if (node.isLeaf()) continue;
                drawKdSplit(canvas, node, cellOf(int(id)), at,
                            LineStyle{depthWidth(node.depth), depthColor(node.depth, kt.depth())});
            }
        if (common_.hasLayer("objects"))
            for (const Vec3& p : points) canvas.drawPoint(at + p, 4.0f, roleColor(Role::Ink), true, 0.0f);
        outlineRect(canvas, frame, at, lineStyle(Role::Ink, 1.5f));
    };

    // Left: nearest neighbour.
    drawTree(offsets[0], nt);
    if (common_.hasLayer("queries") && nearest.index >= 0) {
        const Vec3 at = offsets[0];
        const double r = std::sqrt(nearest.distanceSquared);
        std::vector<Vec3> circle;
        for (int k = 0; k < 96; ++k)
            circle.push_back(at + query + r * P(std::cos(2 * M_PI * k / 96), std::sin(2 * M_PI * k / 96)));
        canvas.drawPolyline(circle, true, lineStyle(Role::Result, 2.0f, true, true));
        // Improvements of the best point, in order: the search narrows.
        for (std::size_t k = 0; k + 1 < nt.bestSoFar.size(); ++k)
            canvas.drawPoint(at + points[std::size_t(nt.bestSoFar[k])], 7.0f, roleColor(Role::Simplex), true, 1.5f);
        canvas.drawLine(at + query, at + points[std::size_t(nearest.index)],
                        lineStyle(Role::Result, 3.0f, false, true));
        canvas.drawPoint(at + points[std::size_t(nearest.index)], 8.0f, roleColor(Role::Result), true, 2.0f);
        canvas.drawPoint(at + query, 9.0f, roleColor(Role::Query), true, 2.0f);
        if (common_.hasLayer("labels"))
            canvas.drawText(at + query, "q", TextStyle{20.0f, roleColor(Role::Ink), Anchor::Left, true, true, {10, 0}});
    }
    heading(canvas, offsets[0] + P(frame.min.x(), frame.max.y()), "Nearest neighbour of q",
            std::to_string(nt.distanceTests) + " of " + std::to_string(points.size()) + " points tested, " +
                std::to_string(nt.pruned.size()) + " subtrees pruned");
    // Under each panel: the two cell tints drawTree paints, then what the query's points mean.
    const auto keyWith = [&](const KeyItem& points) {
        return std::vector<KeyItem>{
            {roleColor(Role::Highlight).mixed(roleColor(Role::Background), 0.6f), "leaf searched"},
            {roleColor(Role::Muted), "subtree pruned"},
            points};
    };
    if (common_.hasLayer("labels"))
        keyBelow(canvas, offsets[0] + frame.min, keyWith({roleColor(Role::Simplex), "earlier best"}));
    // Right: range query.
    drawTree(offsets[1], rt);
    if (common_.hasLayer("queries")) {
        const Vec3 at = offsets[1];
        fillRect(canvas, range, at, roleColor(Role::Simplex).withAlpha(0.25f));
        outlineRect(canvas, range, at, lineStyle(Role::Simplex, 3.0f, false, true));
        for (int i : hits) canvas.drawPoint(at + points[std::size_t(i)], 7.0f, roleColor(Role::Result), true, 1.5f);
    }
    heading(canvas, offsets[1] + P(frame.min.x(), frame.max.y()), "Range query (box)",
            std::to_string(hits.size()) + " hits, " + std::to_string(rt.distanceTests) + " points tested, " +
                std::to_string(rt.pruned.size()) + " subtrees pruned");
    if (common_.hasLayer("labels")) keyBelow(canvas, offsets[1] + frame.min, keyWith({roleColor(Role::Result), "hit"}));
    out.frames.push_back(titledFrame(canvas, "kd_query"));
    return out;
}

}  // namespace cdlab::demos::spacefig
