// Point vs triangle / tetrahedron Voronoi regions (Ericson, Real-Time Collision Detection §5.1.5,
// §5.1.6). All geometry comes from core (closest_point.h, voronoi_regions.h): this file only draws.
//
// Scene keys (besides the common ones in scene.h):
//   "triangle": [a, b, c]  or  "tetrahedron": [a, b, c, d]  or  "polygon": [[x, y, z], ...] (convex, planar)
//   or  "box": {"half_extents", "position", "rotation"}
//   "queries": [[x, y, z], ...]     query points
//   "views": ["plane", "3d"]        triangle: which overview frames to draw (tetrahedron: "3d" only)
//   "margin": number                how far the drawn regions extend beyond the simplex (default: its size)
// Layers: "regions" (coloured zones / region faces), "boundaries" (region boundaries: lines in the
// plane view, translucent slabs in 3D), "labels", "closest" (segment to the closest point), "queries".
#include "app/scene/json_reader.h"
#include "demos/voronoi_triangle/voronoi_triangle_demo.h"

#include <algorithm>
#include <optional>

#include "core/closest/closest_point.h"
#include "core/closest/voronoi_regions.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/step_frames.h"
#include "app/scene/scene_limits.h"
#include "demos/voronoi_triangle/box_regions.h"
#include "demos/voronoi_triangle/polygon_regions.h"
#include "render/canvas.h"

namespace cdlab::demos {

namespace {

using namespace render;

const std::vector<std::string> kLayers = {"regions", "boundaries", "labels", "closest", "queries"};

// ---------------------------------------------------------------------------------------------
// Numeric part: one closest-point query per point, with its exact region tests.

struct TriangleQuery {
    Vec3 point;
    ClosestPointTrace trace;  // trace.result is the answer
};

struct TetrahedronQuery {
    Vec3 point;
    TetrahedronTrace trace;
};


template <class Test>
Json testsJson(const std::vector<Test>& tests) {
    Json out = Json::array();
    for (const auto& t : tests) {
        Json terms = Json::array();
        for (int i = 0; i < t.termCount; ++i)
            terms.push_back({{"name", t.terms[i].name},
                             {"formula", t.terms[i].formula},
                             {"sign", t.terms[i].sign},
                             {"exact_fallback", t.terms[i].exactFallback}});
        out.push_back({{"candidate", nameOf(t.candidate)},
                       {"condition", t.condition},
                       {"terms", terms},
                       {"accepted", t.accepted}});
    }
    return out;
}

// One query of the trace: the same fields for triangle and tetrahedron results.
template <class Result, class Tests>
Json queryJson(const Vec3& point, const Result& r, const Tests& tests) {
    Json weights = Json::array();
    for (int i = 0; i < r.barycentric.size(); ++i) weights.push_back(r.barycentric[i]);
    return {{"point", vec3Json(point)},
            {"region", nameOf(r.region)},
            {"closest", vec3Json(r.point)},
            {"barycentric", weights},
            {"distance", std::sqrt(r.distanceSquared)},
            {"degenerate", r.status != SimplexStatus::Regular},
            {"tests", testsJson(tests)}};
}

/// Each query point through `closest(point, &trace)`, its trace kept (Query: TriangleQuery or TetrahedronQuery).
template <class Query, class Closest>
std::vector<Query> runQueries(const std::vector<Vec3>& points, const Closest& closest) {
    std::vector<Query> results;
    for (const Vec3& q : points) {
        Query r{q, {}};
        closest(q, &r.trace);
        results.push_back(r);
    }
    return results;
}

/// Every query of a run (a TriangleQuery or TetrahedronQuery list) as trace JSON.
template <class Query>
Json queriesJson(const std::vector<Query>& results) {
    Json qs = Json::array();
    for (const auto& r : results) qs.push_back(queryJson(r.point, r.trace.result, r.trace.tests));
    return qs;
}

// Ericson's region tests of a query in the order made, one entry each: the candidate, every
// term evaluated with its double value and its exact sign, and the outcome
// ("AB: vc = -0.5 < 0, d1 = 2 > 0, d3 = -1 < 0 → yes").
template <class Tests>
std::vector<std::string> regionTestEntries(const Tests& tests) {
    std::vector<std::string> out;
    for (const auto& t : tests) {
        std::string e = std::string(nameOf(t.candidate)) + ": ";
        for (int k = 0; k < t.termCount; ++k) {
            const PredicateSign& p = t.terms[std::size_t(k)];
            e += std::string(k ? ", " : "") + p.name + " = " + formatNumber(p.value) +
                 (p.sign > 0   ? " > 0"
                  : p.sign < 0 ? " < 0"
                               : " = 0") +
                 (p.exactFallback ? " (exact)" : "");
        }
        if (t.termCount == 0) e += "otherwise";
        out.push_back(e + (t.accepted ? " → yes" : " → no"));
    }
    return out;
}

// The region tests written as a block whose last line ends at pixel row `bottom` (above the
// caption), entries joined and wrapped to `width`: the step frame's account of how the region
// was found.
void drawRegionTests(Canvas& canvas, double x, double bottom, double width, const std::vector<std::string>& entries) {
    const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, false};
    const double lineH = 22;
    const std::vector<std::string> lines = wrapPieces(canvas, entries, ";   ", ts, width);
    double y = bottom - lineH * double(lines.size() + 1);
    canvas.drawTextPx(
        x, y, "Region tests in Ericson's order:", TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    for (const std::string& l : lines) canvas.drawTextPx(x, y += lineH, l, ts);
}

// Caption of the step frame of query i.
template <class Result>
std::string focusCaption(int i, const Vec3& point, const Result& r) {
    return "q" + std::to_string(i + 1) + " " + formatPoint(point) + ": region " + nameOf(r.region) + ", closest " +
           formatPoint(r.point) + ", distance " + formatNumber(std::sqrt(r.distanceSquared));
}

// A query point's name: right of the point when free, else where the placement step finds room.
TextStyle queryLabelStyle() {
    TextStyle ts{18.0f, roleColor(Role::Ink), Anchor::Center, true, false};
    ts.offsetPx = Eigen::Vector2d(24, 0);
    ts.place = true;
    return ts;
}

Color regionColor(int regionIndex) { return triangleRegionColor(regionIndex); }

// Tetrahedron regions are coloured by the dimension of their feature (vertex, edge, face, inside).
int tetraFeatureDimension(TetrahedronRegion r) {
    int i = int(r);
    return i < 4 ? 0 : i < 10 ? 1 : i < 14 ? 2 : 3;
}
Color tetraRegionColor(TetrahedronRegion r) { return featureDimensionColor(tetraFeatureDimension(r)); }

Vec3 polygonCentroid(const std::vector<Vec3>& poly) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : poly) c += p;
    return poly.empty() ? c : Vec3(c / double(poly.size()));
}

// ---------------------------------------------------------------------------------------------

class VoronoiScene final : public PreparedScene {
public:
    VoronoiScene(SceneCommon common, std::vector<Vec3> simplex, std::vector<Vec3> queries,
                 std::vector<std::string> views, double margin)
        : PreparedScene(std::move(common)),
          simplex_(std::move(simplex)),
          queries_(std::move(queries)),
          views_(std::move(views)),
          margin_(margin) {}

    DemoOutput execute(const RunContext& ctx) const override {
        return simplex_.size() == 3 ? runTriangle(ctx) : runTetrahedron(ctx);
    }

private:
    std::vector<Vec3> simplex_;
    std::vector<Vec3> queries_;
    std::vector<std::string> views_;
    double margin_;

    Vec3 center() const { return polygonCentroid(simplex_); }
    double size() const {
        double r = 0;
        for (const Vec3& v : simplex_) r = std::max(r, (v - center()).norm());
        return r;
    }
    double margin() const { return margin_ > 0 ? margin_ : size(); }

    // -------------------------------------------------------------------------------- triangle

    DemoOutput runTriangle(const RunContext& ctx) const {
        const Triangle tri{simplex_[0], simplex_[1], simplex_[2]};
        const auto results = runQueries<TriangleQuery>(
            queries_, [&](const Vec3& q, auto* trace) { closestPointOnTriangle(q, tri, trace); });
        DemoOutput out;
        out.trace["simplex"] = "triangle";
        out.trace["vertices"] = {vec3Json(tri.a), vec3Json(tri.b), vec3Json(tri.c)};
        out.trace["queries"] = queriesJson(results);
        if (numericOnly(ctx, out)) return out;
        // Region geometry only when something draws it.
        TriangleVoronoiDiagram diagram;
        if (common_.hasLayer("regions") || common_.hasLayer("boundaries"))
            diagram = triangleVoronoiRegions({tri, margin(), margin() * 0.6});
        else out.skipped.push_back("region geometry (no 'regions' or 'boundaries' layer)");
        // The region names and the vertex letters where the overview of the steps' view placed
        // them, in every step frame too (the review: "region A" moved between frames as the query
        // labels around it changed).
        std::vector<std::pair<std::string, Eigen::Vector2d>> pinnedLabels;
        for (const std::string& view : views_) {
            out.frames.push_back(drawTriangleFrame(*ctx.gl, ctx, tri, diagram, results, view, -1, {}));
            if (view != views_.front()) continue;
            const Image& im = out.frames.back().image;
            for (const LayoutLabel& l : im.layout.labels)
                if (l.text.rfind("region ", 0) == 0 || l.text == "A" || l.text == "B" || l.text == "C")
                    pinnedLabels.push_back({l.text, l.box.center() / im.scale});
        }
        if (common_.steps || ctx.stepsOverride)
            addQueryFramesAndSheet(*ctx.gl, common_, int(queries_.size()), [&](int i) {
                return drawTriangleFrame(*ctx.gl, ctx, tri, diagram, results, views_.front(), i, pinnedLabels);
            }, out);
        else out.skipped.push_back("per-step frames and contact sheet (steps off)");
        return out;
    }

    Camera triangleCamera(const Triangle& tri, const TriangleVoronoiDiagram& diagram, const std::string& view) const {
        Vec3 n = (tri.b - tri.a).cross(tri.c - tri.a);
        if (n.squaredNorm() == 0) n = Vec3::UnitZ();  // collinear: any view direction works
        n.normalize();
        Vec3 u = (tri.b - tri.a).squaredNorm() > 0 ? Vec3((tri.b - tri.a).normalized()) : Vec3::UnitX();
        if (std::abs(u.dot(n)) > 0.9) u = n.unitOrthogonal();
        Vec3 up = n.cross(u).normalized();
        double radius = size() + margin();
        if (common_.camera && view == "3d") return *common_.camera;
        if (view == "plane") {
            // Frame the regions' clip rectangle (when drawn), with room for the title and caption.
            Vec3 middle = center();
            double extent = 2 * radius;
            if (diagram.valid) {
                middle = (diagram.rectangle[0] + diagram.rectangle[2]) * 0.5;
                extent = std::max((diagram.rectangle[1] - diagram.rectangle[0]).norm(),
                                  (diagram.rectangle[3] - diagram.rectangle[0]).norm());
            }
            Camera cam = framingCamera(middle, radius, n, up, false);
            cam.viewHeight = 1.2 * extent;
            return cam;
        }
        // 3D: look from above the plane, off to the side, so the slabs read as planes.
        return framingCamera(center(), radius * 1.1, n * 1.1 - up * 1.4 + u * 0.7, n, true);
    }

    Frame drawTriangleFrame(GlContext& gl, const RunContext& ctx, const Triangle& tri,
                            const TriangleVoronoiDiagram& diagram, const std::vector<TriangleQuery>& results,
                            const std::string& view, int focus,
                            const std::vector<std::pair<std::string, Eigen::Vector2d>>& pinnedLabels) const {
        Canvas canvas(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        canvas.setCamera(triangleCamera(tri, diagram, view));
        const bool is3d = view == "3d";

        if (diagram.valid && common_.hasLayer("regions"))
            for (const auto& region : diagram.regions)
                canvas.drawPolygon(region.vertices, regionColor(int(region.region)).withAlpha(is3d ? 0.30f : 0.42f));
        if (diagram.valid && common_.hasLayer("boundaries")) {
            for (std::size_t i = 0; i < diagram.boundaries.size(); ++i) {
                const auto& b = diagram.boundaries[i];
                // In the plane view a boundary plane is seen edge-on: draw its in-plane segment.
                Vec3 p0 = (b.quad[0] + b.quad[3]) * 0.5, p1 = (b.quad[1] + b.quad[2]) * 0.5;
                canvas.drawLine(p0, p1, lineStyle(Role::Muted, 2.0f, true));
                if (is3d) {
                    Color c = (i < 6 ? roleColor(Role::Direction) : roleColor(Role::Simplex)).withAlpha(0.16f);
                    canvas.drawPolygon(std::vector<Vec3>(b.quad.begin(), b.quad.end()), c);
                }
            }
        }
        // The triangle itself (in the plane view with regions it is region ABC, already tinted).
        if (!(diagram.valid && common_.hasLayer("regions") && !is3d))
            canvas.drawPolygon({tri.a, tri.b, tri.c}, roleColor(Role::Background).mixed(roleColor(Role::ShapeA), 0.25f),
                               is3d);
        canvas.drawPolyline({tri.a, tri.b, tri.c}, true, lineStyle(Role::Ink, 3.5f));

        const bool labels = common_.hasLayer("labels");
        // Where the overview placed a label of this text (step frames keep it there), if it did.
        const auto pinnedAt = [&](const std::string& text) -> std::optional<Eigen::Vector2d> {
            for (const auto& [t, at] : pinnedLabels)
                if (t == text) return at;
            return std::nullopt;
        };
        if (labels) {
            const Vec3 c = center();
            const char* names[3] = {"A", "B", "C"};
            const Vec3 corners[3] = {tri.a, tri.b, tri.c};
            for (int i = 0; i < 3; ++i) {  // outside the triangle, off the query and closest points
                // Pinned where the overview put it when that is beside the corner and clear of the
                // step's query; placed afresh otherwise.
                const std::optional<Eigen::Vector2d> at = pinnedAt(names[i]);
                Eigen::Vector2d corner, q;
                const bool clear =
                    at && canvas.project(corners[i], corner) && (*at - corner).norm() < 45.0 &&
                    !(focus >= 0 && canvas.project(results[std::size_t(focus)].point, q) && (q - *at).norm() < 40.0);
                if (clear) canvas.drawTextPx(at->x(), at->y(), names[i], labelStyle(Role::Ink, 28.0f));
                else drawLabelAway(canvas, corners[i], c, names[i], labelStyle(Role::Ink, 28.0f), 10.0);
            }
            if (diagram.valid && common_.hasLayer("regions") && !is3d)
                for (const auto& region : diagram.regions) {
                    if (region.vertices.empty()) continue;
                    Vec3 at = polygonCentroid(region.vertices);
                    if (region.region == TriangleRegion::ABC) at = c;
                    else at = c + (at - c) * 0.85;  // pull labels of unbounded regions inwards, off the frame edge
                    TextStyle ts{20.0f, regionColor(int(region.region)).scaled(0.55f), Anchor::Center, true, true};
                    const std::string name = std::string("region ") + nameOf(region.region);
                    // Pinned unless the step's query (drawn larger than in the overview) is under it.
                    const std::optional<Eigen::Vector2d> pinned = pinnedAt(name);
                    Eigen::Vector2d q;
                    const Eigen::Vector2d half = 0.5 * canvas.measureText(name, ts) + Eigen::Vector2d(16, 16);
                    if (pinned && !(focus >= 0 && canvas.project(results[std::size_t(focus)].point, q) &&
                                    std::abs(q.x() - pinned->x()) <= half.x() && std::abs(q.y() - pinned->y()) <= half.y())) {
                        canvas.drawTextPx(pinned->x(), pinned->y(), name, ts);
                        continue;
                    }
                    ts.place = true;  // on the region's centre, or beside it when a query point is there
                    canvas.drawText(at, name, ts);
                }
        }
        for (std::size_t i = 0; i < results.size(); ++i) {
            const auto& r = results[i].trace.result;
            const bool faded = focus >= 0 && int(i) != focus;
            Color qc = regionColor(int(r.region));
            if (faded) qc = qc.withAlpha(0.25f);
            if (common_.hasLayer("closest") && !faded) {
                LineStyle s = lineStyle(Role::Result, 3.0f, false, true);
                canvas.drawLine(results[i].point, r.point, s);
                canvas.drawPoint(r.point, 6.0f, roleColor(Role::Result));
            }
            if (common_.hasLayer("queries")) {
                canvas.drawPoint(results[i].point, focus == int(i) ? 12.0f : 9.0f, qc, true, 2.0f,
                                 faded ? roleColor(Role::Muted) : roleColor(Role::Ink));
                if (labels && !faded) canvas.drawText(results[i].point, "q" + std::to_string(i + 1), queryLabelStyle());
            }
        }
        std::string caption = common_.caption;
        if (focus >= 0) caption = focusCaption(focus, results[focus].point, results[focus].trace.result);
        if (focus >= 0 && labels)
            drawRegionTests(canvas, 18, canvas.height() - 44, canvas.width() - 36,
                            regionTestEntries(results[focus].trace.tests));
        drawTitleAndCaption(canvas, common_.title + (is3d ? " (3D)" : ""), caption);
        Frame f;
        f.name = focus >= 0 ? stepFrameName(focus + 1) : view;
        f.caption = focus >= 0 ? "q" + std::to_string(focus + 1) + ": " + nameOf(results[focus].trace.result.region)
                               : common_.title + " — " + view;
        f.image = canvas.readPixels();
        return f;
    }

    // ----------------------------------------------------------------------------- tetrahedron

    DemoOutput runTetrahedron(const RunContext& ctx) const {
        const Tetrahedron tet{simplex_[0], simplex_[1], simplex_[2], simplex_[3]};
        const auto results = runQueries<TetrahedronQuery>(
            queries_, [&](const Vec3& q, auto* trace) { closestPointOnTetrahedron(q, tet, trace); });
        DemoOutput out;
        out.trace["simplex"] = "tetrahedron";
        out.trace["vertices"] = {vec3Json(tet.a), vec3Json(tet.b), vec3Json(tet.c), vec3Json(tet.d)};
        out.trace["queries"] = queriesJson(results);
        out.trace["slices"] = slicesJson(tet);
        if (numericOnly(ctx, out)) return out;
        // The 15 region geometries are drawn only in step frames (one region each).
        TetrahedronVoronoiDiagram diagram;
        if ((common_.steps || ctx.stepsOverride) && (common_.hasLayer("regions") || common_.hasLayer("boundaries")))
            diagram = tetrahedronVoronoiRegions({tet, margin_ > 0 ? margin_ : 0.5 * size()});
        else out.skipped.push_back("region geometry (not drawn without steps and a 'regions'/'boundaries' layer)");
        out.frames.push_back(drawTetrahedronFrame(*ctx.gl, ctx, tet, diagram, results, -1));
        if (tetrahedronVoronoiRegions({tet, size()}).valid) out.frames.push_back(drawTetrahedronRegions(*ctx.gl, ctx, tet));
        else out.skipped.push_back("regions frame (a flat tetrahedron has no 3D regions)");
        if (common_.steps || ctx.stepsOverride)
            addQueryFramesAndSheet(*ctx.gl, common_, int(queries_.size()),
                                   [&](int i) { return drawTetrahedronFrame(*ctx.gl, ctx, tet, diagram, results, i); }, out);
        return out;
    }

    /// Frame "regions": the 15 regions seen together in four slices parallel to face ABC — below it,
    /// through the tetrahedron, near D, above D. Each region is the intersection of its half-spaces (core's
    /// tetrahedronVoronoiRegions); its slice is the plane's window clipped by them (core's
    /// clipConvexPolygon), coloured by the dimension of its feature and named.
    struct RegionSlice {
        double fraction = 0;  ///< of D's height above face ABC
        Vec3 origin = Vec3::Zero();
        std::vector<std::pair<TetrahedronRegion, std::vector<Vec3>>> cells;  ///< each region's polygon (world)
    };

    /// The four slices parallel to face ABC, each a square window of side 3.2 size() about the point
    /// above ABC's centroid, cut into the regions' polygons (core's half-spaces, clipConvexPolygon).
    std::vector<RegionSlice> tetrahedronSlices(const Tetrahedron& tet, Vec3& u, Vec3& v, double& half) const {
        const TetrahedronVoronoiDiagram diagram = tetrahedronVoronoiRegions({tet, size()});
        Vec3 n = (tet.b - tet.a).cross(tet.c - tet.a).normalized();
        if (n.dot(tet.d - tet.a) < 0) n = -n;  // towards D
        const double height = n.dot(tet.d - tet.a);
        u = (tet.b - tet.a).normalized(), v = n.cross(u);
        half = 1.6 * size();
        const Vec3 mid = (tet.a + tet.b + tet.c) / 3.0;
        std::vector<RegionSlice> out;
        for (double f : {-0.35, 0.4, 0.85, 1.3}) {
            RegionSlice sl{f, mid + f * height * n, {}};
            const std::vector<Vec3> window = {sl.origin + half * (-u - v), sl.origin + half * (u - v),
                                              sl.origin + half * (u + v), sl.origin + half * (-u + v)};
            for (int r = 0; r < 15 && diagram.valid; ++r) {
                std::vector<Vec3> poly = window;
                for (const HalfSpace& h : diagram.regions[r].halfSpaces) poly = clipConvexPolygon(poly, h);
                if (poly.size() >= 3) sl.cells.emplace_back(TetrahedronRegion(r), std::move(poly));
            }
            out.push_back(std::move(sl));
        }
        return out;
    }

    Json slicesJson(const Tetrahedron& tet) const {
        Vec3 u, v;
        double half = 0;
        Json out = Json::array();
        for (const RegionSlice& sl : tetrahedronSlices(tet, u, v, half)) {
            Json cells = Json::array();
            for (const auto& [region, poly] : sl.cells) {
                Json pts = Json::array();
                for (const Vec3& p : poly) pts.push_back(vec3Json(p));
                cells.push_back({{"region", nameOf(region)}, {"polygon", pts}});
            }
            out.push_back({{"fraction", sl.fraction}, {"origin", vec3Json(sl.origin)}, {"half_width", half},
                           {"u", vec3Json(u)}, {"v", vec3Json(v)}, {"cells", cells}});
        }
        return out;
    }

    Frame drawTetrahedronRegions(GlContext& gl, const RunContext& ctx, const Tetrahedron& tet) const {
        Vec3 u, v;
        double half = 0;
        const std::vector<RegionSlice> slices = tetrahedronSlices(tet, u, v, half);
        const int W = common_.image.width, H = common_.image.height;
        Canvas canvas(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)), Camera::pixels(W, H));
        const double pw = W / 2.0, ph = (H - 120.0) / 2.0, box = std::min(pw - 40, ph - 70);
        int seen[4] = {0, 0, 0, 0};
        std::vector<bool> counted(15, false);
        for (int k = 0; k < 4; ++k) {
            const Vec3 origin = slices[std::size_t(k)].origin;
            const double fraction = slices[std::size_t(k)].fraction;
            const double px0 = (k % 2) * pw, py0 = 56 + (k / 2) * ph;
            const auto S = [&](const Vec3& p) {
                const double x = (p - origin).dot(u) / (2 * half), y = (p - origin).dot(v) / (2 * half);
                return Vec3(px0 + 0.5 * pw + x * box, H - (py0 + 52 + 0.5 * box - y * box), 0);
            };
            for (const auto& [region, poly] : slices[std::size_t(k)].cells) {
                const int r = int(region);
                if (!counted[std::size_t(r)]) counted[std::size_t(r)] = true, ++seen[tetraFeatureDimension(region)];
                std::vector<Vec3> px;
                Vec3 c = Vec3::Zero();
                for (const Vec3& p : poly) px.push_back(S(p)), c += p;
                const Color color = tetraRegionColor(region);
                canvas.drawPolygon(px, color.withAlpha(0.45f));
                canvas.drawPolyline(px, true, LineStyle{1.2f, color.scaled(0.6f), 0.0f, false});
                if (common_.hasLayer("labels")) {
                    TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
                    ts.place = true;
                    canvas.drawText(S(c / double(poly.size())), nameOf(region), ts);
                }
            }
            const std::string where = fraction < 0     ? "below face ABC"
                                      : fraction < 0.6 ? "through the tetrahedron"
                                      : fraction < 1   ? "near D"
                                                       : "above D";
            canvas.drawTextPx(px0 + 20, py0 + 4, where, TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, true});
            canvas.drawTextPx(px0 + 20, py0 + 26, "at " + formatNumber(fraction) + " of D's height above ABC",
                              TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        }
        drawTitleAndCaption(canvas, common_.title,
                            "Slices parallel to face ABC; together they show " + std::to_string(seen[0]) + " vertex, " +
                                std::to_string(seen[1]) + " edge, " + std::to_string(seen[2]) + " face regions and " +
                                std::to_string(seen[3]) + " inside" +
                                (seen[0] + seen[1] + seen[2] + seen[3] == 15 ? ": all 15" : " of the 15"));
        return Frame{"regions", "the 15 regions in four slices", canvas.readPixels()};
    }

    Frame drawTetrahedronFrame(GlContext& gl, const RunContext& ctx, const Tetrahedron& tet,
                               const TetrahedronVoronoiDiagram& diagram, const std::vector<TetrahedronQuery>& results,
                               int focus) const {
        Canvas canvas(gl, sceneCanvasOptions(common_, figureScale(common_, ctx)));
        // A step frame frames the scene wider: its region tests need the bottom of the picture.
        double radius = (size() + 0.6 * margin()) * (focus >= 0 ? 1.35 : 1.0);
        canvas.setCamera(common_.camera ? *common_.camera
                                        : framingCamera(center(), radius, Vec3(1.0, 0.75, 1.6), Vec3::UnitY(), true));
        const Vec3 v[4] = {tet.a, tet.b, tet.c, tet.d};
        const std::vector<Vec3> verts(v, v + 4);
        canvas.drawMesh(
            verts,
            {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2), Eigen::Vector3i(1, 2, 3)},
            roleColor(Role::ShapeA).withAlpha(0.28f), true);
        // Edge ij joins the faces opposite the other two vertices k and l; behind the body it is dashed.
        const auto outward = [&](int i, int j, int l, int k) {  // face ijl, opposite vertex k
            const Vec3 n = (v[j] - v[i]).cross(v[l] - v[i]);
            return n.dot(v[k] - v[i]) > 0 ? Vec3(-n) : n;
        };
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                int k = 0;
                while (k == i || k == j) ++k;
                const int l = 6 - i - j - k;
                canvas.drawLine(v[i], v[j],
                                edgeStyleSeen(canvas.camera(), 0.5 * (v[i] + v[j]), outward(i, j, l, k),
                                              outward(i, j, k, l), lineStyle(Role::Ink, 3.0f)));
            }

        // In a step frame, the focused point's region: its clipped boundary faces, faintly (all 15
        // at once would hide the tetrahedron).
        std::vector<bool> shown(15, false);
        if (focus >= 0) shown[int(results[focus].trace.result.region)] = true;
        if (diagram.valid && common_.hasLayer("regions"))
            for (int r = 0; r < 15; ++r) {
                if (!shown[r] || r == int(TetrahedronRegion::ABCD)) continue;
                for (const auto& face : diagram.regions[r].faces)
                    if (face.size() >= 3)
                        canvas.drawPolygon(face, tetraRegionColor(TetrahedronRegion(r)).withAlpha(0.13f));
            }
        if (diagram.valid && common_.hasLayer("boundaries"))
            for (int r = 0; r < 15; ++r) {
                if (!shown[r]) continue;
                for (const auto& face : diagram.regions[r].faces)
                    if (face.size() >= 2) canvas.drawPolyline(face, true, lineStyle(Role::Muted, 1.5f, true));
            }
        const bool labels = common_.hasLayer("labels");
        if (labels) {
            const char* names[4] = {"A", "B", "C", "D"};
            for (int i = 0; i < 4; ++i)
                drawLabelAway(canvas, v[i], center(), names[i], labelStyle(Role::Ink, 28.0f), 12.0);
        }
        for (std::size_t i = 0; i < results.size(); ++i) {
            const auto& r = results[i].trace.result;
            const bool faded = focus >= 0 && int(i) != focus;
            Color qc = tetraRegionColor(r.region);
            if (faded) qc = qc.withAlpha(0.25f);
            if (common_.hasLayer("closest") && !faded && r.region != TetrahedronRegion::ABCD) {
                canvas.drawLine(results[i].point, r.point, lineStyle(Role::Result, 3.0f, false, true));
                canvas.drawPoint(r.point, 6.0f, roleColor(Role::Result));
            }
            if (common_.hasLayer("queries")) {
                canvas.drawPoint(results[i].point, focus == int(i) ? 12.0f : 9.0f, qc, true, 2.0f,
                                 faded ? roleColor(Role::Muted) : roleColor(Role::Ink));
                if (labels && !faded)
                    canvas.drawText(results[i].point, "q" + std::to_string(i + 1) + ": " + nameOf(r.region),
                                    queryLabelStyle());
            }
        }
        // Legend: colour by feature dimension.
        const char* kinds[4] = {"vertex region", "edge region", "face region", "inside"};
        for (int k = 0; k < 4; ++k) {
            double y = 70 + 28 * k;
            TextStyle ts{18.0f,
                         tetraRegionColor(TetrahedronRegion(k == 0   ? 0
                                                            : k == 1 ? 4
                                                            : k == 2 ? 10
                                                                     : 14))
                             .scaled(0.8f),
                         Anchor::Left, true, true};
            canvas.drawTextPx(22, y, kinds[k], ts);
        }
        std::string caption = common_.caption;
        if (focus >= 0) caption = focusCaption(focus, results[focus].point, results[focus].trace.result);
        if (focus >= 0 && labels)
            drawRegionTests(canvas, 18, canvas.height() - 44, canvas.width() - 36,
                            regionTestEntries(results[focus].trace.tests));
        drawTitleAndCaption(canvas, common_.title, caption);
        Frame f;
        f.name = focus >= 0 ? stepFrameName(focus + 1) : "3d";
        f.caption = focus >= 0 ? "q" + std::to_string(focus + 1) + ": " + nameOf(results[focus].trace.result.region)
                               : common_.title;
        f.image = canvas.readPixels();
        return f;
    }

};

// "box": {"half_extents": e, "position": p, "rotation": q} (the scenes' box), its queries and margin.
std::unique_ptr<PreparedScene> readBox(ObjectReader& r, SceneCommon common) {
    ObjectReader b(r.get("box"));
    const Vec3 e = sceneSizes(b.get("half_extents"));
    Vec3 c = Vec3::Zero();
    if (auto p = b.find("position")) c = sceneVec3(*p);
    Quat q = Quat::Identity();
    if (auto rot = b.find("rotation")) q = rot->asQuat();
    b.finish();
    std::vector<Vec3> queries = sceneVec3List(r.get("queries"), 1, kMaxQueryPoints);
    double margin = 0;
    if (auto m = r.find("margin")) margin = sceneSize(*m);
    if (auto v = r.find("views")) {
        for (const JsonNode& item : v->items()) item.asEnum({"3d"});
        if (v->size() == 0) v->fail("expected at least one view");
    }
    r.finish();
    common.frames = {1, int(queries.size()) + 2, 0};  // the view; with steps a frame per query and the sheet
    return makeBoxRegionsScene(std::move(common), Obb::fromRotation(c, e, q), std::move(queries), margin);
}

// "polygon": [[x, y, z], ...] — a convex planar polygon (3 or more corners, either turn), its queries,
// views and margin.
std::unique_ptr<PreparedScene> readPolygon(ObjectReader& r, SceneCommon common) {
    JsonNode pn = r.get("polygon");
    std::vector<Vec3> polygon = sceneVec3List(pn, 3, kMaxShapeVertices);
    // Planar and convex, to rounding of its size: every corner on the plane of Newell's normal, every
    // turn the same way.
    Vec3 n = Vec3::Zero(), centre = Vec3::Zero();
    double size = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        n += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
        centre += polygon[i];
    }
    centre /= double(polygon.size());
    for (const Vec3& v : polygon) size = std::max(size, (v - centre).norm());
    if (!(n.norm() > 1e-12 * size * size)) pn.fail("the corners span no area");
    n.normalize();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        if (std::abs((polygon[i] - centre).dot(n)) > 1e-9 * size)
            pn.at(i).fail("this corner is off the polygon's plane (the corners must lie in one plane)");
        const Vec3 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()], &c = polygon[(i + 2) % polygon.size()];
        if (!((b - a).cross(c - b).dot(n) > 1e-12 * size * size))
            pn.at((i + 1) % polygon.size())
                .fail("the polygon does not turn at this corner (it must be convex, no repeated or collinear corners)");
    }
    std::vector<Vec3> queries = sceneVec3List(r.get("queries"), 1, kMaxQueryPoints);
    double margin = 0;
    if (auto m = r.find("margin")) margin = sceneSize(*m);
    std::vector<std::string> views = {"plane", "3d"};
    if (auto v = r.find("views")) {
        views.clear();
        for (const JsonNode& item : v->items()) views.push_back(item.asEnum({"plane", "3d"}));
        if (views.empty()) v->fail("expected at least one view");
    }
    r.finish();
    // The views; with steps a frame per query and the sheet.
    common.frames = {int(views.size()), int(views.size() + queries.size()) + 1, 0};
    return makePolygonRegionsScene(std::move(common), std::move(polygon), std::move(queries), margin, std::move(views));
}

class VoronoiDemo final : public Demo {
public:
    std::string name() const override { return "voronoi_triangle"; }
    std::string description() const override {
        return "point vs triangle (7 Voronoi regions), convex polygon, tetrahedron (15) and box (27), closest points";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{}, {}}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        std::vector<Vec3> simplex;
        std::vector<std::string> views;
        if (int(r.has("triangle")) + int(r.has("tetrahedron")) + int(r.has("box")) + int(r.has("polygon")) != 1)
            r.node().fail("expected exactly one of 'triangle', 'tetrahedron', 'polygon' or 'box'");
        if (r.has("box")) return readBox(r, std::move(common));
        if (r.has("polygon")) return readPolygon(r, std::move(common));
        if (r.has("triangle")) {
            JsonNode t = r.get("triangle");
            if (t.size() != 3) t.fail("expected [a, b, c]");
            simplex = sceneVec3List(t, 3, 3);
            views = {"plane", "3d"};
        } else {
            JsonNode t = r.get("tetrahedron");
            if (t.size() != 4) t.fail("expected [a, b, c, d]");
            simplex = sceneVec3List(t, 4, 4);
            views = {"3d"};
        }
        // One frame per query point with "steps": the list is the frame count.
        std::vector<Vec3> queries = sceneVec3List(r.get("queries"), 1, kMaxQueryPoints);
        if (auto v = r.find("views")) {
            views.clear();
            for (const JsonNode& item : v->items())
                views.push_back(item.asEnum(simplex.size() == 3 ? std::vector<std::string>{"plane", "3d"}
                                                                : std::vector<std::string>{"3d"}));
            if (views.empty()) v->fail("expected at least one view");
        }
        double margin = 0;
        if (auto m = r.find("margin")) margin = sceneSize(*m);
        r.finish();
        // The views; with steps a frame per query and the sheet.
        common.frames = {int(views.size()), int(views.size() + queries.size()) + 1, 0};
        return std::make_unique<VoronoiScene>(std::move(common), std::move(simplex), std::move(queries),
                                              std::move(views), margin);
    }
};

}  // namespace

const Demo& voronoiDemo() {
    static const VoronoiDemo demo;
    return demo;
}

}  // namespace cdlab::demos
