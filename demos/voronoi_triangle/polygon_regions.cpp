// Point vs a convex polygon in 3D: its n vertex, n edge regions and the face, seen in the polygon's
// plane (the regions as coloured zones) and in 3D, and one frame per query with the region tests that
// chose its region (core/closest/closest_point_polygon.h). This file only draws.
#include "app/scene/json_reader.h"
#include "demos/voronoi_triangle/polygon_regions.h"

#include <algorithm>

#include "core/closest/closest_point_polygon.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/step_frames.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;


/// The tests as made: "v0: 1.2 ≤ 0? no", "v0v1: 0.4 > 0, 0 < 0.7 < 4 → yes".
std::vector<std::string> testEntries(const ClosestPointPolygonResult& r) {
    std::vector<std::string> out;
    for (const PolygonRegionTest& t : r.tests) {
        const bool vertex = t.candidate.find('v', 1) == std::string::npos;  // "v3", not "v3v4"
        std::string e = t.candidate + ": ";
        if (vertex) e += "(q − v)·e_next = " + formatNumber(t.first) + ", (q − v)·e_prev = " + formatNumber(t.second);
        else e += "outside " + formatNumber(t.first) + ", along " + formatNumber(t.second);
        out.push_back(e + (t.accepted ? " → yes" : " → no"));
    }
    if (r.dimension == 2) out.push_back("face: otherwise → yes");
    return out;
}

class PolygonRegionsScene final : public PreparedScene {
public:
    PolygonRegionsScene(SceneCommon common, std::vector<Vec3> polygon, std::vector<Vec3> queries, double margin,
                        std::vector<std::string> views)
        : PreparedScene(std::move(common)),
          polygon_(std::move(polygon)),
          queries_(std::move(queries)),
          margin_(margin),
          views_(std::move(views)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        std::vector<ClosestPointPolygonResult> results;
        for (const Vec3& q : queries_) results.push_back(closestPointOnConvexPolygon(q, polygon_));
        DemoOutput out;
        out.trace["simplex"] = "polygon";
        Json corners = Json::array();
        for (const Vec3& v : polygon_) corners.push_back(vec3Json(v));
        out.trace["vertices"] = corners;
        Json qs = Json::array();
        for (std::size_t i = 0; i < queries_.size(); ++i) {
            const ClosestPointPolygonResult& r = results[i];
            Json tests = Json::array();
            for (const PolygonRegionTest& t : r.tests)
                tests.push_back({{"candidate", t.candidate}, {"terms", {t.first, t.second}}, {"accepted", t.accepted}});
            qs.push_back({{"point", vec3Json(queries_[i])},
                          {"region", regionName(r, int(polygon_.size()))},
                          {"dimension", r.dimension},
                          {"closest", vec3Json(r.point)},
                          {"distance", r.distance},
                          {"tests", tests}});
        }
        out.trace["queries"] = qs;
        if (numericOnly(ctx, out)) return out;
        PolygonVoronoiDiagram diagram;
        if (common_.hasLayer("regions")) diagram = polygonVoronoiRegions(polygon_, margin());
        else out.skipped.push_back("region geometry (no 'regions' layer)");
        for (const std::string& view : views_) out.frames.push_back(drawFrame(*ctx.gl, ctx, diagram, results, view, -1));
        if (common_.steps || ctx.stepsOverride) {
            addQueryFramesAndSheet(*ctx.gl, common_, int(queries_.size()), [&](int i) {
                return drawFrame(*ctx.gl, ctx, diagram, results, views_.front(), i);
            }, out);
        } else {
            out.skipped.push_back("per-step frames and contact sheet (steps off)");
        }
        return out;
    }

private:
    std::vector<Vec3> polygon_;
    std::vector<Vec3> queries_;
    double margin_;
    std::vector<std::string> views_;

    Vec3 center() const {
        Vec3 c = Vec3::Zero();
        for (const Vec3& v : polygon_) c += v;
        return c / double(polygon_.size());
    }
    double size() const {
        double r = 0;
        for (const Vec3& v : polygon_) r = std::max(r, (v - center()).norm());
        return r;
    }
    double margin() const { return margin_ > 0 ? margin_ : size(); }

    Camera cameraFor(const std::string& view, const Vec3& normal, int focus) const {
        if (common_.camera) return *common_.camera;
        const Vec3 u = (polygon_[1] - polygon_[0]).normalized();
        double reach = size() + margin();
        for (const Vec3& q : queries_) reach = std::max(reach, (q - center()).norm());
        if (view == "plane") {
            Camera cam = framingCamera(center(), reach, normal, normal.cross(u), false);
            cam.viewHeight = (focus >= 0 ? 2.9 : 2.4) * reach;
            return cam;
        }
        return framingCamera(center(), reach * (focus >= 0 ? 1.2 : 1.0), normal * 1.1 - normal.cross(u) * 1.4 + u * 0.7, normal,
                             true);
    }

    Frame drawFrame(GlContext& gl, const RunContext& ctx, const PolygonVoronoiDiagram& diagram,
                    const std::vector<ClosestPointPolygonResult>& results, const std::string& view, int focus) const {
        Canvas c(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        const Vec3 normal = results.empty() || !results.front().valid ? Vec3::UnitZ() : results.front().normal;
        c.setCamera(cameraFor(view, normal, focus));
        const bool labels = common_.hasLayer("labels");
        const bool plane = view == "plane";
        // The regions as zones; in a step frame the query's own region stronger, the rest faint.
        const auto zone = [&](const std::vector<Vec3>& poly, int dimension, bool own) {
            const float alpha = focus < 0 ? (plane ? 0.40f : 0.25f) : own ? 0.55f : 0.12f;
            c.drawPolygon(poly, featureDimensionColor(dimension).withAlpha(alpha));
        };
        const ClosestPointPolygonResult* focused = focus >= 0 ? &results[std::size_t(focus)] : nullptr;
        for (std::size_t i = 0; i < diagram.vertexRegions.size(); ++i)
            zone(diagram.vertexRegions[i], 0, focused && focused->dimension == 0 && focused->index == int(i));
        for (std::size_t i = 0; i < diagram.edgeRegions.size(); ++i)
            zone(diagram.edgeRegions[i], 1, focused && focused->dimension == 1 && focused->index == int(i));
        if (!diagram.face.empty()) zone(diagram.face, 2, focused && focused->dimension == 2);
        if (diagram.face.empty()) c.drawPolygon(polygon_, roleColor(Role::ShapeA).withAlpha(0.3f));
        c.drawPolyline(polygon_, true, lineStyle(Role::Ink, 3.5f));
        if (labels) {
            for (std::size_t i = 0; i < polygon_.size(); ++i)
                drawLabelAway(c, polygon_[i], center(), "v" + std::to_string(i), labelStyle(Role::Ink, 24.0f), 12.0);
        }
        for (std::size_t i = 0; i < queries_.size(); ++i) {
            const ClosestPointPolygonResult& r = results[i];
            const bool faded = focus >= 0 && int(i) != focus;
            Color qc = featureDimensionColor(r.dimension);
            if (faded) qc = qc.withAlpha(0.25f);
            if (common_.hasLayer("closest") && !faded) {
                c.drawLine(queries_[i], r.point, lineStyle(Role::Result, 3.0f, false, true));
                c.drawPoint(r.point, 6.0f, roleColor(Role::Result));
            }
            if (!plane && !faded) {
                // In 3D the zones lie in the plane and the points above or below it: a dashed drop line
                // to each point's foot shows which zone it is over.
                const Vec3 foot = queries_[i] - (queries_[i] - polygon_[0]).dot(normal) * normal;
                c.drawLine(queries_[i], foot, lineStyle(Role::Muted, 2.0f, true, true));
                c.drawPoint(foot, 4.0f, roleColor(Role::Muted));
            }
            if (common_.hasLayer("queries")) {
                c.drawPoint(queries_[i], focus == int(i) ? 12.0f : 9.0f, qc, true, 2.0f,
                            faded ? roleColor(Role::Muted) : roleColor(Role::Ink));
                if (labels && !faded) {
                    TextStyle ts{18.0f, roleColor(Role::Ink), Anchor::Center, true, false};
                    ts.offsetPx = Eigen::Vector2d(24, 0);
                    ts.place = true;
                    c.drawText(queries_[i],
                               "q" + std::to_string(i + 1) + (focus < 0 ? ": " + regionName(r, int(polygon_.size())) : ""), ts);
                }
            }
        }
        drawKey(c, 20, 62,
                {{featureDimensionColor(0), "vertex region"},
                 {featureDimensionColor(1), "edge region"},
                 {featureDimensionColor(2), "face region"}},
                17.0f);
        std::string caption = common_.caption;
        if (focused) {
            caption = "q" + std::to_string(focus + 1) + " " + formatPoint(queries_[std::size_t(focus)]) + ": region " +
                      regionName(*focused, int(polygon_.size())) + ", closest " + formatPoint(focused->point) + ", distance " +
                      formatNumber(focused->distance);
            if (labels) {
                const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
                const std::vector<std::string> lines = wrapPieces(c, testEntries(*focused), ";   ", ts, c.width() - 36.0);
                double y = c.height() - 44 - 22.0 * double(lines.size() + 1);
                c.drawTextPx(18, y, "Region tests, vertices first, then edges:",
                             TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
                for (const std::string& l : lines) c.drawTextPx(18, y += 22.0, l, ts);
            }
        }
        drawTitleAndCaption(c, common_.title + (plane ? "" : " (3D)"), caption);
        Frame f;
        if (focused) {
            f.name = stepFrameName(focus + 1);
            f.caption = "q" + std::to_string(focus + 1) + ": " + regionName(*focused, int(polygon_.size()));
        } else {
            f.name = view;
            f.caption = common_.title + " — " + view;
        }
        f.image = c.readPixels();
        return f;
    }
};

}  // namespace

std::unique_ptr<PreparedScene> makePolygonRegionsScene(SceneCommon common, std::vector<Vec3> polygon,
                                                       std::vector<Vec3> queries, double margin,
                                                       std::vector<std::string> views) {
    return std::make_unique<PolygonRegionsScene>(std::move(common), std::move(polygon), std::move(queries), margin,
                                                 std::move(views));
}

}  // namespace cdlab::demos
