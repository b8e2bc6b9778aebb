// Point vs box: the 27 Voronoi regions of a solid box — 8 vertex, 12 edge, 6 face regions and the
// inside (Ericson, Real-Time Collision Detection §5.1.4). In the box's frame each region is a cell of
// a 3 × 3 × 3 grid cut by the faces' planes, so a step frame draws the query's cell (clipped to a
// margin around the box), the feature that holds its closest point, and the three slab tests that
// chose it. Numbers: core/closest/closest_point_box.h; this file only draws.
#include "app/scene/json_reader.h"
#include "demos/voronoi_triangle/box_regions.h"

#include <algorithm>

#include "core/closest/closest_point_box.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/step_frames.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;


Json queryJson(const Vec3& p, const BoxRegionResult& r) {
    Json tests = Json::array();
    for (const BoxAxisTest& t : r.tests)
        tests.push_back({{"coordinate", t.coordinate}, {"half_extent", t.halfExtent}, {"side", t.side}});
    return {{"point", vec3Json(p)},
            {"region", regionName(r)},
            {"dimension", r.dimension},
            {"closest", vec3Json(r.point)},
            {"distance", r.distance},
            {"corners", r.corners},
            {"tests", tests}};
}

/// The slab tests in words: "u_x = 1.3 > e_x = 1: + side", one piece per axis, then the region.
std::vector<std::string> testEntries(const BoxRegionResult& r) {
    std::vector<std::string> out;
    const char* axes = "xyz";
    for (int i = 0; i < 3; ++i) {
        const BoxAxisTest& t = r.tests[std::size_t(i)];
        const std::string u = std::string("u_") + axes[i] + " = " + formatNumber(t.coordinate);
        const std::string e = formatNumber(t.halfExtent);
        if (t.side > 0) out.push_back(u + " > " + e + ": + side");
        else if (t.side < 0) out.push_back(u + " < −" + e + ": − side");
        else out.push_back(u + " in [−" + e + ", " + e + "]");
    }
    out.push_back("→ " + regionName(r));
    return out;
}

/// Box corner k in world (bit i set: the + side of axis i).
Vec3 corner(const Obb& box, int k, const Vec3& halfExtents) {
    Vec3 local;
    for (int i = 0; i < 3; ++i) local[i] = (k >> i) & 1 ? halfExtents[i] : -halfExtents[i];
    return box.center + box.axes * local;
}

class BoxRegionsScene final : public PreparedScene {
public:
    BoxRegionsScene(SceneCommon common, const Obb& box, std::vector<Vec3> queries, double margin)
        : PreparedScene(std::move(common)), box_(box), queries_(std::move(queries)), margin_(margin) {}

    DemoOutput execute(const RunContext& ctx) const override {
        std::vector<BoxRegionResult> results;
        for (const Vec3& q : queries_) results.push_back(closestPointOnBox(q, box_));
        DemoOutput out;
        out.trace["simplex"] = "box";
        out.trace["center"] = vec3Json(box_.center);
        out.trace["half_extents"] = vec3Json(box_.halfExtents);
        out.trace["axes"] = {vec3Json(box_.axes.col(0)), vec3Json(box_.axes.col(1)), vec3Json(box_.axes.col(2))};
        Json qs = Json::array();
        for (std::size_t i = 0; i < queries_.size(); ++i) qs.push_back(queryJson(queries_[i], results[i]));
        out.trace["queries"] = qs;
        // The 27 regions together: core's answer for the centre of each cell of the slab grid.
        const std::vector<PartitionCell> cells = partition();
        Json ps = Json::array();
        for (const PartitionCell& cell : cells)
            ps.push_back({{"signs", cell.signs}, {"centre", vec3Json(cell.centre)}, {"region", regionName(cell.region)},
                          {"dimension", cell.region.dimension}});
        out.trace["partition"] = ps;
        if (numericOnly(ctx, out)) return out;
        out.frames.push_back(drawFrame(*ctx.gl, ctx, results, -1));
        out.frames.push_back(drawPartition(*ctx.gl, ctx, cells));
        if (common_.steps || ctx.stepsOverride) {
            addQueryFramesAndSheet(*ctx.gl, common_, int(queries_.size()),
                                   [&](int i) { return drawFrame(*ctx.gl, ctx, results, i); }, out);
        } else {
            out.skipped.push_back("per-step frames and contact sheet (steps off)");
        }
        return out;
    }

private:
    Obb box_;
    std::vector<Vec3> queries_;
    double margin_;

    /// One cell of the 3 × 3 × 3 grid the faces' planes cut space into: its side per axis (−1, 0,
    /// +1), its centre (the outer cells reach the margin) and core's region for that centre.
    struct PartitionCell {
        std::array<int, 3> signs{};
        Vec3 centre = Vec3::Zero();
        Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  ///< box frame
        BoxRegionResult region;
    };

    std::vector<PartitionCell> partition() const {
        std::vector<PartitionCell> cells;
        const Vec3 e = box_.halfExtents;
        const double m = 0.5 * e.maxCoeff();  // how far the outer cells are drawn (they are unbounded)
        for (int k = 0; k < 27; ++k) {
            PartitionCell cell;
            for (int i = 0; i < 3; ++i) {
                const int side = (k / (i == 0 ? 1 : i == 1 ? 3 : 9)) % 3 - 1;
                cell.signs[std::size_t(i)] = side;
                cell.lo[i] = side > 0 ? e[i] : side < 0 ? -e[i] - m : -e[i];
                cell.hi[i] = side > 0 ? e[i] + m : side < 0 ? -e[i] : e[i];
            }
            cell.centre = box_.center + box_.axes * (0.5 * (cell.lo + cell.hi));
            cell.region = closestPointOnBox(cell.centre, box_);
            cells.push_back(cell);
        }
        return cells;
    }

    /// Frame "partition": the 27 cells pulled apart from the centre, coloured by core's region of
    /// each cell's centre (vertex, edge, face, inside), the counts in the key.
    Frame drawPartition(GlContext& gl, const RunContext& ctx, const std::vector<PartitionCell>& cells) const {
        Canvas c(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        const double gap = 0.9 * box_.halfExtents.maxCoeff();
        const Vec3 view = Vec3(1.0, 0.75, 1.6).normalized();
        c.setCamera(framingCamera(box_.center, (size() + margin() + gap) * 1.05, view, Vec3::UnitY(), true));
        int count[4] = {0, 0, 0, 0};
        for (const PartitionCell& cell : cells) {
            const Vec3 shift(cell.signs[0] * gap, cell.signs[1] * gap, cell.signs[2] * gap);
            const Obb block{box_.center + box_.axes * (0.5 * (cell.lo + cell.hi) + shift), 0.5 * (cell.hi - cell.lo), box_.axes};
            const int dim = std::clamp(cell.region.dimension, 0, 3);
            ++count[dim];
            drawBody(c, boxDrawable(block), featureDimensionColor(dim), 1.0f, featureDimensionColor(dim).scaled(0.55f), 1.5f,
                     false);
        }
        // One of each kind named by core's region name, on the side the camera sees.
        if (common_.hasLayer("labels"))
            for (const PartitionCell& cell : cells) {
                const std::array<int, 3>& sg = cell.signs;
                const bool example = sg[2] == 1 && ((sg[0] == 1 && sg[1] == 1) || (sg[0] == 0 && sg[1] == 1) || (sg[0] == 0 && sg[1] == 0));
                if (!example && !(sg[0] == 0 && sg[1] == 0 && sg[2] == 0)) continue;
                const Vec3 shift(sg[0] * gap, sg[1] * gap, sg[2] * gap);
                TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                ts.place = true;
                c.drawText(cell.centre + box_.axes * shift, regionName(cell.region), ts);
            }
        drawKey(c, 20, 62,
                {{featureDimensionColor(0), std::to_string(count[0]) + " vertex regions"},
                 {featureDimensionColor(1), std::to_string(count[1]) + " edge regions"},
                 {featureDimensionColor(2), std::to_string(count[2]) + " face regions"},
                 {featureDimensionColor(3), std::to_string(count[3]) + " inside"}},
                17.0f);
        drawTitleAndCaption(c, common_.title,
                            "The faces' planes cut space into 3 × 3 × 3 cells, pulled apart here; each cell's colour is "
                            "the region of its centre");
        return Frame{"partition", "the 27 regions pulled apart", c.readPixels()};
    }

    double size() const { return box_.halfExtents.norm(); }
    double margin() const { return margin_ > 0 ? margin_ : 0.6 * box_.halfExtents.maxCoeff(); }

    /// The region's cell in the box frame, clipped to the box grown by the margin (or to the query): on each axis
    /// [−e − m, −e], [−e, e] or [e, e + m] by the test's side.
    ConvexDrawable cellOf(const BoxRegionResult& r) const {
        Vec3 lo, hi;
        for (int i = 0; i < 3; ++i) {
            const int side = r.tests[std::size_t(i)].side;
            // Far enough out to hold the query point itself.
            const double e = box_.halfExtents[i],
                         m = std::max(margin(), std::abs(r.tests[std::size_t(i)].coordinate) - e + 0.2 * margin());
            lo[i] = side > 0 ? e : side < 0 ? -e - m : -e;
            hi[i] = side > 0 ? e + m : side < 0 ? -e : e;
        }
        return boxDrawable(Obb{box_.center + box_.axes * (0.5 * (lo + hi)), 0.5 * (hi - lo), box_.axes});
    }

    /// The feature holding the closest point, drawn over the box: a vertex, an edge or a face.
    void drawFeature(Canvas& c, const BoxRegionResult& r) const {
        const Color color = featureDimensionColor(r.dimension);
        std::vector<Vec3> pts;
        for (int k : r.corners) pts.push_back(corner(box_, k, box_.halfExtents));
        // The faces holding it: one per axis the query lies outside of, on that side.
        std::vector<Vec3> normals;
        for (int i = 0; i < 3; ++i)
            if (const int side = r.tests[std::size_t(i)].side; side != 0) normals.push_back(side * box_.axes.col(i));
        // On the box's far side (every face holding it turned away): dashed and hollow (the view
        // rule HiddenFilled; the review found the −x face filled with a solid outline).
        const bool hidden = !normals.empty() && std::none_of(normals.begin(), normals.end(), [&](const Vec3& n) {
            return facesCamera(c.camera(), box_.center, n);
        });
        if (pts.size() == 4) std::swap(pts[2], pts[3]);  // corners in bit order (00, 01, 10, 11) to a loop
        // The region's feature saturated over the faded box (issue 42 §3; StepFeatureFaded): an
        // edge in its colour, a face filled nearly opaque.
        c.noteFeature({regionName(r), pts, normals, pts.size() == 4 && !hidden, true, color});
        if (pts.size() == 1) c.drawPoint(pts[0], 10.0f, color, true, 2.0f, roleColor(Role::Ink));
        LineStyle ls = lineStyle(Role::Ink, pts.size() == 2 ? 8.0f : 4.0f, false, true);
        ls.color = pts.size() == 2 ? color : color.scaled(0.75f);
        if (hidden) ls.dashPx = 10.0f;
        if (pts.size() == 2) c.drawLine(pts[0], pts[1], ls);
        else if (pts.size() == 4) {
            if (!hidden) c.drawPolygon(pts, color.withAlpha(0.9f));
            c.drawPolyline(pts, true, ls);
        }
    }

    Frame drawFrame(GlContext& gl, const RunContext& ctx, const std::vector<BoxRegionResult>& results, int focus) const {
        Canvas c(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        double reach = size() + margin();
        for (const Vec3& q : queries_) reach = std::max(reach, (q - box_.center).norm());
        // A step frame leaves the bottom to its slab tests: the view is pulled back a little.
        // A step frame whose feature lies on the box's far side looks from that side instead: the
        // view's component along each axis the query is outside of takes the query's side (the
        // view rule FeatureFromBehind; the review found face −x seen from behind).
        // A face seen nearly edge-on that way turns further towards its normal, until its normal is
        // within 60° of the view (FeatureEdgeOn).
        Vec3 view = Vec3(1.0, 0.75, 1.6).normalized();
        if (focus >= 0 && results[std::size_t(focus)].valid) {
            Vec3 outward = Vec3::Zero();
            for (int i = 0; i < 3; ++i) {
                const int side = results[std::size_t(focus)].tests[std::size_t(i)].side;
                const Vec3 axis = box_.axes.col(i);
                if (side != 0 && side * axis.dot(view) < 0) view -= 2 * axis.dot(view) * axis;
                outward += side * axis;
            }
            if (results[std::size_t(focus)].dimension == 2)
                for (int k = 0; k < 10 && outward.normalized().dot(view) < 0.5; ++k)
                    view = (view + 0.25 * outward.normalized()).normalized();
        }
        c.setCamera(common_.camera ? *common_.camera
                                   : framingCamera(box_.center, reach * (focus >= 0 ? 0.95 : 0.8), view,
                                                   Vec3::UnitY(), true));
        const bool labels = common_.hasLayer("labels");
        if (focus >= 0 && common_.hasLayer("regions") && results[std::size_t(focus)].valid) {
            const BoxRegionResult& r = results[std::size_t(focus)];
            if (r.dimension < 3)
                drawBody(c, cellOf(r), featureDimensionColor(r.dimension), 0.16f,
                         featureDimensionColor(r.dimension).scaled(0.7f), 1.5f);
        }
        // The box in neutral grey: the colours are the regions'.
        drawBody(c, boxDrawable(box_), roleColor(Role::Muted), 0.22f, roleColor(Role::Ink), 3.0f);
        if (focus >= 0) drawFeature(c, results[std::size_t(focus)]);
        if (labels) {
            // The box's own axes from its centre, so "+x−z" can be read off the picture.
            const char* names[3] = {"x", "y", "z"};
            for (int i = 0; i < 3; ++i) {
                const Vec3 tip = box_.center + box_.axes.col(i) * (box_.halfExtents[i] + 0.45 * margin());
                c.drawArrow(box_.center, tip, lineStyle(Role::Ink, 2.0f, false, true));
                TextStyle ts{18.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                ts.offsetPx = Eigen::Vector2d(12, -12);
                ts.place = true;
                c.drawText(tip, std::string("+") + names[i], ts);
            }
        }
        for (std::size_t i = 0; i < queries_.size(); ++i) {
            const BoxRegionResult& r = results[i];
            const bool faded = focus >= 0 && int(i) != focus;
            Color qc = featureDimensionColor(r.dimension);
            if (faded) qc = qc.withAlpha(0.25f);
            if (common_.hasLayer("closest") && !faded && r.dimension < 3) {
                c.drawLine(queries_[i], r.point, lineStyle(Role::Result, 3.0f, false, true));
                c.drawPoint(r.point, 6.0f, roleColor(Role::Result));
            }
            if (common_.hasLayer("queries")) {
                c.drawPoint(queries_[i], focus == int(i) ? 12.0f : 9.0f, qc, true, 2.0f,
                            faded ? roleColor(Role::Muted) : roleColor(Role::Ink));
                if (labels && !faded) {
                    TextStyle ts{18.0f, roleColor(Role::Ink), Anchor::Center, true, false};
                    ts.offsetPx = Eigen::Vector2d(24, 0);
                    ts.place = true;
                    c.drawText(queries_[i], "q" + std::to_string(i + 1) + (focus < 0 ? ": " + regionName(r) : ""), ts);
                }
            }
        }
        // Key: colour by feature dimension, as for the tetrahedron.
        drawKey(c, 20, 62,
                {{featureDimensionColor(0), "vertex region"},
                 {featureDimensionColor(1), "edge region"},
                 {featureDimensionColor(2), "face region"},
                 {featureDimensionColor(3), "inside"}},
                17.0f);
        std::string caption = common_.caption;
        if (focus >= 0) {
            const BoxRegionResult& r = results[std::size_t(focus)];
            caption = "q" + std::to_string(focus + 1) + " " + formatPoint(queries_[std::size_t(focus)]) + ": " + regionName(r) +
                      ", closest " + formatPoint(r.point) + ", distance " + formatNumber(r.distance);
            if (labels) {
                const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
                const std::vector<std::string> lines = wrapPieces(c, testEntries(r), ";   ", ts, c.width() - 36.0);
                double y = c.height() - 44 - 24.0 * double(lines.size() + 1);
                c.drawTextPx(18, y, "Slab tests in the box's frame (u = (q − centre)·axis):",
                             TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
                for (const std::string& l : lines) c.drawTextPx(18, y += 24.0, l, ts);
            }
        }
        drawTitleAndCaption(c, common_.title, caption);
        Frame f;
        if (focus >= 0) {
            f.name = stepFrameName(focus + 1);
            f.caption = "q" + std::to_string(focus + 1) + ": " + regionName(results[std::size_t(focus)]);
        } else {
            f.name = "3d";
            f.caption = common_.title;
        }
        f.image = c.readPixels();
        return f;
    }
};

}  // namespace

std::unique_ptr<PreparedScene> makeBoxRegionsScene(SceneCommon common, const Obb& box, std::vector<Vec3> queries,
                                                   double margin) {
    return std::make_unique<BoxRegionsScene>(std::move(common), box, std::move(queries), margin);
}

}  // namespace cdlab::demos
