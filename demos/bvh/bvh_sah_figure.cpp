// The BVH demo's sah_split figure (demos/bvh/bvh_scene.h: BvhScene and its helpers): how a top-down
// SAH build chooses each split (Wald 2007; MacDonald and Booth 1990's cost model). For the root and
// the nodes below it to the scene's tree_depth - 1 (at most six), one plot: every bin plane's cost
// (A_L N_L + A_R N_R) / A against its position, one line per axis, beside the cost of keeping the
// node a leaf (N) and of the median split the top-down median build takes. Every number from
// core's traced buildBvh (BvhBuildStep::candidates, medianCost). Test:
// tests/demos/bvh/bvh_sah_test.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "demos/bvh/bvh_scene.h"
#include "demos/draw/plot.h"

namespace cdlab::demos::bvhfig {

void BvhScene::runSahSplit(const RunContext& ctx, DemoOutput& out) const {
    const MeshSpec& m = meshes[0];
    BvhBuildTrace trace;
    trace.candidatesToDepth = treeDepth - 1;  // the nodes drawn
    const Bvh tree = buildChecked(m.mesh, BvKind::Aabb, BvhBuildMethod::TopDownSah, &trace);
    constexpr int kMaxFrames = 6;
    std::vector<const BvhBuildStep*> shown;
    for (const BvhBuildStep& s : trace.steps)
        if (s.splitAxis >= 0 && !s.candidates.empty() && s.depth < treeDepth && int(shown.size()) < kMaxFrames)
            shown.push_back(&s);
    Json nodes = Json::array();
    for (const BvhBuildStep* s : shown) {
        Json cs = Json::array();
        for (const BvhBuildStep::SahCandidate& c : s->candidates)
            cs.push_back({{"axis", c.axis}, {"position", c.position}, {"left_count", c.leftCount},
                          {"right_count", c.rightCount}, {"left_area", c.leftArea}, {"right_area", c.rightArea},
                          {"cost", c.cost}});
        nodes.push_back({{"node", s->node}, {"depth", s->depth}, {"count", s->count}, {"split_axis", s->splitAxis},
                         {"split_position", s->splitPosition}, {"cost", s->cost}, {"median_axis", s->medianAxis},
                         {"median_position", s->medianPosition}, {"median_cost", s->medianCost}, {"candidates", cs}});
    }
    out.trace = {{"mesh", m.kind}, {"triangles", m.mesh.triangleCount()}, {"bins", build.sahBins}, {"nodes", nodes}};
    if (!ctx.gl) return;
    static const char* kAxis = "xyz";
    for (const BvhBuildStep* s : shown) {
        PlotOptions po;
        po.width = W();
        po.height = H();
        po.scale = ss_;
        po.logX = po.logY = false;
        po.legendWidth = 250;
        po.title = common_.title + (s->depth == 0 ? ": the root" : ": node " + std::to_string(s->node)) + ", " +
                   std::to_string(s->count) + " triangles";
        po.xLabel = "bin plane position on its axis";
        po.yLabel = "SAH cost (A_L N_L + A_R N_R) / A";
        po.hLines.push_back({double(s->count), "as a leaf: N = " + std::to_string(s->count)});
        po.hLines.push_back({s->medianCost, "median split on " + std::string(1, kAxis[s->medianAxis]) + ": " + fmt(s->medianCost)});
        const BvhBuildStep::SahCandidate* best = nullptr;
        for (const auto& c : s->candidates)
            if (!best || c.cost < best->cost) best = &c;
        po.subtitle = "lowest " + fmt(best->cost) + " at " + std::string(1, kAxis[best->axis]) + " = " + fmt(best->position) +
                      " (" + std::to_string(best->leftCount) + " | " + std::to_string(best->rightCount) +
                      " triangles, areas " + fmt(best->leftArea) + " | " + fmt(best->rightArea) + ")" +
                      (s->medianCost < best->cost ? "; the median split, on no bin plane, costs less" : "");
        std::vector<PlotSeries> series;
        static constexpr int kStyles[3] = {5, 2, 1};
        for (int axis = 0; axis < 3; ++axis) {
            PlotSeries p{"split on " + std::string(1, kAxis[axis]), kStyles[axis], true, true, {}, {}};
            for (const auto& c : s->candidates)
                if (c.axis == axis) p.points.emplace_back(c.position, c.cost);
            if (!p.points.empty()) series.push_back(std::move(p));
        }
        PlotSeries chosen{"chosen (lowest)", 0, false, true, {{best->position, best->cost}}, {}};
        series.push_back(chosen);
        char name[32];
        std::snprintf(name, sizeof name, "sah_node_%02d", s->node);
        out.frames.push_back(Frame{name, po.title, drawLogLogPlot(*ctx.gl, po, series)});
    }
}

}  // namespace cdlab::demos::bvhfig
