// The space_partition demo's grid_tradeoff figure (demos/space_partition/space_partition_scene.h):
// the uniform grid's cell size against its work. For each cell size h of the scene, core's
// UniformGrid::build over the same boxes: the (cell, box) entries it stores and the box pairs it
// tests in shared cells, beside brute force's n(n − 1)/2 and the overlapping pairs every h finds.
// Small cells: each box enters many cells (memory, insertion); large cells: many unrelated boxes
// share a cell (tests). Test: tests/demos/space_partition/grid_tradeoff_test.cpp.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "demos/draw/plot.h"
#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos::spacefig {

DemoOutput SpaceScene::runGridTradeoff(const RunContext& ctx) const {
    DemoOutput out;
    const double n = double(boxes.size());
    double meanSide = 0;
    for (const Aabb& b : boxes) meanSide += 0.5 * ((b.max.x() - b.min.x()) + (b.max.y() - b.min.y()));
    meanSide /= std::max(1.0, n);
    Json rows = Json::array();
    std::vector<std::pair<double, double>> tests, entries, pairs;
    for (double h : cellSizes) {
        UniformGrid grid;
        UniformGridOptions o;
        o.cellSize = h;
        const UniformGridResult r = grid.build(boxes, o);
        rows.push_back({{"cell_size", h}, {"status", r.status == GridStatus::Ok ? "ok" : "refused"}, {"entries", r.entries},
                        {"pair_tests", r.pairTests}, {"pairs", r.pairs}});
        if (r.status != GridStatus::Ok) continue;
        tests.emplace_back(h, std::max(1.0, double(r.pairTests)));
        entries.emplace_back(h, double(r.entries));
        pairs.emplace_back(h, std::max(1.0, double(r.pairs)));
    }
    out.trace["boxes"] = int(boxes.size());
    Json list = Json::array();
    for (const Aabb& b : boxes) list.push_back({b.min.x(), b.min.y(), b.max.x(), b.max.y()});
    out.trace["box_list"] = list;
    out.trace["mean_side"] = meanSide;
    out.trace["brute_force_tests"] = n * (n - 1) / 2;
    out.trace["rows"] = rows;
    if (numericOnly(ctx, out)) return out;
    PlotOptions po = scenePlotOptions(common_, figureScale(common_, ctx));
    po.subtitle = common_.caption;
    po.legendWidth = 280;
    po.xLabel = "cell size h (mean box side " + formatNumber(meanSide) + ")";
    po.yLabel = "count per build";
    po.xFloor = po.yFloor = 1e-9;
    po.hLines.push_back({n * (n - 1) / 2, "brute force: n(n − 1)/2 = " + std::to_string((long long)(n * (n - 1) / 2))});
    std::vector<PlotSeries> series = {{"pairs tested in shared cells", 5, true, true, tests, {}},
                                      {"(cell, box) entries stored", 1, true, true, entries, {}},
                                      {"overlapping pairs: " + std::to_string(pairs.empty() ? 0 : (long long)pairs.front().second),
                                       2, true, false, pairs, {}}};
    Frame f;
    f.name = "tradeoff";
    f.caption = common_.title;
    f.image = drawLogLogPlot(*ctx.gl, po, series);
    out.frames.push_back(std::move(f));
    return out;
}

}  // namespace cdlab::demos::spacefig
