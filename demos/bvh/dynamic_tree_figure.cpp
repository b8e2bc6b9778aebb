#include "demos/bvh/dynamic_tree_figure.h"

#include <algorithm>
#include <map>

#include "core/broadphase/dynamic_tree.h"
#include "demos/bvh/bvh_draw.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"

namespace cdlab::demos::bvhdemo {

namespace {

using namespace render;

std::string boxName(int i) { return std::string(1, static_cast<char>('A' + i)); }

// A node named by the boxes under it, in name order: "C", "{A,C,D}".
std::string nodeName(const DynamicAabbTree& tree, int node) {
    std::vector<int> leaves, stack{node};
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        const auto& n = tree.node(i);
        if (n.leaf()) leaves.push_back(n.userId);
        else stack.insert(stack.end(), {n.child1, n.child2});
    }
    std::sort(leaves.begin(), leaves.end());
    if (leaves.size() == 1) return boxName(leaves[0]);
    std::string s = "{";
    for (std::size_t k = 0; k < leaves.size(); ++k) s += (k ? "," : "") + boxName(leaves[k]);
    return s + "}";
}

// The tree as nested parentheses: "((A,B),C)".
std::string treeText(const DynamicAabbTree& tree, int node) {
    if (node == DynamicAabbTree::kNull) return "";
    const auto& n = tree.node(node);
    if (n.leaf()) return boxName(n.userId);
    return "(" + treeText(tree, n.child1) + "," + treeText(tree, n.child2) + ")";
}

int depthOf(const DynamicAabbTree& tree, int node) {
    int d = 0;
    for (int p = tree.node(node).parent; p != DynamicAabbTree::kNull; p = tree.node(p).parent) ++d;
    return d;
}

/// One step as the figure shows it.
struct Step {
    bool insert = true;
    int box = 0;
    bool reinserted = true;  ///< a move: the box left its fat box
    Aabb oldFat{Vec3::Zero(), Vec3::Zero()};
    DynamicTreeInsertTrace trace;
    std::string sibling;
    double parentArea = 0.0;
    std::vector<std::string> rotationText;
};

class Figure {
public:
    Figure(const DynamicTreeSpec& spec, const DynamicTreeDrawing& drawing) : spec_(spec), d_(drawing) {
        boxes_ = spec.boxes;
        leaf_.assign(boxes_.size(), DynamicAabbTree::kNull);
        fat_.resize(boxes_.size());
        // A fixed camera: every box at every step, fat margins included.
        lo_ = Vec3::Constant(INFINITY), hi_ = Vec3::Constant(-INFINITY);
        std::vector<Aabb> at = boxes_;
        const auto grow = [&](const Aabb& b) {
            lo_ = lo_.cwiseMin(b.min - Vec3::Constant(spec.margin));
            hi_ = hi_.cwiseMax(b.max + Vec3::Constant(spec.margin));
        };
        for (const Aabb& b : at) grow(b);
        for (const auto& m : spec.moves) {
            at[m.box] = Aabb{at[m.box].min + m.by, at[m.box].max + m.by};
            grow(at[m.box]);
        }
    }

    Json run(std::vector<Frame>& frames) {
        Json steps = Json::array();
        for (int i = 0; i < static_cast<int>(boxes_.size()); ++i) {
            Step s;
            s.box = i;
            fat_[i] = grown(boxes_[i]);
            leaf_[i] = tree_.insert(fat_[i], i, &s.trace);
            finish(s);
            steps.push_back(stepJson(s));
            if (d_.gl) frames.push_back(drawStep(s, "insert_" + twoDigits(i + 1)));
        }
        int k = 0;
        for (const auto& m : spec_.moves) {
            Step s;
            s.insert = false;
            s.box = m.box;
            s.oldFat = fat_[m.box];
            boxes_[m.box] = Aabb{boxes_[m.box].min + m.by, boxes_[m.box].max + m.by};
            s.reinserted = !contains(fat_[m.box], boxes_[m.box]);
            if (s.reinserted) {
                fat_[m.box] = grown(boxes_[m.box]);
                tree_.move(leaf_[m.box], fat_[m.box], &s.trace);
                finish(s);
            }
            steps.push_back(stepJson(s));
            if (d_.gl) frames.push_back(drawStep(s, "move_" + twoDigits(++k)));
        }
        Json t = Json::object();
        t["margin"] = spec_.margin;
        t["steps"] = steps;
        t["tree"] = treeText(tree_, tree_.root());
        t["height"] = tree_.height();
        t["internal_area"] = tree_.internalArea();
        t["rotations"] = tree_.counters().rotations;
        return t;
    }

private:
    static std::string twoDigits(int k) { return (k < 10 ? "0" : "") + std::to_string(k); }
    Aabb grown(const Aabb& b) const {
        const Vec3 m = Vec3::Constant(spec_.margin);
        return Aabb{b.min - m, b.max + m};
    }

    // Names and areas of what the insertion did, read from its trace and the tree after it.
    void finish(Step& s) const {
        if (s.trace.sibling == DynamicAabbTree::kNull) return;  // the first box: the root
        s.sibling = nodeName(tree_, s.trace.sibling);
        s.parentArea = surfaceArea(unionOf(tree_.node(s.trace.sibling).box, fat_[s.box]));
        // Named by the swapped subtrees, which later rotations move whole; the node where it
        // happened may lose a child to a rotation above it, so its leaves are not named.
        for (const DynamicTreeRotation& r : s.trace.rotations)
            s.rotationText.push_back(nodeName(tree_, r.from) + " swapped with " + nodeName(tree_, r.to) + " (depth " +
                                     std::to_string(depthOf(tree_, r.node)) + "), area " + formatNumber(r.areaSaved) +
                                     " smaller");
    }

    Json stepJson(const Step& s) const {
        Json j = {{"kind", s.insert ? "insert" : "move"}, {"box", boxName(s.box)}};
        if (!s.insert) j["left_fat_box"] = s.reinserted;
        if (!s.reinserted) return j;
        j["sibling"] = s.sibling.empty() ? Json() : Json(s.sibling);
        j["sah_cost"] = s.trace.cost;
        j["new_parent_area"] = s.parentArea;
        j["nodes_costed"] = s.trace.costed.size();
        Json rot = Json::array();
        for (const DynamicTreeRotation& r : s.trace.rotations)
            rot.push_back({{"child", nodeName(tree_, r.from)},
                           {"grandchild", nodeName(tree_, r.to)},
                           {"area_saved", r.areaSaved}});
        j["rotations"] = rot;
        j["tree"] = treeText(tree_, tree_.root());
        j["height"] = tree_.height();
        return j;
    }

    // ---- drawing

    Image worldPanel(const Step& s, int w, int h) const {
        Canvas c(*d_.gl, canvasOptions(w, h, d_.scale));
        const Vec3 center = 0.5 * (lo_ + hi_);
        c.setCamera(sphereCamera(center, 0.5 * (hi_ - lo_).norm(), spec_.view, w, h));
        const int count = s.insert ? s.box + 1 : static_cast<int>(boxes_.size());
        // Node boxes by depth (internal nodes), then the leaves: box filled, fat box dashed.
        for (int i = 0; i < tree_.nodeCapacity(); ++i) {
            const auto& n = tree_.node(i);
            if (n.height <= 0) continue;
            drawBoxWire(c, obbFromAabb(n.box), LineStyle{2.0f, levelColor(depthOf(tree_, i)), 0.0f, false});
        }
        for (int b = 0; b < count; ++b) {
            drawBoxFill(c, obbFromAabb(boxes_[b]), roleColor(Role::ShapeA).withAlpha(0.30f));
            c.setStrokeOwner(bodyOwner(boxName(b)));  // its name may cross its own box and fat box
            drawBoxWire(c, obbFromAabb(boxes_[b]), lineStyle(Role::ShapeA, 1.5f));
            drawBoxWire(c, obbFromAabb(fat_[b]), lineStyle(Role::Muted, 1.5f, true));
            c.setStrokeOwner(0);
        }
        if (!s.insert && s.reinserted) drawBoxWire(c, obbFromAabb(s.oldFat), lineStyle(Role::Muted, 3.0f));
        if (s.reinserted && s.trace.sibling != DynamicAabbTree::kNull)
            drawBoxWire(c, obbFromAabb(tree_.node(s.trace.sibling).box), lineStyle(Role::Query, 4.0f, true));
        drawBoxWire(c, obbFromAabb(fat_[s.box]), lineStyle(Role::Query, 4.0f));
        if (d_.labels)
            for (int b = 0; b < count; ++b) {
                TextStyle ts = labelStyle(Role::Ink, 20.0f);
                ts.place = true;
                ts.names = bodyOwner(boxName(b));
                c.drawText(0.5 * (boxes_[b].min + boxes_[b].max), boxName(b), ts);
            }
        const std::string what = s.insert ? "Insert " + boxName(s.box) : "Move " + boxName(s.box);
        std::string sub;
        if (!s.reinserted) sub = "still inside its fat box: the tree is unchanged";
        else if (s.sibling.empty()) sub = "the first box: the root";
        else sub = "paired with " + s.sibling + "; " + std::to_string(s.trace.costed.size()) + " nodes costed";
        drawHeading(c, what, sub);
        return c.readPixels();
    }

    Image treePanel(const Step& s, int w, int h) const {
        // The diagram wants node 0 as the root: number the nodes depth first.
        std::map<int, int> index;
        std::vector<int> order, stack;
        if (tree_.root() != DynamicAabbTree::kNull) stack.push_back(tree_.root());
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            index[i] = static_cast<int>(order.size());
            order.push_back(i);
            const auto& n = tree_.node(i);
            if (!n.leaf()) stack.insert(stack.end(), {n.child2, n.child1});
        }
        TreeDiagramInput in;
        in.maxDepth = 8;
        in.levelLabels = true;
        for (int i : order) {
            const auto& n = tree_.node(i);
            in.children.push_back(n.leaf() ? std::array<int, 2>{-1, -1}
                                           : std::array<int, 2>{index[n.child1], index[n.child2]});
            TreeNodeLook look{n.leaf() ? roleColor(Role::ShapeA) : levelColor(depthOf(tree_, i)), 5.0f, false};
            if (s.reinserted && i == leaf_[s.box]) look = {roleColor(Role::Query), 7.0f, true};
            if (s.reinserted && i == s.trace.sibling) look = {look.color, 8.0f, true};
            in.look.push_back(look);
            in.names.push_back(n.leaf() ? boxName(n.userId) : "");  // the review: leaves carried no letters
        }
        if (s.reinserted)
            for (int p = leaf_[s.box]; p != DynamicAabbTree::kNull; p = tree_.node(p).parent) in.litEdges.push_back(index[p]);
        in.heading = "The tree: " + std::to_string(tree_.leafCount()) + (tree_.leafCount() == 1 ? " leaf" : " leaves") +
                     ", height " + std::to_string(tree_.height());
        in.sub = "leaves left to right: " + leafOrder(order);
        return drawTreeDiagram(*d_.gl, w, h, d_.scale, in);
    }

    std::string leafOrder(const std::vector<int>& order) const {
        std::string s;
        for (int i : order)
            if (tree_.node(i).leaf()) s += (s.empty() ? "" : " ") + boxName(tree_.node(i).userId);
        return s;
    }

    Frame drawStep(const Step& s, const std::string& name) const {
        GridLayout L;
        L.width = d_.width;
        L.height = d_.height;
        L.columns = d_.treePanel ? 2 : 1;
        L.rows = 1;
        L.captionBand = 100;
        if (d_.treePanel) L.columnWidths = {d_.width * 3 / 5, d_.width - d_.width * 3 / 5};
        std::vector<Image> panels = {worldPanel(s, L.panelWidth(0), L.panelHeight())};
        if (d_.treePanel) panels.push_back(treePanel(s, L.panelWidth(1), L.panelHeight()));
        std::vector<LegendItem> legend;
        for (int level = 0; level < std::min(tree_.height(), 4); ++level)
            legend.push_back({LegendItem::Swatch::Line, levelColor(level), "level " + std::to_string(level)});
        legend.push_back({LegendItem::Swatch::Dashed, roleColor(Role::Muted), "fat box (margin " + formatNumber(spec_.margin) + ")"});
        legend.push_back({LegendItem::Swatch::Line, roleColor(Role::Query), s.insert ? "new leaf" : "moved leaf"});
        if (s.reinserted && !s.sibling.empty()) legend.push_back({LegendItem::Swatch::Dashed, roleColor(Role::Query), "its sibling"});
        if (!s.insert && s.reinserted) legend.push_back({LegendItem::Swatch::Line, roleColor(Role::Muted), "old fat box"});
        std::vector<std::string> caption;
        if (!d_.caption.empty()) caption.push_back(d_.caption);
        std::string line;
        if (!s.reinserted) {
            line = boxName(s.box) + " moved but stays inside its fat box: no re-insertion, no tree work.";
        } else if (s.sibling.empty()) {
            line = boxName(s.box) + " is the root.";
        } else {
            line = std::string(s.insert ? "" : "It left its fat box: removed, re-inserted. ") + "SAH cost of pairing with " +
                   s.sibling + ": " + formatNumber(s.trace.cost) + " = new parent's area " + formatNumber(s.parentArea) +
                   " + ancestors' growth " + formatNumber(s.trace.cost - s.parentArea) + ".";
        }
        caption.push_back(line);
        if (s.reinserted && !s.sibling.empty())
            caption.push_back(s.rotationText.empty() ? "No rotation: no child-grandchild swap shrinks a box."
                                                     : "Rotation: " + s.rotationText.front() +
                                                           (s.rotationText.size() > 1
                                                                ? " (+" + std::to_string(s.rotationText.size() - 1) + " more)"
                                                                : ""));
        const std::string frameCaption = s.insert ? "insert " + boxName(s.box) : "move " + boxName(s.box);
        return Frame{name, frameCaption, composeGrid(*d_.gl, L, d_.scale, d_.title, panels, legend, caption)};
    }

    const DynamicTreeSpec& spec_;
    const DynamicTreeDrawing& d_;
    DynamicAabbTree tree_;
    std::vector<Aabb> boxes_, fat_;
    std::vector<int> leaf_;
    Vec3 lo_, hi_;
};

}  // namespace

Json runDynamicTreeFigure(const DynamicTreeSpec& spec, const DynamicTreeDrawing& drawing, std::vector<Frame>& frames) {
    Figure f(spec, drawing);
    return f.run(frames);
}

}  // namespace cdlab::demos::bvhdemo
