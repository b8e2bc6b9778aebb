// The space_partition demo's bsp_scores figure: how each splitting plane of the bsp_shape tree was
// chosen (Ericson §8.3.2). One frame per split whose node had two or more candidates: the node's
// region with the polygon pieces that reached it, coloured by the side of the chosen line they went
// to (pieces on the line stay at the node, cut pieces marked where the line cuts them), and every
// candidate's counts and score from core's BspSplitStep::scores. Test:
// tests/demos/space_partition/bsp_scores_test.cpp recomputes the root's scores with exact
// orientation tests.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "demos/space_partition/space_partition_scene.h"

namespace cdlab::demos::spacefig {

namespace {

const Color kFrontColor = categorical(4);  // blue
const Color kBackColor = categorical(2);   // bluish green

/// Node `id` and every node below it.
std::vector<int> subtree(const BspTree& bt, int id) {
    std::vector<int> out, stack = {id};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        out.push_back(n);
        const BspNode& node = bt.nodes()[std::size_t(n)];
        if (node.kind == BspNodeKind::Inner) stack.push_back(node.back), stack.push_back(node.front);
    }
    return out;
}

/// Sources with a fragment stored somewhere below `id`.
std::set<int> sourcesBelow(const BspTree& bt, int id) {
    std::set<int> s;
    for (int n : subtree(bt, id))
        for (int f : bt.nodes()[std::size_t(n)].fragments) s.insert(bt.fragments()[std::size_t(f)].source);
    return s;
}

}  // namespace

Json bspStepsJson(const BspTrace& trace) {
    Json steps = Json::array();
    for (const BspSplitStep& s : trace.steps) {
        Json scores = Json::array();
        for (const BspCandidateScore& c : s.scores)
            scores.push_back({{"edge", c.source},
                              {"front", c.front},
                              {"back", c.back},
                              {"straddling", c.straddling},
                              {"score", c.score}});
        steps.push_back({{"node", s.node},
                         {"depth", s.depth},
                         {"splitter", s.splitter},
                         {"polygons", s.polygons},
                         {"front", s.front},
                         {"back", s.back},
                         {"coplanar", s.coplanar},
                         {"straddling", s.straddling},
                         {"score", s.score},
                         {"candidates", scores}});
    }
    return steps;
}

DemoOutput SpaceScene::runBspScores(const RunContext& ctx) const {
    DemoOutput out;
    std::vector<BspPolygon> walls;
    addWalls(polygon, walls);
    BspTree bt;
    BspTrace trace;
    bt.build(walls, bsp, &trace);
    out.trace["edges"] = int(polygon.size());
    out.trace["split_weight"] = bsp.splitWeight;
    out.trace["steps"] = bspStepsJson(trace);
    if (numericOnly(ctx, out)) return out;
    int drawn = 0;
    for (std::size_t k = 0; k < trace.steps.size() && drawn < scoreFrames; ++k) {
        if (trace.steps[k].scores.size() < 2) continue;
        out.frames.push_back(drawBspScoreFrame(*ctx.gl, figureScale(common_, ctx), bt, trace.steps[k]));
        ++drawn;
    }
    return out;
}

Frame SpaceScene::drawBspScoreFrame(GlContext& gl, int ss, const BspTree& bt, const BspSplitStep& step) const {
    Canvas canvas(gl, sceneCanvasOptions(common_, ss));
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const Vec3& v : polygon) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double W = (hi - lo).head<2>().maxCoeff() * 1.2;
    const Vec3 c = 0.5 * (lo + hi);
    const Aabb frame{P(c.x() - 0.5 * W, c.y() - 0.5 * W), P(c.x() + 0.5 * W, c.y() + 0.5 * W)};
    // The square panel 540 px wide, its left side 40 px from the image's, its centre 20 px below the
    // image's; the table to its right in pixels.
    const double width = common_.image.width, height = common_.image.height;
    const double scale = 540.0 / W;
    canvas.setCamera(Camera::twoD(frame.min.x() + (0.5 * width - 40) / scale, c.y() + 20 / scale, height / scale));
    const auto regions = bspRegions(bt, rectPolygon(frame));
    const BspNode& node = bt.nodes()[std::size_t(step.node)];
    // The whole polygon faint, the node's region shaded.
    std::vector<Vec3> outline = polygon;
    canvas.drawPolyline(outline, true, lineStyle(Role::Muted, 1.5f));
    if (regions[std::size_t(step.node)].size() >= 3)
        canvas.drawPolygon(regions[std::size_t(step.node)], roleColor(Role::Highlight).withAlpha(0.10f));
    canvas.drawPolyline(regions[std::size_t(step.node)], true, lineStyle(Role::Ink, 1.0f, true));
    // The pieces that reached the node, by where they went: kept on the line, front, back.
    const std::set<int> front = sourcesBelow(bt, node.front), back = sourcesBelow(bt, node.back);
    const std::vector<int> frontList = subtree(bt, node.front);
    const std::set<int> frontNodes(frontList.begin(), frontList.end());
    for (int n : subtree(bt, step.node))
        for (int f : bt.nodes()[std::size_t(n)].fragments) {
            Vec3 p, q;
            fragmentSegment(bt.fragments()[std::size_t(f)], p, q);
            // A cut piece's halves are drawn in the side they went to; the cut point is marked below.
            const Color col = n == step.node ? roleColor(Role::Ink) : frontNodes.count(n) ? kFrontColor : kBackColor;
            canvas.drawLine(p, q, LineStyle{5.0f, col, 0.0f, false});
        }
    // The chosen line across the node's region, with its front side.
    const Vec3 nrm = P(node.plane.normal.x(), node.plane.normal.y());
    Vec3 a, b;
    if (lineInPolygon(regions[std::size_t(step.node)], nrm, node.plane.offset, a, b)) {
        canvas.drawLine(a, b, LineStyle{2.5f, roleColor(Role::Ink), 8.0f, false});
        const Vec3 m = 0.5 * (a + b);
        canvas.drawArrow(m, m + nrm * (0.07 * W), lineStyle(Role::Ink, 2.0f));
        TextStyle ts{15.0f, roleColor(Role::Ink), Anchor::Center, true, true, {0, 0}};
        ts.place = true;
        canvas.drawText(m + nrm * (0.1 * W), "front", ts);
    }
    // Cut points: where the chosen line crosses a source with pieces on both sides.
    for (int src : front)
        if (back.count(src) && src != step.splitter) {
            const Vec3 p0 = polygon[std::size_t(src)], p1 = polygon[(std::size_t(src) + 1) % polygon.size()];
            const double s0 = nrm.dot(p0) - node.plane.offset, s1 = nrm.dot(p1) - node.plane.offset;
            if ((s0 < 0) != (s1 < 0)) canvas.drawPoint(p0 + (p1 - p0) * (s0 / (s0 - s1)), 10.0f, roleColor(Role::Highlight), true, 2.0f);
        }
    // Each candidate's name once, outside the middle of its longest piece below this node.
    for (const BspCandidateScore& cs : step.scores) {
        Vec3 best0 = Vec3::Zero(), best1 = Vec3::Zero();
        for (int n : subtree(bt, step.node))
            for (int f : bt.nodes()[std::size_t(n)].fragments) {
                if (bt.fragments()[std::size_t(f)].source != cs.source) continue;
                Vec3 p, q;
                fragmentSegment(bt.fragments()[std::size_t(f)], p, q);
                if ((q - p).squaredNorm() > (best1 - best0).squaredNorm()) best0 = p, best1 = q;
            }
        const Vec3 e = polygon[(std::size_t(cs.source) + 1) % polygon.size()] - polygon[std::size_t(cs.source)];
        const Vec3 outward = Vec3(e.y(), -e.x(), 0).normalized();
        TextStyle ts{16.0f, roleColor(Role::Ink), Anchor::Center, true, true};
        ts.place = true;
        ts.offsetPx = Eigen::Vector2d(outward.x(), -outward.y()) * 18.0;
        canvas.drawText(0.5 * (best0 + best1), "e" + std::to_string(cs.source), ts);
    }
    heading(canvas, P(frame.min.x(), frame.max.y()),
            step.depth == 0 ? "The root: all " + std::to_string(step.polygons) + " edges" : "Node " + std::to_string(step.node) + " (depth " + std::to_string(step.depth) + "): " + std::to_string(step.polygons) + " pieces",
            "split by e" + std::to_string(step.splitter) + "'s line");
    keyBelow(canvas, frame.min,
             {{kFrontColor, "front"}, {kBackColor, "back"}, {roleColor(Role::Ink), "on the line"}, {roleColor(Role::Highlight), "where the line cuts an edge"}});
    // The table: every candidate in the order scored.
    const double x0 = 630;
    double y = 104;
    const TextStyle head{16.0f, roleColor(Role::Ink), Anchor::Left, false, true};
    const double K = bsp.splitWeight;
    canvas.drawTextPx(x0, y, "score = K · cut + (1 − K) · |front − back|", head);
    y += 24;
    canvas.drawTextPx(x0, y, "K = " + formatNumber(K) + "; on the line counts as front", TextStyle{15.0f, roleColor(Role::Ink), Anchor::Left, false, false});
    y += 34;
    const double col[5] = {x0, x0 + 70, x0 + 135, x0 + 195, x0 + 250};
    const char* names[5] = {"edge", "front", "back", "cut", "score"};
    const TextStyle th{15.0f, roleColor(Role::Muted).scaled(0.7f), Anchor::Left, false, false};
    for (int i = 0; i < 5; ++i) canvas.drawTextPx(col[i], y, names[i], th);
    y += 24;
    const double rowH = std::min(24.0, (height - 120 - y) / double(step.scores.size()));
    bool chosenSeen = false;
    int lowest = 0;  // candidates with the chosen (lowest) score: more than one is a tie the first wins
    for (const BspCandidateScore& cs : step.scores) lowest += cs.score == step.score;
    for (const BspCandidateScore& cs : step.scores) {
        const bool chosen = !chosenSeen && cs.source == step.splitter && cs.score == step.score;
        chosenSeen |= chosen;
        TextStyle t{static_cast<float>(std::min(15.0, rowH - 4)), chosen ? roleColor(Role::Highlight) : roleColor(Role::Ink), Anchor::Left, false, chosen};
        const std::string cells[5] = {"e" + std::to_string(cs.source), std::to_string(cs.front), std::to_string(cs.back),
                                      std::to_string(cs.straddling), formatNumber(cs.score) + (chosen ? "  ← chosen" : "")};
        for (int i = 0; i < 5; ++i) canvas.drawTextPx(col[i], y, cells[i], t);
        y += rowH;
    }
    if (lowest > 1)
        canvas.drawTextPx(x0, y + 8, std::to_string(lowest) + " candidates tie at the lowest score: the first scored wins",
                          TextStyle{15.0f, roleColor(Role::Ink), Anchor::Left, false, false});
    char name[32];
    std::snprintf(name, sizeof name, "split_%02d", step.node);
    Frame fr = titledFrame(canvas, name);
    fr.caption = common_.title + ": node " + std::to_string(step.node) + " split by e" + std::to_string(step.splitter);
    return fr;
}

}  // namespace cdlab::demos::spacefig
