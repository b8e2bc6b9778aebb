// The space_partition demo's bsp_shape figure (demos/space_partition/space_partition_scene.h: SpaceScene
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

DemoOutput SpaceScene::runBspShape(const RunContext& ctx) const {
    DemoOutput out;
    std::vector<BspPolygon> walls;
    addWalls(polygon, walls);
    BspTree bt;
    BspTrace trace;
    bt.build(walls, bsp, &trace);
    const BspStats bs = bt.stats();
    static const char* kClass[3] = {"inside", "outside", "on"};
    std::vector<BspPointClass> classes;
    for (const Vec3& q : queries) classes.push_back(bt.classifyPoint(q));
    BspRayResult ray;
    if (hasSegment) ray = bt.segmentQuery(segment);
    out.trace["edges"] = int(polygon.size());
    out.trace["nodes"] = bs.nodeCount;
    out.trace["inner"] = bs.innerCount;
    out.trace["solid_leaves"] = bs.solidLeaves;
    out.trace["empty_leaves"] = bs.emptyLeaves;
    out.trace["depth"] = bs.depth;
    out.trace["splits"] = bs.splits;
    out.trace["fragments"] = bs.fragmentCount;
    out.trace["steps"] = bspStepsJson(trace);
    Json qs = Json::array();
    for (std::size_t i = 0; i < queries.size(); ++i)
        qs.push_back({{"point", vec2Json(queries[i])}, {"class", kClass[int(classes[i])]}});
    out.trace["queries"] = qs;
    if (hasSegment)
        out.trace["segment"] = {{"from", vec2Json(segment.a)},
                                {"to", vec2Json(segment.b)},
                                {"hit", ray.hit},
                                {"t", ray.t},
                                {"point", vec2Json(ray.point)}};
    if (numericOnly(ctx, out)) return out;
    Canvas canvas(*ctx.gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
    // Shape panel on the left (square), tree diagram on the right.
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const Vec3& v : polygon) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double W = (hi - lo).head<2>().maxCoeff() * 1.25;
    const Vec3 c = 0.5 * (lo + hi);
    const Aabb frame{P(c.x() - 0.5 * W, c.y() - 0.5 * W), P(c.x() + 0.5 * W, c.y() + 0.5 * W)};
    const double treeW = 0.85 * W, gap = 0.08 * W;
    const double aspect = double(common_.image.width) / double(common_.image.height);
    const double viewH = std::max(W * 1.32, (W + gap + treeW) * 1.04 / aspect);
    canvas.setCamera(Camera::twoD(frame.min.x() + 0.5 * (W + gap + treeW), c.y() + 0.02 * W, viewH));
    const auto regions = bspRegions(bt, rectPolygon(frame));
    const auto& nodes = bt.nodes();
    if (common_.hasLayer("cells"))
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            if (nodes[i].kind == BspNodeKind::Inner || regions[i].size() < 3) continue;
            const bool solid = nodes[i].kind == BspNodeKind::SolidLeaf;
            canvas.drawPolygon(regions[i],
                               solid ? roleColor(Role::ShapeA).withAlpha(0.38f) : roleColor(Role::Background));
        }
    if (common_.hasLayer("splits")) drawBspSplits(canvas, bt, regions, Vec3::Zero(), 1.0f);
    if (common_.hasLayer("objects")) drawBspFragments(canvas, bt, Vec3::Zero(), 4.0f, 4.0f);
    outlineRect(canvas, frame, Vec3::Zero(), lineStyle(Role::Ink, 1.5f));
    const bool labels = common_.hasLayer("labels");
    if (labels)  // edge names e0, e1, ... at the midpoints, pushed outwards
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const Vec3 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
            const Vec3 out2 = Vec3(b.y() - a.y(), a.x() - b.x(), 0).normalized();
            TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
            ts.place = true;  // outside the edge's midpoint, off the query points
            ts.offsetPx = Eigen::Vector2d(out2.x(), -out2.y()) * 18.0;
            canvas.drawText(0.5 * (a + b), "e" + std::to_string(i), ts);
        }
    if (common_.hasLayer("queries")) {
        for (std::size_t i = 0; i < queries.size(); ++i) {
            const Role role = classes[i] == BspPointClass::Inside    ? Role::Result
                              : classes[i] == BspPointClass::Outside ? Role::Query
                                                                     : Role::Simplex;
            canvas.drawPoint(queries[i], 8.0f, roleColor(role), true, 2.0f);
            if (labels) {  // right of the point when free, else around it (off the split lines)
                TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::Center, true, false, {30, 0}};
                ts.place = true;
                canvas.drawText(queries[i], kClass[int(classes[i])], ts);
            }
        }
        if (hasSegment) {
            canvas.drawArrow(segment.a, segment.b, lineStyle(Role::Direction, 2.5f, true, true));
            if (ray.hit) {
                canvas.drawPoint(ray.point, 9.0f, roleColor(Role::Support), true, 2.0f);
                if (labels) {  // below left of the hit when free, else around it
                    TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::Center, true, true, {-36, 8}};
                    ts.place = true;
                    canvas.drawText(ray.point, "first hit", ts);  // its t in the subtitle
                }
            }
        }
    }
    heading(canvas, P(frame.min.x(), frame.max.y()), "Splits and leaf regions (top view)",
            std::to_string(bs.innerCount) + " planes, " + std::to_string(bs.splits) +
                (bs.splits == 1 ? " edge" : " edges") + " cut" +
                (hasSegment && ray.hit ? "; the ray's first hit at t = " + formatNumber(ray.t) : std::string()));
    if (common_.hasLayer("labels")) keyBelow(canvas, frame.min, {{roleColor(Role::Highlight), "an edge cut in two"}});
    if (common_.hasLayer("tree"))
        drawTreeDiagram(canvas, bt, P(frame.max.x() + gap, frame.min.y()), treeW, W, bs.depth);
    out.frames.push_back(titledFrame(canvas, "bsp_shape"));
    return out;
}

void SpaceScene::drawTreeDiagram(Canvas& canvas, const BspTree& bt, const Vec3& corner, double w, double h,
                                 int depth) const {
    const auto& nodes = bt.nodes();
    std::vector<double> x(nodes.size(), 0.0);
    int leafCount = 0;
    for (const BspNode& n : nodes) leafCount += n.kind != BspNodeKind::Inner;
    int next = 0;
    std::function<double(int)> place = [&](int id) -> double {
        const BspNode& n = nodes[std::size_t(id)];
        if (n.kind != BspNodeKind::Inner) return x[std::size_t(id)] = (next++ + 0.5) / double(leafCount);
        const double a = place(n.front), b = place(n.back);
        return x[std::size_t(id)] = 0.5 * (a + b);
    };
    place(0);
    const double rowH = h / double(depth + 1);
    auto pos = [&](int id) -> Vec3 {
        return corner + P(x[std::size_t(id)] * w, h - (nodes[std::size_t(id)].depth + 0.5) * rowH);
    };
    // Tree edges stop at the nodes' discs (an inner node's 17 px disc holds its splitter's name,
    // which an edge to its centre crossed), a leaf's 6 px dot.
    const auto discRadiusPx = [&](int id) { return nodes[std::size_t(id)].kind == BspNodeKind::Inner ? 10.0 : 4.0; };
    const auto edge = [&](int from, int to, const LineStyle& style) {
        const Vec3 a = pos(from), b = pos(to);
        Eigen::Vector2d pa, pb;
        if (!canvas.project(a, pa) || !canvas.project(b, pb) || !((pa - pb).norm() > 0)) return;
        const double len = (pa - pb).norm();
        const double s0 = std::min(0.45, discRadiusPx(from) / len), s1 = std::min(0.45, discRadiusPx(to) / len);
        canvas.drawLine(a + s0 * (b - a), b - s1 * (b - a), style);
    };
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const BspNode& n = nodes[i];
        if (n.kind != BspNodeKind::Inner) continue;
        edge(int(i), n.front, lineStyle(Role::Muted, 1.8f));
        edge(int(i), n.back, lineStyle(Role::Ink, 1.8f, true));
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const BspNode& n = nodes[i];
        const Vec3 p = pos(int(i));
        if (n.kind == BspNodeKind::Inner) {
            // The splitter's name inside its node: 13 px text (1.6 % of the 800 px frame) in a 17 px disc.
            canvas.drawPoint(p, 17.0f, depthColor(n.depth, depth).mixed(roleColor(Role::Background), 0.35f), true,
                             1.5f);
            canvas.drawText(p, "e" + std::to_string(n.splitter),
                            TextStyle{13.0f, roleColor(Role::Ink), Anchor::Center, false, true});
        } else {
            const bool solid = n.kind == BspNodeKind::SolidLeaf;
            canvas.drawPoint(p, 6.0f, solid ? roleColor(Role::ShapeA) : roleColor(Role::Muted), true, 1.5f);
        }
    }
    Eigen::Vector2d px;
    if (canvas.project(corner, px))
        drawKey(canvas, px.x(), px.y() - 18,
                {{roleColor(Role::ShapeA), "solid leaf (inside)"}, {roleColor(Role::Muted), "empty leaf (outside)"}});
    heading(canvas, corner + P(0, h), "The tree", "edge name = splitting line; solid: front child, dashed: back");
}

}  // namespace cdlab::demos::spacefig
